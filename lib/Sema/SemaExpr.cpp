//===- SemaExpr.cpp - types of expressions and assignments ----------------===//
//
// Every check returns the expression's type and stores it in Expr::Ty. The
// error type is poison: a check that sees it among its operands returns the
// error type without a message, so one mistake gives one message.
//
// The only implicit conversion is int to float. It is made visible in the
// tree (an implicit ConversionExpr around the int operand) so that CodeGen
// never has to re-derive the typing rules.
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"

using namespace bsc;
using namespace bsc::sema;

std::string Sema::getText(const Expr *E) const {
  if (auto *N = llvm::dyn_cast<NameExpr>(E))
    return N->Name.str();
  llvm::SMRange R = E->getRange();
  const char *B = R.Start.getPointer(), *End = R.End.getPointer();
  if (B && End && End > B)
    return std::string(B, End);
  return "expression";
}

void Sema::promoteToFloat(Expr *&E) {
  auto *C = Ctx.create<ConversionExpr>(E->getRange(), QualifiedName(), E,
                                       /*Implicit=*/true);
  C->Ty = Types.getFloat();
  E = C;
}

Sema::ImplicitConversion Sema::classifyImplicit(const Type *From,
                                                const Type *To) {
  if (From == To || From->isError() || To->isError())
    return ImplicitConversion::Unchanged;
  if (From->isInt() && To->isFloat())
    return ImplicitConversion::IntToFloat;
  return ImplicitConversion::None;
}

bool Sema::convertImplicitly(Expr *&E, const Type *To) {
  if (!E || !E->Ty)
    return true;
  switch (classifyImplicit(E->Ty, To)) {
  case ImplicitConversion::Unchanged:
    return true;
  case ImplicitConversion::IntToFloat:
    promoteToFloat(E);
    return true;
  case ImplicitConversion::None:
    return false;
  }
  llvm_unreachable("unknown conversion");
}

const Type *Sema::checkExpr(Expr *E, Access A) {
  const Type *T = checkExprOrArray(E, A);
  if (T->isArray()) {
    // b-script has no array values: an array field is only indexed.
    diag(E->getLoc(), diag::err_array_not_indexed)
        << getText(E) << T->getName() << E->getRange();
    E->Ty = T = Types.getError();
  }
  return T;
}

const Type *Sema::checkExprOrArray(Expr *E, Access A) {
  if (!E) // A part the parser could not build; it reported that.
    return Types.getError();
  const Type *T = checkExprImpl(E, A);
  E->Ty = T;
  if (T->isClass())
    Out.UsesClasses = true;
  return T;
}

const Type *Sema::checkExprImpl(Expr *E, Access A) {
  switch (E->getKind()) {
  case NodeKind::IntLiteralExpr:
    return Types.getInt();
  case NodeKind::FloatLiteralExpr:
    return Types.getFloat();
  case NodeKind::BoolLiteralExpr:
    return Types.getBool();
  case NodeKind::StringLiteralExpr:
    return Types.getString();
  case NodeKind::NameExpr:
    return checkName(llvm::cast<NameExpr>(E), A);
  case NodeKind::MemberExpr:
    return checkMember(llvm::cast<MemberExpr>(E), A);
  case NodeKind::IndexExpr:
    return checkIndex(llvm::cast<IndexExpr>(E), A);
  case NodeKind::CallExpr:
    return checkCall(llvm::cast<CallExpr>(E), /*AsStatement=*/false);
  case NodeKind::UnaryExpr:
    return checkUnary(llvm::cast<UnaryExpr>(E));
  case NodeKind::BinaryExpr:
    return checkBinary(llvm::cast<BinaryExpr>(E));
  case NodeKind::TaskStateExpr:
    return checkTaskState(llvm::cast<TaskStateExpr>(E));
  case NodeKind::ConversionExpr:
    return checkConversion(llvm::cast<ConversionExpr>(E));
  case NodeKind::ErrorExpr:
    return Types.getError();
#define DECL(Class) case NodeKind::Class:
#define STMT(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    break;
  }
  llvm_unreachable("not an expression");
}

//===----------------------------------------------------------------------===//
// Names, input and output, members
//===----------------------------------------------------------------------===//

bool Sema::checkIOAccess(NameExpr *E, bool IsInput, Access A,
                         llvm::StringRef Method) {
  // The direction rules do not depend on the type: input is read-only,
  // output write-only. A use of a part is a use of the whole (the access
  // is passed down member chains), and calling any method reads.
  bool Reads = false, Writes = false;
  switch (A) {
  case Access::Read:
  case Access::MethodBase:
    Reads = true;
    break;
  case Access::Write:
    Writes = true;
    break;
  case Access::Modify:
  case Access::MutatingMethodBase:
    Reads = Writes = true;
    break;
  }
  // Between cycles the REPL stands in for the world.
  if (Repl)
    return true;
  if (IsInput && A == Access::MutatingMethodBase) {
    diag(E->getLoc(), diag::err_non_const_method_on_input)
        << Method << E->getRange();
    return false;
  }
  if (IsInput && Writes) {
    diag(E->getLoc(), diag::err_assign_to_input) << E->getRange();
    return false;
  }
  // An assertion may read what the cycle wrote so far (docs/language.md,
  // "Assertions"); SemaAssert keeps it from changing anything.
  if (!IsInput && Reads && !(InAssertCondition && !Writes)) {
    diag(E->getLoc(), diag::err_read_of_output) << E->getRange();
    return false;
  }
  return true;
}

const Type *Sema::checkIO(NameExpr *E, bool IsInput, Access A) {
  E->Kind = IsInput ? NameKind::Input : NameKind::Output;
  if (!checkIOAccess(E, IsInput, A))
    return Types.getError();
  // The one place that decides the types of input and output: the classes
  // the world module registers.
  const NativeClass *C =
      World ? (IsInput ? World->Input : World->Output) : nullptr;
  if (!C) {
    // Once per compilation: every later use has the same cause.
    bool &Reported = IsInput ? ReportedNoInput : ReportedNoOutput;
    if (!Reported && Unbound)
      noteUnbound({IsInput ? UnboundName::Input : UnboundName::Output,
                   IsInput ? "input" : "output", E->getRange(), ""});
    else if (!Reported)
      diag(E->getLoc(),
           IsInput ? diag::err_no_input_type : diag::err_no_output_type)
          << E->getRange();
    Reported = true;
    return Types.getError();
  }
  return Types.getClass(C);
}

bool Sema::checkParamAccess(NameExpr *E, ParamDecl *P, Access A) {
  if (A == Access::Read || A == Access::MethodBase)
    return true;
  auto *Task = llvm::dyn_cast_or_null<TaskDecl>(P->Owner);
  if (!Task)
    return true;
  diag(E->getLoc(), diag::err_assign_to_task_param)
      << E->Name.str() << Task->getName().Name << E->getRange();
  return false;
}

const Type *Sema::applyLookup(NameExpr *E, const LookupResult &L, Access A) {
  const char *What = nullptr;
  switch (L.Kind) {
  case LookupKind::Error:
    return Types.getError();
  case LookupKind::Local:
    E->Kind = NameKind::Local;
    E->Local = L.Var;
    // A prompt's line reads a task's kept local as it is; it is no nested
    // func of the task, and the checked behavior must not change.
    if (Repl) {
      if (!checkReplFieldAccess(L.Var, E->getRange(), A))
        return Types.getError();
    } else if (L.Var->Owner != CurCallable) {
      L.Var->UsedByNestedFunc = true;
      TaskLocalsUsed[CurCallable].push_back(L.Var);
    }
    return L.Var->Ty ? L.Var->Ty : Types.getError();
  case LookupKind::Param:
    E->Kind = NameKind::Param;
    E->Param = L.Param;
    if (Repl) {
      if (!checkReplFieldAccess(L.Param, E->getRange(), A))
        return Types.getError();
    } else if (L.Param->Owner != CurCallable) {
      L.Param->ReadByNestedFunc = true;
    }
    if (!checkParamAccess(E, L.Param, A))
      return Types.getError();
    return L.Param->Ty ? L.Param->Ty : Types.getError();
  case LookupKind::EnumValue:
    E->Kind = NameKind::EnumValue;
    E->EnumValue = L.Value;
    E->BuiltinState = L.BuiltinState;
    return L.Ty;
  case LookupKind::Constant:
    if (A != Access::Read && A != Access::MethodBase) {
      diag(E->getLoc(), diag::err_assign_to_constant)
          << E->Name.str() << E->getRange();
      return Types.getError();
    }
    // A constant used by another constant's value may not be checked yet.
    checkConst(L.Const);
    if (L.Const->State != ConstDecl::CheckState::Done || !L.Const->Ty)
      return Types.getError();
    E->Kind = NameKind::Constant;
    E->Const = L.Const;
    return L.Const->Ty;
  case LookupKind::Input:
    return checkIO(E, /*IsInput=*/true, A);
  case LookupKind::Output:
    return checkIO(E, /*IsInput=*/false, A);
  case LookupKind::Callable:
    if (llvm::isa<TaskDecl>(L.Callable)) {
      diag(E->getLoc(), diag::err_task_not_a_value)
          << E->Name.str() << E->getRange();
      return Types.getError();
    }
    What = "function";
    break;
  case LookupKind::NativeFn:
    What = "function";
    break;
  case LookupKind::Module:
    What = "module";
    break;
  case LookupKind::TypeName:
    What = "type";
    break;
  }
  diag(E->getLoc(), diag::err_not_a_value)
      << E->Name.str() << What << E->getRange();
  return Types.getError();
}

const Type *Sema::checkName(NameExpr *E, Access A) {
  return applyLookup(E, lookup(E->Name, LookupMode::Value), A);
}

const Type *Sema::checkMember(MemberExpr *E, Access A) {
  if (Repl)
    if (const Type *T = checkTaskField(E, A))
      return T;
  // A part of input or output (or of a task parameter) follows the rules of
  // the whole, so the use is passed down to the root of a member chain.
  const Type *BaseTy = checkExpr(E->Base, A);
  if (BaseTy->isError())
    return Types.getError();
  if (!BaseTy->isClass()) {
    diag(E->Base->getLoc(), diag::err_member_of_non_class)
        << getText(E->Base) << BaseTy->getName() << E->Base->getRange();
    return Types.getError();
  }
  const NativeFunction *M = findValueMember(BaseTy, E->Member);
  if (!M)
    return Types.getError();
  E->Resolved = M;
  if (!M->isData()) {
    diag(E->getLoc(), diag::err_not_a_value)
        << getText(E) << "method" << E->getRange();
    return Types.getError();
  }
  if (M->ReadOnly && A != Access::Read && A != Access::MethodBase) {
    diag(E->Member.Loc, diag::err_read_only_member)
        << M->Name << BaseTy->getName() << E->getRange();
    return Types.getError();
  }
  return resolveNativeType(M->Result);
}

/// The array field an index expression's base names, or null.
static const NativeType *getArrayField(const Expr *Base) {
  if (const auto *I = llvm::dyn_cast<IndexExpr>(Base))
    return I->Field;
  if (const auto *M = llvm::dyn_cast<MemberExpr>(Base))
    return M->Resolved ? &M->Resolved->Result : nullptr;
  return nullptr;
}

const Type *Sema::checkIndex(IndexExpr *E, Access A) {
  // An element is a part of its array, which is a part of its object: the
  // use passes down to the root, as for members.
  const Type *BaseTy = checkExprOrArray(E->Base, A);
  const Type *IndexTy = checkExpr(E->Index);
  if (BaseTy->isError() || IndexTy->isError())
    return Types.getError();
  const NativeType *Field = getArrayField(E->Base);
  if (!BaseTy->isArray() || !Field) {
    diag(E->Base->getLoc(), diag::err_index_of_non_array)
        << getText(E->Base) << BaseTy->getName() << E->Base->getRange();
    return Types.getError();
  }
  if (IndexTy->isEnum() || IndexTy->isTaskState()) {
    // `pressed[Key::chest]`: no implicit conversion, but `int(e)` gives
    // the number (docs/language.md, Enums).
    std::string Converted = "int(" + getText(E->Index) + ")";
    diag(E->Index->getLoc(), diag::err_index_enum)
        << IndexTy->getName() << Converted << E->Index->getRange()
        << llvm::SMFixIt(E->Index->getRange(), Converted);
    return Types.getError();
  }
  if (!IndexTy->isInt()) {
    diag(E->Index->getLoc(), diag::err_index_type)
        << IndexTy->getName() << E->Index->getRange();
    return Types.getError();
  }
  E->Field = Field;
  E->Extent = BaseTy->getExtent();
  // The dimension this index selects in: the field's outermost one less
  // the dimensions the base indexed already.
  size_t Dim = 0;
  for (const Expr *B = E->Base; llvm::isa<IndexExpr>(B);
       B = llvm::cast<IndexExpr>(B)->Base)
    ++Dim;
  E->Stride = Field->StorageSize;
  for (size_t D = Dim + 1; D < Field->Extents.size(); ++D)
    E->Stride *= Field->Extents[D];
  // A constant index is checked here; any other is clamped at run time
  // (docs/language.md, "Array fields").
  if (std::optional<ConstDecl::ValueFields> V = evaluateConstant(E->Index)) {
    if (V->Int < 0 || uint32_t(V->Int) >= E->Extent) {
      diag(E->Index->getLoc(), diag::err_index_out_of_bounds)
          << V->Int << getText(E->Base) << E->Extent << E->Index->getRange();
      return Types.getError();
    }
    E->ConstIndex = V->Int;
  }
  return BaseTy->getElement();
}

//===----------------------------------------------------------------------===//
// Operators and conversions
//===----------------------------------------------------------------------===//

const Type *Sema::checkUnary(UnaryExpr *E) {
  const Type *T = checkExpr(E->Operand);
  if (T->isError())
    return T;
  if (T->isClass() && E->Op == UnaryOp::Neg)
    return checkClassUnary(E);
  switch (E->Op) {
  case UnaryOp::Neg:
    if (T->isArithmetic())
      return T;
    break;
  case UnaryOp::Not:
    if (T->isBool())
      return T;
    break;
  }
  diag(E->getLoc(), diag::err_unary_operand)
      << getSpelling(E->Op) << T->getName() << E->getRange();
  return Types.getError();
}

/// Promotes the int side of a mixed int/float pair; returns the common type.
static const Type *promoteArithmetic(Sema &S, Expr *&L, Expr *&R) {
  if (L->Ty == R->Ty)
    return L->Ty;
  if (L->Ty->isInt())
    S.promoteToFloat(L);
  else
    S.promoteToFloat(R);
  return S.Types.getFloat();
}

/// The task an operand names (`a` in `a == b`), without reporting
/// anything: null for everything else, a local or parameter of that name
/// included.
const TaskDecl *Sema::getNamedTask(const Expr *E) {
  const auto *N = llvm::dyn_cast<NameExpr>(E);
  if (!N || N->Name.isQualified() || N->Name.empty())
    return nullptr;
  LookupResult L = findUnqualified(N->Name.Parts[0].Name, LookupMode::Value);
  return L.Kind == LookupKind::Callable ? llvm::dyn_cast<TaskDecl>(L.Callable)
                                        : nullptr;
}

/// `taskState(t) == TaskState::running` asks whether t is running, whatever
/// running state (> 0) its `yield N` set; `== TaskState::failure` likewise
/// for any failure (< 0). Only those names, written so, are kind tests: a
/// named state of the same number (`Button::pressed`, 1) or a constant
/// (`const TaskState GAVE_UP = TaskState::failure`) compares by number.
void Sema::markStateKindTest(BinaryExpr *E) {
  auto NamedState = [](const Expr *Side) -> std::optional<int32_t> {
    const auto *N = llvm::dyn_cast<NameExpr>(Side);
    if (!N || N->Kind != NameKind::EnumValue || !N->BuiltinState)
      return std::nullopt;
    return N->EnumValue;
  };
  std::optional<int32_t> V = NamedState(E->RHS);
  E->NamedStateOnLeft = !V;
  if (!V)
    V = NamedState(E->LHS);
  if (V == 1)
    E->StateTest = BinaryExpr::StateKindTest::Running;
  else if (V == -1)
    E->StateTest = BinaryExpr::StateKindTest::Failure;
}

const Type *Sema::checkBinary(BinaryExpr *E) {
  // `a == b` between tasks, as if tasks were objects: one error that says
  // what to compare instead.
  if (E->Op == BinaryOp::Eq || E->Op == BinaryOp::Ne)
    if (const TaskDecl *LT = getNamedTask(E->LHS))
      if (const TaskDecl *RT = getNamedTask(E->RHS)) {
        diag(E->getLoc(), diag::err_compare_tasks)
            << LT->getName().Name << (E->Op == BinaryOp::Eq ? "==" : "!=")
            << RT->getName().Name << E->getRange();
        return Types.getError();
      }
  const Type *L = checkExpr(E->LHS);
  const Type *R = checkExpr(E->RHS);
  if (L->isError() || R->isError())
    return Types.getError();
  if (L->isClass())
    return checkClassBinary(E);
  bool Arith = L->isArithmetic() && R->isArithmetic();
  switch (E->Op) {
  case BinaryOp::Add:
  case BinaryOp::Sub:
  case BinaryOp::Mul:
  case BinaryOp::Div:
    if (Arith)
      return promoteArithmetic(*this, E->LHS, E->RHS);
    break;
  case BinaryOp::Rem:
    if (L->isInt() && R->isInt())
      return L;
    break;
  case BinaryOp::Lt:
  case BinaryOp::Le:
  case BinaryOp::Gt:
  case BinaryOp::Ge:
    if (!Arith)
      break;
    promoteArithmetic(*this, E->LHS, E->RHS);
    return Types.getBool();
  case BinaryOp::Eq:
  case BinaryOp::Ne:
    if (Arith) {
      promoteArithmetic(*this, E->LHS, E->RHS);
      return Types.getBool();
    }
    if (L->isTaskState() && R->isTaskState())
      markStateKindTest(E);
    if (L == R && (L->isBool() || L->isEnum() || L->isTaskState() ||
                   L->isString()))
      return Types.getBool();
    break;
  case BinaryOp::And:
  case BinaryOp::Or:
    if (L->isBool() && R->isBool())
      return L;
    break;
  }
  diag(E->getLoc(), diag::err_binary_operands)
      << getSpelling(E->Op) << L->getName() << R->getName() << E->getRange();
  return Types.getError();
}

const Type *Sema::checkConversion(ConversionExpr *E) {
  const Type *From = checkExpr(E->Operand);
  if (E->Implicit)
    return Types.getFloat();
  const Type *To = resolveType(E->TargetName);
  if (From->isError() || To->isError())
    return Types.getError();
  bool OK = false;
  switch (To->getKind()) {
  case TypeKind::Int:
    OK = From->isArithmetic() || From->isBool() || From->isEnum() ||
         From->isTaskState();
    break;
  case TypeKind::Float:
    OK = From->isArithmetic();
    break;
  case TypeKind::Bool:
    OK = From->isBool();
    break;
  case TypeKind::Error:
  case TypeKind::Void:
  case TypeKind::String:
  case TypeKind::TaskState:
  case TypeKind::Enum:
  case TypeKind::Class:
  case TypeKind::Array: // Not a type name.
    break;
  }
  if (!OK) {
    diag(E->getLoc(), diag::err_invalid_conversion)
        << From->getName() << To->getName() << E->getRange();
    return Types.getError();
  }
  return To;
}

//===----------------------------------------------------------------------===//
// Assignments
//===----------------------------------------------------------------------===//

const Type *Sema::checkAssignTarget(Expr *T, Access A) {
  if (!T)
    return Types.getError();
  if (auto *N = llvm::dyn_cast<NameExpr>(T)) {
    LookupResult L = lookup(N->Name, LookupMode::Value);
    switch (L.Kind) {
    case LookupKind::Error:
    case LookupKind::Local:
    case LookupKind::Param: // applyLookup keeps task parameters read-only.
    case LookupKind::Constant: // ...and constants constant.
    case LookupKind::Input:
    case LookupKind::Output:
      return N->Ty = applyLookup(N, L, A);
    case LookupKind::Callable:
    case LookupKind::NativeFn:
    case LookupKind::EnumValue:
    case LookupKind::Module:
    case LookupKind::TypeName:
      N->Ty = Types.getError();
      diag(N->getLoc(), diag::err_not_assignable) << N->getRange();
      return Types.getError();
    }
    llvm_unreachable("unknown lookup result");
  }
  if (llvm::isa<MemberExpr, IndexExpr>(T))
    return checkExpr(T, A);
  // Literals, calls, operators: checked for their own mistakes first.
  if (!checkExpr(T)->isError())
    diag(T->getLoc(), diag::err_not_assignable) << T->getRange();
  return Types.getError();
}

void Sema::checkAssign(AssignStmt *S) {
  BinaryOp Bin = BinaryOp::Add;
  bool Compound = getCompoundOperator(S->Op, Bin);
  const Type *TargetTy =
      checkAssignTarget(S->Target, Compound ? Access::Modify : Access::Write);
  const Type *ValueTy = checkExpr(S->Value);
  if (TargetTy->isError() || ValueTy->isError())
    return;

  auto Mismatch = [&](const Type *From) {
    diag(S->Value->getLoc(), diag::err_assign_type_mismatch)
        << From->getName() << getText(S->Target) << TargetTy->getName()
        << S->Value->getRange();
  };
  if (!Compound) {
    if (!convertImplicitly(S->Value, TargetTy)) {
      Mismatch(ValueTy);
      return;
    }
    // A property's setter (or a field without offset) copies in C++.
    const auto *ME = llvm::dyn_cast<MemberExpr>(S->Target);
    bool ThroughSetter = ME && ME->Resolved &&
                         !(ME->Resolved->Kind == NativeFunction::Field &&
                           ME->Resolved->FieldOffset);
    if (!ThroughSetter)
      checkCopyable(TargetTy, S->Value->getRange(), "an assignment",
                    /*Assigns=*/true);
    return;
  }
  if (!TargetTy->isArithmetic()) {
    diag(S->Target->getLoc(), diag::err_compound_assign_type)
        << getSpelling(S->Op) << TargetTy->getName() << S->Target->getRange();
    return;
  }
  // `t op= v` follows the rules of `t op v`, whose result must then fit t.
  bool OK = ValueTy->isArithmetic() &&
            (Bin != BinaryOp::Rem || (TargetTy->isInt() && ValueTy->isInt()));
  if (!OK) {
    diag(S->getLoc(), diag::err_binary_operands)
        << getSpelling(S->Op) << TargetTy->getName() << ValueTy->getName()
        << S->getRange();
    return;
  }
  if (!convertImplicitly(S->Value, TargetTy))
    Mismatch(ValueTy);
}
