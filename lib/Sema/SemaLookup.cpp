//===- SemaLookup.cpp - what a name denotes -------------------------------===//
//
// Every name in a behavior is resolved here, once, into a LookupResult that
// the checks of expressions, types and calls act on; Sema.cpp's header
// states the rules. A name that resolves to nothing is reported here with
// what may have been meant (`did you mean`, the enum an unqualified
// enumerator belongs to, a missing `requires` or --bind), then answered as
// poison, so the caller adds no second message.
//
// Qualified names go in steps: the module the qualifier names, then the
// member of that script or native module, or else a value of the enum the
// qualifier names; a qualifier that names neither is reported once.
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"
#include "llvm/ADT/StringSwitch.h"

using namespace bsc;
using namespace bsc::sema;

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
