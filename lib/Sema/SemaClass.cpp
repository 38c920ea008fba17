//===- SemaClass.cpp - members, methods and operators of C++ classes ------===//
//
// Registered C++ classes are value types whose members come from the
// binding (Native.h): fields and properties are read with `v.f` and written
// with `v.f = x` (unless read-only), methods are called with `v.m(...)`,
// and the operators of docs/bindings.md ("Operator names") call methods of
// fixed names on the left operand. Everything resolved here is recorded in
// the tree (MemberExpr::Resolved, CallExpr::NativeFn with CallKind::Method,
// UnaryExpr/BinaryExpr::Operator), so CodeGen never looks a member up.
//
// Class-scope functions (registered functions without an object parameter)
// are not members of values: `v.f()` for one of them is err_no_member.
//
// A method that is not const modifies its object, so its object is checked
// like an assignment target: not `input` (or a part of it), not a task
// parameter, and not reached through a read-only member. The check walks
// the member chain after the method is known (the object's type must be
// known before the method can be found); checkIOAccess still makes the call
// on `input`.
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"

using namespace bsc;
using namespace bsc::sema;

const NativeFunction *Sema::findValueMember(const Type *ClassTy,
                                            const Ident &Name) {
  const NativeFunction *M = ClassTy->getClass()->findMember(Name.Name);
  if (!M)
    if (const UnusableMember *U =
            findUnusable(ClassTy->getClass()->Unusable, Name.Name)) {
      diag(Name.Loc, diag::err_member_unusable)
          << (ClassTy->getName() + "." + U->Name).str() << U->Reason
          << Name.getRange();
      return nullptr;
    }
  if (!M || !M->hasSelf()) {
    diag(Name.Loc, diag::err_no_member)
        << ClassTy->getName() << Name.Name << Name.getRange();
    if (!M) {
      llvm::SmallVector<llvm::StringRef, 16> Names;
      for (const NativeFunction &F : ClassTy->getClass()->Members)
        if (F.hasSelf() && !llvm::StringRef(F.Name).starts_with("_"))
          Names.push_back(F.Name);
      suggestNearest(Name, Names);
    }
    return nullptr;
  }
  return M;
}

bool Sema::resolveMethodCallee(CallExpr *C, MemberExpr *M) {
  const Type *BaseTy = checkExpr(M->Base, Access::MethodBase);
  if (BaseTy->isError())
    return false;
  if (!BaseTy->isClass()) {
    diag(M->Base->getLoc(), diag::err_member_of_non_class)
        << getText(M->Base) << BaseTy->getName() << M->Base->getRange();
    return false;
  }
  const NativeFunction *F = findValueMember(BaseTy, M->Member);
  if (!F)
    return false;
  M->Resolved = F;
  if (F->Kind != NativeFunction::Method) {
    diag(M->getLoc(), diag::err_not_callable) << getText(M) << M->getRange();
    return false;
  }
  if (!F->ConstSelf)
    checkMutatingMethodBase(M->Base, *F);
  C->Kind = CallKind::Method;
  C->NativeFn = F;
  return true;
}

void Sema::checkMutatingMethodBase(Expr *Base, const NativeFunction &Method) {
  Expr *Cur = Base;
  while (llvm::isa<MemberExpr, IndexExpr>(Cur)) {
    if (auto *IE = llvm::dyn_cast<IndexExpr>(Cur)) {
      Cur = IE->Base;
      continue;
    }
    auto *ME = llvm::cast<MemberExpr>(Cur);
    if (ME->Resolved && ME->Resolved->ReadOnly) {
      diag(ME->Member.Loc, diag::err_read_only_member)
          << ME->Resolved->Name << ME->Base->Ty->getName() << ME->getRange();
      return;
    }
    Cur = ME->Base;
  }
  // Other roots (call results, operator results) are temporaries.
  auto *N = llvm::dyn_cast<NameExpr>(Cur);
  if (!N)
    return;
  switch (N->Kind) {
  case NameKind::Input:
    checkIOAccess(N, /*IsInput=*/true, Access::MutatingMethodBase, Method.Name);
    return;
  case NameKind::Param:
    checkParamAccess(N, N->Param, Access::MutatingMethodBase);
    return;
  case NameKind::Output: // Rejected as a read already.
  case NameKind::Local:
  case NameKind::Unresolved:
  case NameKind::Callable:
  case NameKind::NativeFunction:
  case NameKind::EnumValue:
  case NameKind::Constant:
    return;
  }
}

/// The method an operator on a class value calls (docs/bindings.md).
static llvm::StringRef getOperatorMethod(BinaryOp Op) {
  switch (Op) {
  case BinaryOp::Add:
    return "_plus_";
  case BinaryOp::Sub:
    return "_min_";
  case BinaryOp::Mul:
    return "_mul_";
  case BinaryOp::Div:
    return "_div_";
  case BinaryOp::Rem:
    return "_mod_";
  case BinaryOp::Lt:
    return "_lt_";
  case BinaryOp::Le:
    return "_le_";
  case BinaryOp::Gt:
    return "_gt_";
  case BinaryOp::Ge:
    return "_ge_";
  case BinaryOp::Eq:
    return "_eq_";
  case BinaryOp::Ne:
    return "_ne_";
  case BinaryOp::And:
  case BinaryOp::Or:
    break;
  }
  return "";
}

/// A method of `C` usable as a binary operator: one parameter, a result.
static const NativeFunction *findOperator(const NativeClass &C,
                                          llvm::StringRef Name) {
  if (Name.empty())
    return nullptr;
  const NativeFunction *F = C.findMember(Name);
  if (!F || F->Kind != NativeFunction::Method || F->Params.size() != 1 ||
      F->Result.TheCode == NativeType::Void)
    return nullptr;
  return F;
}

const Type *Sema::checkClassBinary(BinaryExpr *E) {
  const Type *L = E->LHS->Ty, *R = E->RHS->Ty;
  const NativeClass &C = *L->getClass();
  const NativeFunction *F = findOperator(C, getOperatorMethod(E->Op));
  bool Negate = false;
  // `a != b` falls back to `!(a == b)` (docs/bindings.md).
  if (!F && E->Op == BinaryOp::Ne) {
    F = findOperator(C, "_eq_");
    Negate = F && F->Result.TheCode == NativeType::Bool;
    if (!Negate)
      F = nullptr;
  }
  if (!F || !convertImplicitly(E->RHS, resolveNativeType(F->Params[0]))) {
    diag(E->getLoc(), diag::err_binary_operands)
        << getSpelling(E->Op) << L->getName() << R->getName() << E->getRange();
    return Types.getError();
  }
  if (!F->ConstSelf)
    checkMutatingMethodBase(E->LHS, *F);
  E->Operator = F;
  E->NegateOperator = Negate;
  return resolveNativeType(F->Result);
}

const Type *Sema::checkClassUnary(UnaryExpr *E) {
  const Type *T = E->Operand->Ty;
  const NativeFunction *F = T->getClass()->findMember("_neg_");
  if (!F || F->Kind != NativeFunction::Method || F->getMinArgs() != 0 ||
      F->Result.TheCode == NativeType::Void) {
    diag(E->getLoc(), diag::err_unary_operand)
        << getSpelling(E->Op) << T->getName() << E->getRange();
    return Types.getError();
  }
  if (!F->ConstSelf)
    checkMutatingMethodBase(E->Operand, *F);
  E->Operator = F;
  return resolveNativeType(F->Result);
}

Expr *Sema::makeDefaultArg(const NativeDefault &D, const Type *ParamTy,
                           llvm::SMLoc Loc) {
  // The registered value as each scalar type reads it; makeConstantExpr
  // picks the one ParamTy needs.
  ConstantValue V;
  V.Int = D.IsFloat ? int32_t(D.Float) : D.Int;
  V.Float = D.IsFloat ? D.Float : float(D.Int);
  V.Bool = D.IsFloat ? D.Float != 0 : D.Int != 0;
  return makeConstantExpr(V, ParamTy, Loc);
}
