//===- SemaImpl.h - the checker shared by the lib/Sema files ---*- C++ -*-===//
//
// Private to lib/Sema. One Sema object checks one behavior; its members are
// split over files by construct (Sema.cpp: module tables, SemaLookup.cpp:
// name lookup, SemaDecl.cpp: types, signatures and declarations,
// SemaStmt.cpp, SemaExpr.cpp, SemaCall.cpp, SemaConst.cpp: module constants
// and constant folding, SemaLoops.cpp: what loops do with yields,
// SemaTask.cpp: yields, taskState and the call graph, SemaClass.cpp:
// members, method calls and operators of registered classes, SemaRepl.cpp:
// the REPL's prompt).
// Keeping all state in one class lets each file stay a plain walk over the
// tree without threading a context parameter through every function.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_SEMA_SEMAIMPL_H
#define BSC_LIB_SEMA_SEMAIMPL_H

#include "bsc/AST/AST.h"
#include "bsc/Basic/Diagnostic.h"
#include "bsc/Sema/Sema.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/DenseSet.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSet.h"
#include <optional>

namespace bsc {
namespace sema {

/// What a (possibly qualified) name denotes. Lookup reports the errors it
/// can judge by itself (unknown qualifier, module not required, ...) and
/// then answers Error, which callers treat as poison.
enum class LookupKind {
  Error,       ///< Already diagnosed, or a name of an unknown module.
  Local,       ///< Var.
  Param,       ///< Param.
  Callable,    ///< Callable: a func or a task.
  NativeFn,    ///< NativeFn.
  EnumValue,   ///< Ty (an enum or TaskState) and Value.
  Constant,    ///< Const: a module constant.
  Input,       ///< The `input` global.
  Output,      ///< The `output` global.
  Module,      ///< A module name on its own.
  TypeName,    ///< A type: a built-in, TaskState, a registered enum or
               ///< class (Ty).
};

/// The answer of a lookup: a kind and the fields that kind names.
struct LookupResult {
  LookupKind Kind = LookupKind::Error;
  VarDecl *Var = nullptr;
  ParamDecl *Param = nullptr;
  CallableDecl *Callable = nullptr;
  const NativeFunction *NativeFn = nullptr;
  const Type *Ty = nullptr;
  int32_t Value = 0;
  /// For EnumValue: `TaskState::done|running|failure` itself, not a named
  /// state of the same number.
  bool BuiltinState = false;
  ConstDecl *Const = nullptr;
};

/// Whether lookup looks for a value (locals first) or a type (module-level
/// names only; an unknown name is then an unknown type).
enum class LookupMode { Value, Type };

/// How an expression is used; decides what `input` and `output` (and
/// read-only members and task parameters) allow. A member chain passes its
/// use down to its root: `output.walkTarget.x = 1` writes `output`.
enum class Access {
  Read,       ///< Its value is read.
  Write,      ///< It is the target of `=`.
  Modify,     ///< It is the target of `+=` etc., or the argument of a
              ///< non-const `T&` parameter (read and written).
  MethodBase, ///< A method is called on it (read; checkMutatingMethodBase
              ///< adds the write of a non-const method).
  MutatingMethodBase, ///< A non-const method is called on it.
};

/// The module a qualifier names from the point of view of one module.
struct QualifierModule {
  enum { None, Script, Native, Poison } Kind = None;
  ModuleAST *ScriptModule = nullptr;
  const NativeModule *NativeMod = nullptr;
};

/// The name tables of one module.
struct ModuleInfo {
  ModuleAST *AST = nullptr;
  /// The module's namespace: its top-level funcs and tasks...
  llvm::StringMap<CallableDecl *> Decls;
  /// ...its constants...
  llvm::StringMap<ConstDecl *> Consts;
  /// ...and its enums.
  llvm::StringMap<EnumDecl *> Enums;
  /// The modules it requires, by name (resolved or poison).
  llvm::StringMap<const RequireDecl *> Requires;
};

/// One call site in the call graph.
struct CallEdge {
  CallableDecl *Callee;
  llvm::SMLoc Loc;
  /// Sema::ScopeClock at the call: a local of the caller with a larger
  /// ScopeBegin is declared after it.
  unsigned Clock = 0;
};

/// What a call's callee expects, as checkCall learns it.
struct CallSignature {
  std::string Name; ///< The callee as written, for messages.
  llvm::SmallVector<const Type *, 4> ParamTys;
  const Type *ResultTy = nullptr; ///< Null: no callee (reported).
  /// The arguments it needs: the parameters before the first default.
  size_t MinArgs = 0;
  /// A constructor's arguments are checked to choose it.
  bool ArgsChecked = false;
};

/// The checker. See Sema.cpp for the rules it implements.
class Sema {
public:
  Sema(ASTContext &Ctx, DiagnosticEngine &Diags, Behavior &Out,
       const NativeRegistry *Natives);
  /// Checks every module; returns false if an error was reported.
  bool run(llvm::ArrayRef<ModuleAST *> Modules);

  //--- Sema.cpp: reporting, module tables; SemaLookup.cpp: name lookup -----
  DiagnosticBuilder diag(llvm::SMLoc Loc, diag::Kind K);
  void buildModuleTables(llvm::ArrayRef<ModuleAST *> Modules);
  LookupResult lookup(const QualifiedName &N, LookupMode Mode);
  LookupResult lookupUnqualified(const Ident &Id, LookupMode Mode);
  /// lookupUnqualified without diagnostics: Kind Error when not found.
  LookupResult findUnqualified(llvm::StringRef Name, LookupMode Mode);
  /// `M::x`, `M::E::v`, `E::v` (an enum of this module, TaskState or a
  /// required native module's): the qualifier first, then the member.
  LookupResult lookupQualified(const QualifiedName &N);
  /// The module the qualifier `Name` names here, or None.
  QualifierModule findQualifierModule(llvm::StringRef Name);
  /// `M::x` and `M::E::v` in script module `Mod`.
  LookupResult lookupInScriptModule(const QualifiedName &N,
                                    const ModuleInfo &Mod);
  /// `M::x` and `M::E::v` in native module `Mod`.
  LookupResult lookupInNativeModule(const QualifiedName &N,
                                    const NativeModule &Mod);
  /// `E::v` where `E` names no module: an enum, or an unknown qualifier.
  LookupResult lookupInEnumQualifier(const QualifiedName &N);
  /// `A::B::c` where `A::B` is no enum: reports `A::B` as an unknown
  /// qualifier and returns true; false for a name of two parts.
  bool reportMemberOfNonEnum(const QualifiedName &N);
  /// `Member` is not a usable member of native module `Mod` (named `Q`).
  void reportNoNativeMember(const Ident &Q, const Ident &Member,
                            const NativeModule &Mod);
  /// `Q` names no module or enum here: not required, a missing --bind or a
  /// typo (once per name).
  void reportUnknownQualifier(const Ident &Q);
  /// What a qualifier may name here, for `did you mean`.
  llvm::SmallVector<llvm::StringRef, 16> getQualifierNames();
  /// The visible value name closest to `Name` by edit distance, if one is
  /// close enough to suggest (`did you mean`).
  std::optional<std::string> findNearValueName(llvm::StringRef Name);
  /// The enums visible here that have a value `Name`, as {the enum, the
  /// value} spelled from this module (`SoccerState`,
  /// `SoccerState::playDead`), for an enumerator written unqualified.
  std::vector<std::pair<std::string, std::string>>
  findEnumsWithValue(llvm::StringRef Name);
  /// Adds note_did_you_mean at `Id` for the candidate nearest to its name
  /// (NearestName's rule), if one is near enough.
  void suggestNearest(const Ident &Id,
                      llvm::ArrayRef<llvm::StringRef> Candidates);
  /// The value `Value` of the enum `EnumName` whose values are `Values`
  /// (null: TaskState's own done, running, failure) and of type `ValueTy`.
  LookupResult lookupEnumValue(const Type *ValueTy, const NativeEnum *Values,
                               llvm::StringRef EnumName, const Ident &Value);
  /// The same for an enum type (TaskState, a registered enum).
  LookupResult lookupEnumValue(const Type *EnumTy, llvm::StringRef EnumName,
                               const Ident &Value) {
    return lookupEnumValue(EnumTy, EnumTy->isTaskState() ? nullptr
                                                          : EnumTy->getEnum(),
                           EnumName, Value);
  }
  /// Numbers the enumerators of a script enum and gives it its type.
  void checkEnum(EnumDecl *E);
  /// The type of a registered enum (`M::E`).
  const Type *getEnumType(const NativeModule &M, const NativeEnum &E);
  /// The enum named `E` of a native module the current module requires,
  /// or of the world module.
  const Type *findRequiredEnum(llvm::StringRef E);
  /// The class named `C` of the world module (visible unqualified).
  const Type *findWorldClass(llvm::StringRef C);
  /// A registered constant as a checked module constant (made once), so
  /// that it folds and generates like the script's own.
  ConstDecl *getNativeConstant(const NativeConstant &C);

  //--- SemaDecl.cpp: types, signatures, declarations, bodies ----------------
  const Type *resolveType(const QualifiedName &N);
  /// The b-script type of a native type (an array field's is an array).
  const Type *resolveNativeType(const NativeType &T);
  /// ...and of one of its elements (the type itself unless an array).
  const Type *resolveNativeElementType(const NativeType &T);
  void checkSignature(CallableDecl *C);
  /// Reports a class value of type `T` that `What` would copy ("a
  /// parameter", ...) when the class has neither a copy thunk (nor, if the
  /// copy `Assigns` to a constructed value, an assign thunk) nor may be
  /// copied as bytes (err_class_not_copyable).
  /// Reports a value of a class without default constructor where b-script
  /// default-constructs one; `Fix` says what to do instead.
  void checkDefaultConstructible(const Type *T, llvm::SMRange R,
                                 llvm::StringRef Fix);
  void checkCopyable(const Type *T, llvm::SMRange R, llvm::StringRef What,
                     bool Assigns = false);
  void checkTopLevelCallable(CallableDecl *C);
  void checkCallableBody(CallableDecl *C);
  void checkNestedFunc(FuncDecl *F);
  /// Marks the locals of CurTask that a nested func may use before their
  /// declarations run (VarDecl::ReadBeforeDeclared).
  void markLocalsUsedBeforeDeclared();
  void pushScope() { Scopes.emplace_back(); }
  /// Closes the innermost scope: its locals' ScopeEnd.
  void popScope();
  /// Adds a local or parameter to the innermost scope; a name that is
  /// already visible as a local or parameter is err_shadowing.
  void declare(Decl *D);
  Decl *findVisible(llvm::StringRef Name);
  const TaskDecl *getNamedTask(const Expr *E);
  void markStateKindTest(BinaryExpr *E);
  /// SemaConst.cpp: checks and evaluates a module constant (and, first,
  /// the constants its value uses, in any module).
  void checkConst(ConstDecl *C);
  /// Checks a parameter's default: a constant expression of its type.
  void checkDefaultArg(ParamDecl *P);
  /// A literal of type `Ty` with the value `V` (a default argument).
  Expr *makeConstantExpr(const ConstantValue &V, const Type *Ty,
                         llvm::SMLoc Loc);
  /// The value of a constant expression already checked, or nothing if
  /// it is not one.
  std::optional<ConstDecl::ValueFields> evaluateConstant(const Expr *E);
  //--- SemaLoops.cpp --------------------------------------------------------
  /// warn_yield_loop: a loop that certainly never ends once entered.
  void warnIfEndless(const ForStmt *S);
  /// warn_loop_skips_yield: a task's loop with a path around it that
  /// passes none of its yields (after its body is checked).
  void checkLoopYields(ForStmt *S);
  void checkVarDecl(VarDecl *V);

  //--- SemaStmt.cpp ---------------------------------------------------------
  void checkBlock(BlockStmt *B);
  void checkStmt(Stmt *S);
  void checkIf(IfStmt *S);
  void checkFor(ForStmt *S);
  void checkReturn(ReturnStmt *S);
  void checkCondition(Expr *&Cond);
  void checkMissingReturn(FuncDecl *F);
  /// `assert(cond[, "message"])`: a bool condition, remembered for
  /// checkAssertionEffects.
  void checkAssert(AssertStmt *S);

  //--- SemaAssert.cpp: assertions change nothing ---------------------------
  /// Reports every assertion whose condition could change the behavior
  /// (objects for the robot leave assertions out by default).
  void checkAssertionEffects();
  /// Checking a REPL line (ReplChecker), where `assert` has no use.
  bool InReplLine = false;
  /// Checking an `assert`'s condition, which may read `output` (what the
  /// cycle wrote so far): it changes nothing the robot does.
  bool InAssertCondition = false;

  //--- SemaExpr.cpp ---------------------------------------------------------
  /// Checks `E` (for the given use), sets E->Ty and returns it.
  const Type *checkExpr(Expr *E, Access A = Access::Read);
  /// checkExpr without refusing an array: for the base of an index.
  const Type *checkExprOrArray(Expr *E, Access A);
  const Type *checkExprImpl(Expr *E, Access A);
  const Type *checkName(NameExpr *E, Access A);
  const Type *applyLookup(NameExpr *E, const LookupResult &L, Access A);
  const Type *checkIO(NameExpr *E, bool IsInput, Access A);
  /// The direction rules of `input` (read-only) and `output` (write-only;
  /// an assertion's condition may read it), the one place that decides
  /// them. `Method` names a non-const method
  /// for MutatingMethodBase. Returns false after reporting.
  bool checkIOAccess(NameExpr *E, bool IsInput, Access A,
                     llvm::StringRef Method = "");
  /// Task parameters are read-only; false after reporting.
  bool checkParamAccess(NameExpr *E, ParamDecl *P, Access A);
  const Type *checkMember(MemberExpr *E, Access A);
  const Type *checkIndex(IndexExpr *E, Access A);
  const Type *checkUnary(UnaryExpr *E);
  const Type *checkBinary(BinaryExpr *E);
  const Type *checkConversion(ConversionExpr *E);
  void checkAssign(AssignStmt *S);
  const Type *checkAssignTarget(Expr *T, Access A);
  /// Converts `E` to `To` if the language allows it implicitly (wrapping an
  /// int in an implicit int-to-float conversion); false if not allowed.
  bool convertImplicitly(Expr *&E, const Type *To);
  /// The language's one rule of implicit conversion, as a question: a
  /// value of `From` passes as `To` unchanged (the same type, or poison),
  /// after int-to-float promotion, or not at all.
  enum class ImplicitConversion { Unchanged, IntToFloat, None };
  static ImplicitConversion classifyImplicit(const Type *From, const Type *To);
  void promoteToFloat(Expr *&E);
  /// The source text of an expression, for messages.
  std::string getText(const Expr *E) const;

  //--- SemaCall.cpp: calls -------------------------------------------------
  /// Checks a call; a call statement may call a task or a void function.
  const Type *checkCall(CallExpr *C, bool AsStatement);
  /// Resolves C's callee (a name, a method, or a poison expression) to
  /// what it expects; no ResultTy after reporting.
  CallSignature resolveCallee(CallExpr *C);
  /// ...for a callee `N` that is a name: a func, task, registered function
  /// or class (its constructor).
  CallSignature resolveNamedCallee(CallExpr *C, NameExpr *N);
  /// Picks the constructor of class `T` for the (checked) arguments of
  /// `C` and makes `C` a call of it; false after reporting.
  bool resolveConstructor(CallExpr *C, NameExpr *Callee, const Type *T);
  /// Appends the defaults of the parameters C's arguments leave out.
  void addDefaultArgs(CallExpr *C, const CallSignature &Sig);
  /// Converts each argument to its parameter's type, reporting those that
  /// do not convert (and the signature once).
  void convertArgs(CallExpr *C, const CallSignature &Sig);
  /// After an argument error in a call of `Name`: a note with the
  /// callee's signature, its parameters named (at a script callee's
  /// declaration; at the call for registered C++).
  void noteSignature(const CallExpr *C, llvm::StringRef Name,
                     llvm::ArrayRef<const Type *> ParamTys,
                     const Type *ResultTy);

  //--- SemaClass.cpp: registered classes -----------------------------------
  /// The field, property or method `Name` of class `C`, or null after
  /// reporting err_no_member.
  const NativeFunction *findValueMember(const Type *ClassTy, const Ident &Name);
  /// `base.method` as a callee: resolves the method and records it on the
  /// call; returns false after reporting (or for poison).
  bool resolveMethodCallee(CallExpr *C, MemberExpr *M);
  /// A non-const method (or operator) is called on `Base`: its root must
  /// not be `input` or a task parameter, nor any member on the way read-only.
  void checkMutatingMethodBase(Expr *Base, const NativeFunction &Method);
  /// `a op b` and `-a` on class values; the operator methods of
  /// docs/bindings.md. Only called with a class-typed (left) operand.
  const Type *checkClassBinary(BinaryExpr *E);
  const Type *checkClassUnary(UnaryExpr *E);
  /// A literal for a default argument, typed as the parameter.
  Expr *makeDefaultArg(const NativeDefault &D, const Type *ParamTy,
                       llvm::SMLoc Loc);
  //--- SemaRepl.cpp: what only the REPL's prompt allows ----------------------
  /// A loaded module named `Name` that the current one does not require
  /// (at the prompt every module is reachable qualified), or None.
  QualifierModule findReplModule(llvm::StringRef Name);
  /// `Task.x` at the prompt: if E's base names a task (and no value),
  /// checks the read of its field and returns its type (an error type after
  /// reporting); null if the base is no task and E is an ordinary member.
  const Type *checkTaskField(MemberExpr *E, Access A);
  /// Reports a write to a task's parameter or local at the prompt; true if
  /// `D` may be used with `A`.
  bool checkReplFieldAccess(const Decl *D, llvm::SMRange R, Access A);
  //--- SemaTask.cpp ---------------------------------------------------------
  void checkYield(YieldStmt *S);
  const Type *checkTaskState(TaskStateExpr *E);
  void recordCall(CallableDecl *Callee, llvm::SMLoc Loc);
  /// Fills Behavior::Calls from Calls.
  void exportCalls();
  void checkCallGraph();

  //--- State ----------------------------------------------------------------
  ASTContext &Ctx;
  TypeContext &Types;
  DiagnosticEngine &Diags;
  Behavior &Out;
  bool HadError = false;
  /// Checking a REPL line (ReplChecker): `input` is writable and `output`
  /// readable.
  bool Repl = false;
  /// REPL: the task parameters and locals lines may read (ReplChecker::
  /// setFrameFields).
  llvm::DenseSet<const Decl *> ReplFrameFields;
  /// REPL: the task of `:frame`, whose nested funcs are visible.
  const TaskDecl *ReplFrame = nullptr;
  /// The task whose nested funcs an unqualified name may call: the one
  /// being checked, or at the prompt the frame's.
  const TaskDecl *getNestingTask() const {
    return CurTask ? CurTask : ReplFrame;
  }
  llvm::DenseMap<const NativeConstant *, ConstDecl *> NativeConstants;
  /// checkBehavior's: whether a module file could be required (or null).
  ModuleFileFinder FindModuleFile = nullptr;

  std::vector<std::unique_ptr<ModuleInfo>> ModuleInfos;
  llvm::DenseMap<const ModuleAST *, ModuleInfo *> InfoOf;
  /// Names of every module a `requires` could name (known modules).
  llvm::StringSet<> KnownModules;
  /// err_no_input_type / err_no_output_type were reported (once is enough).
  bool ReportedNoInput = false, ReportedNoOutput = false;
  /// The unknown qualifiers reported (each once).
  llvm::StringSet<> ReportedQualifiers;
  /// note_maybe_unbound was given (once is enough).
  bool NotedUnbound = false;
  /// checkBehavior's Unbound: set when the compilation has no binding
  /// object.
  std::vector<UnboundName> *Unbound = nullptr;
  /// Adds a use to Unbound (instead of an error) and fails the check.
  void noteUnbound(UnboundName N);
  /// err_redefinition at `New`, with a note at `Prev`.
  void reportRedefinition(const Decl &New, const Decl &Prev);
  /// Whether some native module came from a --bind object.
  bool hasBindingModules() const;
  /// Every native module some module requires (for native enum types).
  std::vector<const NativeModule *> AllNatives;
  /// The compilation's native modules (null: the built-in ones only).
  const NativeRegistry *Natives = nullptr;
  /// The module declaring `input`/`output`, or null.
  const NativeModule *World = nullptr;

  ModuleInfo *CurModule = nullptr;
  /// The func or task whose body is being checked (a nested func when
  /// inside one).
  CallableDecl *CurCallable = nullptr;
  /// The task whose context the current code runs in (the enclosing task of
  /// a nested func), or null.
  TaskDecl *CurTask = nullptr;
  unsigned LoopDepth = 0;
  llvm::DenseSet<const FuncDecl *> CheckedNested;

  using Scope = llvm::SmallVector<std::pair<llvm::StringRef, Decl *>, 4>;
  std::vector<Scope> Scopes;
  /// Numbers declarations and scope ends (VarDecl::ScopeBegin/End).
  unsigned ScopeClock = 0;

  /// Call sites of each func and task, in source order.
  llvm::DenseMap<const CallableDecl *, std::vector<CallEdge>> Calls;
  /// The enclosing task's locals each nested func uses itself.
  llvm::DenseMap<const CallableDecl *, llvm::SmallVector<VarDecl *, 4>>
      TaskLocalsUsed;
};

} // namespace sema
} // namespace bsc

#endif
