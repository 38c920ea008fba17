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
  case NodeKind::MemberExpr:
  case NodeKind::IndexExpr:
  case NodeKind::CallExpr:
  case NodeKind::TaskStateExpr:
    return false;
#define EXPR(Class)
#define NODE(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    llvm_unreachable("not an expression");
  }
  llvm_unreachable("unknown node kind");
}

/// int division as the generated code does it, without traps: x / 0 == 0,
/// INT_MIN / -1 == INT_MIN.
int32_t intDiv(int32_t L, int32_t R) {
  if (R == 0)
    return 0;
  if (L == INT32_MIN && R == -1)
    return INT32_MIN;
  return L / R;
}

/// ...and its remainder: x % 0 == x, INT_MIN % -1 == 0.
int32_t intRem(int32_t L, int32_t R) {
  if (R == 0)
    return L;
  if (L == INT32_MIN && R == -1)
    return 0;
  return L % R;
}

/// `L op R` for an arithmetic operator on ints (wrapping) or, if `IsFloat`,
/// IEEE singles; nothing for a float `%`, which Sema allows on ints only.
std::optional<ConstantValue> foldArithmetic(BinaryOp Op, bool IsFloat,
                                            const ConstantValue &L,
                                            const ConstantValue &R) {
  uint32_t A = uint32_t(L.Int), B = uint32_t(R.Int);
  ConstantValue V;
  switch (Op) {
  case BinaryOp::Add:
    if (IsFloat)
      V.Float = L.Float + R.Float;
    else
      V.Int = int32_t(A + B);
    return V;
  case BinaryOp::Sub:
    if (IsFloat)
      V.Float = L.Float - R.Float;
    else
      V.Int = int32_t(A - B);
    return V;
  case BinaryOp::Mul:
    if (IsFloat)
      V.Float = L.Float * R.Float;
    else
      V.Int = int32_t(A * B);
    return V;
  case BinaryOp::Div:
    if (IsFloat)
      V.Float = L.Float / R.Float;
    else
      V.Int = intDiv(L.Int, R.Int);
    return V;
  case BinaryOp::Rem:
    if (IsFloat)
      return std::nullopt;
    V.Int = intRem(L.Int, R.Int);
    return V;
  case BinaryOp::Lt:
  case BinaryOp::Le:
  case BinaryOp::Gt:
  case BinaryOp::Ge:
  case BinaryOp::Eq:
  case BinaryOp::Ne:
  case BinaryOp::And:
  case BinaryOp::Or:
    llvm_unreachable("not an arithmetic operator");
  }
  llvm_unreachable("unknown binary operator");
}

/// `A op C` for a comparison operator, on numbers, bools or strings.
template <typename T> bool compare(BinaryOp Op, const T &A, const T &C) {
  switch (Op) {
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
  case BinaryOp::Ne:
    return A != C;
  case BinaryOp::Mul:
  case BinaryOp::Div:
  case BinaryOp::Rem:
  case BinaryOp::Add:
  case BinaryOp::Sub:
  case BinaryOp::And:
  case BinaryOp::Or:
    llvm_unreachable("not a comparison");
  }
  llvm_unreachable("unknown binary operator");
}

/// The value of a name: an enum value or a (checked) constant.
std::optional<ConstantValue> evaluateName(const NameExpr &N) {
  if (N.Kind == NameKind::EnumValue) {
    ConstantValue V;
    V.Int = N.EnumValue;
    return V;
  }
  if (N.Kind == NameKind::Constant)
    return N.Const->Value;
  return std::nullopt;
}

/// `-O` and `!O` on the value `O` of U's operand.
ConstantValue foldUnary(const UnaryExpr &U, ConstantValue O) {
  switch (U.Op) {
  case UnaryOp::Not:
    O.Bool = !O.Bool;
    return O;
  case UnaryOp::Neg:
    if (U.Ty->isFloat())
      O.Float = -O.Float;
    else
      O.Int = int32_t(0u - uint32_t(O.Int));
    return O;
  }
  llvm_unreachable("unknown unary operator");
}

/// An explicit or implicit conversion of the value `O` of CE's operand.
std::optional<ConstantValue> foldConversion(const ConversionExpr &CE,
                                            const ConstantValue &O) {
  ConstantValue V;
  const Type *From = CE.Operand->Ty;
  if (CE.Ty->isFloat()) {
    if (!From->isFloat())
      V.Float = float(O.Int);
    else
      V.Float = O.Float;
  } else if (CE.Ty->isInt()) {
    if (From->isFloat()) {
      // llvm.fptosi.sat: NaN is 0, out of range saturates.
      float F = O.Float;
      V.Int = std::isnan(F)             ? 0
              : F >= 2147483648.0f      ? INT32_MAX
              : F <= -2147483648.0f     ? INT32_MIN
                                        : int32_t(F);
    } else if (From->isBool()) {
      V.Int = O.Bool ? 1 : 0;
    } else {
      V.Int = O.Int;
    }
  } else if (CE.Ty->isBool()) {
    V.Bool = O.Bool;
  } else {
    return std::nullopt;
  }
  return V;
}

/// A comparison: numbers, bools, enums, task states and strings by value.
bool foldComparison(const BinaryExpr &B, const ConstantValue &L,
                    const ConstantValue &R) {
  if (B.StateTest != BinaryExpr::StateKindTest::None) {
    // As at run time: the kind of the state the other side holds.
    bool RunningTest = B.StateTest == BinaryExpr::StateKindTest::Running;
    int32_t State = B.NamedStateOnLeft ? R.Int : L.Int;
    bool Is = RunningTest ? State > 0 : State < 0;
    return B.Op == BinaryOp::Eq ? Is : !Is;
  }
  const Type *OpTy = B.LHS->Ty;
  if (OpTy->isFloat())
    return compare(B.Op, L.Float, R.Float);
  if (OpTy->isBool())
    return compare(B.Op, L.Bool, R.Bool);
  if (OpTy->isString()) // == and != compare contents.
    return compare(B.Op, llvm::StringRef(L.String), llvm::StringRef(R.String));
  return compare(B.Op, L.Int, R.Int);
}

/// `L op R` on the values of B's operands.
std::optional<ConstantValue> foldBinary(const BinaryExpr &B,
                                        const ConstantValue &L,
                                        const ConstantValue &R) {
  const Type *OpTy = B.LHS->Ty;
  ConstantValue V;
  switch (B.Op) {
  case BinaryOp::And:
    V.Bool = L.Bool && R.Bool;
    return V;
  case BinaryOp::Or:
    V.Bool = L.Bool || R.Bool;
    return V;
  case BinaryOp::Add:
  case BinaryOp::Sub:
  case BinaryOp::Mul:
  case BinaryOp::Div:
  case BinaryOp::Rem:
    if (OpTy->isString())
      return std::nullopt;
    return foldArithmetic(B.Op, OpTy->isFloat(), L, R);
  case BinaryOp::Lt:
  case BinaryOp::Le:
  case BinaryOp::Gt:
  case BinaryOp::Ge:
  case BinaryOp::Eq:
  case BinaryOp::Ne:
    V.Bool = foldComparison(B, L, R);
    return V;
  }
  llvm_unreachable("unknown binary operator");
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
  ConstantValue V;
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
  case NodeKind::NameExpr:
    return evaluateName(*llvm::cast<NameExpr>(E));
  case NodeKind::UnaryExpr: {
    const auto *U = llvm::cast<UnaryExpr>(E);
    if (U->Operator)
      return std::nullopt;
    std::optional<ConstantValue> O = evaluateConstant(U->Operand);
    if (!O)
      return std::nullopt;
    return foldUnary(*U, std::move(*O));
  }
  case NodeKind::ConversionExpr: {
    const auto *CE = llvm::cast<ConversionExpr>(E);
    std::optional<ConstantValue> O = evaluateConstant(CE->Operand);
    if (!O)
      return std::nullopt;
    return foldConversion(*CE, *O);
  }
  case NodeKind::BinaryExpr: {
    const auto *B = llvm::cast<BinaryExpr>(E);
    if (B->Operator)
      return std::nullopt;
    std::optional<ConstantValue> L = evaluateConstant(B->LHS);
    std::optional<ConstantValue> R = evaluateConstant(B->RHS);
    if (!L || !R)
      return std::nullopt;
    return foldBinary(*B, *L, *R);
  }
  case NodeKind::MemberExpr:
  case NodeKind::IndexExpr:
  case NodeKind::CallExpr:
  case NodeKind::TaskStateExpr:
  case NodeKind::ErrorExpr:
    return std::nullopt;
#define EXPR(Class)
#define NODE(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    llvm_unreachable("not an expression");
  }
  llvm_unreachable("unknown node kind");
}
