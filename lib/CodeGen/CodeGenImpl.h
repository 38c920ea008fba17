//===- CodeGenImpl.h - what the IR generator's classes share ----*- C++ -*-===//
//
// The state's fields, task words, frames and yield plans that the
// generator's classes share, each class in a header of its own (as Clang
// keeps CodeGenModule, CodeGenFunction and CGDebugInfo):
// ModuleEmitter.h, FunctionEmitter.h, DebugInfoEmitter.h.
//
// Two levels, as in Clang's CodeGenModule/CodeGenFunction:
// - ModuleEmitter owns what is shared by the whole behavior: the state and
//   frame struct types (laid out with the target's DataLayout), the LLVM
//   function of every func and task, native declarations, string constants.
//   Its parts are CodeGen.cpp (run), CGTypes.cpp (types), CGNative.cpp
//   (thunks and strings), CGLayout.cpp (the state and frames),
//   CGEntries.cpp (declarations, entries, the info table, `main`) and
//   CGRepl.cpp (REPL lines).
// - FunctionEmitter lowers one func or task body. Statements are in
//   CGStmt.cpp, expressions in CGExpr.cpp, and everything that exists only
//   because a task is a generator (prologue, reset check, resume switch,
//   yields, task states) in CGTask.cpp. DWARF for -g (DebugInfoEmitter) is
//   in CGDebugInfo.cpp.
//
// Storage of values (docs/design/backend.md):
// - A task's parameters and locals live in its frame inside the behavior
//   state, so they survive a `yield` and nested funcs reach them through
//   the `ptr %state` every generated function receives. No SSA value is
//   live across a yield: the resume switch may jump into the middle of any
//   loop, and only memory connects the code before and after a yield.
// - A func's parameters and locals live in allocas (SROA/mem2reg turn them
//   into registers at -O1 and above).
// - bool is i1 in registers and i8 in memory, as in Clang.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_CODEGEN_CODEGENIMPL_H
#define BSC_LIB_CODEGEN_CODEGENIMPL_H

#include "bsc/CodeGen/CodeGen.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/IR/DIBuilder.h"
#include "llvm/IR/IRBuilder.h"

namespace bsc {
namespace codegen {

/// Field numbers of `%bs.state` (bs_state_header in bscript.h); the frame
/// of task i is field FirstFrameField + i, the tasks' narrow headers
/// follow the frames (ModuleEmitter::getHeadersField).
enum StateField : unsigned {
  StateCycle = 0,
  StateInput = 1,
  StateOutput = 2,
  StateUser = 3,
  FirstFrameField = 4,
};

/// The name (in IR and DWARF) of the state pointer every generated function
/// takes first. Reserved (`__`) so that no script parameter or local named
/// `state` shadows it in a debugger: `print __bs_state->M.task` works in
/// every frame (docs/repl.md, "gdb: -g").
constexpr llvm::StringLiteral StateParamName = "__bs_state";

/// A frame (`%bs.frame.*`) starts with the task's last call; its resume
/// point and state follow when they take 4 bytes (TaskWordInfo), then the
/// parameters and locals.
constexpr unsigned FrameLastCall = 0;

/// Values of a task's state (bscript.h BS_TASK_*).
constexpr int32_t TaskDone = 0;
constexpr int32_t TaskRunning = 1;
constexpr int32_t TaskFailure = -1;
/// The bit of a task's last call that marks a call that ended the task
/// (bscript.h BS_LAST_CALL_ENDED).
constexpr uint32_t LastCallEnded = 0x80000000u;

/// The two words of a task header that may be narrow (bscript.h
/// bs_task_info): the resume point and the state.
enum class TaskWord { Resume, State };

/// Where one of them lives: a 4-byte field of the frame, or a field of the
/// task's narrow header (`%bs.header.*`) in the state's header area.
struct TaskWordInfo {
  llvm::IntegerType *Ty = nullptr; ///< i8, i16 or i32.
  bool InFrame = true;
  unsigned Field = 0; ///< Of the frame, or of the narrow header.
};

/// Where a task's frame sits in the state and how its fields are numbered.
struct FrameInfo {
  llvm::StructType *Ty = nullptr;
  unsigned StateFieldNo = 0; ///< Field of %bs.state holding this frame.
  unsigned TaskIndex = 0;    ///< In the task table (B.Tasks order).
  TaskWordInfo Resume, State;
  /// The task's narrow header (its narrow words) and its field in the
  /// state's header area; null if both words are in the frame.
  llvm::StructType *HeaderTy = nullptr;
  unsigned HeaderFieldNo = 0;
  /// ParamDecl or VarDecl of the task -> field of the frame struct.
  llvm::DenseMap<const Decl *, unsigned> Fields;
  /// Per field, the name its address gets in the IR (`fib.b`).
  llvm::SmallVector<std::string, 8> FieldNames;
  /// Frames holding class values with a destructor: the trailing `i8 live`
  /// field (1 while the values are constructed; a zeroed state has 0) and
  /// `bs.<M>.<task>.destroy`. Otherwise 0 and null.
  unsigned LiveField = 0;
  llvm::Function *Destroy = nullptr;

  const TaskWordInfo &getWord(TaskWord W) const {
    return W == TaskWord::Resume ? Resume : State;
  }
};

/// What the task's yields store (CGTask.cpp, "Which stores").
struct YieldPlan {
  /// Every yield leaves the state running (1) or ends the task (a
  /// constant <= 0): the reset stores running, running yields do not.
  bool OnlyRunning = true;
  /// The resume point of the one yield that leaves the task running,
  /// if it has exactly one: the reset stores it, that yield does not.
  unsigned SingleResume = 0;
  /// Some yield's value is known only at run time (`yield acc + 1`): an
  /// instrumented task writes it into its trace record's state word.
  bool ComputedStates = false;
};
YieldPlan planYields(const TaskDecl &T);
/// The task state a yield's value always has, if it is a constant: none
/// (running), an int literal, `-` one, a named state
/// (`TaskState::failure`) or a module constant.
std::optional<int64_t> getConstantState(const Expr *Value);

} // namespace codegen
} // namespace bsc

#endif
