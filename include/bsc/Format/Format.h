//===- Format.h - b-script's one canonical layout --------------*- C++ -*-===//
//
// `bsc format` and the language server's formatting: one layout for every
// program, as gofmt has one (docs/language.md "Layout"):
//
// - Blocks indent by 4 spaces; a line continued inside `( )` by 8.
// - One space around binary and assignment operators and ` : ` of a
//   result or enum type, one after `,` and `;`; none inside brackets, none
//   after a unary `-` or `!`, none before the `(` of a call, `if(` or
//   `for(` (the paper's style).
// - At most one blank line in a row; none at the start of a block or the
//   file; one before each module-level `task`, `func` and `enum` (before
//   the comments directly above it, which belong to it).
// - Every comment is kept with its text: a comment line is indented as the
//   code it stands in, a comment after code follows it two spaces apart.
// - A line over 80 columns whose statement ends in a call holding most of
//   it is broken after that call's `(`, one argument per line; a comment
//   inside `( )` ends its line where it stands.
//
// The formatter reads tokens, never the tree, so it cannot lose what the
// parser drops; it refuses a file with syntax errors (reported to Diags),
// and it checks its own output: the same tokens and the same comments, or
// an internal error instead of a changed program.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_FORMAT_FORMAT_H
#define BSC_FORMAT_FORMAT_H

#include "bsc/Basic/Diagnostic.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/SourceMgr.h"
#include <optional>
#include <string>
#include <vector>

namespace bsc {
namespace format {

/// What formatting one buffer gave: the whole text, and per source line
/// range the text that replaces it, for formatting a range only.
struct FormattedFile {
  std::string Text;
  /// One piece per statement line or comment line, in order: source lines
  /// First..Last (1-based) become Text (whole lines, each ending in '\n',
  /// with the blank lines the layout puts before the piece).
  struct Piece {
    unsigned First, Last;
    std::string Text;
  };
  std::vector<Piece> Pieces;
};

/// Formats buffer `BufferID` of `SM`. Returns nothing after reporting a
/// syntax error to Diags; an llvm::Error is an internal error (output that
/// would change the program).
llvm::Expected<std::optional<FormattedFile>>
formatBuffer(const llvm::SourceMgr &SM, unsigned BufferID,
             DiagnosticEngine &Diags);

/// Whether two texts are the same program: the same tokens and the same
/// comments (the formatter's check of its own output). An error names the
/// first difference.
llvm::Error checkSameProgram(llvm::StringRef Before, llvm::StringRef After);

/// The edit that formats source lines First..Last (1-based) of a formatted
/// buffer: the whole lines FromLine..ToLine (1-based, inclusive) are
/// replaced by Text. Lines only partly in the range are formatted whole.
struct RangeEdit {
  unsigned FromLine = 0, ToLine = 0;
  std::string Text;
};
std::optional<RangeEdit> formatLines(const FormattedFile &F, unsigned First,
                                     unsigned Last);

} // namespace format
} // namespace bsc

#endif
