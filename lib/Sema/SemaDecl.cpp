//===- SemaDecl.cpp - types, signatures, locals and callable bodies -------===//
//
// Types are resolved by name at module level only (built-ins, TaskState,
// enums of required native modules, classes and enums of native modules by
// `M::Name`, and the world module's unqualified); locals never name types. Signatures
// are resolved in a pass of their own before any body, so a call can be
// checked against a callee declared later or in another module.
//
// Scopes are a stack of small vectors searched from the top: b-script bodies
// are short, so a linear search beats hashing, and the stack makes "visible
// from the declaration to the end of the block" fall out of push/pop. A
// nested func is checked at the point of its declaration with the task's
// scopes still on the stack, which is exactly the "params and top-level
// locals declared before the func" rule.
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"

using namespace bsc;
using namespace bsc::sema;

const Type *Sema::resolveType(const QualifiedName &N) {
  LookupResult L = lookup(N, LookupMode::Type);
  switch (L.Kind) {
  case LookupKind::Error:
    return Types.getError();
  case LookupKind::TypeName:
    if (L.Ty->isClass())
      Out.UsesClasses = true;
    return L.Ty;
  case LookupKind::Local:
  case LookupKind::Param:
  case LookupKind::Callable:
  case LookupKind::NativeFn:
  case LookupKind::EnumValue:
  case LookupKind::Constant:
  case LookupKind::Input:
  case LookupKind::Output:
  case LookupKind::Module:
    break;
  }
  diag(N.getLoc(), diag::err_not_a_type) << N.str() << N.getRange();
  // `task Activity(Activity a)`: the task hides the world's enum.
  if (!N.isQualified()) {
    const Type *Hidden = findRequiredEnum(N.Parts[0].Name);
    if (!Hidden)
      Hidden = findWorldClass(N.Parts[0].Name);
    if (Hidden)
      diag(N.getLoc(), diag::note_type_hidden)
          << N.str() << Hidden->getName()
          << llvm::SMFixIt(N.getRange(), Hidden->getName().str());
  }
  return Types.getError();
}

const Type *Sema::resolveNativeType(const NativeType &T) {
  const Type *Element = resolveNativeElementType(T);
  if (Element->isError())
    return Element;
  // `float m[3][3]`: an array of 3 arrays of 3 floats.
  for (uint32_t Extent : llvm::reverse(T.Extents))
    Element = Types.getArray(Element, Extent);
  return Element;
}

const Type *Sema::resolveNativeElementType(const NativeType &T) {
  switch (T.TheCode) {
  case NativeType::Void:
    return Types.getVoid();
  case NativeType::Bool:
    return Types.getBool();
  case NativeType::Int:
    return Types.getInt();
  case NativeType::Float:
    return Types.getFloat();
  case NativeType::String:
    return Types.getString();
  case NativeType::Enum: {
    if (T.TheEnum && T.TheEnum->Module)
      return getEnumType(*T.TheEnum->Module, *T.TheEnum);
    llvm::StringRef Name = T.Name;
    auto [ModName, EnumName] = Name.rsplit("::");
    for (const NativeModule *M : AllNatives)
      if (M->Name == ModName)
        if (const NativeEnum *E = M->findEnum(EnumName))
          return getEnumType(*M, *E);
    // An enum of a module this behavior does not load: unusable, but the
    // binding was checked when it was registered, so stay silent.
    return Types.getError();
  }
  case NativeType::Class:
    // Binding modules always resolve their class types (lib/Bind).
    if (T.TheClass)
      return Types.getClass(T.TheClass);
    return Types.getError();
  }
  llvm_unreachable("unknown native type code");
}

void Sema::checkCopyable(const Type *T, llvm::SMRange R, llvm::StringRef What,
                         bool Assigns) {
  if (!T || !T->isClass())
    return;
  const NativeClass *C = T->getClass();
  // CodeGen copy-constructs with the copy thunk, and assigns with the
  // assign thunk or else by destroying and copy-constructing.
  if (C->CopiesAsBytes || !C->Copy.empty() || (Assigns && !C->Assign.empty()))
    return;
  diag(R.Start, diag::err_class_not_copyable) << T->getName() << What << R;
}

void Sema::checkDefaultConstructible(const Type *T, llvm::SMRange R,
                                     llvm::StringRef Fix) {
  if (!T || !T->isClass())
    return;
  const NativeClass *C = T->getClass();
  // Zero bytes are a value of a class that copies as bytes and needs no
  // destruction (C++20's implicit-lifetime types), so such a class may
  // start zeroed; any other class must be constructed before its
  // assignment, copy or destructor runs on it.
  if (C->DefaultConstructible ||
      (C->CopiesAsBytes && C->TriviallyDestructible))
    return;
  diag(R.Start, diag::err_class_not_default_constructible)
      << T->getName() << Fix << R;
}

/// Why a task's class parameters and locals need a default constructor.
static constexpr llvm::StringLiteral TaskConstructsAtStart =
    "a task constructs its parameters and locals when it starts, so register "
    "a default constructor for it, or pass it to a func instead";

void Sema::checkSignature(CallableDecl *C) {
  // Every call copies its arguments into the parameters: a func's own
  // copies (copy-constructed), a task's in its frame (assigned).
  const ParamDecl *FirstDefaulted = nullptr;
  for (ParamDecl *P : C->Params) {
    P->Ty = resolveType(P->TypeName);
    checkCopyable(P->Ty, P->TypeName.getRange(), "a parameter",
                  /*Assigns=*/llvm::isa<TaskDecl>(C));
    if (llvm::isa<TaskDecl>(C))
      checkDefaultConstructible(P->Ty, P->TypeName.getRange(),
                                TaskConstructsAtStart);
    checkDefaultArg(P);
    // Defaults are trailing: a call leaves out a tail of the arguments.
    if (P->Default && !FirstDefaulted)
      FirstDefaulted = P;
    else if (!P->Default && FirstDefaulted)
      diag(P->getName().Loc, diag::err_default_not_trailing)
          << P->getName().Name << FirstDefaulted->getName().Name
          << P->getName().getRange();
  }
  if (auto *F = llvm::dyn_cast<FuncDecl>(C))
    F->ResultTy = F->ResultTypeName.empty() ? Types.getVoid()
                                            : resolveType(F->ResultTypeName);
}

Decl *Sema::findVisible(llvm::StringRef Name) {
  for (auto S = Scopes.rbegin(), E = Scopes.rend(); S != E; ++S)
    for (auto It = S->rbegin(), IE = S->rend(); It != IE; ++It)
      if (It->first == Name)
        return It->second;
  return nullptr;
}

void Sema::declare(Decl *D) {
  const Ident &Name = D->getName();
  if (Decl *Prev = findVisible(Name.Name)) {
    // The same scope: declared twice; an enclosing one: hidden (b-script
    // allows neither, but they are different mistakes).
    bool SameScope = llvm::any_of(
        Scopes.back(), [&](const auto &Entry) { return Entry.second == Prev; });
    diag(Name.Loc, SameScope ? diag::err_redefinition : diag::err_shadowing)
        << Name.Name << Name.getRange();
    diag(Prev->getName().Loc, diag::note_previous_definition);
  }
  // Declared even after an error, so later uses find the newest one.
  Scopes.back().push_back({Name.Name, D});
  if (auto *V = llvm::dyn_cast<VarDecl>(D))
    V->ScopeBegin = ++ScopeClock;
}

void Sema::popScope() {
  ++ScopeClock;
  for (auto &[Name, D] : Scopes.back())
    if (auto *V = llvm::dyn_cast<VarDecl>(D))
      V->ScopeEnd = ScopeClock;
  Scopes.pop_back();
}

void Sema::checkVarDecl(VarDecl *V) {
  V->Owner = CurCallable;
  CurCallable->Locals.push_back(V);
  V->Ty = resolveType(V->TypeName);
  // The initializer is checked before the variable is visible: `int x = x`
  // reads an outer `x` (and is then a shadowing error anyway).
  if (V->Init) {
    const Type *InitTy = checkExpr(V->Init);
    if (!V->Ty->isError() && !InitTy->isError() &&
        !convertImplicitly(V->Init, V->Ty))
      diag(V->Init->getLoc(), diag::err_init_type_mismatch)
          << V->getName().Name << V->Ty->getName() << InitTy->getName()
          << V->Init->getRange();
    else if (!V->Ty->isError() && !InitTy->isError())
      // A task's local is constructed at the reset and assigned here.
      checkCopyable(V->Ty, V->Init->getRange(), "an initialiser",
                    /*Assigns=*/llvm::isa<TaskDecl>(CurCallable));
  }
  if (llvm::isa<TaskDecl>(CurCallable))
    checkDefaultConstructible(V->Ty, V->TypeName.getRange(),
                              TaskConstructsAtStart);
  else if (!V->Init)
    checkDefaultConstructible(V->Ty, V->TypeName.getRange(),
                              ("give '" + V->getName().Name +
                               "' an initial value")
                                  .str());
  declare(V);
}

void Sema::checkCallableBody(CallableDecl *C) {
  CallableDecl *SavedCallable = CurCallable;
  unsigned SavedLoopDepth = LoopDepth;
  CurCallable = C;
  LoopDepth = 0;

  pushScope();
  for (ParamDecl *P : C->Params)
    declare(P);
  if (C->Body)
    checkBlock(C->Body);
  popScope();

  if (auto *F = llvm::dyn_cast<FuncDecl>(C))
    checkMissingReturn(F);
  CurCallable = SavedCallable;
  LoopDepth = SavedLoopDepth;
}

void Sema::checkNestedFunc(FuncDecl *F) {
  // Only a func the parser recorded as nested in the current task is
  // checked here; a misplaced one was diagnosed by the parser.
  if (!CurTask || F->EnclosingTask != CurTask || CurCallable != CurTask ||
      !CheckedNested.insert(F).second)
    return;
  checkCallableBody(F);
}

void Sema::checkTopLevelCallable(CallableDecl *C) {
  Scopes.clear();
  CurTask = llvm::dyn_cast<TaskDecl>(C);
  checkCallableBody(C);
  if (CurTask) {
    // A nested func the task body did not reach (it sat where the parser
    // refused it) still gets its fields filled in, seeing the task's params.
    for (FuncDecl *F : CurTask->NestedFuncs) {
      if (CheckedNested.count(F))
        continue;
      CheckedNested.insert(F);
      pushScope();
      for (ParamDecl *P : CurTask->Params)
        Scopes.back().push_back({P->getName().Name, P});
      checkCallableBody(F);
      popScope();
    }
    markLocalsUsedBeforeDeclared();
  }
  CurTask = nullptr;
  CurCallable = nullptr;
}
