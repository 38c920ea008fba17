//===- Layout.h - where a compiled behavior keeps things --------*- C++ -*-===//
//
// What code generation decides and the tools around it read: the state's
// and frames' layout (BehaviorLayout), the probes' sites, the conditions
// `:why` logs and the log's format, the section of the debug tables. Only
// data, no code, beside the AST it points into (and the checked Behavior,
// AST/Behavior.h): lib/Debug, lib/Timeline and the REPL read it without
// linking the code generator and its LLVM back ends.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_AST_LAYOUT_H
#define BSC_AST_LAYOUT_H

#include "bsc/AST/AST.h"
#include "llvm/Support/SMLoc.h"
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bsc {

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
    Assert,    ///< `assert(cond)`: never in the log; a failure's record is
               ///< copied to AssertRecordSymbol (AssertionMode::Report).
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

/// What `assert` compiles to (bscript.h "Assertions").
enum class AssertionMode {
  None,  ///< Nothing: the condition is not evaluated (objects by default).
  Count, ///< A failure adds one to its counter in the state.
  Trap,  ///< A failure executes a trap instruction.
  /// The JIT's (with probes): a failure copies its condition's record
  /// (an ExplainSite of kind Assert) to AssertRecordSymbol and traps, so
  /// that the session's guard ends the cycle and the driver reports the
  /// assertion with the values of its operands.
  Report,
  /// `bsc verify`'s: each assertion and assumption is a call of
  /// VerifyCheckSymbol (its condition, its index in Behavior::Assertions,
  /// whether it is an assumption), which the verifier reads; no branch.
  Verify,
};
/// AssertionMode::Verify: `void (i1 holds, i32 index, i1 assume)`.
inline constexpr const char *VerifyCheckSymbol = "bs.verify.check";
/// AssertionMode::Report: the record of the assertion that failed.
inline constexpr const char *AssertRecordSymbol = "bs.assert.record";
/// Its room: a header and 64 operands of the largest size.
inline constexpr uint32_t AssertRecordCapacity =
    ExplainRecordHeaderSize + MaxExplainOperands * MaxExplainedClassSize;

/// A counter of CodeGenOptions::Coverage: counter k of the global
/// CoverageCountersSymbol counts what BehaviorLayout::CoverageSites[k] says.
struct CoverageSite {
  enum SiteKind {
    Call,  ///< Calls of Owner (N is Owner).
    Stmt,  ///< Runs of statement N (a `yield` counts when it is reached).
    True,  ///< An `if` or `for` (N) whose condition held...
    False, ///< ...or did not; the two are adjacent.
  };
  SiteKind Kind;
  const Node *N;
  const CallableDecl *Owner; ///< The func or task whose code holds it.
};
inline constexpr const char *CoverageCountersSymbol = "bs.coverage.counters";

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
  /// With CodeGenOptions::FlightRecorder: `bs_<Name>_flight`, the table of
  /// bscript/flight.h; empty otherwise.
  std::string FlightTableSymbol;
  /// With CodeGenOptions::Probes: the sites, numbered from 1 (0 in a probe
  /// global means "none").
  std::vector<DebugSite> Sites;
  /// With CodeGenOptions::Explain: the sites of the log's records,
  /// numbered from 1.
  std::vector<ExplainSite> ExplainSites;
  /// With CodeGenOptions::Coverage: what each counter counts.
  std::vector<CoverageSite> CoverageSites;
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
  /// CodeGenOptions::Assertions (bscript.h bs_assertion_layout); the
  /// assertions are Behavior::Assertions.
  struct AssertionLayout {
    AssertionMode Mode = AssertionMode::None;
    uint64_t Offset = 0; ///< Count: of the uint32 counters in the state.
  };
  AssertionLayout Assertions;
  /// Every thunk of registered C++ the code calls (functions, methods,
  /// setters, life cycles), by its symbol: what the JIT's recorder calls
  /// it and what it may write (CodeGenOptions::Boundary; bsc/JIT/
  /// Boundary.h), for `bsc verify`'s counterexamples.
  struct NativeCall {
    std::string Name;   ///< `Math::abs`, `Math::Vector2f (construct)`.
    uint32_t Flags = 0; ///< BoundarySiteFlags.
    bool Pure = false;  ///< Registered `.pure()`: never recorded.
    /// A field's or property's getter: what it reads is its object, so
    /// `bsc verify` takes the same bytes to give the same value.
    bool Getter = false;
    /// The pointer arguments it may write (a class result's storage, a
    /// non-const method's object, `T&`) and those it reads (the object of
    /// a method, class arguments), as (thunk argument, bytes).
    std::vector<std::pair<unsigned, uint64_t>> Writes, Reads;
  };
  std::map<std::string, NativeCall> NativeCalls;
};

} // namespace bsc

#endif
