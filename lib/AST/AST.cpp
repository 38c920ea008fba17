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
