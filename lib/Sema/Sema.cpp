//===- Sema.cpp - checking a behavior: entry, module tables ---------------===//
//
// Sema checks all modules of a behavior together (whole program), because
// the task rules (no task reachable from itself) are about the whole call
// graph. It runs in three passes: module tables (namespaces and requires),
// signatures (parameter and result types of every func and task, so calls
// across modules can be checked in any order), then bodies; the call graph is
// checked last.
//
// The rules, in short (docs/language.md has the long form):
// - Names. A module's top-level funcs and tasks are its namespace. An
//   unqualified name is looked up in the local scopes from the innermost out
//   (a nested func sees its own params and locals, then the enclosing task's
//   params and the task's top-level locals declared before the func), then
//   the nested funcs of the current task, the module's funcs and tasks, and
//   `input`/`output`. `M::name` needs M to be this module or a required one;
//   `TaskState::done|running|failure` are 0, 1, -1; `E::value` names a value
//   of an enum E of a required native module, `M::E::value` too. The world
//   module (the native module declaring `input`/`output`) counts as
//   required everywhere, and its classes and enums are also visible
//   unqualified (`MotionType::kick`, as in the paper). Nested funcs
//   are not visible outside their task. Names of an unknown module (already
//   diagnosed by the loader) are poison.
// - Scopes. Blocks and `for` heads open scopes; a local is visible from its
//   declaration to the end of its block. Redeclaring a visible local or
//   parameter is an error (shadowing and same-scope redeclaration alike); a
//   local named like a func or task is fine and wins.
// - Types: int, float, bool, string, TaskState, registered enums and
//   classes (`M::Class`; world classes also unqualified). `int`
//   converts implicitly to `float` (arithmetic, comparison, assignment,
//   initialisation, arguments, return); everything else is explicit:
//   `int(x)` from float, bool, enum, TaskState, int; `float(x)` from int,
//   float; `bool(x)` from bool. TaskState and int do not mix implicitly.
// - Operators: arithmetic on int/float (promoting), `%` on ints only,
//   ordering on int/float, `==`/`!=` on same-typed int/float/bool/enum/
//   TaskState (never strings), `&&` `||` `!` on bool, unary `-` on int/float.
//   On a class-typed left operand an operator calls the class's operator
//   method (`+` is `_plus_`, ...; SemaClass.cpp). Conditions are bool.
// - Members: `v.f` reads a field or property of a class value, `v.m(...)`
//   calls a method; arguments are checked like those of functions, and
//   `.defaults(...)` of the binding fill in missing trailing ones.
// - Statements: an expression statement must be a call; a task call is a
//   statement only. Task parameters are read-only (also from nested funcs),
//   `input` is read-only and `output` write-only. A func with a result
//   returns on every path (an endless `for` without `break` counts). Code
//   right after return/break/continue is warned about once per block.
// - Tasks: `yield` only in a task body, its value int or TaskState; yields are
//   numbered in source order (resume point N is after the Nth yield).
// - No recursion at all: any cycle in the call graph of funcs and tasks is an
//   error that names the cycle (tasks have one context each; funcs get a
//   statically bounded stack).
// - `input`/`output` are typed by the world module's classes (without a
//   world module every use reports the missing type once). `input` is
//   read-only (no assignment to any part, no non-const method on any part),
//   `output` write-only (no read of any part: no method call, no argument,
//   no compound assignment). checkIOAccess is the one place for these rules.
// - One mistake, one message: the error type is poison.
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"

using namespace bsc;
using namespace bsc::sema;

Sema::Sema(ASTContext &Ctx, DiagnosticEngine &Diags, Behavior &Out,
           const NativeRegistry *Natives)
    : Ctx(Ctx), Types(Ctx.getTypes()), Diags(Diags), Out(Out),
      Natives(Natives) {
  if (Natives)
    World = Natives->getWorld();
  Out.World = World;
}

DiagnosticBuilder Sema::diag(llvm::SMLoc Loc, diag::Kind K) {
  if (getSeverity(K) == Severity::Error)
    HadError = true;
  return Diags.report(Loc, K);
}

bool Sema::run(llvm::ArrayRef<ModuleAST *> Modules) {
  Out.Modules.assign(Modules.begin(), Modules.end());
  buildModuleTables(Modules);

  // Constants first: signatures and bodies use their values.
  for (ModuleAST *M : Modules)
    for (ConstDecl *C : M->Consts)
      checkConst(C);

  for (ModuleAST *M : Modules) {
    CurModule = InfoOf[M];
    for (CallableDecl *C : M->Decls) {
      checkSignature(C);
      if (auto *T = llvm::dyn_cast<TaskDecl>(C))
        for (FuncDecl *F : T->NestedFuncs)
          checkSignature(F);
    }
  }

  for (ModuleAST *M : Modules) {
    CurModule = InfoOf[M];
    for (CallableDecl *C : M->Decls) {
      if (Diags.tooManyErrors())
        return false;
      checkTopLevelCallable(C);
    }
  }
  CurModule = nullptr;

  for (ModuleAST *M : Modules)
    for (CallableDecl *C : M->Decls) {
      if (auto *F = llvm::dyn_cast<FuncDecl>(C)) {
        Out.Funcs.push_back(F);
        continue;
      }
      auto *T = llvm::cast<TaskDecl>(C);
      Out.Tasks.push_back(T);
      for (FuncDecl *F : T->NestedFuncs)
        Out.Funcs.push_back(F);
    }

  exportCalls();
  checkCallGraph();
  checkAssertionEffects();
  return !HadError;
}

void Sema::buildModuleTables(llvm::ArrayRef<ModuleAST *> Modules) {
  if (Natives)
    for (const auto &NM : Natives->Modules) {
      KnownModules.insert(NM->Name);
      if (!NM->Standard)
        Out.BindingModules.push_back(NM.get());
    }

  for (ModuleAST *M : Modules) {
    KnownModules.insert(M->Name);
    ModuleInfos.push_back(std::make_unique<ModuleInfo>());
    ModuleInfo *Info = ModuleInfos.back().get();
    Info->AST = M;
    InfoOf[M] = Info;

    for (const RequireDecl &R : M->Requires) {
      Info->Requires.try_emplace(R.Name, &R);
      // An unknown module is not "known": naming it elsewhere without a
      // `requires` should not suggest adding one.
      if (R.Script || R.Native)
        KnownModules.insert(R.Name);
      if (R.Native && llvm::find(AllNatives, R.Native) == AllNatives.end()) {
        AllNatives.push_back(R.Native);
        Out.NativeModules.push_back(R.Native);
      }
    }

    // Enums, constants, funcs and tasks share the module's namespace.
    for (EnumDecl *E : M->Enums) {
      auto [It, Inserted] = Info->Enums.try_emplace(E->getName().Name, E);
      if (!Inserted)
        reportRedefinition(*E, *It->second);
      checkEnum(E);
    }
    for (ConstDecl *C : M->Consts) {
      if (EnumDecl *E = Info->Enums.lookup(C->getName().Name))
        reportRedefinition(*C, *E);
      auto [It, Inserted] = Info->Consts.try_emplace(C->getName().Name, C);
      if (!Inserted)
        reportRedefinition(*C, *It->second);
    }
    for (CallableDecl *C : M->Decls) {
      if (ConstDecl *Const = Info->Consts.lookup(C->getName().Name))
        reportRedefinition(*C, *Const);
      if (EnumDecl *E = Info->Enums.lookup(C->getName().Name))
        reportRedefinition(*C, *E);
      auto [It, Inserted] = Info->Decls.try_emplace(C->getName().Name, C);
      if (!Inserted)
        reportRedefinition(*C, *It->second);
      // Two nested funcs of one task with one name are a redefinition too.
      auto *T = llvm::dyn_cast<TaskDecl>(C);
      if (!T)
        continue;
      llvm::StringMap<FuncDecl *> Nested;
      for (FuncDecl *F : T->NestedFuncs) {
        auto [NIt, NInserted] = Nested.try_emplace(F->getName().Name, F);
        if (!NInserted)
          reportRedefinition(*F, *NIt->second);
      }
    }
  }
}

void Sema::checkEnum(EnumDecl *E) {
  // The REPL builds the tables of a checked behavior again.
  E->Values.Values.clear();
  E->Values.Name = E->getName().Name.str();
  E->Ty = E->IsTaskState
              ? Types.getTaskState()
              : Types.getEnum(&E->Values, E->Module->Name + "::" +
                                              E->getName().Name.str());
  // Named task states count from 1 (the first running state after
  // TaskState::done); other enums from 0, as in C.
  int64_t Next = E->IsTaskState ? 1 : 0;
  llvm::StringMap<const Enumerator *> Seen;
  for (const Enumerator &En : E->Enumerators) {
    int64_t Value = En.Explicit ? *En.Explicit : Next;
    Next = Value + 1;
    llvm::SMLoc Loc = En.Explicit ? En.ValueRange.Start : En.Name.Loc;
    if (Value < INT32_MIN || Value > INT32_MAX) {
      diag(Loc, diag::err_enumerator_out_of_range)
          << En.Name.Name << std::to_string(Value);
      continue;
    }
    if (E->IsTaskState && Value == 0) {
      diag(Loc, diag::err_task_state_enumerator_zero)
          << E->getName().Name << En.Name.Name;
      continue;
    }
    auto [It, Inserted] = Seen.try_emplace(En.Name.Name, &En);
    if (!Inserted) {
      diag(En.Name.Loc, diag::err_duplicate_enumerator)
          << En.Name.Name << E->getName().Name << En.Name.getRange();
      diag(It->second->Name.Loc, diag::note_previous_definition);
      continue;
    }
    E->Values.Values.push_back({En.Name.Name.str(), int32_t(Value)});
  }
}

const Type *Sema::getEnumType(const NativeModule &M, const NativeEnum &E) {
  return Types.getEnum(&E, M.Name + "::" + E.Name);
}

const Type *Sema::findRequiredEnum(llvm::StringRef Name) {
  for (const RequireDecl &R : CurModule->AST->Requires)
    if (R.Native)
      if (const NativeEnum *E = R.Native->findEnum(Name))
        return getEnumType(*R.Native, *E);
  if (World)
    if (const NativeEnum *E = World->findEnum(Name))
      return getEnumType(*World, *E);
  return nullptr;
}

ConstDecl *Sema::getNativeConstant(const NativeConstant &C) {
  ConstDecl *&D = NativeConstants[&C];
  if (D)
    return D;
  D = Ctx.create<ConstDecl>(llvm::SMRange(), Ident{Ctx.saveString(C.Name), {}},
                            QualifiedName(), nullptr);
  D->Ty = resolveNativeType(C.Type);
  D->Value.Int = C.Int;
  D->Value.Float = C.Float;
  D->Value.Bool = C.Int != 0;
  D->State = ConstDecl::CheckState::Done;
  if (D->Ty->isError())
    D->Ty = nullptr; // Poison: an enum of a module not loaded.
  return D;
}

const Type *Sema::findWorldClass(llvm::StringRef Name) {
  if (World)
    if (const NativeClass *C = World->findClass(Name))
      return Types.getClass(C);
  return nullptr;
}

void Sema::reportRedefinition(const Decl &New, const Decl &Prev) {
  diag(New.getName().Loc, diag::err_redefinition) << New.getName().Name;
  diag(Prev.getName().Loc, diag::note_previous_definition);
}

void Sema::noteUnbound(UnboundName N) {
  Unbound->push_back(std::move(N));
  HadError = true; // The front end reports it.
}

bool Sema::hasBindingModules() const {
  // The required native modules and the world module (which may be the
  // only one given).
  auto FromFile = [](const NativeModule *M) { return !M->File.empty(); };
  return llvm::any_of(AllNatives, FromFile) || (World && FromFile(World));
}

bool bsc::checkBehavior(llvm::ArrayRef<ModuleAST *> Modules, ASTContext &Ctx,
                        DiagnosticEngine &Diags, Behavior &Out,
                        const NativeRegistry *Natives,
                        ModuleFileFinder FindModuleFile,
                        std::vector<UnboundName> *Unbound) {
  Sema S(Ctx, Diags, Out, Natives);
  S.FindModuleFile = FindModuleFile;
  S.Unbound = Unbound;
  return S.run(Modules);
}

bool bsc::isCallableFromC(const CallableDecl &D) {
  for (const ParamDecl *P : D.Params)
    if (!P->Ty || !(P->Ty->isInt() || P->Ty->isFloat() || P->Ty->isBool()))
      return false;
  const auto *F = llvm::dyn_cast<FuncDecl>(&D);
  return !(F && F->ResultTy && F->ResultTy->isClass());
}

std::vector<const CallableDecl *> bsc::findBehaviorRoots(const Behavior &B) {
  llvm::DenseSet<const CallableDecl *> Called;
  for (const CallSite &Call : B.Calls)
    Called.insert(Call.Callee);
  std::vector<const CallableDecl *> Roots;
  for (const ModuleAST *M : B.Modules)
    for (const CallableDecl *D : M->Decls)
      if (!Called.count(D) && isCallableFromC(*D))
        Roots.push_back(D);
  return Roots;
}
