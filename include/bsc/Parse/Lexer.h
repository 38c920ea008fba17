//===- Lexer.h - b-script source to tokens ---------------------*- C++ -*-===//
//
// The lexer turns one source buffer into tokens on demand, so that a 10 MB
// file never exists as a token array. Indentation is CPython's: a stack of
// columns turned into `indent` and `dedent` tokens. The decisions, which
// the parser relies on:
//
// - `#` starts a comment that runs to the end of the line. Blank lines and
//   comment-only lines produce no tokens at all (no newline, no indent).
// - Every line with tokens ends with a `newline` token, also the last line
//   of a file without a final '\n'. At the end of the buffer the lexer emits
//   `dedent`s down to column 0, then `eof` (forever).
// - A line indented deeper than the one before always gives `indent`, even
//   if the line before does not open a block: the parser reports that.
//   A dedent to a column that was never opened reports
//   err_inconsistent_dedent and continues at the nearest enclosing level;
//   an `error` token then starts the line, so the parser drops it quietly.
// - Tabs advance to the next multiple of 8. Indenting some lines with tabs
//   and others with spaces, or mixing both in one line's indentation,
//   reports err_mixed_tabs_spaces once per file.
// - Inside `( )` newlines and indentation are ignored. An unmatched `)` and
//   a `(` still open at the end of the buffer are errors. So is a `(` still
//   open when the next line starts with a statement keyword (`if`, `for`,
//   `return`, ...): the line ends there. The lexer also forgets open
//   brackets at an unterminated string, so that one missing `)` or quote
//   does not swallow the rest of the file.
// - Literals: decimal and hex (`0x`) ints, floats `1.5`, `1.5e-3`, `1e3`,
//   strings with the escapes \n \t \\ \" \0. A decimal int above 2147483647
//   is too large, except exactly 2147483648, which the parser accepts only
//   right after a unary minus; hex means the 32-bit pattern (0xFFFFFFFF is
//   -1). `1.`, `.5`, `1e`, `0x` and `12abc` are invalid numbers.
// - Any other byte (control characters, non-ASCII outside strings and
//   comments) is an invalid character; one diagnostic per run of them.
//
// Everything the lexer diagnoses becomes an `error` token (or, for a bad
// escape, a string literal), which the parser treats as already reported.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_PARSE_LEXER_H
#define BSC_PARSE_LEXER_H

#include "bsc/Basic/Diagnostic.h"
#include "bsc/Parse/Token.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/Support/SourceMgr.h"
#include <vector>

namespace llvm {
class raw_ostream;
}

namespace bsc {

class Lexer {
public:
  Lexer(const llvm::SourceMgr &SM, unsigned BufferID, DiagnosticEngine &Diags);

  /// Returns the next token; after the end of the buffer, `eof` forever.
  Token lex();

  /// Appends each comment (from `#` to the end of its line, without a
  /// '\r') to `Sink` as the lexer passes it: the formatter and the language
  /// server keep what the parser never sees.
  void keepComments(std::vector<llvm::StringRef> *Sink) { Comments = Sink; }

private:
  void lexIndentation(Token &Result);
  bool measureIndentation(unsigned &Column);
  void lexNumber(Token &Result);
  void lexString(Token &Result);
  void lexInvalidRun(Token &Result);
  bool lexPunctuator(Token &Result);
  bool nextLineStartsStatement();
  void skipComment();
  void reportUnclosed();
  void makeToken(Token &Result, tok::Kind K, const char *Start);
  void makeMarker(Token &Result, tok::Kind K, const char *At);
  DiagnosticBuilder report(const char *At, diag::Kind K) {
    return Diags.report(llvm::SMLoc::getFromPointer(At), K);
  }

  DiagnosticEngine &Diags;
  const char *BufStart;
  const char *BufEnd;
  const char *Cur;

  /// Columns of the open indentation levels; the bottom is 0.
  llvm::SmallVector<unsigned, 16> Indents{0};
  /// Dedents still to hand out, and where they are reported.
  unsigned PendingDedents = 0;
  const char *DedentLoc = nullptr;
  /// `(`s not yet closed; newlines are ignored while there are any.
  std::vector<const char *> OpenParens;
  /// Errors reported before the outermost `(` opened.
  unsigned ErrorsAtOpenParen = 0;
  /// The last look past a newline inside brackets: where it ended and
  /// whether the line there starts with a statement keyword.
  const char *PeekEnd = nullptr;
  bool PeekResult = false;
  /// At the start of a line, before its indentation was looked at.
  bool AtLineStart = true;
  /// The current line already produced a token (so it needs a newline).
  bool LineHasTokens = false;
  /// Which indentation characters the file used so far.
  bool SawTabIndent = false, SawSpaceIndent = false, ReportedMixed = false;
  /// The columns of the first line indented with spaces only: one level.
  unsigned SpaceIndentUnit = 0;
  bool ReachedEnd = false;
  /// An inconsistent dedent was reported; an `error` token follows it.
  bool PendingBadDedent = false;
  std::vector<llvm::StringRef> *Comments = nullptr;
};

/// Lexes the whole buffer and prints one token per line for
/// `bsc --emit=tokens`:
///
///   line:col kind 'spelling'
///
/// where kind is the TokenKinds.def name (`identifier`, `kw_task`,
/// `l_paren`, `int_literal`, ...). newline, indent, dedent and eof have no
/// spelling and print as `3:11 newline`, `4:1 indent`. Literals print their
/// source text, e.g. `5:9 string_literal '"a\n"'`. Diagnostics go to Diags.
void dumpTokens(const llvm::SourceMgr &SM, unsigned BufferID,
                DiagnosticEngine &Diags, llvm::raw_ostream &OS);

} // namespace bsc

#endif
