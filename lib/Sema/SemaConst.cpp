//===- SemaConst.cpp - module constants -----------------------------------===//
//
// `const int KICK = 3` names a value at module scope. Its value must be
// known at compile time: literals, enum values (TaskState's too), other
// constants (of this module, or `M::NAME` of a required one) and the
// operators and conversions on them. Sema computes it here with the
// language's own arithmetic (docs/language.md: int wraps, x / 0 == 0,
// floats are IEEE singles), so code generation only emits the result.
//
// Constants are checked before any signature or body, in module order; a
// constant whose value uses one not checked yet checks that one first
// (switching to its module), and one that reaches itself is an error.
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"
#include <cmath>
#include <cstdint>

using namespace bsc;
using namespace bsc::sema;

namespace {
/// Whether `E` is built only of what a constant's value may contain (its
/// names are checked by lookup); anything else is refused before checkExpr,
/// which expects a func or task around calls and `input`.
bool hasConstantShape(const Expr *E) {
  switch (E->getKind()) {
  case NodeKind::IntLiteralExpr:
  case NodeKind::FloatLiteralExpr:
  case NodeKind::BoolLiteralExpr:
  case NodeKind::StringLiteralExpr:
  case NodeKind::ErrorExpr:
    return true;
  case NodeKind::NameExpr: {
    const auto *N = llvm::cast<NameExpr>(E);
    return N->Name.isQualified() ||
           (N->Name.Parts[0].Name != "input" &&
            N->Name.Parts[0].Name != "output");
  }
  case NodeKind::UnaryExpr:
    return hasConstantShape(llvm::cast<UnaryExpr>(E)->Operand);
  case NodeKind::BinaryExpr:
    return hasConstantShape(llvm::cast<BinaryExpr>(E)->LHS) &&
           hasConstantShape(llvm::cast<BinaryExpr>(E)->RHS);
  case NodeKind::ConversionExpr:
    return hasConstantShape(llvm::cast<ConversionExpr>(E)->Operand);
  default:
    return false;
  }
}

/// int arithmetic as the generated code does it: wrapping, and division
/// without traps (x / 0 == 0, x % 0 == x, INT_MIN / -1 == INT_MIN).
int32_t intArith(BinaryOp Op, int32_t L, int32_t R) {
  uint32_t A = uint32_t(L), B = uint32_t(R);
  switch (Op) {
  case BinaryOp::Add:
    return int32_t(A + B);
  case BinaryOp::Sub:
    return int32_t(A - B);
  case BinaryOp::Mul:
    return int32_t(A * B);
  case BinaryOp::Div:
    if (R == 0)
      return 0;
    if (L == INT32_MIN && R == -1)
      return INT32_MIN;
    return L / R;
  case BinaryOp::Rem:
    if (R == 0)
      return L;
    if (L == INT32_MIN && R == -1)
      return 0;
    return L % R;
  default:
    return 0;
  }
}
} // namespace

void Sema::checkConst(ConstDecl *C) {
  if (C->State == ConstDecl::CheckState::Done)
    return;
  if (C->State == ConstDecl::CheckState::Checking) {
    diag(C->getName().Loc, diag::err_const_cycle) << C->getName().Name;
    C->Ty = nullptr;
    return;
  }
  C->State = ConstDecl::CheckState::Checking;
  ModuleInfo *Outer = CurModule;
  CurModule = InfoOf[C->Module];
  const Type *Ty = resolveType(C->TypeName);
  if (!Ty->isError() && !Ty->isInt() && !Ty->isFloat() && !Ty->isBool() &&
      !Ty->isString() && !Ty->isEnum() && !Ty->isTaskState()) {
    diag(C->TypeName.getLoc(), diag::err_const_type) << Ty->getName();
    Ty = Types.getError();
  }
  std::optional<ConstDecl::ValueFields> Value;
  if (!hasConstantShape(C->Init)) {
    diag(C->Init->getLoc(), diag::err_const_not_constant)
        << C->getName().Name << C->Init->getRange();
  } else {
    const Type *InitTy = checkExpr(C->Init);
    if (!Ty->isError() && !InitTy->isError()) {
      if (!convertImplicitly(C->Init, Ty))
        diag(C->Init->getLoc(), diag::err_init_type_mismatch)
            << C->getName().Name << Ty->getName() << InitTy->getName()
            << C->Init->getRange();
      else if (!(Value = evaluateConstant(C->Init)))
        diag(C->Init->getLoc(), diag::err_const_not_constant)
            << C->getName().Name << C->Init->getRange();
    }
  }
  CurModule = Outer;
  C->Ty = Value ? Ty : nullptr;
  if (Value)
    C->Value = std::move(*Value);
  C->State = ConstDecl::CheckState::Done;
}

void Sema::checkDefaultArg(ParamDecl *P) {
  if (!P->Default)
    return;
  llvm::StringRef Name = P->getName().Name;
  if (!hasConstantShape(P->Default)) {
    diag(P->Default->getLoc(), diag::err_default_not_constant)
        << Name << P->Default->getRange();
    return;
  }
  const Type *DefaultTy = checkExpr(P->Default);
  if (P->Ty->isError() || DefaultTy->isError())
    return;
  if (!convertImplicitly(P->Default, P->Ty)) {
    diag(P->Default->getLoc(), diag::err_default_type)
        << Name << P->Ty->getName() << DefaultTy->getName()
        << P->Default->getRange();
    return;
  }
  P->DefaultValue = evaluateConstant(P->Default);
  if (!P->DefaultValue)
    diag(P->Default->getLoc(), diag::err_default_not_constant)
        << Name << P->Default->getRange();
}

Expr *Sema::makeConstantExpr(const ConstantValue &V, const Type *Ty,
                             llvm::SMLoc Loc) {
  llvm::SMRange R(Loc, Loc);
  Expr *E;
  if (Ty->isFloat())
    E = Ctx.create<FloatLiteralExpr>(R, V.Float);
  else if (Ty->isBool())
    E = Ctx.create<BoolLiteralExpr>(R, V.Bool);
  else if (Ty->isString())
    E = Ctx.create<StringLiteralExpr>(R, V.String);
  else // int, an enum or a task state: the number, typed as such.
    E = Ctx.create<IntLiteralExpr>(R, V.Int);
  E->Ty = Ty;
  return E;
}

std::optional<ConstDecl::ValueFields>
Sema::evaluateConstant(const Expr *E) {
  using Value = ConstDecl::ValueFields;
  Value V;
  switch (E->getKind()) {
  case NodeKind::IntLiteralExpr:
    V.Int = llvm::cast<IntLiteralExpr>(E)->Value;
    return V;
  case NodeKind::FloatLiteralExpr:
    V.Float = llvm::cast<FloatLiteralExpr>(E)->Value;
    return V;
  case NodeKind::BoolLiteralExpr:
    V.Bool = llvm::cast<BoolLiteralExpr>(E)->Value;
    return V;
  case NodeKind::StringLiteralExpr:
    V.String = llvm::cast<StringLiteralExpr>(E)->Value;
    return V;
  case NodeKind::NameExpr: {
    const auto *N = llvm::cast<NameExpr>(E);
    if (N->Kind == NameKind::EnumValue) {
      V.Int = N->EnumValue;
      return V;
    }
    if (N->Kind == NameKind::Constant)
      return N->Const->Value;
    return std::nullopt;
  }
  case NodeKind::UnaryExpr: {
    const auto *U = llvm::cast<UnaryExpr>(E);
    if (U->Operator)
      return std::nullopt;
    std::optional<Value> O = evaluateConstant(U->Operand);
    if (!O)
      return std::nullopt;
    if (U->Op == UnaryOp::Not) {
      O->Bool = !O->Bool;
    } else if (E->Ty->isFloat()) {
      O->Float = -O->Float;
    } else {
      O->Int = int32_t(0u - uint32_t(O->Int));
    }
    return O;
  }
  case NodeKind::ConversionExpr: {
    const auto *CE = llvm::cast<ConversionExpr>(E);
    std::optional<Value> O = evaluateConstant(CE->Operand);
    if (!O)
      return std::nullopt;
    const Type *From = CE->Operand->Ty;
    if (E->Ty->isFloat()) {
      if (!From->isFloat())
        V.Float = float(O->Int);
      else
        V.Float = O->Float;
    } else if (E->Ty->isInt()) {
      if (From->isFloat()) {
        // llvm.fptosi.sat: NaN is 0, out of range saturates.
        float F = O->Float;
        V.Int = std::isnan(F)             ? 0
                : F >= 2147483648.0f      ? INT32_MAX
                : F <= -2147483648.0f     ? INT32_MIN
                                          : int32_t(F);
      } else if (From->isBool()) {
        V.Int = O->Bool ? 1 : 0;
      } else {
        V.Int = O->Int;
      }
    } else if (E->Ty->isBool()) {
      V.Bool = O->Bool;
    } else {
      return std::nullopt;
    }
    return V;
  }
  case NodeKind::BinaryExpr: {
    const auto *B = llvm::cast<BinaryExpr>(E);
    if (B->Operator)
      return std::nullopt;
    std::optional<Value> L = evaluateConstant(B->LHS);
    std::optional<Value> R = evaluateConstant(B->RHS);
    if (!L || !R)
      return std::nullopt;
    const Type *OpTy = B->LHS->Ty;
    switch (B->Op) {
    case BinaryOp::And:
      V.Bool = L->Bool && R->Bool;
      return V;
    case BinaryOp::Or:
      V.Bool = L->Bool || R->Bool;
      return V;
    case BinaryOp::Add:
    case BinaryOp::Sub:
    case BinaryOp::Mul:
    case BinaryOp::Div:
    case BinaryOp::Rem:
      if (OpTy->isString())
        return std::nullopt;
      if (!OpTy->isFloat()) {
        V.Int = intArith(B->Op, L->Int, R->Int);
        return V;
      }
      // IEEE single arithmetic (Sema has no `%` on floats).
      switch (B->Op) {
      case BinaryOp::Add:
        V.Float = L->Float + R->Float;
        break;
      case BinaryOp::Sub:
        V.Float = L->Float - R->Float;
        break;
      case BinaryOp::Mul:
        V.Float = L->Float * R->Float;
        break;
      default:
        V.Float = L->Float / R->Float;
        break;
      }
      return V;
    default:
      break;
    }
    // Comparisons: numbers, bools, enums, task states and strings by value.
    auto Compare = [&](auto A, auto C) {
      switch (B->Op) {
      case BinaryOp::Lt:
        return A < C;
      case BinaryOp::Le:
        return A <= C;
      case BinaryOp::Gt:
        return A > C;
      case BinaryOp::Ge:
        return A >= C;
      case BinaryOp::Eq:
        return A == C;
      default:
        return A != C;
      }
    };
    if (B->StateTest != BinaryExpr::StateKindTest::None) {
      // As at run time: the kind of the state the other side holds.
      bool RunningTest = B->StateTest == BinaryExpr::StateKindTest::Running;
      int32_t State = B->NamedStateOnLeft ? R->Int : L->Int;
      bool Is = RunningTest ? State > 0 : State < 0;
      V.Bool = B->Op == BinaryOp::Eq ? Is : !Is;
      return V;
    }
    if (OpTy->isFloat())
      V.Bool = Compare(L->Float, R->Float);
    else if (OpTy->isBool())
      V.Bool = Compare(L->Bool, R->Bool);
    else if (OpTy->isString()) // == and != compare contents.
      V.Bool = Compare(llvm::StringRef(L->String), llvm::StringRef(R->String));
    else
      V.Bool = Compare(L->Int, R->Int);
    return V;
  }
  default:
    return std::nullopt;
  }
}
