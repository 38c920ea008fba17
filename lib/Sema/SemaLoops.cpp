//===- SemaLoops.cpp - loops that can keep a cycle from ending ------------===//
//
// A behavior runs inside the robot's control thread: a cycle that does not
// return stops the robot's thinking. Two checks look at loops for that,
// both structural walks over a loop's checked body:
//
// - A loop that certainly never ends once entered (no condition, or `true`,
//   and no `yield`, `return` or `break` of its own): warn_yield_loop, in
//   tasks and funcs alike.
// - A *cycle loop*, a task's loop with a `yield` of its own, must yield on
//   every pass: if some path through its body comes back to its head (the
//   end of the body, or a `continue`, then a step that is not `yield`)
//   without passing one of its `yield`s, and the loop is not counted, a
//   cycle that takes that path may never end. warn_loop_skips_yield names
//   the loop, and a note the branch where the path leaves the yields
//   (Céu calls these "tight loops" and rejects them; Blech checks that
//   every reaction ends). A `yield` in a called task does not count: the
//   callee returns within the cycle.
//
// Counted means the compiler sees the count (docs/language.md, "Loops that
// end a cycle"): `for(int i = A; i < B; i += C)` with A, B and C constant,
// C moving i toward B (any of `<`, `<=`, `>`, `>=`, the counter on either
// side; `-=`), and nothing in the body assigning i. Such a loop ends after
// a known number of passes whatever its body does.
//
// Loops without a `yield` of their own that are not endless (computations
// with a condition) and funcs' loops are not judged here: whether their
// condition ever turns false is beyond a structural check, and
// `--cycle-budget` stops them at run time.
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"

using namespace bsc;
using namespace bsc::sema;

/// Whether running `S` can leave the loop it is in: a `yield` or `return`
/// anywhere in it, or a `break` of this loop (not of a loop inside).
static bool canLeaveLoop(const Stmt *S, bool InInnerLoop) {
  if (!S)
    return false;
  switch (S->getKind()) {
  case NodeKind::YieldStmt:
  case NodeKind::ReturnStmt:
    return true;
  case NodeKind::BreakStmt:
    return !InInnerLoop;
  case NodeKind::BlockStmt:
    return llvm::any_of(llvm::cast<BlockStmt>(S)->Stmts, [&](const Stmt *C) {
      return canLeaveLoop(C, InInnerLoop);
    });
  case NodeKind::IfStmt: {
    const auto *If = llvm::cast<IfStmt>(S);
    return canLeaveLoop(If->Then, InInnerLoop) ||
           canLeaveLoop(If->Else, InInnerLoop);
  }
  case NodeKind::ForStmt: {
    const auto *F = llvm::cast<ForStmt>(S);
    return canLeaveLoop(F->Step, true) || canLeaveLoop(F->Body, true);
  }
  case NodeKind::ErrorStmt:
    return true; // Already reported; say nothing more about it.
  case NodeKind::DeclStmt:
  case NodeKind::FuncDeclStmt:
  case NodeKind::AssignStmt:
  case NodeKind::ExprStmt:
  case NodeKind::AssertStmt:
  case NodeKind::ContinueStmt:
    return false;
#define STMT(Class)
#define NODE(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    llvm_unreachable("not a statement");
  }
  llvm_unreachable("unknown node kind");
}

void Sema::warnIfEndless(const ForStmt *S) {
  // Only where it is certain: no condition, or `true`.
  if (S->Cond && !(llvm::isa<BoolLiteralExpr>(S->Cond) &&
                   llvm::cast<BoolLiteralExpr>(S->Cond)->Value))
    return;
  if (canLeaveLoop(S->Step, false) || canLeaveLoop(S->Body, false))
    return;
  diag(S->getLoc(), llvm::isa<TaskDecl>(CurCallable)
                        ? diag::warn_yield_loop
                        : diag::warn_endless_loop_in_func);
}

namespace {
/// Where a path that skips every `yield` leaves the ones it could have
/// passed: the branch a note points at.
struct Witness {
  enum Kind {
    None,        ///< No choice of the path's own (straight code).
    Then,        ///< The `if` branch taken.
    Else,        ///< The `else` branch taken.
    NoElse,      ///< The `if`'s condition false, and it has no `else`.
    Continue,    ///< A `continue` before any yield.
    InnerLoop,   ///< A loop inside that may end before a pass yields.
  } K = None;
  const Stmt *At = nullptr;
};

/// How a statement can complete without having run a `yield` of the
/// loop's task: falling through to the next statement, or by `continue`
/// or `break` of the loop being judged. Each way holds the witness of one
/// such path, if any.
struct SkipPaths {
  std::optional<Witness> FallsThrough, Continues, Breaks;

  static SkipPaths fallThrough() {
    SkipPaths P;
    P.FallsThrough = Witness();
    return P;
  }
  /// The union of two alternatives; the first path found of each way is
  /// kept, and a path with a witness beats one without.
  void merge(const SkipPaths &O) {
    auto Join = [](std::optional<Witness> &A, const std::optional<Witness> &B) {
      if (!A || (A->K == Witness::None && B && B->K != Witness::None))
        A = B ? B : A;
    };
    Join(FallsThrough, O.FallsThrough);
    Join(Continues, O.Continues);
    Join(Breaks, O.Breaks);
  }
};

/// The counted-loop pattern (see the file comment); the number of passes.
std::optional<uint64_t> countPasses(Sema &S, const ForStmt *F);
/// Whether a loop's condition certainly holds when it is entered.
bool runsFirstPass(Sema &S, const ForStmt *F);
bool assigns(const Stmt *S, const VarDecl *V);

/// Whether any statement in S is a `yield` of the task being checked:
/// expressions hold none, and a nested func's body (under a declaration)
/// is not the task's.
bool containsYield(const Node *N) {
  if (!N || llvm::isa<Expr>(N) || llvm::isa<Decl>(N))
    return false;
  if (llvm::isa<YieldStmt>(N))
    return true;
  bool Found = false;
  forEachChild(*N, [&](const Node &C) { Found = Found || containsYield(&C); });
  return Found;
}

/// The paths through S that pass no `yield`.
class SkipFinder {
public:
  explicit SkipFinder(Sema &S) : S(S) {}

  SkipPaths visit(const Stmt *St) {
    if (!St)
      return SkipPaths::fallThrough();
    switch (St->getKind()) {
    case NodeKind::YieldStmt:
    case NodeKind::ReturnStmt:
    case NodeKind::ErrorStmt: // Reported already; assume it yields.
      return {};
    case NodeKind::BreakStmt: {
      SkipPaths P;
      P.Breaks = Witness();
      return P;
    }
    case NodeKind::ContinueStmt: {
      SkipPaths P;
      P.Continues = Witness{Witness::Continue, St};
      return P;
    }
    case NodeKind::BlockStmt:
      return visitBlock(llvm::cast<BlockStmt>(St));
    case NodeKind::IfStmt:
      return visitIf(llvm::cast<IfStmt>(St));
    case NodeKind::ForStmt:
      return visitInnerLoop(llvm::cast<ForStmt>(St));
    case NodeKind::DeclStmt:
    case NodeKind::FuncDeclStmt:
    case NodeKind::AssignStmt:
    case NodeKind::ExprStmt:
    case NodeKind::AssertStmt:
      return SkipPaths::fallThrough();
#define STMT(Class)
#define NODE(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
      llvm_unreachable("not a statement");
    }
    llvm_unreachable("unknown node kind");
  }

private:
  Sema &S;

  SkipPaths visitBlock(const BlockStmt *B) {
    SkipPaths Out = SkipPaths::fallThrough();
    for (const Stmt *St : B->Stmts) {
      if (!Out.FallsThrough)
        break; // The rest runs only after a yield.
      Witness Before = *Out.FallsThrough;
      SkipPaths Here = visit(St);
      // A path through this statement is named by its first choice.
      auto Keep = [&](std::optional<Witness> &W) {
        if (W && Before.K != Witness::None)
          W = Before;
      };
      Keep(Here.FallsThrough);
      Keep(Here.Continues);
      Keep(Here.Breaks);
      Out.FallsThrough.reset();
      Out.merge(Here);
    }
    return Out;
  }

  SkipPaths visitIf(const IfStmt *If) {
    SkipPaths Then = visit(If->Then);
    SkipPaths Else = If->Else ? visit(If->Else) : SkipPaths::fallThrough();
    // A path that avoids a yield the other branch has is the choice a
    // reader must see.
    auto Name = [](SkipPaths &P, Witness W) {
      for (std::optional<Witness> *Way :
           {&P.FallsThrough, &P.Continues, &P.Breaks})
        if (*Way && (*Way)->K == Witness::None)
          *Way = W;
    };
    if (containsYield(If->Then) || containsYield(If->Else)) {
      if (If->Else)
        Name(Else, {Witness::Else, If});
      else
        Name(Else, {Witness::NoElse, If});
      Name(Then, {Witness::Then, If});
    }
    Then.merge(Else);
    return Then;
  }

  SkipPaths visitInnerLoop(const ForStmt *F) {
    // Its `break` and `continue` are its own; it is left by falling
    // through: at its condition, or by a `break` before any yield.
    SkipPaths Body = visit(F->Body);
    bool FirstPass = runsFirstPass(S, F);
    bool Endless = !F->Cond || (llvm::isa<BoolLiteralExpr>(F->Cond) &&
                                llvm::cast<BoolLiteralExpr>(F->Cond)->Value);
    bool StepYields = F->Step && llvm::isa<YieldStmt>(F->Step);
    bool PassMaySkip = Body.FallsThrough || Body.Continues;
    SkipPaths Out;
    Witness Here{containsYield(F) ? Witness::InnerLoop : Witness::None, F};
    if (Body.Breaks)
      Out.FallsThrough = Body.Breaks->K == Witness::None ? Here : *Body.Breaks;
    else if (!FirstPass)
      Out.FallsThrough = Here;
    else if (PassMaySkip && !Endless && !StepYields)
      Out.FallsThrough = Here; // Every pass may skip, then the loop ends.
    return Out;
  }
};

/// Whether S (a loop body) assigns the local V anywhere.
bool assigns(const Stmt *S, const VarDecl *V) {
  if (!S)
    return false;
  if (const auto *A = llvm::dyn_cast<AssignStmt>(S)) {
    const auto *N = llvm::dyn_cast<NameExpr>(A->Target);
    return N && N->Kind == NameKind::Local && N->Local == V;
  }
  // Assignments are statements: only statements hold them.
  bool Found = false;
  forEachChild(*S, [&](const Node &C) {
    if (const auto *Child = llvm::dyn_cast<Stmt>(&C))
      Found = Found || assigns(Child, V);
  });
  return Found;
}

/// `for(int i = A; i OP B; ...)` with A and B constant (the counter on
/// either side of the comparison; OP as if it were on the left).
struct CounterHead {
  const VarDecl *Counter;
  int64_t From, Bound;
  BinaryOp Op;
};

std::optional<CounterHead> matchCounterHead(Sema &S, const ForStmt *F) {
  const auto *Init = llvm::dyn_cast_or_null<DeclStmt>(F->Init);
  const auto *Cond = llvm::dyn_cast_or_null<BinaryExpr>(F->Cond);
  if (!Init || !Cond || !Init->Var->Ty || !Init->Var->Ty->isInt() ||
      !Init->Var->Init)
    return std::nullopt;
  const VarDecl *I = Init->Var;
  auto IsCounter = [&](const Expr *E) {
    const auto *N = llvm::dyn_cast_or_null<NameExpr>(E);
    return N && N->Kind == NameKind::Local && N->Local == I;
  };
  BinaryOp Op = Cond->Op;
  const Expr *Bound;
  if (IsCounter(Cond->LHS)) {
    Bound = Cond->RHS;
  } else if (IsCounter(Cond->RHS)) {
    Bound = Cond->LHS;
    switch (Op) { // B > i is i < B.
    case BinaryOp::Lt: Op = BinaryOp::Gt; break;
    case BinaryOp::Le: Op = BinaryOp::Ge; break;
    case BinaryOp::Gt: Op = BinaryOp::Lt; break;
    case BinaryOp::Ge: Op = BinaryOp::Le; break;
    case BinaryOp::Eq: case BinaryOp::Ne: break;
    case BinaryOp::Mul: case BinaryOp::Div: case BinaryOp::Rem:
    case BinaryOp::Add: case BinaryOp::Sub: case BinaryOp::And:
    case BinaryOp::Or:
      return std::nullopt;
    }
  } else {
    return std::nullopt;
  }
  if (!Bound->Ty || !Bound->Ty->isInt())
    return std::nullopt;
  auto A = S.evaluateConstant(I->Init);
  auto B = S.evaluateConstant(Bound);
  if (!A || !B)
    return std::nullopt;
  return CounterHead{I, A->Int, B->Int, Op};
}

/// Whether a loop's condition holds when it is entered, so that it runs a
/// first pass (a constant head, or `true`).
bool runsFirstPass(Sema &S, const ForStmt *F) {
  if (!F->Cond)
    return true;
  if (const auto *B = llvm::dyn_cast<BoolLiteralExpr>(F->Cond))
    return B->Value;
  std::optional<CounterHead> H = matchCounterHead(S, F);
  if (!H)
    return false;
  switch (H->Op) {
  case BinaryOp::Lt: return H->From < H->Bound;
  case BinaryOp::Le: return H->From <= H->Bound;
  case BinaryOp::Gt: return H->From > H->Bound;
  case BinaryOp::Ge: return H->From >= H->Bound;
  case BinaryOp::Eq: return H->From == H->Bound;
  case BinaryOp::Ne: return H->From != H->Bound;
  case BinaryOp::Mul: case BinaryOp::Div: case BinaryOp::Rem:
  case BinaryOp::Add: case BinaryOp::Sub: case BinaryOp::And:
  case BinaryOp::Or:
    return false; // Not a comparison: matchCounterHead's Bound is no bound.
  }
  llvm_unreachable("unknown operator");
}

std::optional<uint64_t> countPasses(Sema &S, const ForStmt *F) {
  std::optional<CounterHead> H = matchCounterHead(S, F);
  if (!H)
    return std::nullopt;
  bool Up = H->Op == BinaryOp::Lt || H->Op == BinaryOp::Le;
  if (!Up && H->Op != BinaryOp::Gt && H->Op != BinaryOp::Ge)
    return std::nullopt;
  // ...; i += C) or i -= C, C constant and moving i toward the bound.
  const auto *Step = llvm::dyn_cast_or_null<AssignStmt>(F->Step);
  auto IsCounter = [&](const Expr *E) {
    const auto *N = llvm::dyn_cast_or_null<NameExpr>(E);
    return N && N->Kind == NameKind::Local && N->Local == H->Counter;
  };
  if (!Step || !IsCounter(Step->Target) ||
      (Step->Op != AssignOp::AddAssign && Step->Op != AssignOp::SubAssign) ||
      !Step->Value->Ty || !Step->Value->Ty->isInt())
    return std::nullopt;
  auto C = S.evaluateConstant(Step->Value);
  if (!C)
    return std::nullopt;
  int64_t Delta = Step->Op == AssignOp::AddAssign ? int64_t(C->Int)
                                                  : -int64_t(C->Int);
  if (Delta == 0 || (Delta > 0) != Up || assigns(F->Body, H->Counter))
    return std::nullopt;
  // The passes, in 64 bits: the counter stops before it passes the bound,
  // so it never wraps.
  int64_t From = H->From, To = H->Bound;
  if (H->Op == BinaryOp::Le)
    ++To;
  else if (H->Op == BinaryOp::Ge)
    --To;
  int64_t Span = Up ? To - From : From - To;
  if (Span <= 0)
    return 0;
  int64_t Stride = Delta > 0 ? Delta : -Delta;
  return uint64_t((Span + Stride - 1) / Stride);
}
} // namespace

void Sema::checkLoopYields(ForStmt *F) {
  if (!llvm::isa<TaskDecl>(CurCallable) || !F->Body)
    return;
  // Only a cycle loop: one that yields itself, in its step or body.
  if (!containsYield(F->Body) && !(F->Step && containsYield(F->Step)))
    return;
  // Every way round passes the step's yield.
  if (F->Step && llvm::isa<YieldStmt>(F->Step)) {
    F->YieldsEveryPass = true;
    return;
  }
  SkipPaths Paths = SkipFinder(*this).visit(F->Body);
  std::optional<Witness> Round =
      Paths.FallsThrough ? Paths.FallsThrough : Paths.Continues;
  if (!Round) {
    F->YieldsEveryPass = true;
    return;
  }
  if (countPasses(*this, F))
    return;
  diag(F->getLoc(), diag::warn_loop_skips_yield);
  const Witness &W = *Round;
  switch (W.K) {
  case Witness::None:
    break;
  case Witness::Then:
    diag(W.At->getLoc(), diag::note_skip_then);
    break;
  case Witness::Else:
    diag(llvm::cast<IfStmt>(W.At)->ElseLoc, diag::note_skip_else);
    break;
  case Witness::NoElse:
    diag(W.At->getLoc(), diag::note_skip_no_else);
    break;
  case Witness::Continue:
    diag(W.At->getLoc(), diag::note_skip_continue);
    break;
  case Witness::InnerLoop:
    diag(W.At->getLoc(), diag::note_skip_inner_loop);
    break;
  }
}
