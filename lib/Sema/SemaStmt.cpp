//===- SemaStmt.cpp - checking statements ---------------------------------===//
//
// Statements are checked in source order (so `for` heads, including a
// `yield` step, come before the loop body, which is the order resume points
// are numbered in). Whether a func returns on every path is a separate,
// purely structural walk after its body is checked: it needs no types, and
// keeping it apart keeps the rule easy to read and to document.
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"

using namespace bsc;
using namespace bsc::sema;

/// The keyword of a statement that ends its block, or null.
static const char *getTerminatorKeyword(const Stmt *S) {
  if (llvm::isa<ReturnStmt>(S))
    return "return";
  if (llvm::isa<BreakStmt>(S))
    return "break";
  if (llvm::isa<ContinueStmt>(S))
    return "continue";
  return nullptr;
}

void Sema::checkBlock(BlockStmt *B) {
  pushScope();
  const char *Terminator = nullptr;
  bool Warned = false;
  for (Stmt *S : B->Stmts) {
    if (Diags.tooManyErrors())
      break;
    if (!S)
      continue;
    // A nested func declared after a `return` is not dead code: it runs
    // when called.
    if (Terminator && !Warned && !llvm::isa<FuncDeclStmt>(S) &&
        !llvm::isa<ErrorStmt>(S)) {
      diag(S->getLoc(), diag::warn_unreachable_code) << Terminator;
      Warned = true;
    }
    checkStmt(S);
    if (!Terminator)
      Terminator = getTerminatorKeyword(S);
  }
  popScope();
}

void Sema::checkCondition(Expr *&Cond) {
  const Type *T = checkExpr(Cond);
  if (Cond && !T->isError() && !T->isBool())
    diag(Cond->getLoc(), diag::err_condition_not_bool)
        << T->getName() << Cond->getRange();
}

void Sema::checkAssert(AssertStmt *S) {
  if (InReplLine) {
    diag(S->getLoc(), diag::err_repl_assert) << S->getKeyword();
    return;
  }
  InAssertCondition = true;
  checkCondition(S->Cond);
  InAssertCondition = false;
  Out.Assertions.push_back({S, CurCallable});
}

void Sema::checkIf(IfStmt *S) {
  checkCondition(S->Cond);
  if (S->Then)
    checkBlock(S->Then);
  if (S->Else)
    checkStmt(S->Else);
}

void Sema::checkFor(ForStmt *S) {
  warnIfEndless(S);
  // `for(;; yield)` whose body also yields on every pass: two steps per
  // iteration, which a CABSL port rarely means.
  if (S->Step && llvm::isa<YieldStmt>(S->Step) && S->Body)
    for (Stmt *B : S->Body->Stmts)
      if (auto *Y = llvm::dyn_cast<YieldStmt>(B)) {
        diag(Y->getLoc(), diag::warn_double_yield);
        diag(S->Step->getLoc(), diag::note_step_yield);
        break;
      }
  pushScope(); // The head's scope: `for(int i = 0; ...)`.
  if (S->Init)
    checkStmt(S->Init);
  if (S->Cond)
    checkCondition(S->Cond);
  ++LoopDepth;
  if (S->Step)
    checkStmt(S->Step);
  if (S->Body)
    checkBlock(S->Body);
  --LoopDepth;
  checkLoopYields(S);
  popScope();
}

void Sema::checkReturn(ReturnStmt *S) {
  if (llvm::isa<TaskDecl>(CurCallable)) {
    if (S->Value && !llvm::isa<ErrorExpr>(S->Value)) {
      checkExpr(S->Value);
      diag(S->Value->getLoc(), diag::err_return_value_in_task)
          << getText(S->Value) << S->Value->getRange();
    }
    return;
  }
  auto *F = llvm::cast<FuncDecl>(CurCallable);
  const Type *ResultTy = F->ResultTy;
  if (!S->Value) {
    if (!ResultTy->isVoid() && !ResultTy->isError())
      diag(S->getLoc(), diag::err_return_missing_value)
          << F->getName().Name << ResultTy->getName();
    return;
  }
  const Type *T = checkExpr(S->Value);
  if (llvm::isa<ErrorExpr>(S->Value))
    return;
  if (ResultTy->isVoid()) {
    diag(S->Value->getLoc(), diag::err_return_value_in_void_func)
        << F->getName().Name << S->Value->getRange();
    return;
  }
  if (T->isError() || ResultTy->isError())
    return;
  if (!convertImplicitly(S->Value, ResultTy))
    diag(S->Value->getLoc(), diag::err_return_type_mismatch)
        << T->getName() << F->getName().Name << ResultTy->getName()
        << S->Value->getRange();
  else
    checkCopyable(ResultTy, S->Value->getRange(), "a returned value");
}

void Sema::checkStmt(Stmt *S) {
  switch (S->getKind()) {
  case NodeKind::BlockStmt:
    return checkBlock(llvm::cast<BlockStmt>(S));
  case NodeKind::DeclStmt:
    if (VarDecl *V = llvm::cast<DeclStmt>(S)->Var)
      checkVarDecl(V);
    return;
  case NodeKind::FuncDeclStmt:
    if (FuncDecl *F = llvm::cast<FuncDeclStmt>(S)->Func)
      checkNestedFunc(F);
    return;
  case NodeKind::AssignStmt:
    return checkAssign(llvm::cast<AssignStmt>(S));
  case NodeKind::ExprStmt: {
    auto *ES = llvm::cast<ExprStmt>(S);
    if (auto *C = llvm::dyn_cast_or_null<CallExpr>(ES->E)) {
      C->Ty = checkCall(C, /*AsStatement=*/true);
      return;
    }
    const Type *T = checkExpr(ES->E);
    if (ES->E && !T->isError())
      diag(ES->E->getLoc(), diag::err_expression_unused) << ES->E->getRange();
    return;
  }
  case NodeKind::IfStmt:
    return checkIf(llvm::cast<IfStmt>(S));
  case NodeKind::ForStmt:
    return checkFor(llvm::cast<ForStmt>(S));
  case NodeKind::BreakStmt:
    if (LoopDepth == 0)
      diag(S->getLoc(), diag::err_break_outside_loop);
    return;
  case NodeKind::ContinueStmt:
    if (LoopDepth == 0)
      diag(S->getLoc(), diag::err_continue_outside_loop);
    return;
  case NodeKind::ReturnStmt:
    return checkReturn(llvm::cast<ReturnStmt>(S));
  case NodeKind::YieldStmt:
    return checkYield(llvm::cast<YieldStmt>(S));
  case NodeKind::AssertStmt:
    return checkAssert(llvm::cast<AssertStmt>(S));
  case NodeKind::ErrorStmt:
    return;
#define DECL(Class) case NodeKind::Class:
#define EXPR(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    break;
  }
  llvm_unreachable("not a statement");
}

//===----------------------------------------------------------------------===//
// Every path of a func with a result ends in a return
//===----------------------------------------------------------------------===//

/// Whether `S` contains a `break` of the loop it is in (not of a nested one).
static bool containsBreak(const Stmt *S) {
  if (!S)
    return false;
  if (llvm::isa<BreakStmt>(S))
    return true;
  if (auto *B = llvm::dyn_cast<BlockStmt>(S)) {
    for (const Stmt *Sub : B->Stmts)
      if (containsBreak(Sub))
        return true;
    return false;
  }
  if (auto *I = llvm::dyn_cast<IfStmt>(S))
    return containsBreak(I->Then) || containsBreak(I->Else);
  // A nested `for` owns its breaks; nothing else contains statements.
  return false;
}

static bool endsEveryPath(const Stmt *S);

static bool blockEndsEveryPath(const BlockStmt *B) {
  if (!B)
    return false;
  for (const Stmt *S : B->Stmts)
    if (S && endsEveryPath(S))
      return true;
  return false;
}

/// Whether control never falls through `S`: it returns on every path, or
/// loops forever.
static bool endsEveryPath(const Stmt *S) {
  if (llvm::isa<ReturnStmt>(S))
    return true;
  if (auto *B = llvm::dyn_cast<BlockStmt>(S))
    return blockEndsEveryPath(B);
  if (auto *I = llvm::dyn_cast<IfStmt>(S))
    return I->Else && blockEndsEveryPath(I->Then) && endsEveryPath(I->Else);
  if (auto *F = llvm::dyn_cast<ForStmt>(S)) {
    auto *Lit = llvm::dyn_cast_or_null<BoolLiteralExpr>(F->Cond);
    bool Endless = !F->Cond || (Lit && Lit->Value);
    return Endless && !containsBreak(F->Body);
  }
  return false;
}

void Sema::checkMissingReturn(FuncDecl *F) {
  if (!F->ResultTy || F->ResultTy->isVoid() || F->ResultTy->isError() ||
      !F->Body)
    return;
  if (!blockEndsEveryPath(F->Body))
    diag(F->getName().Loc, diag::err_missing_return)
        << F->getName().Name << F->getName().getRange();
}
