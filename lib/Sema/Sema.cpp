//===- Sema.cpp - checking a behavior: entry, module tables, lookup -------===//
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
#include "llvm/ADT/StringSwitch.h"

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

LookupResult Sema::lookup(const QualifiedName &N, LookupMode Mode) {
  if (N.empty())
    return {};
  if (!N.isQualified())
    return lookupUnqualified(N.Parts[0], Mode);
  return lookupQualified(N);
}

LookupResult Sema::lookupUnqualified(const Ident &Id, LookupMode Mode) {
  LookupResult R = findUnqualified(Id.Name, Mode);
  if (R.Kind != LookupKind::Error)
    return R;
  llvm::StringRef Name = Id.Name;
  diag(Id.Loc, Mode == LookupMode::Type ? diag::err_unknown_type
                                        : diag::err_undeclared_name)
      << Name << Id.getRange();
  if (Mode != LookupMode::Value)
    return R;
  // An enumerator written without its enum (`playDead` for
  // `SoccerState::playDead`): enumerators are always qualified
  // (docs/language.md, Enums), so name the spellings that are.
  std::vector<std::pair<std::string, std::string>> Enums =
      findEnumsWithValue(Name);
  for (const auto &[Enum, Spelling] : Enums)
    diag(Id.Loc, diag::note_enumerator_unqualified)
        << Name << Enum << Spelling << llvm::SMFixIt(Id.getRange(), Spelling);
  if (Enums.empty())
    if (std::optional<std::string> Near = findNearValueName(Name))
      diag(Id.Loc, diag::note_did_you_mean)
          << *Near << llvm::SMFixIt(Id.getRange(), *Near);
  return R;
}

std::vector<std::pair<std::string, std::string>>
Sema::findEnumsWithValue(llvm::StringRef Name) {
  std::vector<std::pair<std::string, std::string>> Found;
  // `Prefix` is how this module spells the enum's qualifier.
  auto Consider = [&](const std::string &Prefix, const NativeEnum &E) {
    for (const NativeEnum::Value &V : E.Values)
      if (V.Name == Name)
        Found.push_back({Prefix + E.Name, Prefix + E.Name + "::" + V.Name});
  };
  for (const auto &Entry : CurModule->Enums)
    Consider("", Entry.getValue()->Values);
  for (const auto &Entry : CurModule->Requires) {
    const RequireDecl *R = Entry.getValue();
    std::string Prefix = R->Name + "::";
    if (R->Native)
      for (const NativeEnum &E : R->Native->Enums)
        Consider(Prefix, E);
    else if (ModuleInfo *Info = R->Script ? InfoOf.lookup(R->Script) : nullptr)
      for (const auto &E : Info->Enums)
        Consider(Prefix, E.getValue()->Values);
  }
  // The world module's enums are visible unqualified (bindings.md), unless
  // a name of this module hides them.
  if (World && !CurModule->Requires.count(World->Name))
    for (const NativeEnum &E : World->Enums) {
      bool Hidden = CurModule->Decls.count(E.Name) ||
                    CurModule->Consts.count(E.Name) ||
                    CurModule->Enums.count(E.Name);
      Consider(Hidden ? World->Name + "::" : "", E);
    }
  for (llvm::StringRef State : {"done", "running", "failure"})
    if (Name == State)
      Found.push_back({"TaskState", "TaskState::" + State.str()});
  return Found;
}

LookupResult Sema::findUnqualified(llvm::StringRef Name, LookupMode Mode) {
  LookupResult R;
  if (Mode == LookupMode::Type) {
    const Type *Builtin = llvm::StringSwitch<const Type *>(Name)
                              .Case("int", Types.getInt())
                              .Case("float", Types.getFloat())
                              .Case("bool", Types.getBool())
                              .Case("string", Types.getString())
                              .Case("TaskState", Types.getTaskState())
                              .Default(nullptr);
    if (Builtin) {
      R.Kind = LookupKind::TypeName;
      R.Ty = Builtin;
      return R;
    }
  } else if (Decl *D = findVisible(Name)) {
    if (auto *V = llvm::dyn_cast<VarDecl>(D)) {
      R.Kind = LookupKind::Local;
      R.Var = V;
    } else {
      R.Kind = LookupKind::Param;
      R.Param = llvm::cast<ParamDecl>(D);
    }
    return R;
  }

  // An enum before the module's other names: a func or constant of the
  // same name is a redefinition, reported once, and types stay usable.
  if (EnumDecl *E = CurModule->Enums.lookup(Name)) {
    R.Kind = LookupKind::TypeName;
    R.Ty = E->Ty;
    return R;
  }
  if (const TaskDecl *Nesting = getNestingTask())
    for (FuncDecl *F : Nesting->NestedFuncs)
      if (F->getName().Name == Name) {
        R.Kind = LookupKind::Callable;
        R.Callable = F;
        return R;
      }
  auto It = CurModule->Decls.find(Name);
  if (It != CurModule->Decls.end()) {
    R.Kind = LookupKind::Callable;
    R.Callable = It->second;
    return R;
  }
  if (ConstDecl *C = CurModule->Consts.lookup(Name)) {
    R.Kind = LookupKind::Constant;
    R.Const = C;
    return R;
  }
  if (Name == "input" || Name == "output") {
    R.Kind = Name == "input" ? LookupKind::Input : LookupKind::Output;
    return R;
  }
  if (Name == CurModule->AST->Name || CurModule->Requires.count(Name)) {
    R.Kind = LookupKind::Module;
    return R;
  }
  if (const Type *E = findRequiredEnum(Name)) {
    R.Kind = LookupKind::TypeName;
    R.Ty = E;
    return R;
  }
  if (const Type *C = findWorldClass(Name)) {
    R.Kind = LookupKind::TypeName;
    R.Ty = C;
    return R;
  }
  // The world module's functions and constants, like its classes and
  // enums.
  if (World && Mode == LookupMode::Value) {
    if (const NativeFunction *F = World->findFunction(Name)) {
      R.Kind = LookupKind::NativeFn;
      R.NativeFn = F;
      return R;
    }
    if (const NativeConstant *C = World->findConstant(Name)) {
      R.Kind = LookupKind::Constant;
      R.Const = getNativeConstant(*C);
      return R;
    }
  }
  if (Mode == LookupMode::Value && Name == "TaskState") {
    R.Kind = LookupKind::TypeName;
    R.Ty = Types.getTaskState();
    return R;
  }
  return R; // Not found: Kind Error, nothing reported.
}

namespace {
/// The candidate nearest to a misspelt name. Clang's rule of thumb: at most
/// one edit per three characters (rounded up), and fewer edits than the
/// name has characters (`i` is not a typo of `p`).
class NearestName {
public:
  explicit NearestName(llvm::StringRef Name)
      : Name(Name),
        Best(std::min<size_t>((Name.size() + 2) / 3, Name.size() - 1) + 1) {}
  void consider(llvm::StringRef Candidate) {
    if (Candidate.empty() || Candidate == Name)
      return;
    unsigned D = Name.edit_distance(Candidate, true, Best);
    if (D < Best) {
      Best = D;
      Result = Candidate.str();
    }
  }
  const std::optional<std::string> &get() const { return Result; }

private:
  llvm::StringRef Name;
  unsigned Best; ///< One more than what a candidate may need.
  std::optional<std::string> Result;
};
} // namespace

void Sema::suggestNearest(const Ident &Id,
                          llvm::ArrayRef<llvm::StringRef> Candidates) {
  NearestName Near(Id.Name);
  for (llvm::StringRef C : Candidates)
    Near.consider(C);
  if (Near.get())
    diag(Id.Loc, diag::note_did_you_mean)
        << *Near.get() << llvm::SMFixIt(Id.getRange(), *Near.get());
}

std::optional<std::string> Sema::findNearValueName(llvm::StringRef Name) {
  NearestName Near(Name);
  auto Consider = [&](llvm::StringRef Candidate) { Near.consider(Candidate); };
  for (const Scope &S : Scopes)
    for (const auto &Entry : S)
      Consider(Entry.first);
  if (CurTask)
    for (FuncDecl *F : CurTask->NestedFuncs)
      Consider(F->getName().Name);
  for (const auto &Entry : CurModule->Decls)
    Consider(Entry.getKey());
  for (const auto &Entry : CurModule->Consts)
    Consider(Entry.getKey());
  for (const auto &Entry : CurModule->Enums)
    Consider(Entry.getKey());
  for (const auto &Entry : CurModule->Requires)
    Consider(Entry.getKey());
  // `True`, `FALSE`: Python's and C's spellings of the literals.
  for (llvm::StringRef Literal : {"true", "false"})
    if (Name.equals_insensitive(Literal))
      return Literal.str();
  if (World || Repl) {
    Consider("input");
    Consider("output");
  }
  if (World) {
    for (const NativeFunction &F : World->Functions)
      Consider(F.Name);
    for (const NativeConstant &C : World->Constants)
      Consider(C.Name);
  }
  return Near.get();
}

LookupResult Sema::lookupEnumValue(const Type *ValueTy,
                                   const NativeEnum *Values,
                                   llvm::StringRef EnumName,
                                   const Ident &Value) {
  LookupResult R;
  if (!Values) {
    int32_t V = 0;
    bool Found = true;
    if (Value.Name == "done")
      V = 0;
    else if (Value.Name == "running")
      V = 1;
    else if (Value.Name == "failure")
      V = -1;
    else
      Found = false;
    if (Found) {
      R.Kind = LookupKind::EnumValue;
      R.Ty = ValueTy;
      R.Value = V;
      R.BuiltinState = true;
      return R;
    }
  } else {
    for (const NativeEnum::Value &NV : Values->Values)
      if (NV.Name == Value.Name) {
        R.Kind = LookupKind::EnumValue;
        R.Ty = ValueTy;
        R.Value = NV.Number;
        return R;
      }
  }
  diag(Value.Loc, diag::err_no_enum_value) << EnumName << Value.Name
                                           << Value.getRange();
  llvm::SmallVector<llvm::StringRef, 8> Names;
  if (!Values)
    Names = {"done", "running", "failure"};
  else
    for (const NativeEnum::Value &NV : Values->Values)
      Names.push_back(NV.Name);
  suggestNearest(Value, Names);
  return R;
}

/// The first `Count` parts of `N` joined with `::` (`M::E` of `M::E::v`).
static std::string joinParts(const QualifiedName &N, size_t Count) {
  std::string S;
  for (size_t I = 0; I != Count; ++I)
    S += (I ? "::" : "") + N.Parts[I].Name.str();
  return S;
}

bool Sema::reportMemberOfNonEnum(const QualifiedName &N) {
  if (N.Parts.size() != 3)
    return false;
  diag(N.Parts[0].Loc, diag::err_unknown_qualifier) << joinParts(N, 2);
  return true;
}

QualifierModule Sema::findQualifierModule(llvm::StringRef Name) {
  QualifierModule QM;
  if (Name == CurModule->AST->Name) {
    QM.Kind = QualifierModule::Script;
    QM.ScriptModule = CurModule->AST;
    return QM;
  }
  auto It = CurModule->Requires.find(Name);
  if (It != CurModule->Requires.end()) {
    const RequireDecl *Req = It->second;
    if (Req->Script) {
      QM.Kind = QualifierModule::Script;
      QM.ScriptModule = Req->Script;
    } else if (Req->Native) {
      QM.Kind = QualifierModule::Native;
      QM.NativeMod = Req->Native;
    } else {
      QM.Kind = QualifierModule::Poison;
    }
  } else if (World && Name == World->Name) {
    QM.Kind = QualifierModule::Native;
    QM.NativeMod = World;
  } else if (Repl) {
    QM = findReplModule(Name);
  }
  return QM;
}

LookupResult Sema::lookupQualified(const QualifiedName &N) {
  const Ident &Q = N.Parts[0];
  QualifierModule QM = findQualifierModule(Q.Name);
  if (N.Parts.size() > 3) {
    if (QM.Kind != QualifierModule::Poison)
      diag(Q.Loc, diag::err_unknown_qualifier)
          << joinParts(N, N.Parts.size() - 1);
    return LookupResult();
  }
  switch (QM.Kind) {
  case QualifierModule::Poison:
    return LookupResult();
  case QualifierModule::Script:
    return lookupInScriptModule(N, *InfoOf[QM.ScriptModule]);
  case QualifierModule::Native:
    return lookupInNativeModule(N, *QM.NativeMod);
  case QualifierModule::None:
    return lookupInEnumQualifier(N);
  }
  llvm_unreachable("unknown qualifier kind");
}

LookupResult Sema::lookupInScriptModule(const QualifiedName &N,
                                        const ModuleInfo &Mod) {
  LookupResult R;
  const Ident &Q = N.Parts[0], &Second = N.Parts[1];
  if (EnumDecl *E = Mod.Enums.lookup(Second.Name)) {
    if (N.Parts.size() == 3)
      return lookupEnumValue(E->Ty, &E->Values, joinParts(N, 2), N.Parts[2]);
    R.Kind = LookupKind::TypeName;
    R.Ty = E->Ty;
    return R;
  }
  if (ConstDecl *C = Mod.Consts.lookup(Second.Name)) {
    if (reportMemberOfNonEnum(N))
      return R;
    R.Kind = LookupKind::Constant;
    R.Const = C;
    return R;
  }
  auto It = Mod.Decls.find(Second.Name);
  if (It == Mod.Decls.end()) {
    diag(Second.Loc, diag::err_no_member_in_module)
        << Q.Name << Second.Name << Second.getRange();
    llvm::SmallVector<llvm::StringRef, 16> Names;
    for (const auto &Entry : Mod.Decls)
      Names.push_back(Entry.getKey());
    for (const auto &Entry : Mod.Consts)
      Names.push_back(Entry.getKey());
    for (const auto &Entry : Mod.Enums)
      Names.push_back(Entry.getKey());
    suggestNearest(Second, Names);
    return R;
  }
  if (reportMemberOfNonEnum(N))
    return R;
  R.Kind = LookupKind::Callable;
  R.Callable = It->second;
  return R;
}

LookupResult Sema::lookupInNativeModule(const QualifiedName &N,
                                        const NativeModule &Mod) {
  LookupResult R;
  const Ident &Q = N.Parts[0], &Second = N.Parts[1];
  llvm::StringRef Member = Second.Name;
  if (const NativeClass *Cls = Mod.findClass(Member)) {
    if (reportMemberOfNonEnum(N))
      return R;
    R.Kind = LookupKind::TypeName;
    R.Ty = Types.getClass(Cls);
    return R;
  }
  if (const NativeEnum *E = Mod.findEnum(Member)) {
    const Type *Ty = getEnumType(Mod, *E);
    if (N.Parts.size() == 3)
      return lookupEnumValue(Ty, joinParts(N, 2), N.Parts[2]);
    R.Kind = LookupKind::TypeName;
    R.Ty = Ty;
    return R;
  }
  if (const NativeConstant *C = Mod.findConstant(Member)) {
    if (reportMemberOfNonEnum(N))
      return R;
    R.Kind = LookupKind::Constant;
    R.Const = getNativeConstant(*C);
    return R;
  }
  const NativeFunction *F = Mod.findFunction(Member);
  if (!F) {
    reportNoNativeMember(Q, Second, Mod);
    return R;
  }
  if (reportMemberOfNonEnum(N))
    return R;
  R.Kind = LookupKind::NativeFn;
  R.NativeFn = F;
  return R;
}

void Sema::reportNoNativeMember(const Ident &Q, const Ident &Member,
                                const NativeModule &Mod) {
  if (const UnusableMember *U = findUnusable(Mod.Unusable, Member.Name)) {
    diag(Member.Loc, diag::err_member_unusable)
        << Q.Name.str() + "::" + U->Name << U->Reason << Member.getRange();
    return;
  }
  diag(Member.Loc, diag::err_no_member_in_module)
      << Q.Name << Member.Name << Member.getRange();
  llvm::SmallVector<llvm::StringRef, 16> Names;
  for (const NativeFunction &NF : Mod.Functions)
    Names.push_back(NF.Name);
  for (const NativeConstant &NC : Mod.Constants)
    Names.push_back(NC.Name);
  for (const NativeEnum &NE : Mod.Enums)
    Names.push_back(NE.Name);
  for (const NativeClass &NC : Mod.Classes)
    Names.push_back(NC.Name);
  suggestNearest(Member, Names);
}

LookupResult Sema::lookupInEnumQualifier(const QualifiedName &N) {
  // Not a module: an enum of this module, TaskState, or an enum of a
  // required native module.
  const Ident &Q = N.Parts[0];
  const Type *EnumTy = nullptr;
  const NativeEnum *Values = nullptr; // TaskState's own names.
  if (EnumDecl *E = CurModule->Enums.lookup(Q.Name)) {
    EnumTy = E->Ty;
    Values = &E->Values;
  } else if (Q.Name == "TaskState") {
    EnumTy = Types.getTaskState();
  } else if ((EnumTy = findRequiredEnum(Q.Name))) {
    Values = EnumTy->getEnum();
  }
  if (!EnumTy) {
    reportUnknownQualifier(Q);
    return LookupResult();
  }
  if (reportMemberOfNonEnum(N))
    return LookupResult();
  return lookupEnumValue(EnumTy, Values, Q.Name, N.Parts[1]);
}

void Sema::reportUnknownQualifier(const Ident &Q) {
  // A module loaded for another file, or a file the loader would find.
  if (KnownModules.count(Q.Name) ||
      (FindModuleFile && FindModuleFile(*CurModule->AST, Q.Name))) {
    diag(Q.Loc, diag::err_module_not_required) << Q.Name << Q.getRange();
    return;
  }
  // One error per unknown qualifier: its other uses have the same cause.
  if (!ReportedQualifiers.insert(Q.Name).second)
    return;
  // Without any native module from a file, the likeliest cause is a
  // missing --bind, not a typo.
  if (Unbound && !hasBindingModules()) {
    noteUnbound({UnboundName::Qualifier, Q.Name.str(), Q.getRange(), ""});
    return;
  }
  diag(Q.Loc, diag::err_unknown_qualifier) << Q.Name << Q.getRange();
  if (!hasBindingModules()) {
    if (!NotedUnbound)
      diag(Q.Loc, diag::note_maybe_unbound) << Q.Name;
    NotedUnbound = true;
    return;
  }
  suggestNearest(Q, getQualifierNames());
}

llvm::SmallVector<llvm::StringRef, 16> Sema::getQualifierNames() {
  // Modules, TaskState, enums.
  llvm::SmallVector<llvm::StringRef, 16> Names = {CurModule->AST->Name,
                                                  "TaskState"};
  for (const auto &Entry : CurModule->Enums)
    Names.push_back(Entry.getKey());
  for (const auto &Entry : CurModule->Requires)
    Names.push_back(Entry.getKey());
  for (const RequireDecl &Req : CurModule->AST->Requires)
    if (Req.Native)
      for (const NativeEnum &NE : Req.Native->Enums)
        Names.push_back(NE.Name);
  if (World) {
    Names.push_back(World->Name);
    for (const NativeEnum &NE : World->Enums)
      Names.push_back(NE.Name);
  }
  return Names;
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
