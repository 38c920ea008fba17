//===- CGStmt.cpp - lowering statements -----------------------------------===//
//
// Statements become ordinary control flow, the same in funcs and tasks:
// a `yield` is just one more statement that ends its block with `ret` and
// starts a new block the resume switch can jump to (CGTask.cpp). Loops
// therefore need nothing special to survive a yield, and `break` and
// `continue` after a yield branch to the same blocks as before it.
//
// Code that follows a terminator (`return`, `break`, `continue`) goes into
// a fresh block without predecessors; FunctionEmitter::run deletes such
// blocks at the end, which keeps the emitters free of "is this reachable?"
// bookkeeping.
//
//===----------------------------------------------------------------------===//
#include "FunctionEmitter.h"
#include "llvm/IR/Constants.h"
#include "llvm/Support/ErrorHandling.h"

using namespace bsc;
using namespace bsc::codegen;

void FunctionEmitter::startDeadBlock() {
  Builder.SetInsertPoint(
      llvm::BasicBlock::Create(CGM.getContext(), "dead", Fn));
}

void FunctionEmitter::emitBranch(llvm::BasicBlock *Dest) {
  if (!Builder.GetInsertBlock()->getTerminator())
    Builder.CreateBr(Dest);
}

void FunctionEmitter::emitDestroy(const NativeClass *C, llvm::Value *Addr) {
  Builder.CreateCall(CGM.getLifeThunk(C, C->Destroy, 1), {Addr});
}

void FunctionEmitter::pushTemp(const NativeClass *C, llvm::Value *Addr) {
  if (ModuleEmitter::needsDestroy(C))
    Temps.push_back({C, Addr});
}

void FunctionEmitter::popTemps(size_t Depth) {
  while (Temps.size() > Depth) {
    Cleanup T = Temps.pop_back_val();
    emitDestroy(T.Class, T.Addr);
  }
}

void FunctionEmitter::emitLiveCleanups(size_t Depth, bool Forget) {
  for (size_t I = Live.size(); I > Depth; --I)
    emitDestroy(Live[I - 1].Class, Live[I - 1].Addr);
  if (Forget)
    Live.resize(std::min(Live.size(), Depth));
}

llvm::Value *FunctionEmitter::emitFullCond(const Expr *E) {
  size_t Depth = Temps.size();
  llvm::Value *V = emitCond(E);
  popTemps(Depth);
  return V;
}

void FunctionEmitter::emitBlock(const BlockStmt *S) {
  // A block is a scope: the func locals it constructed die at its end (a
  // task's live on in the frame; Live stays empty in tasks).
  size_t Depth = Live.size();
  // The body's own block is the subprogram's scope.
  bool Nested = S != D.Body;
  if (Nested)
    pushDebugScope(S->getLoc());
  for (const Stmt *Child : S->Stmts)
    emitStmt(Child);
  emitLiveCleanups(Depth, /*Forget=*/true);
  if (Nested)
    popDebugScope();
}

void FunctionEmitter::emitStmt(const Stmt *S) {
  // Every statement ends its full expressions: what remains of their
  // temporaries is destroyed here (conditions, `return` and `yield` do it
  // themselves, before they branch).
  size_t Depth = Temps.size();
  llvm::SMLoc Outer = CurStmtLoc;
  llvm::DebugLoc OuterDebugLoc = Builder.getCurrentDebugLocation();
  CurStmtLoc = S->getLoc();
  setDebugLocation(S->getLoc());
  emitStmtCount(*S);
  emitStmtImpl(S);
  popTemps(Depth);
  CurStmtLoc = Outer;
  Builder.SetCurrentDebugLocation(OuterDebugLoc);
}

void FunctionEmitter::emitProbe(const char *Symbol, unsigned Site) {
  Builder.CreateStore(Builder.getInt32(Site), CGM.getProbe(Symbol),
                      /*isVolatile=*/true);
}

void FunctionEmitter::emitStmtImpl(const Stmt *S) {
  switch (S->getKind()) {
  case NodeKind::BlockStmt:
    return emitBlock(llvm::cast<BlockStmt>(S));
  case NodeKind::DeclStmt:
    return emitDecl(*llvm::cast<DeclStmt>(S));
  case NodeKind::FuncDeclStmt:
    // A nested func is a function of its own (ModuleEmitter emits every
    // func of Behavior::Funcs); its declaration runs no code.
    return;
  case NodeKind::AssignStmt:
    return emitAssign(*llvm::cast<AssignStmt>(S));
  case NodeKind::ExprStmt:
    emitExpr(llvm::cast<ExprStmt>(S)->E);
    return;
  case NodeKind::IfStmt:
    return emitIf(*llvm::cast<IfStmt>(S));
  case NodeKind::ForStmt:
    return emitFor(*llvm::cast<ForStmt>(S));
  case NodeKind::BreakStmt:
    return emitBreak(*llvm::cast<BreakStmt>(S));
  case NodeKind::ContinueStmt:
    return emitContinue(*llvm::cast<ContinueStmt>(S));
  case NodeKind::ReturnStmt:
    return emitReturn(*llvm::cast<ReturnStmt>(S));
  case NodeKind::YieldStmt:
    return emitYield(*llvm::cast<YieldStmt>(S));
  case NodeKind::AssertStmt:
    return emitAssert(*llvm::cast<AssertStmt>(S));
  case NodeKind::ErrorStmt:
    llvm_unreachable("a behavior with a parse error never reaches CodeGen");
#define DECL(Class) case NodeKind::Class:
#define EXPR(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    break;
  }
  llvm_unreachable("not a statement");
}

void FunctionEmitter::emitDecl(const DeclStmt &S) {
  const VarDecl *V = S.Var;
  declareForDebugger(*V, V->Ty);
  if (V->Ty->isClass()) {
    const NativeClass *C = V->Ty->getClass();
    llvm::Value *Addr = getDeclAddress(V);
    if (!llvm::isa_and_nonnull<TaskDecl>(V->Owner)) {
      // A func's local is constructed here (copy-constructed from its
      // initialiser) and destroyed at the end of its block.
      if (V->Init)
        emitClassCopy(C, Addr, emitExpr(V->Init), /*DstConstructed=*/false);
      else
        emitClassInit(C, Addr);
      // A REPL variable outlives its line; the REPL destroys it.
      if (ModuleEmitter::needsDestroy(C) && !CGM.getReplSlot(V))
        Live.push_back({C, Addr});
      return;
    }
    // A task's local was constructed at the reset and stays constructed
    // until the task finishes: assign it, or make it a fresh default value.
    if (V->Init) {
      emitStore(V->Ty, emitExpr(V->Init), Addr);
    } else {
      if (ModuleEmitter::needsDestroy(C))
        emitDestroy(C, Addr);
      emitClassInit(C, Addr);
    }
    return;
  }
  // Without an initialiser the local is its type's zero, every time the
  // declaration runs (a declaration in a loop body starts over each pass).
  llvm::Value *Init = V->Init ? emitExpr(V->Init) : CGM.getZeroValue(V->Ty);
  if (V->Init && V->Ty->isFloat() && Init->getType()->isIntegerTy(32))
    Init = Builder.CreateSIToFP(Init, Builder.getFloatTy());
  llvm::Value *Addr = getDeclAddress(V);
  if (V->Init)
    emitStore(V->Ty, Init, Addr);
  else
    createStore(ModuleEmitter::Access::State, Init,
                Addr); // Already in its memory type.
}

void FunctionEmitter::emitAssign(const AssignStmt &S) {
  const Type *T = S.Target->Ty;
  BinaryOp Op;
  bool Compound = getCompoundOperator(S.Op, Op);
  auto Convert = [&](llvm::Value *V) {
    if (T->isFloat() && V->getType()->isIntegerTy(32))
      V = Builder.CreateSIToFP(V, Builder.getFloatTy());
    return V;
  };
  // `output.motion = ...`, `v.x += 1`, `output.wide[k] = 3`: C++ storage
  // reached by offset (a field, an element of an array field)...
  const auto *ME = llvm::dyn_cast<MemberExpr>(S.Target);
  const NativeType *Storage = nullptr;
  llvm::Value *Addr = nullptr;
  if (const auto *IE = llvm::dyn_cast<IndexExpr>(S.Target)) {
    Storage = IE->Field;
    Addr = emitElementAddress(*IE);
  } else if (ME && ME->Resolved->Kind == NativeFunction::Field &&
             ME->Resolved->FieldOffset) {
    Storage = &ME->Resolved->Result;
    Addr = emitFieldAddress(*ME);
  }
  if (Storage) {
    if (T->isClass()) {
      assert(!Compound && "Sema has no compound assignment of classes");
      emitStore(T, emitExpr(S.Value), Addr);
      return;
    }
    llvm::Value *V;
    if (Compound) {
      llvm::Value *Old = emitFieldLoad(T, *Storage, Addr);
      V = emitArith(Op, Old, Convert(emitExpr(S.Value)));
    } else {
      V = Convert(emitExpr(S.Value));
    }
    emitFieldStore(T, *Storage, V, Addr);
    return;
  }
  if (ME) {
    // ...or a property through its getter and setter thunks.
    const NativeFunction &NF = *ME->Resolved;
    llvm::Value *Self = emitExpr(ME->Base);
    llvm::Value *V;
    if (Compound) {
      llvm::Value *Old = emitNativeCallWithValues(NF, Self, {});
      V = emitArith(Op, Old, Convert(emitExpr(S.Value)));
    } else {
      V = Convert(emitExpr(S.Value));
    }
    if (V->getType()->isIntegerTy(1))
      V = Builder.CreateZExt(V, Builder.getInt32Ty());
    Builder.CreateCall(CGM.getNativeSetter(NF), {Self, V});
    return;
  }
  Addr = getLValueAddress(*llvm::cast<NameExpr>(S.Target));
  if (!Compound) {
    emitStore(T, Convert(emitExpr(S.Value)), Addr);
    return;
  }
  // `x op= v` is `x = x op v` with x evaluated once; the target is a plain
  // variable, so reading it first or after `v` is the same (v cannot
  // assign to it: calls cannot reach a caller's locals).
  llvm::Value *Old = emitLoad(T, Addr);
  llvm::Value *V = emitExpr(S.Value);
  if (T->isFloat() && V->getType()->isIntegerTy(32))
    V = Builder.CreateSIToFP(V, Builder.getFloatTy());
  emitStore(T, emitArith(Op, Old, V), Addr);
}

void FunctionEmitter::emitIf(const IfStmt &S) {
  llvm::LLVMContext &Ctx = CGM.getContext();
  llvm::Value *Cond = emitCondition(S, S.Cond);
  llvm::BasicBlock *ThenBB = llvm::BasicBlock::Create(Ctx, "if.then", Fn);
  llvm::BasicBlock *EndBB = llvm::BasicBlock::Create(Ctx, "if.end");
  llvm::BasicBlock *ElseBB = EndBB;
  if (S.Else)
    ElseBB = llvm::BasicBlock::Create(Ctx, "if.else", Fn);
  Builder.CreateCondBr(Cond, ThenBB, ElseBB);

  Builder.SetInsertPoint(ThenBB);
  emitBlock(S.Then);
  emitBranch(EndBB);
  if (S.Else) {
    Builder.SetInsertPoint(ElseBB);
    emitStmt(S.Else);
    emitBranch(EndBB);
  }
  EndBB->insertInto(Fn);
  Builder.SetInsertPoint(EndBB);
}

void FunctionEmitter::emitFor(const ForStmt &S) {
  llvm::LLVMContext &Ctx = CGM.getContext();
  // The head is a scope around the loop: a local declared by `init` lives
  // until the loop ends.
  size_t HeadDepth = Live.size();
  pushDebugScope(S.getLoc());
  if (S.Init)
    emitStmt(S.Init);
  llvm::BasicBlock *CondBB = llvm::BasicBlock::Create(Ctx, "for.cond", Fn);
  llvm::BasicBlock *BodyBB = llvm::BasicBlock::Create(Ctx, "for.body");
  llvm::BasicBlock *StepBB = llvm::BasicBlock::Create(Ctx, "for.step");
  llvm::BasicBlock *EndBB = llvm::BasicBlock::Create(Ctx, "for.end");
  Builder.CreateBr(CondBB);

  // A missing condition is true.
  Builder.SetInsertPoint(CondBB);
  unsigned Site = 0;
  if (CGM.getOptions().Probes) {
    Site = CGM.addSite({DebugSite::Loop, &D, S.getLoc(), ""});
    emitProbe(LoopProbeSymbol, Site);
  }
  if (S.Cond)
    Builder.CreateCondBr(emitCondition(S, S.Cond), BodyBB, EndBB);
  else
    Builder.CreateBr(BodyBB);

  BodyBB->insertInto(Fn);
  Builder.SetInsertPoint(BodyBB);
  Loops.push_back({EndBB, StepBB, Live.size(), Site});
  emitBlock(S.Body);
  Loops.pop_back();
  emitBranch(StepBB);

  // `continue` runs the step, as in C. A `yield` step returns here and the
  // next call resumes at the condition.
  StepBB->insertInto(Fn);
  Builder.SetInsertPoint(StepBB);
  if (S.Step)
    emitStmt(S.Step);
  if (CGM.getOptions().CycleBudget && !S.YieldsEveryPass &&
      !Builder.GetInsertBlock()->getTerminator())
    emitBudgetCharge(S);
  emitBranch(CondBB);

  EndBB->insertInto(Fn);
  Builder.SetInsertPoint(EndBB);
  // Out of the loop, the probe names the enclosing loop again (0: none),
  // so that a watchdog stopping an outer loop does not blame this one.
  if (CGM.getOptions().Probes)
    emitProbe(LoopProbeSymbol, Loops.empty() ? 0 : Loops.back().ProbeSite);
  emitLiveCleanups(HeadDepth, /*Forget=*/true);
  popDebugScope();
}

// `break` and `continue` leave the blocks of the loop body early: their
// func locals are destroyed on the way out, innermost first.
void FunctionEmitter::emitBreak(const BreakStmt &) {
  assert(!Loops.empty() && "Sema allows break only in loops");
  emitLiveCleanups(Loops.back().LiveDepth, /*Forget=*/false);
  Builder.CreateBr(Loops.back().Break);
  startDeadBlock();
}

void FunctionEmitter::emitContinue(const ContinueStmt &) {
  assert(!Loops.empty() && "Sema allows continue only in loops");
  emitLiveCleanups(Loops.back().LiveDepth, /*Forget=*/false);
  Builder.CreateBr(Loops.back().Continue);
  startDeadBlock();
}

void FunctionEmitter::emitReturn(const ReturnStmt &S) {
  // The result is complete before anything dies: the value's temporaries,
  // then every live local and parameter, newest first.
  if (Task) {
    // `return` in a task: done, and start from the top at the next call.
    emitTaskFinish();
  } else if (S.Value && S.Value->Ty && S.Value->Ty->isClass()) {
    // Into the caller's raw storage: copy-construct.
    emitClassCopy(S.Value->Ty->getClass(), Fn->getArg(1), emitExpr(S.Value),
                  /*DstConstructed=*/false);
    popTemps(0);
    emitLiveCleanups(0, /*Forget=*/false);
    Builder.CreateRetVoid();
  } else if (S.Value) {
    llvm::Value *V = emitExpr(S.Value);
    if (Fn->getReturnType()->isFloatTy() && V->getType()->isIntegerTy(32))
      V = Builder.CreateSIToFP(V, Builder.getFloatTy());
    popTemps(0);
    emitLiveCleanups(0, /*Forget=*/false);
    Builder.CreateRet(V);
  } else {
    emitLiveCleanups(0, /*Forget=*/false);
    Builder.CreateRetVoid();
  }
  startDeadBlock();
}
