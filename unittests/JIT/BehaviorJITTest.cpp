//===- BehaviorJITTest.cpp - modules into the JIT, symbols out -------------===//
#include "bsc/JIT/JIT.h"
#include "llvm/IR/IRBuilder.h"
#include "llvm/Support/TargetSelect.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {
/// A module defining `int32_t NAME(int32_t x) { return x + Add; }`.
std::unique_ptr<llvm::Module> makeAdder(llvm::LLVMContext &Ctx,
                                        llvm::StringRef Name, int Add,
                                        const llvm::DataLayout &DL) {
  auto M = std::make_unique<llvm::Module>("adder", Ctx);
  M->setDataLayout(DL);
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  auto *F = llvm::Function::Create(llvm::FunctionType::get(I32, {I32}, false),
                                   llvm::Function::ExternalLinkage, Name,
                                   *M);
  llvm::IRBuilder<> B(llvm::BasicBlock::Create(Ctx, "entry", F));
  B.CreateRet(B.CreateAdd(F->getArg(0), B.getInt32(Add)));
  return M;
}

class BehaviorJITTest : public ::testing::Test {
protected:
  void SetUp() override {
    llvm::InitializeNativeTarget();
    llvm::InitializeNativeTargetAsmPrinter();
    auto J = BehaviorJIT::create(/*OptLevel=*/0);
    ASSERT_TRUE(bool(J)) << llvm::toString(J.takeError());
    JIT = std::move(*J);
  }
  std::unique_ptr<BehaviorJIT> JIT;
};

TEST_F(BehaviorJITTest, ACompiledFunctionRunsAtItsAddress) {
  auto Ctx = std::make_unique<llvm::LLVMContext>();
  auto M = makeAdder(*Ctx, "add41", 41, JIT->getDataLayout());
  ASSERT_FALSE(bool(JIT->addModule(std::move(M), std::move(Ctx), 0)));
  auto *Add = reinterpret_cast<int32_t (*)(int32_t)>(JIT->lookup("add41"));
  ASSERT_NE(Add, nullptr);
  EXPECT_EQ(Add(1), 42);
}

TEST_F(BehaviorJITTest, OptimisedModulesComputeTheSame) {
  auto Ctx = std::make_unique<llvm::LLVMContext>();
  auto M = makeAdder(*Ctx, "add2", 2, JIT->getDataLayout());
  ASSERT_FALSE(bool(JIT->addModule(std::move(M), std::move(Ctx), 2)));
  auto *Add = reinterpret_cast<int32_t (*)(int32_t)>(JIT->lookup("add2"));
  ASSERT_NE(Add, nullptr);
  EXPECT_EQ(Add(-2), 0);
}

TEST_F(BehaviorJITTest, AnUndefinedSymbolIsNull) {
  EXPECT_EQ(JIT->lookup("no_such_function"), nullptr);
}

TEST_F(BehaviorJITTest, TheHostTripleAndLayoutAreSet) {
  EXPECT_FALSE(JIT->getTriple().str().empty());
  EXPECT_EQ(JIT->getDataLayout().getPointerSize(), sizeof(void *));
}
} // namespace
