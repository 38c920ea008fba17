//===- Line.h - lines of b-script compiled into a loaded behavior -*- C++ -*-===//
//
// A line as `bsc repl` takes it (statements or an expression, checked by
// ReplChecker in the scope of the entry's module, reading task fields and
// `output`) compiled into the behavior's JIT as a func of its own, run
// between cycles on a session's state. The REPL's lines, watches and
// breakpoint conditions and `bsc replay --find`'s question are such lines.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_RUN_LINE_H
#define BSC_RUN_LINE_H

#include "bsc/Run/Run.h"
#include "bsc/Sema/Sema.h"
#include <memory>
#include <optional>
#include <vector>

namespace bsc {

/// Storage of a line's result or a REPL variable: aligned, zeroed.
struct Slot {
  void *Ptr = nullptr;
  size_t Size = 0, Align = 1;
  const Type *Ty = nullptr;
};
Slot allocateSlot(const Type *T);
/// Frees it, destroying a class value a line constructed there (with its
/// destroy thunk in `L`'s JIT, when `L` is given).
void destroySlot(const LoadedBehavior *L, Slot &S);

/// A checker of lines against `L` as loaded in `C`: the entry's module,
/// the task fields the state keeps; in `FrameTask`'s frame if it names a
/// task.
std::unique_ptr<ReplChecker> makeLineChecker(Compilation &C,
                                             const LoadedBehavior &L,
                                             llvm::StringRef FrameTask = "");

/// A compiled line: its func, what the checker made of it, and the slot of
/// its result (Ptr null if it has none).
struct CompiledLine {
  void (*Fn)(void *) = nullptr;
  std::optional<ReplChecker::Line> Checked;
  Slot Result;
};
/// Compiles `Text` (added to C.SM as a buffer named `BufferName`, for
/// carets) as line number `Number` into `L`'s JIT; `Variables` are the
/// slots of the checker's variables, grown to match. std::nullopt after
/// reporting to C.Diags (an internal error to errs()).
std::optional<CompiledLine> compileLine(Compilation &C, LoadedBehavior &L,
                                        ReplChecker &Checker,
                                        llvm::StringRef Text,
                                        llvm::StringRef BufferName,
                                        unsigned Number,
                                        std::vector<Slot> &Variables);

} // namespace bsc

#endif
