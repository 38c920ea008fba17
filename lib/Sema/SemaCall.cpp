//===- SemaCall.cpp - calls of funcs, tasks, natives and constructors -----===//
//
// A call is checked in steps: resolve the callee to a signature (a script
// func or task, a registered function or method, or the constructor of a
// registered class its arguments choose), check the arguments, fill in
// the missing trailing ones from the defaults, then convert each argument
// to its parameter's type. An argument error notes the callee's
// signature once, with its parameters named.
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/FormatVariadic.h"

using namespace bsc;
using namespace bsc::sema;

void Sema::noteSignature(const CallExpr *C, llvm::StringRef Name,
                         llvm::ArrayRef<const Type *> ParamTys,
                         const Type *ResultTy) {
  // The parameters by name, where the script or the registration names
  // them, so that two swapped arguments of the same type show.
  std::vector<std::string> Params;
  for (size_t I = 0; I < ParamTys.size(); ++I) {
    std::string P = ParamTys[I]->getName().str();
    llvm::StringRef Name;
    if (C->Target)
      Name = C->Target->Params[I]->getName().Name;
    else if (C->NativeFn && I < C->NativeFn->ParamNames.size())
      Name = C->NativeFn->ParamNames[I];
    if (!Name.empty())
      P += " " + Name.str();
    Params.push_back(std::move(P));
  }
  if (!C->Target && !C->NativeFn)
    return;
  std::string Sig =
      (C->Target ? C->Target->getQualifiedName() : C->NativeFn->Name) + "(" +
      llvm::join(Params, ", ") + ")";
  if (ResultTy && !ResultTy->isVoid() && !ResultTy->isError())
    Sig += " : " + ResultTy->getName().str();
  // A registered callee has no line of its own: the note is at the call.
  if (C->Target)
    diag(C->Target->getLoc(), diag::note_callee_signature) << Sig;
  else
    diag(C->getLoc(), diag::note_native_signature) << Name << Sig;
}

CallSignature Sema::resolveNamedCallee(CallExpr *C, NameExpr *N) {
  CallSignature Sig;
  Sig.Name = N->Name.str();
  LookupResult L = lookup(N->Name, LookupMode::Value);
  if (L.Kind == LookupKind::Callable) {
    N->Kind = NameKind::Callable;
    N->Callable = L.Callable;
    C->Target = L.Callable;
    auto *F = llvm::dyn_cast<FuncDecl>(L.Callable);
    C->Kind = F ? CallKind::Func : CallKind::Task;
    for (ParamDecl *P : L.Callable->Params)
      Sig.ParamTys.push_back(P->Ty ? P->Ty : Types.getError());
    Sig.ResultTy =
        F ? (F->ResultTy ? F->ResultTy : Types.getError()) : Types.getVoid();
    recordCall(L.Callable, N->getLoc());
  } else if (L.Kind == LookupKind::NativeFn) {
    N->Kind = NameKind::NativeFunction;
    N->NativeFn = L.NativeFn;
    C->Kind = CallKind::NativeFunction;
    C->NativeFn = L.NativeFn;
  } else if (L.Kind == LookupKind::TypeName && L.Ty->isClass()) {
    // `Math::Pose2f(1.0, 2.0, 0.5)`: the arguments choose a constructor.
    for (Expr *Arg : C->Args)
      checkExpr(Arg);
    Sig.ArgsChecked = true;
    resolveConstructor(C, N, L.Ty);
  } else if (L.Kind != LookupKind::Error) {
    diag(N->getLoc(), diag::err_not_callable) << Sig.Name << N->getRange();
  }
  N->Ty = Sig.ResultTy ? Sig.ResultTy : Types.getError();
  return Sig;
}

CallSignature Sema::resolveCallee(CallExpr *C) {
  CallSignature Sig;
  if (auto *N = llvm::dyn_cast_or_null<NameExpr>(C->Callee)) {
    Sig = resolveNamedCallee(C, N);
  } else if (auto *M = llvm::dyn_cast_or_null<MemberExpr>(C->Callee)) {
    Sig.Name = getText(M);
    if (!resolveMethodCallee(C, M))
      M->Ty = Types.getError();
  } else {
    const Type *T = checkExpr(C->Callee);
    if (!T->isError() && C->Callee)
      diag(C->Callee->getLoc(), diag::err_not_callable)
          << getText(C->Callee) << C->Callee->getRange();
  }

  // A script callee: the parameters before the first with a default.
  Sig.MinArgs = Sig.ParamTys.size();
  if (C->Target)
    Sig.MinArgs = llvm::count_if(
        C->Target->Params, [](const ParamDecl *P) { return !P->Default; });
  // A native callee (module function or method): its registered signature.
  if (const NativeFunction *NF = C->NativeFn) {
    for (const NativeType &P : NF->Params)
      Sig.ParamTys.push_back(resolveNativeType(P));
    Sig.ResultTy = resolveNativeType(NF->Result);
    Sig.MinArgs = NF->getMinArgs();
    C->Callee->Ty = Sig.ResultTy;
  }
  return Sig;
}

void Sema::addDefaultArgs(CallExpr *C, const CallSignature &Sig) {
  // Missing trailing arguments come from the script parameters' defaults
  // or the binding's `.defaults(...)`.
  const NativeFunction *NF = C->NativeFn;
  for (size_t I = C->Args.size(); I != Sig.ParamTys.size(); ++I) {
    llvm::SMLoc End = C->getRange().End;
    Expr *Arg;
    if (NF) {
      Arg = makeDefaultArg(NF->Defaults[I - Sig.MinArgs], Sig.ParamTys[I], End);
    } else {
      const ParamDecl *P = C->Target->Params[I];
      // A default that was refused is poison: reported at the parameter.
      Arg = P->DefaultValue ? makeConstantExpr(*P->DefaultValue, P->Ty, End)
                            : Ctx.create<ErrorExpr>(llvm::SMRange(End, End));
      if (!P->DefaultValue)
        Arg->Ty = Types.getError();
    }
    C->Args.push_back(Arg);
    ++C->NumDefaultArgs;
  }
}

void Sema::convertArgs(CallExpr *C, const CallSignature &Sig) {
  bool Noted = false;
  for (size_t I = 0, E = C->Args.size(); I != E; ++I) {
    if (!C->Args[I])
      continue;
    const Type *ArgTy = C->Args[I]->Ty;
    if (convertImplicitly(C->Args[I], Sig.ParamTys[I]))
      continue;
    diag(C->Args[I]->getLoc(), diag::err_call_arg_type)
        << I + 1 << Sig.Name << Sig.ParamTys[I]->getName() << ArgTy->getName()
        << C->Args[I]->getRange();
    if (!std::exchange(Noted, true))
      noteSignature(C, Sig.Name, Sig.ParamTys, Sig.ResultTy);
  }
}

const Type *Sema::checkCall(CallExpr *C, bool AsStatement) {
  // Resolve the callee; on failure the arguments are still checked.
  CallSignature Sig = resolveCallee(C);
  const NativeFunction *NF = C->NativeFn;
  for (size_t I = 0, E = C->Args.size(); I != E && !Sig.ArgsChecked; ++I) {
    // An argument for a non-const `T&` parameter may be modified.
    bool Modified = NF && I < NF->Params.size() && NF->Params[I].MutableRef;
    checkExpr(C->Args[I], Modified ? Access::Modify : Access::Read);
  }
  const Type *ResultTy = Sig.ResultTy;
  if (!ResultTy)
    return Types.getError();

  size_t NumArgs = C->Args.size(), NumParams = Sig.ParamTys.size();
  if (NumArgs > NumParams || NumArgs < Sig.MinArgs) {
    if (Sig.MinArgs == NumParams)
      diag(C->getLoc(), diag::err_call_arity)
          << Sig.Name << NumParams << NumArgs << C->getRange();
    else
      diag(C->getLoc(), diag::err_call_arity_range)
          << Sig.Name << Sig.MinArgs << NumParams << NumArgs << C->getRange();
    noteSignature(C, Sig.Name, Sig.ParamTys, ResultTy);
  } else {
    addDefaultArgs(C, Sig);
    convertArgs(C, Sig);
  }

  if (AsStatement)
    return ResultTy;
  if (C->Kind == CallKind::Task) {
    diag(C->getLoc(), diag::err_task_call_in_expression)
        << Sig.Name << C->getRange();
    return Types.getError();
  }
  if (ResultTy->isVoid()) {
    diag(C->getLoc(), diag::err_void_value) << Sig.Name << C->getRange();
    return Types.getError();
  }
  return ResultTy;
}

bool Sema::resolveConstructor(CallExpr *C, NameExpr *Callee, const Type *T) {
  const NativeClass *Cls = T->getClass();
  auto Signature = [&](const NativeFunction &Ctor) {
    std::string S = Cls->Name + "(";
    size_t MinArgs = Ctor.getMinArgs();
    for (size_t I = 0; I != Ctor.Params.size(); ++I) {
      const Type *T = resolveNativeType(Ctor.Params[I]);
      S += (I ? ", " : "") + T->getName().str();
      if (I < Ctor.ParamNames.size() && !Ctor.ParamNames[I].empty())
        S += " " + Ctor.ParamNames[I]; // `float x`: the registered name.
      if (I >= MinArgs) { // `= 0.25`: the registered default.
        const NativeDefault &D = Ctor.Defaults[I - MinArgs];
        S += " = " + (D.IsFloat ? llvm::formatv("{0}", D.Float).str()
                                : std::to_string(D.Int));
      }
    }
    return S + ")";
  };
  if (Cls->Constructors.empty()) {
    diag(Callee->getLoc(), diag::err_no_constructor)
        << T->getName() << Callee->getRange();
    return false;
  }
  // The viable constructor that needs the fewest int-to-float conversions;
  // the other b-script conversions are explicit.
  const NativeFunction *Best = nullptr;
  unsigned BestConversions = ~0u;
  bool Ambiguous = false;
  for (const NativeFunction &Ctor : Cls->Constructors) {
    if (C->Args.size() < Ctor.getMinArgs() ||
        C->Args.size() > Ctor.Params.size())
      continue;
    unsigned Conversions = 0;
    bool Viable = true;
    for (size_t I = 0; I != C->Args.size() && Viable; ++I) {
      switch (classifyImplicit(C->Args[I]->Ty,
                               resolveNativeType(Ctor.Params[I]))) {
      case ImplicitConversion::Unchanged:
        break;
      case ImplicitConversion::IntToFloat:
        ++Conversions;
        break;
      case ImplicitConversion::None:
        Viable = false;
        break;
      }
    }
    if (!Viable || Conversions > BestConversions)
      continue;
    Ambiguous = Conversions == BestConversions;
    Best = &Ctor;
    BestConversions = Conversions;
  }
  if (!Best || Ambiguous) {
    std::string Args;
    for (size_t I = 0; I != C->Args.size(); ++I)
      Args += (I ? ", " : "") + C->Args[I]->Ty->getName().str();
    diag(C->getLoc(), Best ? diag::err_ambiguous_constructor
                           : diag::err_no_matching_constructor)
        << T->getName() << Args << C->getRange();
    for (const NativeFunction &Ctor : Cls->Constructors)
      diag(C->getLoc(), diag::note_constructor_candidate) << Signature(Ctor);
    return false;
  }
  Callee->Kind = NameKind::NativeFunction;
  Callee->NativeFn = Best;
  C->Kind = CallKind::NativeFunction;
  C->NativeFn = Best;
  return true;
}
