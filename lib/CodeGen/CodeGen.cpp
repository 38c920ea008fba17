//===- CodeGen.cpp - a checked behavior to one LLVM module ----------------===//
//
// The entry point `emitLLVM` and the order of the work: ModuleEmitter::run
// lays out the state (CGLayout.cpp), declares the functions, has a
// FunctionEmitter define each (the prologue and epilogue of funcs are
// here, statements, expressions and tasks in CGStmt.cpp, CGExpr.cpp and
// CGTask.cpp), then emits the entries, destroy functions, the info table
// and `main` (CGEntries.cpp) and the i386 fix-ups. Types are in
// CGTypes.cpp, thunks and strings in CGNative.cpp, REPL lines in
// CGRepl.cpp. The ABI these implement is include/bscript/bscript.h and
// docs/design/backend.md; the numbers that robot code sees (state size,
// alignment, frame offsets) are computed only in CGLayout.cpp, from the
// target's DataLayout, and no optimisation level can change them because
// every frame is an explicit struct type rather than something a pass
// computes (which is why tasks are lowered by hand and not with
// llvm.coro.*).
//
//===----------------------------------------------------------------------===//
#include "FunctionEmitter.h"
#include "llvm/IR/Function.h"
#include "llvm/IR/GlobalVariable.h"
#include "llvm/IR/InstIterator.h"
#include "llvm/IR/MDBuilder.h"
#include "llvm/Transforms/Utils/BasicBlockUtils.h"

using namespace bsc;
using namespace bsc::codegen;

//===----------------------------------------------------------------------===//
// ModuleEmitter
//===----------------------------------------------------------------------===//

ModuleEmitter::ModuleEmitter(const Behavior &B, llvm::Module &M,
                             const CodeGenOptions &Opts, BehaviorLayout &Layout)
    : B(B), M(M), Ctx(M.getContext()), Opts(Opts), Layout(Layout) {
  llvm::MDBuilder MDB(Ctx);
  llvm::MDNode *Root = MDB.createTBAARoot("bsc memory");
  auto Tag = [&](llvm::StringRef Name) {
    llvm::MDNode *Ty = MDB.createTBAAScalarTypeNode(Name, Root);
    return MDB.createTBAAStructTagNode(Ty, Ty, 0);
  };
  AccessTags[unsigned(Access::State)] = Tag("behavior state");
  AccessTags[unsigned(Access::Native)] = Tag("registered C++ field");
  AccessTags[unsigned(Access::TraceRecord)] = Tag("trace record");
  AccessTags[unsigned(Access::Budget)] = Tag("budget record");
}

void ModuleEmitter::addCommonAttributes(llvm::Function *F) {
  F->addFnAttr(llvm::Attribute::NoUnwind);
  F->addFnAttr("no-builtins");
  // Unwind tables (.eh_frame), as C++ compilers emit them on x86: a
  // debugger or crash handler stopped in registered C++ walks back through
  // the tasks that called it. They take space in the object, not time.
  F->setUWTableKind(llvm::UWTableKind::Async);
}

unsigned ModuleEmitter::addSite(DebugSite Site) {
  Layout.Sites.push_back(std::move(Site));
  return Layout.Sites.size();
}

llvm::GlobalVariable *ModuleEmitter::getProbe(const char *Symbol) {
  if (llvm::GlobalVariable *G = M.getGlobalVariable(Symbol))
    return G;
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  // A REPL line's module uses the behavior module's probes.
  return new llvm::GlobalVariable(
      M, I32, /*isConstant=*/false, llvm::GlobalValue::ExternalLinkage,
      ReplSlots ? nullptr : llvm::ConstantInt::get(I32, 0), Symbol);
}

void ModuleEmitter::useRegisterCalls() {
  // LLVM's i386 PIC lowering loads the GOT address into EBX before every
  // call that is not a tail call, whatever the callee, so that a call
  // through the PLT finds it: three instructions and a saved register in
  // every function that calls another, though calls between internal
  // functions never go through the PLT. It leaves calls of the regcall
  // convention alone. Only functions whose every use is a direct call can
  // change their convention (bs.destroy is called through
  // bs_behavior_info; the entries are C functions).
  for (llvm::Function &F : M) {
    if (F.isDeclaration() || !F.hasLocalLinkage() ||
        llvm::any_of(F.uses(), [](const llvm::Use &U) {
          const auto *Call = llvm::dyn_cast<llvm::CallBase>(U.getUser());
          return !Call || !Call->isCallee(&U);
        }))
      continue;
    F.setCallingConv(llvm::CallingConv::X86_RegCall);
    for (llvm::Use &U : F.uses())
      llvm::cast<llvm::CallBase>(U.getUser())
          ->setCallingConv(llvm::CallingConv::X86_RegCall);
  }
}

/// Rounds every float `F` computes to a float in memory (a volatile store
/// and load, which no optimisation removes) before anything uses it. The
/// x87 unit computes with 64 mantissa bits and a 15-bit exponent; a value
/// stored as a float is rounded once more to 24 bits and the float's range.
/// Rounding twice gives the same result as rounding once for + - * / when
/// the first precision has at least 2 * 24 + 2 bits (64 does), so the
/// result is the IEEE float result the host computes with SSE.
static void narrowX87Floats(llvm::Function &F) {
  llvm::SmallVector<llvm::Instruction *, 16> Computed;
  for (llvm::Instruction &I : llvm::instructions(F)) {
    if (!I.getType()->isFloatTy())
      continue;
    // Loads, constants, arguments and phis carry floats that were already
    // rounded; negation and selection are exact.
    if (llvm::isa<llvm::BinaryOperator>(I) || llvm::isa<llvm::SIToFPInst>(I) ||
        llvm::isa<llvm::UIToFPInst>(I) || llvm::isa<llvm::CallInst>(I))
      Computed.push_back(&I);
  }
  if (Computed.empty())
    return;
  llvm::IRBuilder<> B(&*F.getEntryBlock().getFirstInsertionPt());
  llvm::AllocaInst *Slot = B.CreateAlloca(B.getFloatTy(), nullptr, "x87.round");
  for (llvm::Instruction *I : Computed) {
    B.SetInsertPoint(I->getNextNode());
    B.SetCurrentDebugLocation(I->getDebugLoc());
    llvm::StoreInst *Store = B.CreateStore(I, Slot, /*isVolatile=*/true);
    llvm::Value *Rounded =
        B.CreateLoad(B.getFloatTy(), Slot, /*isVolatile=*/true,
                     I->getName() + ".rounded");
    I->replaceUsesWithIf(Rounded,
                         [&](llvm::Use &U) { return U.getUser() != Store; });
  }
}

void ModuleEmitter::run() {
  layoutState();
  if (Opts.DebugInfo) {
    assert(Opts.Sources && "debug information needs the sources' lines");
    DebugInfo = std::make_unique<DebugInfoEmitter>(*this, *Opts.Sources);
  }
  declareFunctions();
  for (const CallableDecl *D : getSourceOrder()) {
    FunctionEmitter(*this, *D).run();
    if (Opts.NarrowX87Floats)
      narrowX87Floats(*getFunction(D));
  }
  finishCoverage();
  emitEntries();
  emitDestroyFunctions();
  emitInfo();
  if (Opts.ProgramEntry)
    emitProgramMain();
  if (Opts.FlightRecorder)
    emitFlightTable();
  if (llvm::Triple(M.getTargetTriple()).getArch() == llvm::Triple::x86)
    useRegisterCalls();
  // Both probes exist whenever probes are on: the REPL's lines use them too.
  if (Opts.Probes) {
    getProbe(LoopProbeSymbol);
    getProbe(NativeProbeSymbol);
  }
  if (DebugInfo) {
    // The glue: an entry (and `main`) is attributed to its func's or
    // task's line, the rest to line 0.
    llvm::DenseMap<const llvm::Function *, llvm::SMLoc> GlueLocs;
    for (const BehaviorLayout::Entry &E : Layout.Entries)
      GlueLocs[M.getFunction(E.Symbol)] = E.Decl->getLoc();
    if (Opts.ProgramEntry)
      GlueLocs[M.getFunction("main")] = Opts.ProgramEntry->getLoc();
    for (llvm::Function &F : M)
      if (!F.isDeclaration() && !F.getSubprogram())
        DebugInfo->createGlueFunction(F, GlueLocs.lookup(&F));
    DebugInfo->finalize();
  }
}

//===----------------------------------------------------------------------===//
// FunctionEmitter: what funcs and tasks share
//===----------------------------------------------------------------------===//

FunctionEmitter::FunctionEmitter(ModuleEmitter &CGM, const CallableDecl &D)
    : CGM(CGM), D(D), Task(llvm::dyn_cast<TaskDecl>(&D)),
      Fn(CGM.getFunction(&D)), Builder(CGM.getContext()),
      StatePtr(Fn->getArg(0)) {}

const TaskDecl *FunctionEmitter::getFrameTask() const {
  if (Task)
    return Task;
  return llvm::cast<FuncDecl>(D).EnclosingTask;
}

void FunctionEmitter::run() {
  Builder.SetInsertPoint(llvm::BasicBlock::Create(CGM.getContext(), "entry", Fn));
  // Allocas and frame-field addresses go before this marker, so they all
  // sit at the top of the entry block whatever control flow the body adds:
  // mem2reg promotes only entry-block allocas, and an address computed in
  // the entry block dominates every use, including the resume blocks.
  EntryPoint =
      Builder.CreateAlloca(Builder.getInt8Ty(), nullptr, "entry.point");
  if (CGM.getDebugInfo())
    emitDebugPrologue();
  // A task's prologue is attributed to the task's line. A func's copies its
  // arguments to their slots first, unattributed, as Clang's do: a
  // debugger's breakpoint on the func goes after them.
  if (Task) {
    setDebugLocation(D.getLoc());
    emitTaskPrologue();
  } else {
    emitFuncPrologue();
    setDebugLocation(D.getLoc());
  }
  if (D.Body)
    emitBlock(D.Body);
  if (Task)
    emitTaskEpilogue();
  else
    emitFuncEpilogue();
  // Statements after `return`, `break` or `continue` were emitted into
  // blocks nothing branches to; drop them so -O0 code has no dead blocks.
  llvm::EliminateUnreachableBlocks(*Fn);
  if (CGM.getOptions().Probes)
    restoreLoopProbeOnReturn();
  if (CGM.getOptions().Explain && Task)
    emitExplainTaskMarks();
  if (CGM.getOptions().Coverage)
    emitCallCount();
  EntryPoint->eraseFromParent();
  EntryPoint = nullptr;
}

void FunctionEmitter::restoreLoopProbeOnReturn() {
  // A call leaves the loop probe as it found it: the caller's loop, not a
  // loop of this function that a `return` or `yield` left.
  llvm::GlobalVariable *Probe = CGM.getProbe(LoopProbeSymbol);
  llvm::IRBuilder<> B(EntryPoint);
  llvm::Value *Saved = B.CreateLoad(B.getInt32Ty(), Probe, /*isVolatile=*/true,
                                    "probe.saved");
  for (llvm::BasicBlock &BB : *Fn)
    if (auto *Ret = llvm::dyn_cast<llvm::ReturnInst>(BB.getTerminator())) {
      B.SetInsertPoint(Ret);
      B.CreateStore(Saved, Probe, /*isVolatile=*/true);
    }
}

unsigned FunctionEmitter::getFirstParamArg() const {
  return ModuleEmitter::returnsClass(D) ? 2 : 1;
}

llvm::AllocaInst *FunctionEmitter::createSlot(const Type *T,
                                              const llvm::Twine &Name) {
  llvm::Type *MemTy = CGM.getMemoryType(T);
  auto *Slot = new llvm::AllocaInst(MemTy, 0, Name, EntryPoint);
  Slot->setAlignment(CGM.getModule().getDataLayout().getABITypeAlign(MemTy));
  return Slot;
}

void FunctionEmitter::emitFuncPrologue() {
  // A class parameter is the func's own copy: copy-constructed from the
  // caller's value, destroyed at every return. Locals are constructed by
  // their declarations (emitDecl).
  for (const ParamDecl *P : D.Params) {
    llvm::AllocaInst *Slot = createSlot(P->Ty, P->getName().Name + ".addr");
    Slots[P] = Slot;
    llvm::Value *Arg = Fn->getArg(P->Index + getFirstParamArg());
    if (P->Ty->isClass()) {
      emitClassCopy(P->Ty->getClass(), Slot, Arg, /*DstConstructed=*/false);
      if (ModuleEmitter::needsDestroy(P->Ty))
        Live.push_back({P->Ty->getClass(), Slot});
      continue;
    }
    emitStore(P->Ty, Arg, Slot);
  }
  for (const ParamDecl *P : D.Params)
    declareForDebugger(*P, P->Ty, P->Index + 2);
  for (const VarDecl *V : D.Locals)
    if (!CGM.getReplSlot(V))
      Slots[V] = createSlot(V->Ty, V->getName().Name);
}

void FunctionEmitter::emitFuncEpilogue() {
  // Sema makes every path of a func with a result return; should a path
  // still end here, it returns the zero value rather than anything
  // undefined (runtime safety).
  if (!Builder.GetInsertBlock()->getTerminator())
    emitFuncZeroReturn();
}

void FunctionEmitter::emitFuncZeroReturn() {
  const Type *ResultTy = llvm::cast<FuncDecl>(D).ResultTy;
  emitLiveCleanups(0, /*Forget=*/false);
  if (ResultTy->isClass()) {
    emitClassInit(ResultTy->getClass(), Fn->getArg(1));
    Builder.CreateRetVoid();
  } else if (ResultTy->isVoid())
    Builder.CreateRetVoid();
  else if (ResultTy->isString())
    Builder.CreateRet(CGM.getString(""));
  else
    Builder.CreateRet(llvm::Constant::getNullValue(Fn->getReturnType()));
}

//===----------------------------------------------------------------------===//
// Entry point
//===----------------------------------------------------------------------===//

std::unique_ptr<llvm::Module> bsc::emitLLVM(const Behavior &B,
                                            llvm::LLVMContext &Ctx,
                                            const llvm::Triple &Triple,
                                            const llvm::DataLayout &DL,
                                            const CodeGenOptions &Opts,
                                            BehaviorLayout &Layout) {
  // The driver names the behavior; without a name, the first module's name
  // is the default bscript.h promises.
  CodeGenOptions Named = Opts;
  if (Named.BehaviorName.empty() && !B.Modules.empty())
    Named.BehaviorName = B.Modules.front()->Name;
  auto M = std::make_unique<llvm::Module>(Named.BehaviorName, Ctx);
  M->setTargetTriple(Triple.str());
  M->setDataLayout(DL);
  if (!B.Modules.empty())
    M->setSourceFileName(B.Modules.front()->Path);
  Layout = BehaviorLayout();
  ModuleEmitter(B, *M, Named, Layout).run();
  return M;
}

std::vector<std::string> bsc::getUndefinedSymbols(const llvm::Module &M) {
  std::vector<std::string> Names;
  for (const llvm::GlobalValue &GV : M.global_values())
    if (GV.isDeclaration())
      Names.push_back(GV.getName().str());
  return Names;
}
