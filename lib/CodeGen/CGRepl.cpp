//===- CGRepl.cpp - a REPL line as a module of its own --------------------===//
//
// emitReplLine: a line typed at the REPL becomes a function in a module of
// its own, beside the behavior's. It declares the behavior's state and
// functions (no bodies) and reaches the REPL's variables at the fixed
// addresses the REPL gives them.
//
//===----------------------------------------------------------------------===//
#include "FunctionEmitter.h"
#include "llvm/IR/Constants.h"
#include "llvm/IR/DerivedTypes.h"
#include "llvm/IR/Function.h"

using namespace bsc;
using namespace bsc::codegen;

llvm::Value *ModuleEmitter::getReplSlot(const Decl *D) {
  if (!ReplSlots)
    return nullptr;
  auto It = ReplSlots->find(D);
  if (It == ReplSlots->end())
    return nullptr;
  llvm::Type *I64 = llvm::Type::getInt64Ty(Ctx);
  return llvm::ConstantExpr::getIntToPtr(llvm::ConstantInt::get(I64, It->second),
                                         llvm::PointerType::getUnqual(Ctx));
}

void ModuleEmitter::runReplLine(
    const FuncDecl &Line, llvm::StringRef Symbol,
    const llvm::DenseMap<const Decl *, uint64_t> &Slots) {
  ReplSlots = &Slots;
  // The same types and declarations as the behavior's module, no bodies.
  layoutState();
  declareFunctions();
  auto *F = llvm::Function::Create(
      llvm::FunctionType::get(llvm::Type::getVoidTy(Ctx),
                              {llvm::PointerType::getUnqual(Ctx)}, false),
      llvm::GlobalValue::ExternalLinkage, Symbol, M);
  addCommonAttributes(F);
  F->getArg(0)->setName(StateParamName);
  Functions[&Line] = F;
  FunctionEmitter(*this, Line).run();
}

std::unique_ptr<llvm::Module>
bsc::emitReplLine(const Behavior &B, const FuncDecl &Line,
                  llvm::StringRef Symbol, llvm::LLVMContext &Ctx,
                  const llvm::Triple &Triple, const llvm::DataLayout &DL,
                  const llvm::DenseMap<const Decl *, uint64_t> &Slots,
                  std::vector<DebugSite> &Sites) {
  auto M = std::make_unique<llvm::Module>(Symbol, Ctx);
  M->setTargetTriple(Triple.str());
  M->setDataLayout(DL);
  CodeGenOptions Opts;
  Opts.ExternalFunctions = true;
  Opts.Probes = true;
  BehaviorLayout Layout;
  // The line's sites are numbered after those of the behavior and of the
  // lines before it: they share the probes.
  Layout.Sites = std::move(Sites);
  ModuleEmitter(B, *M, Opts, Layout).runReplLine(Line, Symbol, Slots);
  Sites = std::move(Layout.Sites);
  return M;
}
