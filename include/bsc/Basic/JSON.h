//===- JSON.h - reading JSON text with a bounded nesting depth --*- C++ -*-===//
//
// Every JSON text bsc reads goes through parseJSON: a recording for `bsc run
// --replay` and the REPL's `:replay`, the debug tables of an --instrument
// object, and the language server's messages when it comes. llvm::json's
// parser recurses once per level of nesting, so a line of 100,000 `[`
// overflows the stack. A linear scan that honours strings and escapes
// refuses text nested past MaxJSONDepth before the parser sees it.
//
// Errors carry the byte offset as well as the line and column, so that a
// caller with a SourceMgr can put a caret under the byte.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_BASIC_JSON_H
#define BSC_BASIC_JSON_H

#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/JSON.h"
#include <optional>
#include <string>

namespace bsc {

/// The deepest nesting of arrays and objects bsc reads. A recording nests
/// two levels plus its registered classes' nesting and at most four array
/// dimensions, debug tables four, language server messages about a dozen.
/// 256 levels are far above those, and take about 60 KB of llvm::json's
/// stack (240 bytes a level in a Release build), safe on any thread, also
/// in sanitizer builds whose frames are larger.
constexpr unsigned MaxJSONDepth = 256;

/// Why a JSON text could not be read, and where.
class JSONReadError : public llvm::ErrorInfo<JSONReadError> {
public:
  static char ID;
  JSONReadError(std::string Message, size_t Offset, unsigned Line,
                unsigned Column)
      : Message(std::move(Message)), Offset(Offset), Line(Line),
        Column(Column) {}

  /// What is wrong, without the place: `nesting deeper than 256 levels`.
  std::string Message;
  /// The byte the error is at, counted from 0 at the start of the text.
  size_t Offset;
  /// The line and column (in bytes) of that byte, both from 1.
  unsigned Line, Column;

  /// `LINE:COLUMN: MESSAGE`.
  void log(llvm::raw_ostream &OS) const override;
  std::error_code convertToErrorCode() const override {
    return llvm::inconvertibleErrorCode();
  }
};

/// Parses `Text` as one JSON value. Text that is not JSON, or that nests
/// arrays and objects deeper than MaxJSONDepth, gives a JSONReadError (and
/// no other kind of error).
llvm::Expected<llvm::json::Value> parseJSON(llvm::StringRef Text);

/// Called with each member of a top-level object: its key as written
/// (without the quotes) and the text of its value.
using JSONMemberFn =
    llvm::function_ref<void(llvm::StringRef Key, llvm::StringRef Value)>;

/// Whether parseJSON would accept `Text`, found without building values.
/// If `Text` is an object, `OnMember` (if given) sees its members as they
/// are checked (before the verdict: keep them only if the result is
/// true). A replay parses only the members it needs this way.
bool isJSON(llvm::StringRef Text, JSONMemberFn OnMember = nullptr);

class DiagnosticEngine;
/// parseJSON of one line of a recording held in the engine's SourceMgr;
/// an error is reported there (`invalid JSON: ...`, the caret under the
/// byte) and gives std::nullopt.
std::optional<llvm::json::Value> parseJSONLine(DiagnosticEngine &Diags,
                                               llvm::StringRef Line);

} // namespace bsc

#endif
