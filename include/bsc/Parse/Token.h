//===- Token.h - one lexed token of b-script -------------------*- C++ -*-===//
//
// A token is plain data handed from the lexer to the parser: its kind, its
// spelling (a StringRef into the source buffer, so its location is free) and,
// for literals, the value the lexer already checked. Literal values are
// decoded once, in the lexer, so that the parser never diagnoses a literal.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_PARSE_TOKEN_H
#define BSC_PARSE_TOKEN_H

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/SMLoc.h"
#include <cstdint>
#include <string>

namespace bsc {

namespace tok {
/// Every token kind, from TokenKinds.def.
enum Kind : unsigned char {
#define TOK(Name) Name,
#include "bsc/Parse/TokenKinds.def"
  NumKinds
};

/// The name of a kind as `--emit=tokens` prints it (`identifier`,
/// `kw_func`, `l_paren`).
llvm::StringRef getName(Kind K);
/// The fixed spelling of a keyword or punctuator; empty for the others.
llvm::StringRef getSpelling(Kind K);
} // namespace tok

class Token {
public:
  tok::Kind Kind = tok::eof;
  /// The exact source text. Empty for newline (at a '\n' or at the end of the
  /// buffer), indent, dedent and eof, whose location is still meaningful.
  llvm::StringRef Text;
  llvm::SMLoc Loc;

  /// int_literal: the value as written (decimal up to 2147483648, hex up to
  /// 0xFFFFFFFF). The parser turns it into the two's-complement int32.
  uint64_t IntValue = 0;
  /// int_literal: written in hex (`0x...`), so the bit pattern is meant.
  bool IsHex = false;
  /// float_literal: the value, already checked to be a finite float.
  float FloatValue = 0;
  /// string_literal: the contents with escapes resolved.
  std::string StringValue;

  bool is(tok::Kind K) const { return Kind == K; }
  bool isNot(tok::Kind K) const { return Kind != K; }
  llvm::SMLoc getEndLoc() const {
    return llvm::SMLoc::getFromPointer(Loc.getPointer() + Text.size());
  }
  llvm::SMRange getRange() const { return {Loc, getEndLoc()}; }
};

} // namespace bsc

#endif
