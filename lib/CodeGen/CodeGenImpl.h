//===- CodeGenImpl.h - private interface of the IR generator ---*- C++ -*-===//
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

class ModuleEmitter;

/// The DWARF of `-g` (CodeGenOptions::DebugInfo), as Clang's CGDebugInfo:
/// one compile unit per behavior, a namespace per module (so gdb's
/// `break Motion::walk` works: the CU's language is C++), a subprogram per
/// func and task and for the generated glue, b-script types as DWARF base,
/// enumeration and structure types. Where a variable lives decides how it
/// is described: an alloca by itself; a frame field as the `state`
/// argument plus the field's offset (DW_OP_plus_uconst), which holds
/// wherever the function runs, also after a resume.
class DebugInfoEmitter {
public:
  DebugInfoEmitter(ModuleEmitter &CGM, const llvm::SourceMgr &SM);

  /// The subprogram of the function of a func or task.
  llvm::DISubprogram *createFunction(const CallableDecl &D,
                                     llvm::Function &Fn);
  /// An artificial subprogram for generated glue (entries, `main`, destroy
  /// functions) whose code is attributed to line `Loc` (invalid: line 0).
  /// Every instruction gets that location, so that the calls into the
  /// b-script functions inlined there have one (the verifier insists).
  void createGlueFunction(llvm::Function &Fn, llvm::SMLoc Loc);
  /// Line and column of `Loc` in `Scope`.
  llvm::DILocation *getLocation(llvm::SMLoc Loc, llvm::DIScope *Scope);
  /// A lexical block (a block statement, a `for` head) at `Loc`.
  llvm::DILexicalBlock *createBlock(llvm::DIScope *Parent, llvm::SMLoc Loc);
  /// Describes parameter or local `D` of type `Ty` in `Scope`, which lives
  /// in the alloca `Slot`. `ArgNo`: 0 for locals, else the DWARF argument
  /// number. The dbg.declare goes before `Before`.
  void declareVariable(const Decl &D, const Type *Ty, llvm::DIScope *Scope,
                       llvm::AllocaInst *Slot, unsigned ArgNo,
                       llvm::Instruction *Before);
  /// The same for a task's parameter or local kept in its frame, `Offset`
  /// bytes into the state. Unoptimised code reads the state pointer from
  /// its stack slot `StateSlot` (alive all along); optimised code has it
  /// in `State`, the argument, whose value LLVM tracks through registers.
  void declareFrameVariable(const Decl &D, const Type *Ty,
                            llvm::DIScope *Scope, llvm::Value *State,
                            llvm::AllocaInst *StateSlot, uint64_t Offset,
                            unsigned ArgNo, llvm::Instruction *Before);
  /// Describes the `state` argument, spilled to `Slot`: argument 1, of
  /// type `struct bs_state *` (the header and every frame), so that
  /// `print *state` shows the whole behavior.
  void declareState(llvm::DISubprogram *SP, llvm::Value *Slot,
                    llvm::Instruction *Before);
  /// Completes the types and subprograms.
  void finalize();

private:
  llvm::DIFile *getFile(llvm::SMLoc Loc);
  /// Line and column of `Loc`; 0, 0 where it has none.
  std::pair<unsigned, unsigned> getLineAndColumn(llvm::SMLoc Loc);
  unsigned getLine(llvm::SMLoc Loc);
  llvm::DINamespace *getNamespace(llvm::StringRef Name,
                                  llvm::DIScope *Parent = nullptr);
  llvm::DIType *getType(const Type *T);
  /// A registered C++ field's type as C++ declares it (short, double,
  /// float[3][3], ...), and one element of it.
  llvm::DIType *getNativeType(const NativeType &NT);
  llvm::DIType *getNativeElementType(const NativeType &NT);
  llvm::DIType *getBasicType(llvm::StringRef Name, uint64_t Bits,
                             unsigned Encoding);
  llvm::DIType *getEnumType(const NativeEnum *E);
  /// TaskState of 32 bits (values, frames) or 8 (a narrow task state,
  /// bscript.h bs_task_info): the same enumeration by name.
  llvm::DIType *getTaskStateType(unsigned Bits = 32);
  llvm::DIType *getClassType(const NativeClass *C);
  /// A property's value as its getter thunk returns it (bindings.md, "wire"):
  /// integers as 32 bits, floats as float; null for a class (returned
  /// through an out pointer) or void.
  llvm::DIType *getWireType(const NativeType &NT);
  /// The properties of class `C`, whose DWARF is `Struct`: a member function
  /// per scalar property whose linkage name is its getter thunk (`print
  /// v.x()`), and the union `__bs_properties` that lists every property for
  /// the pretty-printer (tools/gdb/bscript_printers.py); appended to
  /// `Members`.
  void addProperties(const NativeClass *C, llvm::DICompositeType *Struct,
                     llvm::SmallVectorImpl<llvm::Metadata *> &Members);
  llvm::DIType *getStringType();
  llvm::DIType *getStatePointerType();
  /// A member of `Scope` of `Bits` bits at byte `Offset`.
  llvm::DIDerivedType *createMember(llvm::DIScope *Scope, llvm::StringRef Name,
                                    uint64_t Bits, uint64_t Offset,
                                    llvm::DIType *Ty);
  /// The state's member for the frames of the tasks [Begin, End) of the
  /// layout, one module's.
  llvm::DIDerivedType *createModuleFramesMember(llvm::DICompositeType *State,
                                                size_t Begin, size_t End);
  /// A task's frame: its own words and the fields it keeps.
  llvm::DICompositeType *createFrameType(llvm::DIScope *ModStruct,
                                         const BehaviorLayout::Task &Task);
  /// The state's member `headers`: per task with a narrow resume point or
  /// state (bscript.h bs_task_info), a structure of them; null if none.
  llvm::DIDerivedType *createTaskHeadersMember(llvm::DICompositeType *State);
  llvm::DISubroutineType *getSubroutineType(const CallableDecl &D);
  llvm::DILocalVariable *createVariable(const Decl &D, const Type *Ty,
                                        llvm::DIScope *Scope, unsigned ArgNo);

  ModuleEmitter &CGM;
  const llvm::SourceMgr &SM;
  llvm::DIBuilder DIB;
  llvm::DICompileUnit *CU = nullptr;
  llvm::DenseMap<unsigned, llvm::DIFile *> Files; ///< By buffer ID.
  llvm::StringMap<llvm::DINamespace *> Namespaces;
  llvm::StringMap<llvm::DIType *> BasicTypes;
  llvm::DenseMap<const NativeEnum *, llvm::DIType *> Enums;
  llvm::DenseMap<const NativeClass *, llvm::DIType *> Classes;
  llvm::DIType *TaskStateTy = nullptr, *TaskState8Ty = nullptr;
  llvm::DIType *StringTy = nullptr;
  llvm::DIType *StatePtrTy = nullptr;
  bool Optimized; ///< CodeGenOptions::OptLevel > 0.
};

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
  /// recorder sees the call (bsc/JIT/Boundary.h): `Name` for messages,
  /// `Flags` (BoundarySiteFlags), and the arguments the thunk may write
  /// through as (argument index, bytes); else `Thunk` itself.
  llvm::FunctionCallee
  wrapForBoundary(llvm::FunctionCallee Thunk, llvm::StringRef Name,
                  uint32_t Flags,
                  llvm::ArrayRef<std::pair<unsigned, uint64_t>> Writable);
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
  llvm::Function *StringEquals = nullptr;
  llvm::GlobalVariable *Info = nullptr;
  llvm::Function *BehaviorDestroy = nullptr; ///< Null: nothing to destroy.
  llvm::MDNode *AccessTags[4] = {};
  /// emitReplLine: the REPL's variables at their addresses.
  const llvm::DenseMap<const Decl *, uint64_t> *ReplSlots = nullptr;
  std::unique_ptr<DebugInfoEmitter> DebugInfo;
};

/// Lowers the body of one func or task into its (already declared) function.
class FunctionEmitter {
public:
  FunctionEmitter(ModuleEmitter &CGM, const CallableDecl &D);

  /// Emits the whole body.
  void run();

private:
  // CodeGen.cpp: funcs.
  /// An aligned stack slot for a value of `T` in memory, at the top of the
  /// entry block (a func's parameters and locals, a task's short-lived
  /// locals, the debugger's copies).
  llvm::AllocaInst *createSlot(const Type *T, const llvm::Twine &Name);
  void emitFuncPrologue();
  void emitFuncEpilogue();
  /// Returns the zero value of the func's result, after its cleanups.
  void emitFuncZeroReturn();

  // CGTask.cpp: everything a generator needs.
  void emitTaskPrologue();
  void emitTaskEpilogue();
  /// The task ends: its state = `State` (done, or failure when its cycle
  /// ran out of budget); ret [State].
  void emitTaskFinish(int32_t State = TaskDone);
  /// Marks the task's last call as ended (CGTask.cpp, "The last call").
  void markEnded();
  /// Returns from a task's call with its state, or void (CGTask.cpp, "The
  /// result").
  void emitTaskReturn(llvm::Value *State);
  /// With CodeGenOptions::Instrument: writes this call's way out into the
  /// task's slot of the trace record (a yield's resume point, or the
  /// finished value), and a state known only at run time into its word.
  void recordTraceExit(uint32_t Slot, llvm::Value *ComputedState);
  void emitYield(const YieldStmt &S);
  /// A pointer to field `Field` of the frame of `T`.
  llvm::Value *getFrameFieldPtr(const TaskDecl *T, unsigned Field);
  /// A pointer to the resume point or state of `T`, in its frame or in its
  /// narrow header (FrameInfo::getWord gives the type).
  llvm::Value *getTaskWordPtr(const TaskDecl *T, TaskWord W);
  /// The resume point of `T`, in its own type (FrameInfo::Resume).
  llvm::Value *loadResume(const TaskDecl *T);
  void storeResume(const TaskDecl *T, unsigned Point);
  /// The state of `T` as an i32.
  llvm::Value *loadTaskState(const TaskDecl *T, const llvm::Twine &Name);
  /// Stores an i32 state into the state of `T`.
  void storeTaskState(const TaskDecl *T, llvm::Value *State);
  llvm::Value *emitTaskState(const TaskDecl *T);

  // CGStmt.cpp.
  void emitStmt(const Stmt *S);
  void emitStmtImpl(const Stmt *S);
  void emitBlock(const BlockStmt *S);
  void emitDecl(const DeclStmt &S);
  void emitAssign(const AssignStmt &S);
  void emitIf(const IfStmt &S);
  void emitFor(const ForStmt &S);
  /// With CodeGenOptions::CycleBudget, at a loop's jump back to its head:
  /// one pass of the budget, or the end of this func or task when none is
  /// left (CGBudget.cpp).
  void emitBudgetCharge(const ForStmt &S);
  void emitBreak(const BreakStmt &S);
  void emitContinue(const ContinueStmt &S);
  void emitReturn(const ReturnStmt &S);
  /// A condition as a full expression: its temporaries are destroyed
  /// before the branch.
  llvm::Value *emitFullCond(const Expr *E);

  // Destruction (CGStmt.cpp). A func's class parameters and locals live
  // from their construction to the end of their scope; a task's live in its
  // frame from reset to finish (CGTask.cpp). Temporaries live to the end of
  // their full expression, and those of the right operand of && and || to
  // the end of that operand: every exit knows statically what is alive, so
  // no flags are needed.
  struct Cleanup {
    const NativeClass *Class;
    llvm::Value *Addr;
  };
  /// Calls the destroy thunk of a class value.
  void emitDestroy(const NativeClass *C, llvm::Value *Addr);
  /// Records a temporary class value (a call's result) for destruction at
  /// the end of the full expression; nothing for trivial destructors.
  void pushTemp(const NativeClass *C, llvm::Value *Addr);
  /// Destroys the temporaries above `Depth`, newest first, and forgets them.
  void popTemps(size_t Depth);
  /// Destroys the func's live variables above `Depth`, newest first; with
  /// `Forget` they also leave the list (the end of their scope).
  void emitLiveCleanups(size_t Depth, bool Forget);
  /// Starts a new block for code that follows a terminator (after `return`,
  /// `break`, ...); it has no predecessors and is removed at the end.
  void startDeadBlock();
  /// Branches to `Dest` unless the current block is already terminated.
  void emitBranch(llvm::BasicBlock *Dest);

  // CGExpr.cpp.
  llvm::Value *emitExpr(const Expr *E);
  /// Emits a condition as i1.
  llvm::Value *emitCond(const Expr *E);
  llvm::Value *emitName(const NameExpr &E);
  llvm::Value *emitCall(const CallExpr &E);
  llvm::Value *emitUnary(const UnaryExpr &E);
  llvm::Value *emitBinary(const BinaryExpr &E);
  llvm::Value *emitLogical(const BinaryExpr &E);
  llvm::Value *emitConversion(const ConversionExpr &E);
  llvm::Value *emitMember(const MemberExpr &E);
  /// `L op R` for arithmetic and comparison operators on already evaluated
  /// operands of one type (shared with compound assignment). Integers (i32,
  /// and i1 for bool ==/!=) compare signed; floats as in C.
  llvm::Value *emitArith(BinaryOp Op, llvm::Value *L, llvm::Value *R);
  /// Integer `/` and `%` without traps or UB (docs/design/backend.md):
  /// x / 0 == 0, x % 0 == x, INT_MIN / -1 == INT_MIN, INT_MIN % -1 == 0.
  llvm::Value *emitSafeIntDivRem(bool IsRem, llvm::Value *L, llvm::Value *R);
  /// Float `%` without libm: a - b * trunc(a / b).
  llvm::Value *emitFloatRem(llvm::Value *L, llvm::Value *R);
  /// The address of a local or parameter (of this callable, or of the task
  /// a nested func belongs to). Null for a task's parameter in its own body:
  /// there the body reads the argument, which is fresh at every call.
  llvm::Value *getDeclAddress(const Decl *V);
  /// The address of the variable an assignment stores to (fields and
  /// elements: emitAssign).
  llvm::Value *getLValueAddress(const NameExpr &N);
  /// The pointer held in state.input / state.output: the one place where
  /// the `input` and `output` globals are reached.
  llvm::Value *emitGlobalIOPointer(NameKind K);
  /// Loads/stores a value of type `T` from/to memory (bool: i8 <-> i1).
  /// A load or store of memory of kind `A` (ModuleEmitter::Access).
  llvm::LoadInst *createLoad(ModuleEmitter::Access A, llvm::Type *Ty,
                             llvm::Value *Addr, const llvm::Twine &Name = "");
  llvm::StoreInst *createStore(ModuleEmitter::Access A, llvm::Value *V,
                               llvm::Value *Addr);
  llvm::Value *emitLoad(const Type *T, llvm::Value *Addr,
                        const llvm::Twine &Name = "");
  void emitStore(const Type *T, llvm::Value *V, llvm::Value *Addr);

  // Class values (CGExpr.cpp). In registers a class value is a pointer to
  // its storage: a variable, a frame field, a field reached by offset from
  // `input`, or a temporary alloca.
  /// A fresh, aligned alloca for a class value (raw storage).
  llvm::AllocaInst *createClassTemp(const NativeClass *C,
                                    const llvm::Twine &Name = "tmp");
  /// Zeroes the storage with explicit stores, then runs the construct
  /// thunk if the class has one.
  void emitClassInit(const NativeClass *C, llvm::Value *Addr);
  /// *Dst = *Src: loads/stores when the class copies as bytes, else the
  /// assign thunk (Dst constructed) or the copy thunk (Dst raw; a
  /// constructed Dst without assign thunk is destroyed first).
  void emitClassCopy(const NativeClass *C, llvm::Value *Dst, llvm::Value *Src,
                     bool DstConstructed);
  /// Calls a registered function, method, getter or operator: class
  /// arguments as pointers, a class result through a fresh out alloca.
  llvm::Value *emitNativeCall(const NativeFunction &NF, llvm::Value *Self,
                              llvm::ArrayRef<const Expr *> Args);
  llvm::Value *emitNativeCallWithValues(const NativeFunction &NF,
                                        llvm::Value *Self,
                                        llvm::ArrayRef<llvm::Value *> Args);
  /// A scalar field of C++ storage `StorageSize` bytes (a double field is a
  /// b-script float; a short an int).
  llvm::Value *emitFieldLoad(const Type *T, const NativeType &NT,
                             llvm::Value *Addr);
  void emitFieldStore(const Type *T, const NativeType &NT, llvm::Value *V,
                      llvm::Value *Addr);
  /// The address of a field (`base.f` with a FieldOffset).
  llvm::Value *emitFieldAddress(const MemberExpr &E);
  /// The address of an element of an array field (`output.wide[k]`).
  llvm::Value *emitElementAddress(const IndexExpr &E);
  /// The index of the first declared parameter among Fn's arguments.
  unsigned getFirstParamArg() const;

  // Debug information (CodeGenOptions::DebugInfo, CGDebugInfo.cpp); each
  // of these does nothing without it.
  /// The scopes open here: the subprogram, then lexical blocks.
  llvm::SmallVector<llvm::DIScope *, 8> DebugScopes;
  /// The stack slot holding the state pointer.
  llvm::AllocaInst *StateSlot = nullptr;
  /// The subprogram, and stack slots for what the debugger reads all
  /// along: the state pointer, a task's scalar parameters (the arguments
  /// the body reads). No location: gdb's breakpoint goes after them.
  void emitDebugPrologue();
  /// Attributes the instructions emitted next to `Loc`.
  void setDebugLocation(llvm::SMLoc Loc);
  void pushDebugScope(llvm::SMLoc Loc);
  void popDebugScope();
  /// Declares a parameter (`ArgNo` > 0) or local to the debugger where it
  /// lives: its frame field, or its alloca.
  void declareForDebugger(const Decl &D, const Type *Ty, unsigned ArgNo = 0);

  /// With probes: every `ret` stores back the loop probe's value at entry.
  void restoreLoopProbeOnReturn();
  /// With probes: stores site `Site` (0: none) into probe global `Symbol`.
  void emitProbe(const char *Symbol, unsigned Site);
  /// The statement being lowered: the place a native call's probe names.
  llvm::SMLoc CurStmtLoc;

  // Explaining conditions (CodeGenOptions::Explain, CGExplain.cpp).
  /// The condition of an `if` or `for` statement as a full expression
  /// (emitFullCond); with Explain it also writes the condition's record.
  llvm::Value *emitCondition(const Stmt &S, const Expr *Cond);
  llvm::Value *emitExplainedCondition(const Stmt &S, const Expr *Cond);
  /// Evaluates `Cond` as a full expression, writing its operands into the
  /// record that BeginRecord(site number, record size) returns for a new
  /// site of kind `Kind` at `Loc`.
  llvm::Value *emitRecordedCond(
      ExplainSite::SiteKind Kind, llvm::SMLoc Loc, const Expr *Cond,
      llvm::function_ref<llvm::Value *(unsigned, uint32_t)> BeginRecord);
  /// `assert(cond)` as CodeGenOptions::Assertions says (CGAssert.cpp).
  void emitAssert(const AssertStmt &S);
  /// Coverage: counts a run of `S` (not of blocks).
  void emitStmtCount(const Stmt &S);
  /// Coverage: counts which way condition `Cond` of `S` went.
  void emitBranchCount(const Stmt &S, const Expr *Cond, llvm::Value *Holds);
  /// Coverage: counts every call, at the top of the entry block.
  void emitCallCount();
  /// While a condition is explained, emitExpr of one of its operands: the
  /// value, also stored into the record. Null for other expressions, which
  /// emitExpr emits as usual.
  llvm::Value *emitExplainedOperand(const Expr *E);
  /// A task's records of its calls: the start at the top, the state and
  /// resume point it leaves before every `ret`.
  void emitExplainTaskMarks();
  struct ExplainRecord;
  /// The condition being explained, or null.
  ExplainRecord *Explaining = nullptr;

  /// Evaluates a yield's value as an i32 task state.
  llvm::Value *emitToTaskState(const Expr *E);

  /// The enclosing task whose frame this function can reach: the task
  /// itself, or the task a nested func is declared in.
  const TaskDecl *getFrameTask() const;

  ModuleEmitter &CGM;
  const CallableDecl &D;
  const TaskDecl *Task;     ///< Non-null when lowering a task body.
  llvm::Function *Fn;
  llvm::IRBuilder<> Builder;
  llvm::Value *StatePtr;    ///< The first argument.
  /// Allocas of a func's parameters and locals.
  /// (A REPL variable's slot is its fixed address: ReplSlots.)
  llvm::DenseMap<const Decl *, llvm::Value *> Slots;
  /// Where `break` and `continue` of the innermost loops go.
  struct LoopTargets {
    llvm::BasicBlock *Break;
    llvm::BasicBlock *Continue;
    size_t LiveDepth; ///< Variables alive where they branch to.
    unsigned ProbeSite; ///< With probes: the loop's site.
  };
  llvm::SmallVector<LoopTargets, 4> Loops;
  /// Task bodies: the dispatch on the resume point; a case is added per
  /// yield.
  llvm::SwitchInst *ResumeSwitch = nullptr;
  YieldPlan Plan; ///< Of the task being emitted.
  llvm::Value *Cycle = nullptr; ///< The state's cycle, loaded at entry.
  /// The latest call of a task, whose result is that task's state until
  /// another call (emitTaskState).
  llvm::CallInst *LastTaskCall = nullptr;
  /// Where allocas and frame-field addresses go: the top of the entry block.
  llvm::Instruction *EntryPoint = nullptr;
  /// The address of each frame field used, computed once (task, field).
  llvm::DenseMap<std::pair<const TaskDecl *, unsigned>, llvm::Value *>
      FieldAddrs;
  /// The same for the resume points and states used (task, TaskWord).
  llvm::DenseMap<std::pair<const TaskDecl *, unsigned>, llvm::Value *>
      WordAddrs;
  /// Pending temporaries of the current full expression.
  llvm::SmallVector<Cleanup, 4> Temps;
  /// A func's constructed parameters and locals that need destruction,
  /// outermost first.
  llvm::SmallVector<Cleanup, 8> Live;
};

} // namespace codegen
} // namespace bsc

#endif
