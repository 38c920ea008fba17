//===- SemaAssert.cpp - assertions change nothing --------------------------===//
//
// An object for the robot compiles `assert` to nothing by default, while
// the JIT evaluates every condition: the two agree only if evaluating a
// condition changes nothing the behavior can observe. So a condition may
// not call a task (that advances it), call a non-const method on a
// variable or `output`, nor call a func that does any of these or assigns
// anything but its own locals (`output`, or a local of the task around a
// nested func). Registered C++ functions are trusted to be free of
// effects: bsc cannot see into them (docs/language.md "Assertions").
//
// Funcs may be declared after the assertion that calls them, so the check
// runs after every body was checked, over the assertions Sema collected.
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"

using namespace bsc;
using namespace bsc::sema;

namespace {
/// The first thing a func does that an assertion must not: where, and
/// what (the end of err_assert_effect's sentence).
struct Effect {
  llvm::SMLoc Loc;
  std::string What;
};

/// Finds effects in func bodies, remembering each func's answer.
class EffectFinder {
public:
  /// The effect of evaluating `E` in `Self` (null: an assertion's
  /// condition, which may not change even its own callable's locals).
  std::optional<Effect> inExpr(const Expr *E, const CallableDecl *Self);
  /// The first effect of calling `F`.
  std::optional<Effect> ofFunc(const FuncDecl *F);

private:
  std::optional<Effect> inStmt(const Stmt *S, const FuncDecl *Self);
  std::optional<Effect> inCall(const CallExpr *C, const CallableDecl *Self);
  /// A target assigned or mutated in `Self`: its root must be one of
  /// Self's own locals.
  std::optional<Effect> changes(const Expr *Target, const CallableDecl *Self);

  /// Funcs being looked at (a recursive call adds nothing) or done.
  llvm::DenseMap<const FuncDecl *, std::optional<Effect>> Known;
};
} // namespace

/// The variable or global a data path starts at, if any.
static const NameExpr *getRoot(const Expr *E) {
  while (true) {
    if (const auto *M = llvm::dyn_cast<MemberExpr>(E))
      E = M->Base;
    else if (const auto *I = llvm::dyn_cast<IndexExpr>(E))
      E = I->Base;
    else
      return llvm::dyn_cast<NameExpr>(E);
  }
}

std::optional<Effect> EffectFinder::changes(const Expr *Target,
                                            const CallableDecl *Self) {
  const NameExpr *Root = getRoot(Target);
  if (!Root)
    return std::nullopt; // A temporary.
  if (Root->Kind == NameKind::Output)
    return Effect{Target->getLoc(), "writes 'output'"};
  if (Root->Kind == NameKind::Local && (!Self || Root->Local->Owner != Self))
    return Effect{Target->getLoc(),
                  "changes '" + Root->Name.str() + "'"};
  return std::nullopt;
}

std::optional<Effect> EffectFinder::inCall(const CallExpr *C,
                                           const CallableDecl *Self) {
  switch (C->Kind) {
  case CallKind::Task:
    return Effect{C->getLoc(),
                  "calls task '" + C->Target->getQualifiedName() + "'"};
  case CallKind::Func:
    if (std::optional<Effect> E = ofFunc(llvm::cast<FuncDecl>(C->Target)))
      return Effect{E->Loc, "calls '" + C->Target->getQualifiedName() +
                                "', which " + E->What};
    return std::nullopt;
  case CallKind::Method:
    if (C->NativeFn && !C->NativeFn->ConstSelf)
      return changes(llvm::cast<MemberExpr>(C->Callee)->Base, Self);
    return std::nullopt;
  case CallKind::NativeFunction:
  case CallKind::Unresolved:
    return std::nullopt;
  }
  llvm_unreachable("unknown call kind");
}

std::optional<Effect> EffectFinder::inExpr(const Expr *E,
                                           const CallableDecl *Self) {
  if (!E)
    return std::nullopt;
  auto All = [&](std::initializer_list<const Expr *> Es) {
    for (const Expr *Sub : Es)
      if (std::optional<Effect> F = inExpr(Sub, Self))
        return F;
    return std::optional<Effect>();
  };
  switch (E->getKind()) {
  case NodeKind::MemberExpr:
    return inExpr(llvm::cast<MemberExpr>(E)->Base, Self);
  case NodeKind::IndexExpr:
    return All({llvm::cast<IndexExpr>(E)->Base, llvm::cast<IndexExpr>(E)->Index});
  case NodeKind::CallExpr: {
    const auto *C = llvm::cast<CallExpr>(E);
    if (C->Kind == CallKind::Method)
      if (std::optional<Effect> F =
              inExpr(llvm::cast<MemberExpr>(C->Callee)->Base, Self))
        return F;
    for (const Expr *A : C->Args)
      if (std::optional<Effect> F = inExpr(A, Self))
        return F;
    return inCall(C, Self);
  }
  case NodeKind::UnaryExpr:
    return inExpr(llvm::cast<UnaryExpr>(E)->Operand, Self);
  case NodeKind::BinaryExpr:
    return All({llvm::cast<BinaryExpr>(E)->LHS, llvm::cast<BinaryExpr>(E)->RHS});
  case NodeKind::ConversionExpr:
    return inExpr(llvm::cast<ConversionExpr>(E)->Operand, Self);
  case NodeKind::IntLiteralExpr:
  case NodeKind::FloatLiteralExpr:
  case NodeKind::BoolLiteralExpr:
  case NodeKind::StringLiteralExpr:
  case NodeKind::NameExpr:
  case NodeKind::TaskStateExpr:
  case NodeKind::ErrorExpr:
    return std::nullopt;
#define DECL(Class) case NodeKind::Class:
#define STMT(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    break;
  }
  llvm_unreachable("not an expression");
}

std::optional<Effect> EffectFinder::inStmt(const Stmt *S, const FuncDecl *Self) {
  if (!S)
    return std::nullopt;
  switch (S->getKind()) {
  case NodeKind::BlockStmt:
    for (const Stmt *Sub : llvm::cast<BlockStmt>(S)->Stmts)
      if (std::optional<Effect> E = inStmt(Sub, Self))
        return E;
    return std::nullopt;
  case NodeKind::DeclStmt: {
    const VarDecl *V = llvm::cast<DeclStmt>(S)->Var;
    return V ? inExpr(V->Init, Self) : std::nullopt;
  }
  case NodeKind::AssignStmt: {
    const auto *A = llvm::cast<AssignStmt>(S);
    if (std::optional<Effect> E = changes(A->Target, Self))
      return E;
    if (std::optional<Effect> E = inExpr(A->Target, Self))
      return E;
    return inExpr(A->Value, Self);
  }
  case NodeKind::ExprStmt:
    return inExpr(llvm::cast<ExprStmt>(S)->E, Self);
  case NodeKind::IfStmt: {
    const auto *If = llvm::cast<IfStmt>(S);
    if (std::optional<Effect> E = inExpr(If->Cond, Self))
      return E;
    if (std::optional<Effect> E = inStmt(If->Then, Self))
      return E;
    return inStmt(If->Else, Self);
  }
  case NodeKind::ForStmt: {
    const auto *F = llvm::cast<ForStmt>(S);
    for (const Stmt *Sub : {(const Stmt *)F->Init, (const Stmt *)F->Step,
                            (const Stmt *)F->Body})
      if (std::optional<Effect> E = inStmt(Sub, Self))
        return E;
    return inExpr(F->Cond, Self);
  }
  case NodeKind::ReturnStmt:
    return inExpr(llvm::cast<ReturnStmt>(S)->Value, Self);
  case NodeKind::AssertStmt: // Checked on its own.
  case NodeKind::FuncDeclStmt: // Only in task bodies.
  case NodeKind::YieldStmt:
  case NodeKind::BreakStmt:
  case NodeKind::ContinueStmt:
  case NodeKind::ErrorStmt:
    return std::nullopt;
#define STMT(Class)
#define NODE(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    break;
  }
  llvm_unreachable("not a statement");
}

std::optional<Effect> EffectFinder::ofFunc(const FuncDecl *F) {
  auto [It, New] = Known.try_emplace(F, std::nullopt);
  if (!New)
    return It->second;
  std::optional<Effect> E = inStmt(F->Body, F);
  Known[F] = E;
  return E;
}

void Sema::checkAssertionEffects() {
  EffectFinder Finder;
  for (const Behavior::Assertion &Each : Out.Assertions) {
    const AssertStmt *A = Each.S;
    // A condition with errors of its own was reported already.
    if (!A->Cond || !A->Cond->Ty || A->Cond->Ty->isError())
      continue;
    if (std::optional<Effect> E = Finder.inExpr(A->Cond, nullptr)) {
      diag(A->Cond->getLoc(), diag::err_assert_effect)
          << E->What << A->Cond->getRange();
      if (E->Loc != A->Cond->getLoc())
        diag(E->Loc, diag::note_assert_effect_here);
    }
  }
}
