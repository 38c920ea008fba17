//===- CodeGen.h - a checked behavior to LLVM IR ---------------*- C++ -*-===//
//
// Lowers a checked Behavior to one LLVM module for one target. The target
// matters already here: frames and the behavior state are laid out with the
// target's DataLayout, and their sizes are part of the object's interface
// (include/bscript/bscript.h).
//
// The contract this library keeps (the state and frame layout, the
// exported entries and `bs_<Behavior>_info`, runtime safety, no libc,
// class values and their lifetimes, standalone programs) is written down
// in docs/design/backend.md, with the IR it produces; the ABI robot code
// sees is include/bscript/bscript.h. The lowering of a task call is
// described where it is made, in CGTask.cpp.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_CODEGEN_CODEGEN_H
#define BSC_CODEGEN_CODEGEN_H

#include "bsc/Sema/Sema.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/IR/DataLayout.h"
#include "llvm/IR/LLVMContext.h"
#include "llvm/IR/Module.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/TargetParser/Triple.h"
#include <memory>
#include <optional>
#include <string>

namespace bsc {

struct CodeGenOptions {
  /// Prefix of every exported symbol (`bs_<Name>_info`, `bs_<Name>__M__f`).
  std::string BehaviorName;
  /// When set, also emit `int main(void)` that initialises a state on its
  /// stack and calls this entry once per cycle for `ProgramCycles` cycles
  /// (standalone programs and `bsc run`).
  const CallableDecl *ProgramEntry = nullptr;
  unsigned ProgramCycles = 1;
  /// Funcs and tasks (and frames' destroy functions) get external linkage
  /// under their internal names (`bs.M.f`), so that the REPL's lines,
  /// compiled later into the same JIT (emitReplLine), can call them.
  /// Results do not change; only the REPL sets it.
  bool ExternalFunctions = false;
  /// Debugging probes for the JIT (docs/repl.md): each loop's head stores
  /// its site number into the i32 global `bs.probe.loop`, and each call of
  /// registered C++ stores its site into `bs.probe.native` before the call
  /// and 0 after it, so that a watchdog or a crash handler can name the
  /// loop that ran away or the binding that crashed. Values computed do
  /// not change; robot objects never have probes (no mutable globals).
  bool Probes = false;
  /// Explaining conditions for the REPL's `:why` (CGExplain.cpp), JIT only
  /// like Probes: every `if` and `for` condition appends a record to the
  /// log `bs.explain.log` (ExplainLogHeader) with its site
  /// (BehaviorLayout::ExplainSites), its value and the values of its
  /// operands that ran (short-circuiting skips some), and every task call
  /// records its start and the state and resume point it left. The entry
  /// starts a new log in each cycle. Values computed do not change; robot
  /// objects never have it. Needs `Sources` (the sites' lines).
  bool Explain = false;
  /// `--instrument`: every way out of a task call writes the task's slot of
  /// the trace record, which follows the frames in the state
  /// (BehaviorLayout::Trace, bscript.h "Trace records"), and
  /// bs_behavior_info.debug_tables points to the static tables of the
  /// debugger (task names, yield lines and values, frame fields, the call
  /// graph, the record's layout; bsc/Debug/Trace.h) as JSON, in the section
  /// DebugTablesSection, so that a robot's trace log can be decoded offline.
  bool Instrument = false;
  /// `--cycle-budget=N` (bscript.h "Cycle budgets"): every pass of a loop,
  /// at its jump back to the head, costs one of N per cycle; when none is
  /// left the loop fails its task (or returns its func's zero) and the
  /// record after the frames (BehaviorLayout::Budget) names it. Each entry
  /// starts the budget of a new cycle. 0: no budget, and no code for it.
  uint32_t CycleBudget = 0;
  /// Floats on the x87 unit (usesX87Floats): every float that an operation
  /// computes (arithmetic, conversion from int, a result of registered C++)
  /// goes through a float in memory before it is used, so that it has a
  /// float's precision and range, as on every other target
  /// (docs/language.md, "Floats").
  bool NarrowX87Floats = false;
  /// `-g`: DWARF for the behavior (lib/CodeGen/CGDebugInfo.cpp): a line
  /// table, a subprogram per func and task, their parameters and locals
  /// (frame fields included) with b-script types, registered classes with
  /// their C++ layouts. `Sources` maps the AST's locations to lines; it
  /// must be set with DebugInfo (and Explain). At -O1 and above the code generated does
  /// not change; at -O0 the state pointer and task parameters that are
  /// only arguments are also stored on the stack, where the debugger reads
  /// them all along.
  bool DebugInfo = false;
  const llvm::SourceMgr *Sources = nullptr;
  /// The -O level the module will be optimised at. Only the debug
  /// information depends on it: how a frame variable's place is described
  /// (CGDebugInfo.cpp) and whether the unit says it is optimised.
  unsigned OptLevel = 0;
  /// The top-level funcs and tasks exported as entries (`bs_<Name>__M__f`),
  /// each callable from C (isCallableFromC). Everything else is internal,
  /// so the optimiser may inline it into its callers. Unset: the behavior's
  /// roots (findBehaviorRoots).
  std::optional<std::vector<const CallableDecl *>> Exports;
};

/// The section holding the debug tables of an instrumented object.
inline constexpr const char *DebugTablesSection = ".bs_debug_tables";

/// A place in the behavior a probe names (BehaviorLayout::Sites).
struct DebugSite {
  enum SiteKind { Loop, NativeCall };
  SiteKind Kind;
  const CallableDecl *In; ///< The func or task whose body holds it.
  llvm::SMLoc Loc;        ///< The `for`, or the statement making the call.
  std::string Native;     ///< NativeCall: the registered C++ (`Math::fabs`).
  /// NativeCall: it takes the context (bs::Context&), so a crash in it may
  /// come from a null user pointer.
  bool TakesContext = false;
};

/// The probe globals of CodeGenOptions::Probes.
inline constexpr const char *LoopProbeSymbol = "bs.probe.loop";
inline constexpr const char *NativeProbeSymbol = "bs.probe.native";

/// A condition CodeGenOptions::Explain records (or a task call's start or
/// end), numbered from 1 in BehaviorLayout::ExplainSites. The table says
/// how to read a record of the log: the record starts with the site
/// number (uint32), 4 unused bytes and a uint64 mask whose bit k says that
/// operand k ran and its value is at Operands[k].Offset.
struct ExplainSite {
  enum SiteKind {
    If,        ///< `if(cond)`, `else if(cond)`.
    For,       ///< `for(...; cond; ...)`, at each evaluation.
    TaskStart, ///< A call of task In begins; no operands.
    TaskEnd,   ///< It returns: its state and resume point (ExplainTaskEnd*).
  };
  SiteKind Kind;
  const CallableDecl *In; ///< The func or task whose body holds it.
  llvm::SMLoc Loc;        ///< The statement (the task for the markers).
  std::string File;       ///< Without folders.
  unsigned Line = 0;
  /// A sub-expression whose value a record may hold: the condition itself
  /// (operand 0), then the others in source order, each with the operand
  /// that encloses it. Literals, constants and implicit conversions are
  /// left out (their values are in the text), as are strings and class
  /// values that cannot be copied as bytes or are larger than
  /// MaxExplainedClassSize.
  struct Operand {
    const Expr *E;
    std::string Text; ///< As b-script (`input.ball.position.abs()`).
    const Type *Ty;
    int Parent = -1;     ///< Index of the operand that encloses it; -1: none.
    uint32_t Offset = 0; ///< Of its value in the record, stored as a
                         ///< variable stores it (bool: one byte).
  };
  std::vector<Operand> Operands;
  uint32_t RecordSize = 0; ///< A multiple of 8.
};

/// The log of CodeGenOptions::Explain: this header, then the records back
/// to back (ExplainSite); a record that does not fit is not written and
/// counts in Overflow. Only calls of the entry are logged (Active): a
/// REPL line's or a watch's calls are not.
struct ExplainLogHeader {
  uint32_t Cycle;    ///< The state's cycle the records are of.
  uint32_t Active;   ///< 1 while the entry runs.
  uint32_t Used;     ///< Bytes of records.
  uint32_t Overflow; ///< Records that did not fit.
};
inline constexpr const char *ExplainLogSymbol = "bs.explain.log";
/// Room for the records of one cycle: some 10,000 conditions. A loop that
/// runs longer fills it; the rest of the cycle is only counted.
inline constexpr uint32_t ExplainLogCapacity = 256 * 1024;
/// The bytes before a record's operands: site, unused, mask.
inline constexpr uint32_t ExplainRecordHeaderSize = 16;
/// A mask has 64 bits: operands past them are not recorded.
inline constexpr unsigned MaxExplainOperands = 64;
/// Class values larger than this are not copied into records (a Vector2f
/// is 8 bytes, a pose 12).
inline constexpr uint32_t MaxExplainedClassSize = 16;
/// A TaskEnd record: the task's state (int32) and resume point (uint32).
inline constexpr uint32_t ExplainTaskEndState = ExplainRecordHeaderSize;
inline constexpr uint32_t ExplainTaskEndResume = ExplainRecordHeaderSize + 4;

/// Where things ended up; what --emit-header and the JIT need.
struct BehaviorLayout {
  uint64_t StateSize = 0;
  uint64_t StateAlign = 1;
  /// A parameter or local a task keeps in its frame.
  struct FrameField {
    const Decl *D; ///< ParamDecl or VarDecl.
    const Type *Ty;
    uint64_t Offset; ///< From the start of the state.
  };
  /// A task's resume point or state (bscript.h bs_task_info).
  struct TaskWord {
    uint64_t Offset; ///< From the start of the state.
    unsigned Bytes;  ///< 1, 2 or 4.
  };
  struct Task {
    const TaskDecl *Decl;
    /// Of its frame, which starts with its last call (uint32).
    uint64_t FrameOffset;
    uint64_t FrameSize; ///< Of its frame struct, without padding after it.
    TaskWord Resume, State;
    /// Parameters in order, then locals in declaration order.
    std::vector<FrameField> Fields;
    /// The task's yields leave it running (1) or end it with a constant
    /// state <= 0, so its code takes a state > 0 to be 1: a frame may only
    /// be carried into such a task (the REPL's :reload) from one that is
    /// too.
    bool OnlyRunningStates = false;
    /// The state the k-th yield leaves when it is a constant (`yield`,
    /// `yield TaskState::failure`); none for a value computed at run time.
    std::vector<std::optional<int32_t>> YieldValues;
  };
  std::vector<Task> Tasks;
  struct Entry {
    const CallableDecl *Decl;
    std::string Symbol;
  };
  /// The exported entries (CodeGenOptions::Exports), in that order.
  std::vector<Entry> Entries;
  std::string InfoSymbol; ///< `bs_<Name>_info`.
  /// With CodeGenOptions::Probes: the sites, numbered from 1 (0 in a probe
  /// global means "none").
  std::vector<DebugSite> Sites;
  /// With CodeGenOptions::Explain: the sites of the log's records,
  /// numbered from 1.
  std::vector<ExplainSite> ExplainSites;
  /// With CodeGenOptions::Instrument: the declared symbol of the tables.
  std::string DebugTablesSymbol;
  /// With CodeGenOptions::Instrument: the trace record every task call
  /// writes (bscript.h, "Trace records"); RecordSize 0 otherwise.
  struct TraceLayout {
    uint64_t RecordSize = 0;
    uint64_t ClearSize = 0; ///< The slots, rounded up to 4 bytes.
    unsigned SlotBytes = 1;
    uint64_t Offset = 0; ///< Of the record inside the state.
    /// Per task (Tasks order), the offset in the record of the word that
    /// holds a state computed at run time, if it yields one.
    std::vector<std::optional<uint64_t>> StateWords;
    uint32_t finishedSlot() const { return getFinishedSlot(SlotBytes); }
    /// The slot value of a call that failed because its cycle ran out of
    /// budget (CodeGenOptions::CycleBudget): one below finished.
    uint32_t budgetFailedSlot() const { return finishedSlot() - 1; }
    /// With a cycle budget: the word, cleared with the slots, that holds 1
    /// + the loop that ran out of budget in the cycle (0: none).
    std::optional<uint64_t> BudgetWord;
    /// The slot value of a call that finished its task: all ones.
    static uint32_t getFinishedSlot(unsigned SlotBytes) {
      return uint32_t(~0ull >> (64 - 8 * SlotBytes));
    }
  };
  TraceLayout Trace;
  /// With CodeGenOptions::CycleBudget (bscript.h bs_budget_layout).
  struct BudgetLayout {
    uint32_t Budget = 0; ///< 0: none.
    uint64_t Offset = 0; ///< Of the bs_budget_record in the state.
    /// The loops the budget counts (all but the tasks' loops that yield on
    /// every way round), in the order the code was emitted (source order):
    /// loop k is bs_budget_record.loop k + 1.
    struct Loop {
      const CallableDecl *Owner;
      llvm::SMLoc Loc; ///< Of its `for`.
    };
    std::vector<Loop> Loops;
  };
  BudgetLayout Budget;
};

/// Defines the debug tables an instrumented module declares
/// (BehaviorLayout::DebugTablesSymbol) as the NUL-terminated `JSON`. Call
/// it after emitLLVM and before optimising.
void defineDebugTables(llvm::Module &M, const BehaviorLayout &Layout,
                       llvm::StringRef JSON);

/// Builds the IR of a REPL line (ReplChecker::Line::Func) as
/// `void @<Symbol>(ptr state)` in a module of its own that only declares the
/// behavior's funcs and tasks: it runs in the JIT that holds the behavior,
/// compiled with CodeGenOptions::ExternalFunctions. `Slots` gives the
/// addresses of the REPL's variables (the line's result among them), which
/// live in the REPL rather than on the stack and are not destroyed by the
/// line. The line has probes like the behavior (CodeGenOptions::Probes,
/// which the behavior's module must have had); its sites are appended to
/// `Sites`, the behavior's (BehaviorLayout::Sites) and earlier lines'.
std::unique_ptr<llvm::Module>
emitReplLine(const Behavior &B, const FuncDecl &Line, llvm::StringRef Symbol,
             llvm::LLVMContext &Ctx, const llvm::Triple &Triple,
             const llvm::DataLayout &DL,
             const llvm::DenseMap<const Decl *, uint64_t> &Slots,
             std::vector<DebugSite> &Sites);

/// Builds the IR of `B` for `Triple`/`DL`. Never fails on a behavior that
/// Sema accepted.
std::unique_ptr<llvm::Module> emitLLVM(const Behavior &B, llvm::LLVMContext &Ctx,
                                       const llvm::Triple &Triple,
                                       const llvm::DataLayout &DL,
                                       const CodeGenOptions &Opts,
                                       BehaviorLayout &Layout);

/// `bs_<Behavior>__<Module>__<name>`.
std::string getEntrySymbol(llvm::StringRef BehaviorName, const CallableDecl &D);

} // namespace bsc

#endif
