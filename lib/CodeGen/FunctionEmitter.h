//===- FunctionEmitter.h - one func or task lowered -------------*- C++ -*-===//
//
// FunctionEmitter: the body of one func or task (Clang's CodeGenFunction),
// defined in CGStmt.cpp, CGExpr.cpp, CGTask.cpp and the CG files of the
// JIT's instrumentation; CodeGenImpl.h gives the overview of the generator.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_CODEGEN_FUNCTIONEMITTER_H
#define BSC_LIB_CODEGEN_FUNCTIONEMITTER_H

#include "ModuleEmitter.h"

namespace bsc {
namespace codegen {

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
  /// A call of func or task `Target` with its arguments' values: (state,
  /// [the class result's storage], args...). `ResultClass`: the class it
  /// returns, if any.
  llvm::Value *emitCallWithValues(const CallableDecl &Target,
                                  const NativeClass *ResultClass,
                                  llvm::ArrayRef<llvm::Value *> Values);
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
