//===- SemaRepl.cpp - what the REPL's prompt allows beyond a func body ----===//
//
// A line typed at `bsc repl` is checked as the body of a new func
// (ReplChecker) in the entry's module, or in a task's (`:frame`). Beyond a
// func body the prompt reaches the whole loaded behavior: every module
// qualified (`Math::between`) whatever the context module requires, and
// the parameters and locals a task keeps in the state, read-only
// (`Striker.state`, `Striker::Striker.state`; unqualified in the task's
// frame). They are read where the state keeps them: only the fields of the
// state's layout qualify (setFrameFields; the JIT's probes keep every
// parameter and local in the frame).
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSet.h"

using namespace bsc;
using namespace bsc::sema;

//===----------------------------------------------------------------------===//
// Names only the prompt sees
//===----------------------------------------------------------------------===//

QualifierModule Sema::findReplModule(llvm::StringRef Name) {
  QualifierModule QM;
  for (const std::unique_ptr<ModuleInfo> &Info : ModuleInfos)
    if (Info->AST->Name == Name) {
      QM.Kind = QualifierModule::Script;
      QM.ScriptModule = Info->AST;
      return QM;
    }
  if (Natives)
    if (const NativeModule *M = Natives->find(Name)) {
      QM.Kind = QualifierModule::Native;
      QM.NativeMod = M;
    }
  return QM;
}

/// The tasks `N` may name at the prompt: none if it names no task (or an
/// unqualified value: a REPL variable, a frame's local, `input`), one, or
/// for an unqualified name the tasks of that name in several modules.
static llvm::SmallVector<TaskDecl *, 2> findTasksForField(Sema &S,
                                                         const NameExpr &N) {
  const QualifiedName &Name = N.Name;
  llvm::SmallVector<TaskDecl *, 2> Found;
  auto Add = [&](CallableDecl *D) {
    if (auto *T = llvm::dyn_cast_or_null<TaskDecl>(D))
      Found.push_back(T);
  };
  if (Name.Parts.size() == 2) {
    QualifierModule QM = S.findReplModule(Name.Parts[0].Name);
    if (QM.Kind == QualifierModule::Script)
      Add(S.InfoOf[QM.ScriptModule]->Decls.lookup(Name.Parts[1].Name));
    return Found;
  }
  if (Name.isQualified())
    return Found;
  llvm::StringRef Id = Name.Parts[0].Name;
  LookupResult L = S.findUnqualified(Id, LookupMode::Value);
  switch (L.Kind) {
  case LookupKind::Local:
  case LookupKind::Param:
  case LookupKind::Input:
  case LookupKind::Output:
  case LookupKind::Constant:
  case LookupKind::EnumValue:
    return Found; // A value's member.
  case LookupKind::Callable:
    if (llvm::isa<TaskDecl>(L.Callable)) {
      Add(L.Callable);
      return Found;
    }
    break;
  case LookupKind::Error:
  case LookupKind::NativeFn:
  case LookupKind::Module: // `Striker.state`: module Striker's task.
  case LookupKind::TypeName:
    break;
  }
  for (const std::unique_ptr<ModuleInfo> &Info : S.ModuleInfos)
    Add(Info->Decls.lookup(Id));
  return Found;
}

const Type *Sema::checkTaskField(MemberExpr *E, Access A) {
  auto *Base = llvm::dyn_cast<NameExpr>(E->Base);
  if (!Base)
    return nullptr;
  llvm::SmallVector<TaskDecl *, 2> Tasks = findTasksForField(*this, *Base);
  if (Tasks.empty())
    return nullptr;
  if (Tasks.size() > 1) {
    std::vector<std::string> Names;
    for (const TaskDecl *T : Tasks)
      Names.push_back("'" + T->getQualifiedName() + "'");
    diag(Base->getLoc(), diag::err_repl_ambiguous_task)
        << Base->Name.str() << llvm::join(Names, " or ") << Base->getRange();
    return Types.getError();
  }
  const TaskDecl *Task = Tasks.front();
  llvm::StringRef Member = E->Member.Name;
  const Decl *Field = nullptr;
  auto Consider = [&](const Decl *D) {
    if (!Field && D->getName().Name == Member && ReplFrameFields.count(D))
      Field = D;
  };
  for (const ParamDecl *P : Task->Params)
    Consider(P);
  for (const VarDecl *V : Task->Locals)
    Consider(V);
  if (!Field) {
    diag(E->Member.Loc, diag::err_repl_no_task_field)
        << Task->getQualifiedName() << Member << E->getRange();
    return Types.getError();
  }
  if (!checkReplFieldAccess(Field, E->getRange(), A))
    return Types.getError();
  E->TaskField = Field;
  const Type *T = llvm::isa<ParamDecl>(Field)
                      ? llvm::cast<ParamDecl>(Field)->Ty
                      : llvm::cast<VarDecl>(Field)->Ty;
  return T ? T : Types.getError();
}

bool Sema::checkReplFieldAccess(const Decl *D, llvm::SMRange R, Access A) {
  if (A == Access::Read || A == Access::MethodBase ||
      !ReplFrameFields.count(D))
    return true;
  const auto *Owner = llvm::isa<ParamDecl>(D)
                          ? llvm::cast<ParamDecl>(D)->Owner
                          : llvm::cast<VarDecl>(D)->Owner;
  diag(R.Start, diag::err_repl_field_read_only)
      << Owner->getQualifiedName() << D->getName().Name << R;
  return false;
}

//===----------------------------------------------------------------------===//
// ReplChecker
//===----------------------------------------------------------------------===//

ReplChecker::ReplChecker(ASTContext &Ctx, DiagnosticEngine &Diags,
                         const Behavior &B, const NativeRegistry *Natives,
                         ModuleAST *Context)
    : Ctx(Ctx), Context(Context),
      S(std::make_unique<sema::Sema>(Ctx, Diags, Scratch, Natives)) {
  S->buildModuleTables(B.Modules);
  S->Repl = true;
}

ReplChecker::~ReplChecker() = default;

void ReplChecker::setFrameFields(llvm::DenseSet<const Decl *> Kept) {
  S->ReplFrameFields = std::move(Kept);
}

void ReplChecker::setFrame(const TaskDecl *T) { Frame = T; }

std::optional<ReplChecker::Line> ReplChecker::check(BlockStmt *Body,
                                                    unsigned Number) {
  Line L;
  std::string Name = "repl" + std::to_string(Number);
  L.Func = Ctx.create<FuncDecl>(
      Body->getRange(),
      Ident{Ctx.saveString(Name), Body->getRange().Start});
  L.Func->Module = Context;
  L.Func->Body = Body;
  L.Func->ResultTy = Ctx.getTypes().getVoid();

  S->HadError = false;
  S->InReplLine = true;
  S->CurModule = S->InfoOf.lookup(Frame ? Frame->Module : Context);
  S->CurTask = nullptr;
  S->ReplFrame = Frame;
  S->CurCallable = L.Func;
  S->LoopDepth = 0;
  S->Scopes.clear();
  // The frame's kept parameters and locals, then the REPL's variables
  // (which may hide them), then the line's own.
  S->pushScope();
  if (Frame) {
    llvm::StringSet<> Seen;
    auto Add = [&](Decl *D) {
      if (S->ReplFrameFields.count(D) && Seen.insert(D->getName().Name).second)
        S->Scopes.back().push_back({D->getName().Name, D});
    };
    for (ParamDecl *P : Frame->Params)
      Add(P);
    for (VarDecl *V : Frame->Locals)
      Add(V);
  }
  S->pushScope();
  for (VarDecl *V : Vars)
    S->Scopes.back().push_back({V->getName().Name, V});
  S->pushScope();
  for (Stmt *&St : Body->Stmts) {
    auto *ES = llvm::dyn_cast<ExprStmt>(St);
    if (!ES || St != Body->Stmts.back() || !ES->E) {
      S->checkStmt(St);
      continue;
    }
    // The value of the last expression is shown: it initialises a hidden
    // local, the result.
    const Type *T;
    if (auto *C = llvm::dyn_cast<CallExpr>(ES->E))
      T = C->Ty = S->checkCall(C, /*AsStatement=*/true);
    else
      T = S->checkExpr(ES->E);
    if (T->isError() || T->isVoid())
      continue;
    L.Result = Ctx.create<VarDecl>(ES->getRange(),
                                   Ident{"", ES->getRange().Start},
                                   QualifiedName(), ES->E);
    L.Result->Ty = T;
    L.Result->Owner = L.Func;
    L.Func->Locals.push_back(L.Result);
    St = Ctx.create<DeclStmt>(ES->getRange(), L.Result);
  }
  S->Scopes.clear();
  S->CurCallable = nullptr;
  S->CurModule = nullptr;
  S->InReplLine = false;
  if (S->HadError)
    return std::nullopt;
  for (VarDecl *V : L.Func->Locals)
    if (V != L.Result) {
      L.NewVars.push_back(V);
      Vars.push_back(V);
    }
  return L;
}

