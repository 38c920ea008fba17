//===- FormatImpl.h - what the formatter's files pass each other -*- C++ -*-===//
//
// Items.cpp cuts a buffer into items (statement lines with their comments,
// comment lines); Layout.cpp writes one statement line; Format.cpp puts the
// items together with their indentation and blank lines.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_FORMAT_FORMATIMPL_H
#define BSC_LIB_FORMAT_FORMATIMPL_H

#include "bsc/Parse/Token.h"
#include "llvm/Support/SourceMgr.h"
#include <string>
#include <vector>

namespace bsc {
namespace format {

/// The layout's measures (Format.h).
constexpr unsigned IndentWidth = 4, ContinuationWidth = 8, ColumnLimit = 80;

/// A token of a statement line with the comments next to it.
struct LineToken {
  Token Tok;
  /// Comment lines just before it, inside `( )` of a continued line.
  std::vector<llvm::StringRef> Leading;
  /// The comment after it on its source line, if any.
  llvm::StringRef Trailing;
};

/// A statement line (a continuation inside `( )` joined to it) or a line
/// with a comment only.
struct Item {
  bool IsComment = false;
  /// Block depth: 0 at module level.
  unsigned Depth = 0;
  /// The source lines it spans (1-based).
  unsigned First = 0, Last = 0;
  std::vector<LineToken> Tokens;
  llvm::StringRef Comment;
};

/// The items of buffer `BufferID`, which must lex without errors.
std::vector<Item> splitItems(const llvm::SourceMgr &SM, unsigned BufferID);

/// Statement line `S` at depth `Depth`: one or more lines, each ending in
/// '\n'.
std::string layoutStatement(const Item &S);

} // namespace format
} // namespace bsc

#endif
