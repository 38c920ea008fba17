//===- AST.cpp - helpers of the syntax tree -------------------------------===//
#include "bsc/AST/AST.h"
#include "llvm/Support/ErrorHandling.h"

using namespace bsc;

llvm::StringRef bsc::getSpelling(BinaryOp Op) {
  switch (Op) {
#define BINARY_OP(Name, Spelling, Prec)                                        \
  case BinaryOp::Name:                                                         \
    return Spelling;
#include "bsc/AST/OperatorKinds.def"
  }
  llvm_unreachable("unknown binary operator");
}

unsigned bsc::getPrecedence(BinaryOp Op) {
  switch (Op) {
#define BINARY_OP(Name, Spelling, Prec)                                        \
  case BinaryOp::Name:                                                         \
    return Prec;
#include "bsc/AST/OperatorKinds.def"
  }
  llvm_unreachable("unknown binary operator");
}

llvm::StringRef bsc::getSpelling(UnaryOp Op) {
  switch (Op) {
#define UNARY_OP(Name, Spelling)                                               \
  case UnaryOp::Name:                                                          \
    return Spelling;
#include "bsc/AST/OperatorKinds.def"
  }
  llvm_unreachable("unknown unary operator");
}

llvm::StringRef bsc::getSpelling(AssignOp Op) {
  switch (Op) {
#define ASSIGN_OP(Name, Spelling, Bin)                                         \
  case AssignOp::Name:                                                         \
    return Spelling;
#include "bsc/AST/OperatorKinds.def"
  }
  llvm_unreachable("unknown assignment operator");
}

bool bsc::getCompoundOperator(AssignOp Op, BinaryOp &Result) {
  switch (Op) {
  case AssignOp::Assign:
    return false;
  case AssignOp::AddAssign:
    Result = BinaryOp::Add;
    return true;
  case AssignOp::SubAssign:
    Result = BinaryOp::Sub;
    return true;
  case AssignOp::MulAssign:
    Result = BinaryOp::Mul;
    return true;
  case AssignOp::DivAssign:
    Result = BinaryOp::Div;
    return true;
  case AssignOp::RemAssign:
    Result = BinaryOp::Rem;
    return true;
  }
  llvm_unreachable("unknown assignment operator");
}

llvm::StringRef bsc::getNodeKindName(NodeKind K) {
  switch (K) {
#define NODE(Class)                                                            \
  case NodeKind::Class:                                                        \
    return #Class;
#include "bsc/AST/ASTNodes.def"
  }
  llvm_unreachable("unknown node kind");
}

llvm::SMRange QualifiedName::getRange() const {
  if (Parts.empty())
    return {};
  return {Parts.front().Loc, Parts.back().getRange().End};
}

std::string QualifiedName::str() const {
  std::string S;
  for (const Ident &I : Parts) {
    if (!S.empty())
      S += "::";
    S += I.Name.str();
  }
  return S;
}

std::string CallableDecl::getQualifiedName() const {
  std::string S = Module ? Module->Name + "::" : std::string();
  if (auto *F = llvm::dyn_cast<FuncDecl>(this))
    if (F->EnclosingTask)
      S += F->EnclosingTask->getName().Name.str() + ".";
  return S + getName().Name.str();
}

std::vector<ModuleAST *> ASTContext::getModules() const {
  std::vector<ModuleAST *> Result;
  for (const auto &M : Modules)
    Result.push_back(M.get());
  return Result;
}

//===----------------------------------------------------------------------===//
// Children
//===----------------------------------------------------------------------===//

namespace {
using ChildFn = llvm::function_ref<void(const Node &)>;

/// Calls Fn on each of `Children` that is there.
void visit(ChildFn Fn, std::initializer_list<const Node *> Children) {
  for (const Node *C : Children)
    if (C)
      Fn(*C);
}
template <typename T> void visitAll(ChildFn Fn, const std::vector<T *> &Nodes) {
  for (const T *C : Nodes)
    if (C)
      Fn(*C);
}

// One overload per node class: forEachChild's switch, generated from
// ASTNodes.def, calls the one of each kind.
void childrenOf(const CallableDecl &D, ChildFn Fn) {
  visitAll(Fn, D.Params);
  visit(Fn, {D.Body});
}
void childrenOf(const FuncDecl &D, ChildFn Fn) {
  childrenOf(static_cast<const CallableDecl &>(D), Fn);
}
void childrenOf(const TaskDecl &D, ChildFn Fn) {
  childrenOf(static_cast<const CallableDecl &>(D), Fn);
}
void childrenOf(const ParamDecl &D, ChildFn Fn) { visit(Fn, {D.Default}); }
void childrenOf(const VarDecl &D, ChildFn Fn) { visit(Fn, {D.Init}); }
void childrenOf(const ConstDecl &D, ChildFn Fn) { visit(Fn, {D.Init}); }
void childrenOf(const EnumDecl &, ChildFn) {}
void childrenOf(const BlockStmt &S, ChildFn Fn) { visitAll(Fn, S.Stmts); }
void childrenOf(const DeclStmt &S, ChildFn Fn) { visit(Fn, {S.Var}); }
void childrenOf(const FuncDeclStmt &S, ChildFn Fn) { visit(Fn, {S.Func}); }
void childrenOf(const AssignStmt &S, ChildFn Fn) {
  visit(Fn, {S.Target, S.Value});
}
void childrenOf(const ExprStmt &S, ChildFn Fn) { visit(Fn, {S.E}); }
void childrenOf(const IfStmt &S, ChildFn Fn) {
  visit(Fn, {S.Cond, S.Then, S.Else});
}
void childrenOf(const ForStmt &S, ChildFn Fn) {
  visit(Fn, {S.Init, S.Cond, S.Step, S.Body});
}
void childrenOf(const BreakStmt &, ChildFn) {}
void childrenOf(const ContinueStmt &, ChildFn) {}
void childrenOf(const ReturnStmt &S, ChildFn Fn) { visit(Fn, {S.Value}); }
void childrenOf(const YieldStmt &S, ChildFn Fn) { visit(Fn, {S.Value}); }
void childrenOf(const AssertStmt &S, ChildFn Fn) {
  visit(Fn, {S.Cond, S.Message});
}
void childrenOf(const ErrorStmt &, ChildFn) {}
void childrenOf(const IntLiteralExpr &, ChildFn) {}
void childrenOf(const FloatLiteralExpr &, ChildFn) {}
void childrenOf(const BoolLiteralExpr &, ChildFn) {}
void childrenOf(const StringLiteralExpr &, ChildFn) {}
void childrenOf(const NameExpr &, ChildFn) {}
void childrenOf(const MemberExpr &E, ChildFn Fn) { visit(Fn, {E.Base}); }
void childrenOf(const IndexExpr &E, ChildFn Fn) {
  visit(Fn, {E.Base, E.Index});
}
void childrenOf(const CallExpr &E, ChildFn Fn) {
  visit(Fn, {E.Callee});
  visitAll(Fn, E.Args);
}
void childrenOf(const UnaryExpr &E, ChildFn Fn) { visit(Fn, {E.Operand}); }
void childrenOf(const BinaryExpr &E, ChildFn Fn) { visit(Fn, {E.LHS, E.RHS}); }
void childrenOf(const TaskStateExpr &, ChildFn) {}
void childrenOf(const ConversionExpr &E, ChildFn Fn) {
  visit(Fn, {E.Operand});
}
void childrenOf(const ErrorExpr &, ChildFn) {}
} // namespace

void bsc::forEachChild(const Node &N, ChildFn Fn) {
  switch (N.getKind()) {
#define NODE(Class)                                                            \
  case NodeKind::Class:                                                        \
    return childrenOf(llvm::cast<Class>(N), Fn);
#include "bsc/AST/ASTNodes.def"
  }
  llvm_unreachable("unknown node kind");
}
