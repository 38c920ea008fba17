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

#include "bsc/AST/Layout.h"
#include "bsc/Sema/Sema.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/IR/DataLayout.h"
#include "llvm/IR/LLVMContext.h"
#include "llvm/IR/Module.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/TargetParser/Triple.h"
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace bsc {

/// The flags of a boundary wrapper's site (CodeGenOptions::Boundary), as
/// generated code hands them to the JIT's recorder (bsc/JIT/Boundary.h).
enum BoundarySiteFlags : uint32_t {
  SiteNoFlags = 0,
  /// The result is a `const char *` whose characters are kept, not the
  /// pointer (a re-run gets a pointer to the kept copy).
  SiteResultIsString = 1,
  /// A thunk of the standard `io` module, which only prints: what it prints
  /// is the behavior's own output, not captured with the C++'s
  /// (`--world-output`), and it returns and writes nothing, so it is not
  /// kept; a replay calls it or not (Boundary::setReplayCallsStandard).
  SiteStandard = 2,
  /// A call the session makes itself (the world's end hook): kept only if
  /// it wrote something, so a world that only reads costs nothing.
  SitePseudo = 4,
};

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
  /// The boundary to registered C++ for the JIT's records (bsc/JIT/
  /// Boundary.h): every call of a thunk that is not registered `pure`
  /// goes through a wrapper that reports it to bs_boundary_enter and
  /// bs_boundary_leave, so that the REPL's time travel and exact replays
  /// take its effects from a record instead of calling the C++ again.
  /// Values computed do not change; robot objects never have it.
  bool Boundary = false;
  /// `--flight-recorder` (bscript/flight.h), objects for the robot: every
  /// call of a thunk that is not registered `pure` goes through a wrapper
  /// that tells the robot's flight recorder of it (bs_flight_enter and
  /// bs_flight_leave of the runtime, which log its result and effects), and
  /// the object exports the table `bs_<Name>_flight` (bs_flight_table)
  /// that names the call sites, the entries' behavior hashes and the
  /// layout of `input` and `output`. Values computed do not change;
  /// without it the code is what it was, byte for byte.
  bool FlightRecorder = false;
  /// With FlightRecorder: each exported entry's qualified name and the
  /// hash a log of it carries (computeBehaviorHash).
  std::vector<std::pair<std::string, std::string>> FlightEntries;
  /// Explaining conditions for the REPL's `:why` (CGExplain.cpp), JIT only
  /// like Probes: every `if` and `for` condition appends a record to the
  /// log `bs.explain.log` (ExplainLogHeader) with its site
  /// (BehaviorLayout::ExplainSites), its value and the values of its
  /// operands that ran (short-circuiting skips some), and every task call
  /// records its start and the state and resume point it left. The entry
  /// starts a new log in each cycle. Values computed do not change; robot
  /// objects never have it. Needs `Sources` (the sites' lines).
  bool Explain = false;
  /// Behavior coverage (CGCoverage.cpp), JIT only like Probes: a 64-bit
  /// counter per func and task call, per statement run and per way each
  /// `if` and `for` condition went, in the global `bs.coverage.counters`
  /// (BehaviorLayout::CoverageSites says which is which). Values computed
  /// do not change.
  bool Coverage = false;
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
  /// `--assertions=`: what `assert` compiles to (AssertionMode, CGAssert.cpp).
  AssertionMode Assertions = AssertionMode::None;
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
  /// `bsc verify --model`: a call of registered C++ that has a model (a
  /// func of the behavior, checked by lib/Verify to take and return what
  /// the C++ does) calls the model instead, except in the model itself.
  const std::map<const NativeFunction *, const FuncDecl *> *Models = nullptr;
  /// The top-level funcs and tasks exported as entries (`bs_<Name>__M__f`),
  /// each callable from C (isCallableFromC). Everything else is internal,
  /// so the optimiser may inline it into its callers. Unset: the behavior's
  /// roots (findBehaviorRoots).
  std::optional<std::vector<const CallableDecl *>> Exports;
};


/// Defines the debug tables an instrumented module declares
/// (BehaviorLayout::DebugTablesSymbol) as the NUL-terminated `JSON`. Call
/// it after emitLLVM and before optimising.
void defineDebugTables(llvm::Module &M, const BehaviorLayout &Layout,
                       llvm::StringRef JSON);

/// A sub-expression whose value says something (what `:why` shows of a
/// condition, CGExplain.cpp): its text as b-script, and its enclosing
/// part (-1 for none).
struct ExpressionPart {
  const Expr *E;
  std::string Text;
  int Parent;
};
/// `E` (if it is such a part) and its parts, in the order they run.
std::vector<ExpressionPart> listExpressionParts(const Expr &E);

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

/// 16 hex digits that change with the layout of the world's `input` and
/// `output` classes on the compilation's target (sizes, alignments, each
/// field's offset and storage): a log's bytes are this workstation's
/// bytes when the hashes of the two targets agree (docs/repl.md "The
/// robot's log").
std::string getIOLayoutHash(const Behavior &B);

/// The symbols `M` declares but does not define: what its object imports
/// (the binding objects' thunks and descriptors among them).
std::vector<std::string> getUndefinedSymbols(const llvm::Module &M);

/// `bs_<Behavior>__<Module>__<name>`.
std::string getEntrySymbol(llvm::StringRef BehaviorName, const CallableDecl &D);

} // namespace bsc

#endif
