//===- ModuleEmitter.h - what the whole behavior shares ---------*- C++ -*-===//
//
// ModuleEmitter: what the whole behavior shares while it is lowered (Clang's
// CodeGenModule), defined in CodeGen.cpp, CGTypes.cpp, CGNative.cpp,
// CGLayout.cpp, CGEntries.cpp and CGRepl.cpp; CodeGenImpl.h gives the
// overview of the generator.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_CODEGEN_MODULEEMITTER_H
#define BSC_LIB_CODEGEN_MODULEEMITTER_H

#include "DebugInfoEmitter.h"

namespace bsc {
namespace codegen {

/// What the whole behavior shares while it is being lowered.
class ModuleEmitter {
public:
  ModuleEmitter(const Behavior &B, llvm::Module &M, const CodeGenOptions &Opts,
                BehaviorLayout &Layout);

  /// Lays out types, declares and defines every function, the entries, the
  /// info struct and (optionally) `main`.
  void run();

  // Types -----------------------------------------------------------------

  /// The type of a value of `T` in a register (bool is i1).
  llvm::Type *getValueType(const Type *T);
  /// The type of a value of `T` in memory: frames, allocas (bool is i8).
  llvm::Type *getMemoryType(const Type *T);
  /// The value a local has before its declaration assigns it: 0, 0.0,
  /// false, "" (language.md: every local is initialised).
  llvm::Constant *getZeroValue(const Type *T);

  llvm::StructType *getStateType() const { return StateTy; }
  const FrameInfo &getFrame(const TaskDecl *T) const;
  /// Whether a task's parameter or local has a field in its frame: what a
  /// later call or a nested func reads (a local in scope at a yield,
  /// anything a nested func uses, class values, which live from the reset
  /// to the end), and with CodeGenOptions::Probes everything, which the
  /// debugger shows. The rest are the task function's allocas (locals) or
  /// arguments (parameters).
  bool keepsInFrame(const Decl *D) const;

  // Functions and constants -----------------------------------------------

  /// The internal function generated for a func or task.
  llvm::Function *getFunction(const CallableDecl *D) const;
  /// The C-ABI declaration of a native function (int/enum -> i32,
  /// bool -> i32 0/1, float -> float, string -> ptr).
  llvm::FunctionCallee getNative(const NativeFunction &NF);
  /// A private NUL-terminated constant; equal strings share one global.
  llvm::Constant *getString(llvm::StringRef S);
  /// `bs.string.eq(ptr a, ptr b) -> i1`: whether two strings have the same
  /// contents (a null pointer reads as ""), defined in this module on
  /// first use, so that the object needs no strcmp from a libc.
  llvm::Function *getStringEquals();
  /// The C ABI type of a native parameter or result (class values travel
  /// as pointers).
  llvm::Type *getNativeType(const NativeType &NT);
  /// The setter thunk of a field or property: void(T *self, wire(X) v).
  llvm::FunctionCallee getNativeSetter(const NativeFunction &NF);
  /// A life-cycle thunk of class `C`: void(T *) or void(T *dst, const T *src).
  llvm::FunctionCallee getLifeThunk(const NativeClass *C,
                                    llvm::StringRef Symbol, unsigned NumPtrs);
  /// With CodeGenOptions::Boundary, `Thunk` wrapped so that the JIT's
  /// recorder sees the call (bsc/JIT/Boundary.h), with FlightRecorder so
  /// that the robot's does (bscript/flight.h): `Name` for messages,
  /// `Flags` (BoundarySiteFlags), and the arguments the thunk may write
  /// through as (argument index, bytes); else `Thunk` itself.
  llvm::FunctionCallee
  wrapForBoundary(llvm::FunctionCallee Thunk, llvm::StringRef Name,
                  uint32_t Flags,
                  llvm::ArrayRef<std::pair<unsigned, uint64_t>> Writable);
  /// With CodeGenOptions::FlightRecorder, the table `bs_<Name>_flight`
  /// of the sites wrapForBoundary made (call it last); getFlightTable
  /// declares it for code emitted before.
  void emitFlightTable();
  llvm::GlobalVariable *getFlightTable();
  llvm::StructType *getFlightTableType();
  /// The model of `NF` (CodeGenOptions::Models), or null.
  const FuncDecl *getModel(const NativeFunction &NF) const {
    if (!Opts.Models)
      return nullptr;
    auto It = Opts.Models->find(&NF);
    return It == Opts.Models->end() ? nullptr : It->second;
  }
  /// `Module::f` or `Class::m`, and whether the module is a standard one.
  std::string getNativeName(const NativeFunction &NF, bool &Standard) const;
  /// The storage of a registered class value in frames and allocas: Size
  /// bytes with the class's alignment ([Size x i8] when Align is 1, else an
  /// array of Align-sized units whose ABI alignment is Align).
  llvm::Type *getClassMemoryType(const NativeClass *C);
  /// Constructs a value of `C` at `Addr` with `IRB`: zeroes its storage
  /// with explicit stores, then runs the construct thunk (if any).
  void emitClassInit(llvm::IRBuilderBase &IRB, const NativeClass *C,
                     llvm::Value *Addr);
  /// Whether a func returns a class value (through a hidden `ptr` result
  /// parameter after the state).
  static bool returnsClass(const CallableDecl &D);
  /// Whether values of `T` must be destroyed: a class whose destructor is
  /// not trivial (and that has the destroy thunk).
  static bool needsDestroy(const Type *T);
  static bool needsDestroy(const NativeClass *C);

  /// Attributes every generated function carries: nounwind (b-script has no
  /// exceptions) and "no-builtins" so that loop idioms and runs of stores
  /// never become calls of memset/memcpy (the object must not need libc).
  void addCommonAttributes(llvm::Function *F);

  const Behavior &getBehavior() const { return B; }
  const CodeGenOptions &getOptions() const { return Opts; }
  /// Filled in as far as emission has come: the state and frames first.
  const BehaviorLayout &getLayout() const { return Layout; }
  llvm::Module &getModule() { return M; }

  /// The fixed address of a REPL variable (emitReplLine), as a constant
  /// pointer; null for every other declaration.
  llvm::Value *getReplSlot(const Decl *D);
  /// emitReplLine: declares the behavior's functions and emits `Line`.
  void runReplLine(const FuncDecl &Line, llvm::StringRef Symbol,
                   const llvm::DenseMap<const Decl *, uint64_t> &Slots);

  // Alias information ------------------------------------------------------

  /// TBAA access tags of the kinds of memory generated code touches.
  /// The state (cycle, input/output pointers, task headers, scalar
  /// parameters and locals, REPL slots) and the scalar fields of registered
  /// C++ objects (`input`, `output` and class values) never overlap, so a
  /// store to `output.motion` does not force the next read of the output
  /// pointer or of a frame field to reload. Class values are copied and
  /// passed to C++ without a tag (they may alias anything). An
  /// instrumented behavior's trace record overlaps neither, so that
  /// writing it reloads nothing.
  enum class Access { State, Native, TraceRecord, Budget };
  llvm::MDNode *getAccessTag(Access A) const { return AccessTags[unsigned(A)]; }

  /// With CodeGenOptions::DebugInfo, the DWARF being built; else null.
  DebugInfoEmitter *getDebugInfo() { return DebugInfo.get(); }
  /// Whether a task's function returns the state it left (CGTask.cpp, "The
  /// result"): in optimised code without probes. At -O0 nothing would drop
  /// a result that no caller reads; the JIT's modules (probes) and the
  /// REPL's lines then agree on void whatever the -O level.
  bool tasksReturnStates() const { return Opts.OptLevel > 0 && !Opts.Probes; }
  /// Whether taskState(T) right after a call of T reads the call's result
  /// rather than T's frame: not on i386, where the load folds into the
  /// instruction that uses it and the result would tie up EAX
  /// (bench/README.md: wide +49 instructions per cycle).
  bool readsReturnedStates() const {
    return tasksReturnStates() &&
           llvm::Triple(M.getTargetTriple()).getArch() != llvm::Triple::x86;
  }
  /// With CodeGenOptions::Instrument: the field of %bs.state that holds
  /// the cycle's trace record.
  unsigned getTraceRecordField() const { return TraceRecordField; }

  // Cycle budgets (CodeGenOptions::CycleBudget, CGBudget.cpp) ---------------

  /// The words of bs_budget_record: cycle, used, ran_out, loop, loop_cycle.
  enum BudgetWord { BudgetCycle, BudgetUsed, BudgetRanOut, BudgetLoop,
                    BudgetLoopCycle, BudgetRecordWords };
  /// A pointer to a word of the state's budget record.
  llvm::Value *getBudgetWordPtr(llvm::IRBuilderBase &IRB, llvm::Value *State,
                                BudgetWord W);
  /// A load or store of a budget word (at getBudgetWordPtr's address),
  /// with the record's TBAA tag.
  llvm::LoadInst *loadBudgetWord(llvm::IRBuilderBase &IRB, llvm::Value *Addr,
                                 const llvm::Twine &Name = "");
  void storeBudgetWord(llvm::IRBuilderBase &IRB, llvm::Value *V,
                       llvm::Value *Addr);
  /// Adds a loop to the budget's loop table; returns its number (from 1).
  unsigned addBudgetLoop(const CallableDecl *Owner, llvm::SMLoc Loc);
  /// `bs.budget.ran_out(ptr state, i32 loop)`: records that the cycle ran
  /// out in `loop` unless another loop already did in this cycle.
  llvm::Function *getBudgetRanOut();
  /// At an entry: a new cycle (the header's cycle differs from the
  /// record's) starts with no pass used.
  void emitBudgetStart(llvm::IRBuilderBase &IRB, llvm::Value *State);
  /// bs_behavior_info.budget's initializer.
  llvm::Constant *getBudgetInfo(llvm::StructType *LayoutTy,
                                llvm::StructType *LoopTy);
  /// The field of %bs.state holding the tasks' narrow headers (FrameInfo),
  /// 0 if no task has one.
  unsigned getHeadersField() const { return HeadersField; }
  /// The offset of field `Field` of the frame of `T` from the start of
  /// the state.
  uint64_t getFrameFieldOffset(const TaskDecl *T, unsigned Field) const;
  /// The offset of the resume point or state of `T` from the start of the
  /// state.
  uint64_t getTaskWordOffset(const TaskDecl *T, TaskWord W) const;

  // Assertions (CodeGenOptions::Assertions, CGAssert.cpp) -------------------

  /// The index of `S` in Behavior::Assertions.
  unsigned getAssertionIndex(const AssertStmt *S);
  /// AssertionMode::Count: a pointer to the counter of assertion `Index`.
  llvm::Value *getAssertionCounterPtr(llvm::IRBuilderBase &IRB,
                                      llvm::Value *State, unsigned Index);
  /// AssertionMode::Report: the global a failing assertion's record is
  /// copied to (AssertRecordSymbol), defined on first use.
  llvm::GlobalVariable *getAssertRecord();
  /// bs_behavior_info.assertions' initializer.
  llvm::Constant *getAssertionInfo(llvm::StructType *LayoutTy,
                                   llvm::StructType *AssertionTy);

  // Coverage (CodeGenOptions::Coverage, CGCoverage.cpp) ---------------------

  /// Adds a counter; returns its index.
  unsigned addCoverageSite(CoverageSite Site);
  /// `counters[Index] += By` (By: an i64), at IRB's place.
  void emitCoverageAdd(llvm::IRBuilderBase &IRB, unsigned Index,
                       llvm::Value *By);
  /// After every function: the counters' global, sized for every site.
  void finishCoverage();

  // Debugging probes (CodeGenOptions::Probes) -------------------------------

  /// Records a site; returns its number (from 1).
  unsigned addSite(DebugSite Site);
  /// `bs.probe.loop` or `bs.probe.native`, defined on first use.
  llvm::GlobalVariable *getProbe(const char *Symbol);

  // Explaining conditions (CodeGenOptions::Explain, CGExplain.cpp) ---------

  /// Records a site; returns its number (from 1).
  unsigned addExplainSite(ExplainSite Site);
  /// `ptr bs.explain.begin(i32 site, i32 size)`: a record of the log with
  /// its site and an empty mask, or scratch room when the log is not
  /// active or full. Defined on first use, as is the log.
  llvm::Function *getExplainBegin();
  /// At an entry: a new cycle starts a new log, which takes records until
  /// emitExplainEntryEnd.
  void emitExplainEntryStart(llvm::IRBuilderBase &IRB, llvm::Value *State);
  void emitExplainEntryEnd(llvm::IRBuilderBase &IRB);
  llvm::LLVMContext &getContext() { return Ctx; }

private:
  /// Every func and task of the behavior, in source order.
  std::vector<const CallableDecl *> getSourceOrder() const;
  /// Builds `%bs.state` and the frame types and fills in the layout's
  /// sizes and offsets (CGLayout.cpp).
  void layoutState();
  /// The frame of `T`: its last call, the resume point and state if they
  /// take 4 bytes, the parameters and locals it keeps (scalar locals of
  /// disjoint scopes sharing a field), and `live` if it holds class values.
  void layoutFrame(const TaskDecl &T, FrameInfo &FI);
  /// With CodeGenOptions::Instrument: sizes the trace record and appends it
  /// to the state's fields, after the frames and headers.
  void addTraceRecord(llvm::SmallVectorImpl<llvm::Type *> &StateFields);
  /// Records the size and alignment of the finished state, the offsets of
  /// its records, and each task's frame, words and fields in the layout.
  void recordStateLayout();
  /// Internal, or external with CodeGenOptions::ExternalFunctions.
  llvm::GlobalValue::LinkageTypes getFunctionLinkage() const {
    return Opts.ExternalFunctions ? llvm::GlobalValue::ExternalLinkage
                                  : llvm::GlobalValue::InternalLinkage;
  }
  void declareFunctions();
  void emitEntries();
  /// `bs.<M>.<task>.destroy` of every frame with a LiveField, and the
  /// behavior's `bs.destroy` that calls them (bs_behavior_info.destroy).
  void emitDestroyFunctions();
  void emitInfo();
  /// bs_behavior_info.debug_tables: null, or with CodeGenOptions::
  /// Instrument the symbol defineDebugTables defines.
  llvm::Constant *getDebugTables();
  void emitProgramMain();
  /// `main`'s `input` and `output` objects of the world's classes (null
  /// where there is none): allocas before `AllocasBefore`, constructed at
  /// `IRB`.
  void constructWorldObjects(llvm::IRBuilderBase &IRB,
                             const NativeClass *const (&Classes)[2],
                             llvm::Instruction *AllocasBefore,
                             llvm::Value *(&Objects)[2]);
  /// Chooses the width and place of a task's resume point and state
  /// (bscript.h bs_task_info) and builds its narrow header type.
  void chooseTaskWords(const TaskDecl &T, FrameInfo &FI);
  /// Appends `%bs.headers`, the tasks' narrow headers, to the state's
  /// fields (none if no task has one).
  void addTaskHeaders(llvm::SmallVectorImpl<llvm::Type *> &StateFields);
  /// i386: internal functions called only directly use the regcall
  /// convention, whose calls do not set up the GOT pointer.
  void useRegisterCalls();

  const Behavior &B;
  llvm::Module &M;
  llvm::LLVMContext &Ctx;
  const CodeGenOptions &Opts;
  BehaviorLayout &Layout;

  llvm::StructType *StateTy = nullptr;
  unsigned TraceRecordField = 0;
  unsigned BudgetRecordField = 0;
  unsigned AssertionCountersField = 0;
  /// Coverage: where the counters are until finishCoverage sizes them.
  llvm::GlobalVariable *CoveragePlaceholder = nullptr;
  /// Behavior::Assertions' indices, built on first use.
  llvm::DenseMap<const AssertStmt *, unsigned> AssertionIndex;
  llvm::Function *BudgetRanOutFn = nullptr;
  unsigned HeadersField = 0;
  llvm::DenseMap<const TaskDecl *, FrameInfo> Frames;
  llvm::DenseMap<const CallableDecl *, llvm::Function *> Functions;
  llvm::DenseMap<const NativeFunction *, llvm::FunctionCallee> Natives;
  llvm::StringMap<llvm::Constant *> Strings;
  /// The sites of wrapForBoundary, by their index.
  std::vector<llvm::GlobalVariable *> BoundarySites;
  llvm::Function *StringEquals = nullptr;
  llvm::GlobalVariable *Info = nullptr;
  llvm::Function *BehaviorDestroy = nullptr; ///< Null: nothing to destroy.
  llvm::MDNode *AccessTags[4] = {};
  /// emitReplLine: the REPL's variables at their addresses.
  const llvm::DenseMap<const Decl *, uint64_t> *ReplSlots = nullptr;
  std::unique_ptr<DebugInfoEmitter> DebugInfo;
};

} // namespace codegen
} // namespace bsc

#endif
