//===- CodeGenTest.cpp - IR generation from source to module ---------------===//
//
// These tests run the real front end on small programs and check the IR
// generator's promises that lit/FileCheck cannot state well: every program
// gives a module the verifier accepts, for the robot (i586) and the host
// (x86_64) layouts; the state and frame sizes are a function of the
// DataLayout alone, so running LLVM's -O2 pipeline over the module changes
// none of them; and the generated code needs no libc (no memset/memcpy), no
// coroutine intrinsics and nothing that traps, at -O0 and -O2.
//
//===----------------------------------------------------------------------===//
#include "bsc/CodeGen/CodeGen.h"
#include "bsc/CodeGen/Target.h"
#include "bsc/Frontend/Frontend.h"
#include "llvm/IR/Constants.h"
#include "llvm/IR/GlobalVariable.h"
#include "llvm/IR/InstIterator.h"
#include "llvm/IR/Instructions.h"
#include "llvm/IR/Operator.h"
#include "llvm/IR/IntrinsicInst.h"
#include "llvm/IR/Verifier.h"
#include "llvm/Support/CommandLine.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"
#include "bscript/bscript.h"
#include "gtest/gtest.h"
#include <cstddef>
#include <map>

using namespace bsc;

namespace {

/// The DataLayout of `-target i586` (the robot: 4-byte pointers, f64
/// aligned to 4) and of `-target x86_64`.
const char *const I586Layout = "e-m:e-p:32:32-p270:32:32-p271:32:32-p272:64:64-"
                               "i128:128-f64:32:64-f80:32-n8:16:32-S128";
const char *const X86_64Layout = "e-m:e-p270:32:32-p271:32:32-p272:64:64-"
                                 "i64:64-i128:128-f80:128-n8:16:32:64-S128";

struct TargetCase {
  const char *Triple;
  const char *Layout;
};
const TargetCase Targets[] = {{"i586-unknown-linux-gnu", I586Layout},
                              {"x86_64-unknown-linux-gnu", X86_64Layout}};

/// A program: its files (the first is the input) by module name.
using Sources = std::vector<std::pair<std::string, std::string>>;

/// Programs that together use every statement and expression of the
/// language; each must pass the front end.
const std::map<std::string, Sources> &getPrograms() {
  static const std::map<std::string, Sources> Programs = {
      {"fib", {{"fib", R"(requires "io"

task fib()
    int a = 0
    int b = 1
    for(; true; yield)
        io::printi(b)
        int t = b
        b += a
        a = t

func main()
    for(int i = 0; i < 20; i+=1)
        fib()
)"}}},
      {"tasks", {{"tasks", R"(requires "io"

task count(int limit, float scale)
    func scaled(int v) : float
        return v * scale + limit
    int i = 0
    for(; i < limit; i += 1)
        if(i == 2)
            continue
        io::printf(scaled(i))
        yield
        if(i > 5)
            break
    yield TaskState::failure
    io::prints("after failure")
    return

task quiet()
    io::printb(true)

func main()
    count(3, 0.5)
    quiet()
    if(taskState(count) == TaskState::running && taskState(quiet) != TaskState::failure)
        io::prints("running")
    else if(int(taskState(tasks::count)) < 0 || !(taskState(quiet) == TaskState::done))
        io::prints("other")
)"}}},
      {"arith", {{"arith", R"(requires "io"

func ops(int a, int b) : int
    int q = a / b
    int r = a % b
    int w = a * b - -a + b
    q /= b
    r %= b
    w -= 1
    w *= 2
    return q + r + w

func fops(float x, int n) : float
    float y = x / n + n
    y += n
    y -= 0.5
    y *= x
    y /= 2
    return -y

func conv(float f, bool b, int i) : bool
    int a = int(f)
    int c = int(b)
    float g = float(i)
    float h = i
    bool d = bool(b)
    return a < c || g <= h && d || f > 1.5 || f >= g || b == d || i != a

func defaults() : int
    int i
    float f
    bool b
    if(b)
        return 1
    return i + int(f)

func main()
    io::printi(ops(7, 0))
    io::printf(fops(1.5, 3))
    io::printb(conv(2.5, true, 3))
    io::printi(defaults())
    io::printi(int(TaskState::failure))
)"}}},
      {"multi",
       {{"multi", R"(requires "helper"
requires "io"

func main()
    helper::step(2)
    io::printi(helper::twice(21))
)"},
        {"helper", R"(requires "io"

func twice(int x) : int
    return x * 2

task step(int n)
    for(int k = 0; k < n; k += 1)
        io::printi(k)
        yield
)"}}},
      {"nested-loops", {{"loops", R"(requires "io"

task walk()
    for(int i = 0; i < 3; i += 1)
        for(int j = 0; ; j += 1)
            if(j >= i)
                break
            yield
            if(j == 1)
                continue
            io::printi(i * 10 + j)
        yield 2

func main()
    for(int c = 0; c < 10; c += 1)
        walk()
)"}}},
  };
  return Programs;
}

/// Runs the front end over one program and lowers it.
class CodeGenTest : public ::testing::Test {
protected:
  std::unique_ptr<Compilation> C;
  llvm::LLVMContext Ctx;
  llvm::SmallString<128> Dir;

  void SetUp() override {
    ASSERT_FALSE(llvm::sys::fs::createUniqueDirectory("bsc-codegen", Dir));
  }
  void TearDown() override { llvm::sys::fs::remove_directories(Dir); }

  /// Parses and checks `Files`; fails the test on any error.
  bool check(const Sources &Files) {
    C = std::make_unique<Compilation>();
    FrontendOptions O;
    // `io` as the host runtime archive registers it; its signatures are
    // scalar, so the same description serves the i586 layout.
    O.StandardModules = {BSC_HOST_RUNTIME};
    for (const auto &[Name, Text] : Files) {
      llvm::SmallString<128> Path(Dir);
      llvm::sys::path::append(Path, Name + ".bs");
      std::error_code EC;
      llvm::raw_fd_ostream OS(Path, EC);
      EXPECT_FALSE(EC);
      OS << Text;
      if (O.Inputs.empty())
        O.Inputs.push_back(std::string(Path));
    }
    bool OK = runFrontend(*C, O);
    std::string Msgs;
    for (const Diagnostic &D : C->Diags.getDiagnostics())
      Msgs += D.Message + "\n";
    EXPECT_TRUE(OK) << Msgs;
    return OK;
  }

  std::unique_ptr<llvm::Module> emit(const TargetCase &T, BehaviorLayout &L,
                                     CodeGenOptions Opts = {}) {
    if (Opts.BehaviorName.empty())
      Opts.BehaviorName = "B";
    return emitLLVM(C->Checked, Ctx, llvm::Triple(T.Triple),
                    llvm::DataLayout(T.Layout), Opts, L);
  }

  const CallableDecl *findDecl(llvm::StringRef Module, llvm::StringRef Name) {
    for (ModuleAST *M : C->Checked.Modules)
      if (M->Name == Module)
        for (CallableDecl *D : M->Decls)
          if (D->getName().Name == Name)
            return D;
    return nullptr;
  }
};

/// bsc's pipeline at -O`Level` (bsc::optimizeModule), without a target
/// machine.
void optimize(llvm::Module &M, unsigned Level) {
  optimizeModule(M, /*TM=*/nullptr, Level);
}

/// Reports what the generated code must never contain.
std::string findForbidden(const llvm::Module &M) {
  std::string Problems;
  for (const llvm::Function &F : M) {
    llvm::StringRef N = F.getName();
    if (F.isDeclaration() && !F.use_empty() &&
        (N.contains("memset") || N.contains("memcpy") ||
         N.contains("memmove") || N.starts_with("llvm.coro") ||
         N == "llvm.trap" || N == "malloc" || N == "fmodf" || N == "truncf"))
      Problems += "uses " + N.str() + "\n";
    for (const llvm::BasicBlock &BB : F)
      for (const llvm::Instruction &I : BB)
        if (llvm::isa<llvm::UnreachableInst>(I))
          Problems += "unreachable in " + N.str() + "\n";
  }
  return Problems;
}

TEST_F(CodeGenTest, EveryProgramVerifiesOnEveryTarget) {
  for (const auto &[Name, Files] : getPrograms()) {
    SCOPED_TRACE(Name);
    ASSERT_TRUE(check(Files));
    for (const TargetCase &T : Targets) {
      SCOPED_TRACE(T.Triple);
      BehaviorLayout L;
      std::unique_ptr<llvm::Module> M = emit(T, L);
      std::string Err;
      llvm::raw_string_ostream OS(Err);
      EXPECT_FALSE(llvm::verifyModule(*M, &OS)) << Err;
      EXPECT_EQ(findForbidden(*M), "");
      // The generator itself never emits flags that make overflow poison.
      for (const llvm::Function &F : *M)
        for (const llvm::BasicBlock &BB : F)
          for (const llvm::Instruction &I : BB)
            if (const auto *O =
                    llvm::dyn_cast<llvm::OverflowingBinaryOperator>(&I)) {
              EXPECT_FALSE(O->hasNoSignedWrap() || O->hasNoUnsignedWrap())
                  << F.getName().str();
            }
    }
  }
}

TEST_F(CodeGenTest, DebugInfoVerifiesAndCoversEveryFunction) {
  // -g on every program and target, unoptimised and optimised: the module
  // and its debug information verify (the verifier checks every call's
  // location and scope), and every defined function has a subprogram.
  for (const auto &[Name, Files] : getPrograms()) {
    SCOPED_TRACE(Name);
    ASSERT_TRUE(check(Files));
    for (const TargetCase &T : Targets) {
      SCOPED_TRACE(T.Triple);
      for (unsigned Level : {0u, 2u}) {
        CodeGenOptions Opts;
        Opts.DebugInfo = true;
        Opts.Sources = &C->SM;
        Opts.OptLevel = Level;
        BehaviorLayout L;
        std::unique_ptr<llvm::Module> M = emit(T, L, Opts);
        std::string Err;
        llvm::raw_string_ostream OS(Err);
        bool BrokenDebugInfo = false;
        EXPECT_FALSE(llvm::verifyModule(*M, &OS, &BrokenDebugInfo)) << Err;
        EXPECT_FALSE(BrokenDebugInfo) << Err;
        for (const llvm::Function &F : *M) {
          if (!F.isDeclaration()) {
            EXPECT_NE(F.getSubprogram(), nullptr) << F.getName().str();
          }
        }
        if (Level)
          optimize(*M, 2);
        EXPECT_FALSE(llvm::verifyModule(*M, &OS, &BrokenDebugInfo)) << Err;
        EXPECT_FALSE(BrokenDebugInfo) << Err;
      }
    }
  }
}

TEST_F(CodeGenTest, NoLibcNoCoroutinesNoTrapsAfterOptimisation) {
  for (const auto &[Name, Files] : getPrograms()) {
    SCOPED_TRACE(Name);
    ASSERT_TRUE(check(Files));
    for (const TargetCase &T : Targets) {
      SCOPED_TRACE(T.Triple);
      for (unsigned Level : {0, 2, 3}) {
        BehaviorLayout L;
        CodeGenOptions Opts;
        Opts.ProgramEntry = findDecl(Files.front().first, "main");
        Opts.ProgramCycles = 3;
        std::unique_ptr<llvm::Module> M = emit(T, L, Opts);
        optimize(*M, Level);
        EXPECT_FALSE(llvm::verifyModule(*M, &llvm::errs()));
        EXPECT_EQ(findForbidden(*M), "");
      }
    }
  }
}

/// bsc's pipelines keep SimplifyCFG from sinking a task's exit stores into
/// one store of PHIs and limit GVN's search for a load's value
/// (lib/CodeGen/Optimize.cpp); the options are LLVM's, so a new LLVM that
/// renames them fails here.
TEST(OptimizeTest, PipelineDefaultsAreSet) {
  llvm::LLVMContext Ctx;
  llvm::Module M("empty", Ctx);
  optimizeModule(M, /*TM=*/nullptr, 2);
  llvm::StringMap<llvm::cl::Option *> &Options =
      llvm::cl::getRegisteredOptions();
  llvm::cl::Option *Sink = Options.lookup("simplifycfg-sink-common");
  ASSERT_NE(Sink, nullptr);
  EXPECT_FALSE(static_cast<llvm::cl::opt<bool> *>(Sink)->getValue());
  llvm::cl::Option *Blocks = Options.lookup("memdep-block-number-limit");
  ASSERT_NE(Blocks, nullptr);
  EXPECT_EQ(static_cast<llvm::cl::opt<unsigned> *>(Blocks)->getValue(), 40u);
}

/// The state size the module's info struct advertises.
uint64_t getInfoStateSize(const llvm::Module &M) {
  const llvm::GlobalVariable *GV = M.getNamedGlobal("bs_B_info");
  if (!GV || !GV->hasInitializer())
    return 0;
  return llvm::cast<llvm::ConstantInt>(
             GV->getInitializer()->getAggregateElement(1u))
      ->getZExtValue();
}

TEST_F(CodeGenTest, LayoutIsTheSameAtEveryOptLevel) {
  for (const auto &[Name, Files] : getPrograms()) {
    SCOPED_TRACE(Name);
    ASSERT_TRUE(check(Files));
    for (const TargetCase &T : Targets) {
      SCOPED_TRACE(T.Triple);
      BehaviorLayout Reference;
      std::unique_ptr<llvm::Module> M0 = emit(T, Reference);
      EXPECT_EQ(getInfoStateSize(*M0), Reference.StateSize);
      for (unsigned Level : {0, 1, 2, 3}) {
        BehaviorLayout L;
        std::unique_ptr<llvm::Module> M = emit(T, L);
        optimize(*M, Level);
        EXPECT_EQ(L.StateSize, Reference.StateSize);
        EXPECT_EQ(L.StateAlign, Reference.StateAlign);
        ASSERT_EQ(L.Tasks.size(), Reference.Tasks.size());
        for (size_t I = 0; I < L.Tasks.size(); ++I)
          EXPECT_EQ(L.Tasks[I].FrameOffset, Reference.Tasks[I].FrameOffset);
        // What the object tells the embedding survives optimisation.
        EXPECT_EQ(getInfoStateSize(*M), Reference.StateSize);
      }
    }
  }
}

TEST_F(CodeGenTest, FibFrameLayout) {
  ASSERT_TRUE(check(getPrograms().at("fib")));
  // header {cycle, input, output, user}, then fib's frame {last_call, a,
  // b}: three i32; then its narrow header {resume, state}: a byte each (one
  // yield, states 1 and 0). `t` is declared after the for's yield and dies
  // before it: an alloca.
  BehaviorLayout L32, L64;
  std::unique_ptr<llvm::Module> M32 = emit(Targets[0], L32);
  std::unique_ptr<llvm::Module> M64 = emit(Targets[1], L64);
  EXPECT_EQ(L32.StateSize, 16u + 12u + 4u); // 2, rounded to 4
  EXPECT_EQ(L32.StateAlign, 4u);
  ASSERT_EQ(L32.Tasks.size(), 1u);
  EXPECT_EQ(L32.Tasks[0].FrameOffset, 16u);
  EXPECT_EQ(L32.Tasks[0].FrameSize, 12u);
  EXPECT_EQ(L32.Tasks[0].Resume.Offset, 28u);
  EXPECT_EQ(L32.Tasks[0].Resume.Bytes, 1u);
  EXPECT_EQ(L32.Tasks[0].State.Offset, 29u);
  EXPECT_EQ(L32.Tasks[0].State.Bytes, 1u);
  ASSERT_EQ(L32.Tasks[0].Fields.size(), 2u);
  EXPECT_EQ(L32.Tasks[0].Fields[0].D->getName().Name, "a");
  EXPECT_EQ(L32.Tasks[0].Fields[1].D->getName().Name, "b");
  EXPECT_EQ(L64.StateSize, 32u + 12u + 4u); // 46, rounded to 8
  EXPECT_EQ(L64.StateAlign, 8u);
  EXPECT_EQ(L64.Tasks[0].FrameOffset, 32u);
  EXPECT_EQ(L64.Tasks[0].Resume.Offset, 44u);

  llvm::StructType *Frame =
      llvm::StructType::getTypeByName(Ctx, "bs.frame.fib.fib");
  ASSERT_TRUE(Frame);
  EXPECT_EQ(Frame->getNumElements(), 3u);
}

TEST_F(CodeGenTest, ExactFramesKeepEveryVariable) {
  // The JIT's debugger shows every parameter and local between cycles.
  ASSERT_TRUE(check(getPrograms().at("fib")));
  CodeGenOptions Opts;
  Opts.Probes = true;
  BehaviorLayout L;
  std::unique_ptr<llvm::Module> M = emit(Targets[0], L, Opts);
  EXPECT_EQ(L.StateSize, 16u + 16u + 4u);
  ASSERT_EQ(L.Tasks[0].Fields.size(), 3u);
  EXPECT_EQ(L.Tasks[0].Fields[2].D->getName().Name, "t");
}

TEST_F(CodeGenTest, SiblingScopesShareAField) {
  ASSERT_TRUE(check({{"m", R"(task t(int p)
    for(int i = 0; i < p; yield)
        i += 1
    for(int j = 0; j < 2; yield)
        j += 1
    float f = 0.5
    yield
)"}}));
  BehaviorLayout L;
  std::unique_ptr<llvm::Module> M = emit(Targets[0], L);
  // p is read from the argument; i and j share a field; f (another type,
  // its scope the rest of the body) has its own.
  const BehaviorLayout::Task &T = L.Tasks[0];
  ASSERT_EQ(T.Fields.size(), 3u);
  EXPECT_EQ(T.Fields[0].D->getName().Name, "i");
  EXPECT_EQ(T.Fields[1].D->getName().Name, "j");
  EXPECT_EQ(T.Fields[0].Offset, T.Fields[1].Offset);
  EXPECT_EQ(T.Fields[2].D->getName().Name, "f");
  EXPECT_NE(T.Fields[2].Offset, T.Fields[0].Offset);
  EXPECT_EQ(T.FrameSize, 4u + 4u + 4u);
}

TEST_F(CodeGenTest, StateHeaderMatchesBscriptH) {
  ASSERT_TRUE(check(getPrograms().at("tasks")));
  // bs_state_header {u32 cycle, const void *input, void *output, void
  // *user} as a C compiler lays it out for each target (the host's is
  // bscript.h's own); every frame starts with its task's u32 last call.
  const uint64_t InputOffset[] = {4, 8}, OutputOffset[] = {8, 16},
                 UserOffset[] = {12, 24};
  if (sizeof(void *) == 8) {
    EXPECT_EQ(offsetof(bs_state_header, input), InputOffset[1]);
    EXPECT_EQ(offsetof(bs_state_header, output), OutputOffset[1]);
    EXPECT_EQ(offsetof(bs_state_header, user), UserOffset[1]);
  }
  for (unsigned I = 0; I < 2; ++I) {
    SCOPED_TRACE(Targets[I].Triple);
    llvm::LLVMContext LocalCtx;
    BehaviorLayout L;
    std::unique_ptr<llvm::Module> M =
        emitLLVM(C->Checked, LocalCtx, llvm::Triple(Targets[I].Triple),
                 llvm::DataLayout(Targets[I].Layout), CodeGenOptions(), L);
    llvm::StructType *State =
        llvm::StructType::getTypeByName(LocalCtx, "bs.state");
    ASSERT_TRUE(State);
    const llvm::StructLayout *SL =
        M->getDataLayout().getStructLayout(State);
    EXPECT_EQ(SL->getElementOffset(0), 0u);
    EXPECT_EQ(SL->getElementOffset(1), InputOffset[I]);
    EXPECT_EQ(SL->getElementOffset(2), OutputOffset[I]);
    EXPECT_EQ(SL->getElementOffset(3), UserOffset[I]);
    ASSERT_EQ(L.Tasks.size(), 2u);
    uint64_t FramesEnd = 0;
    for (unsigned T = 0; T < L.Tasks.size(); ++T) {
      auto *Frame = llvm::cast<llvm::StructType>(State->getElementType(4 + T));
      EXPECT_EQ(L.Tasks[T].FrameOffset, SL->getElementOffset(4 + T));
      EXPECT_TRUE(Frame->getElementType(0)->isIntegerTy(32));
      EXPECT_EQ(L.Tasks[T].FrameOffset % 4, 0u);
      FramesEnd = L.Tasks[T].FrameOffset + L.Tasks[T].FrameSize;
    }
    // Both tasks have few yields and constant states: their resume points
    // and states take a byte each, after the frames.
    for (const BehaviorLayout::Task &T : L.Tasks)
      for (const BehaviorLayout::TaskWord &W : {T.Resume, T.State}) {
        EXPECT_EQ(W.Bytes, 1u);
        EXPECT_GE(W.Offset, FramesEnd);
        EXPECT_LE(W.Offset + W.Bytes, L.StateSize);
      }
    // Without a name, the first module's name prefixes the exports.
    EXPECT_EQ(L.InfoSymbol, "bs_tasks_info");
  }
}

/// The task table's entries are bscript.h's bs_task_info on the host.
TEST_F(CodeGenTest, TaskInfoMatchesBscriptH) {
  ASSERT_TRUE(check(getPrograms().at("fib")));
  BehaviorLayout L;
  std::unique_ptr<llvm::Module> M = emit(Targets[1], L);
  llvm::StructType *Info = llvm::StructType::getTypeByName(Ctx, "bs_task_info");
  ASSERT_TRUE(Info);
  const llvm::StructLayout *SL = M->getDataLayout().getStructLayout(Info);
  if (sizeof(void *) == 8) {
    EXPECT_EQ(SL->getSizeInBytes(), sizeof(bs_task_info));
    EXPECT_EQ(SL->getElementOffset(1), offsetof(bs_task_info, frame_offset));
    EXPECT_EQ(SL->getElementOffset(2), offsetof(bs_task_info, resume_offset));
    EXPECT_EQ(SL->getElementOffset(3), offsetof(bs_task_info, state_offset));
    EXPECT_EQ(SL->getElementOffset(4), offsetof(bs_task_info, resume_bytes));
    EXPECT_EQ(SL->getElementOffset(5), offsetof(bs_task_info, state_bytes));
  }
  const llvm::GlobalVariable *Tasks = M->getNamedGlobal("bs_B_tasks");
  ASSERT_TRUE(Tasks && Tasks->hasInitializer());
  const llvm::Constant *Fib = Tasks->getInitializer()->getAggregateElement(0u);
  auto Field = [&](unsigned I) {
    return llvm::cast<llvm::ConstantInt>(Fib->getAggregateElement(I))
        ->getZExtValue();
  };
  EXPECT_EQ(Field(1), L.Tasks[0].FrameOffset);
  EXPECT_EQ(Field(2), L.Tasks[0].Resume.Offset);
  EXPECT_EQ(Field(3), L.Tasks[0].State.Offset);
  EXPECT_EQ(Field(4), L.Tasks[0].Resume.Bytes);
  EXPECT_EQ(Field(5), L.Tasks[0].State.Bytes);
}

/// bs_budget_layout, bs_loop_info and bs_budget_record as the IR lays them
/// out, and the layout's figures as BehaviorLayout has them.
TEST_F(CodeGenTest, BudgetInfoMatchesBscriptH) {
  ASSERT_TRUE(check({{"m", R"(
func sum(int n) : int
    int s = 0
    for(int i = 0; i < n; i += 1)
        s += i
    return s
task spin()
    for(;;)
        if(sum(3) > 2)
            yield
)"}}));
  CodeGenOptions Opts;
  Opts.CycleBudget = 77;
  BehaviorLayout L;
  std::unique_ptr<llvm::Module> M = emit(Targets[1], L, Opts);
  const llvm::DataLayout &DL = M->getDataLayout();
  auto *Loop = llvm::StructType::getTypeByName(Ctx, "bs_loop_info");
  auto *Budget = llvm::StructType::getTypeByName(Ctx, "bs_budget_layout");
  ASSERT_TRUE(Loop && Budget);
  if (sizeof(void *) == 8) {
    EXPECT_EQ(DL.getTypeAllocSize(Loop), sizeof(bs_loop_info));
    EXPECT_EQ(DL.getStructLayout(Loop)->getElementOffset(3),
              offsetof(bs_loop_info, task));
    EXPECT_EQ(DL.getTypeAllocSize(Budget), sizeof(bs_budget_layout));
    EXPECT_EQ(DL.getStructLayout(Budget)->getElementOffset(3),
              offsetof(bs_budget_layout, loops));
  }
  EXPECT_EQ(5 * 4u, sizeof(bs_budget_record));
  EXPECT_EQ(77u, L.Budget.Budget);
  ASSERT_EQ(2u, L.Budget.Loops.size());
  EXPECT_EQ("m::sum", L.Budget.Loops[0].Owner->getQualifiedName());
  EXPECT_EQ("m::spin", L.Budget.Loops[1].Owner->getQualifiedName());
  EXPECT_LE(L.Budget.Offset + sizeof(bs_budget_record), L.StateSize);
  EXPECT_EQ(0u, L.Budget.Offset % 4);
}

/// A resume point is as wide as the task's yields need, a state 1 byte
/// only when every state it can hold fits; the widest narrow headers come
/// first so that none is padded.
TEST_F(CodeGenTest, TaskWordsAreAsNarrowAsTheirValues) {
  std::string Many = "task many()\n";
  for (int I = 0; I < 300; ++I)
    Many += "    yield\n";
  ASSERT_TRUE(check({{"m", Many + R"(
task big()
    yield 1000
task small()
    yield 127
    yield -128
task computed(int v)
    yield v
task plain()
    yield
)"}}));
  BehaviorLayout L;
  std::unique_ptr<llvm::Module> M = emit(Targets[0], L);
  ASSERT_EQ(L.Tasks.size(), 5u);
  auto Find = [&](llvm::StringRef Name) -> const BehaviorLayout::Task & {
    for (const BehaviorLayout::Task &T : L.Tasks)
      if (T.Decl->getName().Name == Name)
        return T;
    ADD_FAILURE() << Name.str();
    return L.Tasks[0];
  };
  auto InFrame = [](const BehaviorLayout::Task &T,
                    const BehaviorLayout::TaskWord &W) {
    return W.Offset >= T.FrameOffset && W.Offset < T.FrameOffset + T.FrameSize;
  };
  const BehaviorLayout::Task &Many300 = Find("many"), &Big = Find("big"),
                             &Small = Find("small"),
                             &Computed = Find("computed"),
                             &Plain = Find("plain");
  EXPECT_EQ(Many300.Resume.Bytes, 2u);
  EXPECT_EQ(Many300.State.Bytes, 1u);
  EXPECT_EQ(Big.Resume.Bytes, 1u);
  EXPECT_EQ(Big.State.Bytes, 4u);
  EXPECT_TRUE(InFrame(Big, Big.State));
  EXPECT_EQ(Big.State.Offset, Big.FrameOffset + 4); // After the last call.
  EXPECT_EQ(Small.State.Bytes, 1u);
  EXPECT_EQ(Computed.State.Bytes, 4u);
  EXPECT_TRUE(InFrame(Computed, Computed.State));
  EXPECT_EQ(Plain.Resume.Bytes, 1u);
  EXPECT_EQ(Plain.State.Bytes, 1u);
  EXPECT_FALSE(InFrame(Plain, Plain.Resume));
  // many's 2-byte resume point leads the headers: every word is aligned.
  for (const BehaviorLayout::Task &T : L.Tasks)
    for (const BehaviorLayout::TaskWord &W : {T.Resume, T.State})
      EXPECT_EQ(W.Offset % W.Bytes, 0u) << T.Decl->getName().Name.str();
  for (const BehaviorLayout::Task &T : L.Tasks) {
    if (&T != &Many300 && !InFrame(T, T.Resume)) {
      EXPECT_GT(T.Resume.Offset, Many300.Resume.Offset);
    }
  }
}

/// Optimised code tells the optimiser that a running task whose yields
/// leave it running or end it is running (its callers' checks fold); at
/// -O0 nothing would fold, and the load would only cost time.
TEST_F(CodeGenTest, RunningTasksAssumeTheirStateWhenOptimised) {
  ASSERT_TRUE(check(getPrograms().at("fib")));
  for (unsigned OptLevel : {0u, 1u}) {
    SCOPED_TRACE(OptLevel);
    CodeGenOptions Opts;
    Opts.OptLevel = OptLevel;
    BehaviorLayout L;
    std::unique_ptr<llvm::Module> M = emit(Targets[0], L, Opts);
    const llvm::Function *Fib = M->getFunction("bs.fib.fib");
    ASSERT_TRUE(Fib);
    bool Assumes = false;
    for (const llvm::Instruction &I : llvm::instructions(*Fib))
      Assumes |= llvm::isa<llvm::AssumeInst>(I);
    EXPECT_EQ(Assumes, OptLevel > 0);
  }
}

TEST_F(CodeGenTest, FrameFieldTypes) {
  ASSERT_TRUE(check({{"m", R"(task t(int i, float f, bool b)
    bool local = b
    string s = "x"
    TaskState st = TaskState::running
    yield
)"}}));
  // The debugger's exact frames keep the parameters too.
  CodeGenOptions Opts;
  Opts.Probes = true;
  BehaviorLayout L;
  std::unique_ptr<llvm::Module> M = emit(Targets[0], L, Opts);
  llvm::StructType *Frame = llvm::StructType::getTypeByName(Ctx, "bs.frame.m.t");
  ASSERT_TRUE(Frame);
  // last_call, i, f, b (i8), local (i8), s (ptr), st (i32).
  ASSERT_EQ(Frame->getNumElements(), 7u);
  EXPECT_TRUE(Frame->getElementType(1)->isIntegerTy(32));
  EXPECT_TRUE(Frame->getElementType(2)->isFloatTy());
  EXPECT_TRUE(Frame->getElementType(3)->isIntegerTy(8));
  EXPECT_TRUE(Frame->getElementType(4)->isIntegerTy(8));
  EXPECT_TRUE(Frame->getElementType(5)->isPointerTy());
  EXPECT_TRUE(Frame->getElementType(6)->isIntegerTy(32));
  // 4 + 4 + 4 + 1 + 1 + 2 (pad) + 4 + 4 on i586, and the narrow header
  // (2, padded to 4).
  EXPECT_EQ(L.StateSize, 16u + 24u + 4u);
}

TEST_F(CodeGenTest, EntriesAndInfo) {
  ASSERT_TRUE(check(getPrograms().at("multi")));
  BehaviorLayout L;
  std::unique_ptr<llvm::Module> M = emit(Targets[0], L);
  EXPECT_EQ(L.InfoSymbol, "bs_B_info");
  const llvm::GlobalVariable *Info = M->getNamedGlobal("bs_B_info");
  ASSERT_TRUE(Info);
  EXPECT_TRUE(Info->isConstant());
  EXPECT_TRUE(Info->hasExternalLinkage());
  const llvm::Constant *Init = Info->getInitializer();
  auto Field = [&](unsigned I) {
    return llvm::cast<llvm::ConstantInt>(Init->getAggregateElement(I))
        ->getZExtValue();
  };
  EXPECT_EQ(Field(0), uint64_t(BS_ABI_VERSION));
  // Nothing to destroy: the destroy field is null; not instrumented: no
  // debug tables.
  EXPECT_TRUE(Init->getAggregateElement(7)->isNullValue());
  EXPECT_TRUE(Init->getAggregateElement(8)->isNullValue());
  EXPECT_EQ(Field(1), L.StateSize);
  EXPECT_EQ(Field(2), L.StateAlign);
  EXPECT_EQ(Field(3), 1u); // helper::step

  std::vector<std::string> Symbols;
  for (const BehaviorLayout::Entry &E : L.Entries) {
    Symbols.push_back(E.Symbol);
    EXPECT_EQ(E.Symbol, getEntrySymbol("B", *E.Decl));
    const llvm::Function *F = M->getFunction(E.Symbol);
    ASSERT_TRUE(F) << E.Symbol;
    EXPECT_TRUE(F->hasExternalLinkage());
    EXPECT_FALSE(F->isDeclaration());
  }
  // By default the roots only: main calls the helpers.
  EXPECT_EQ(Symbols, (std::vector<std::string>{"bs_B__multi__main"}));
  // Everything else is internal.
  for (const llvm::Function &F : *M)
    if (!F.isDeclaration() && !F.getName().starts_with("bs_B__")) {
      EXPECT_TRUE(F.hasInternalLinkage()) << F.getName().str();
    }
}

/// In optimised code a task returns the state it left, and on x86_64
/// taskState(T) right after a call of T is that result; at -O0, with
/// probes, and on i586 (where the load folds into its use) it is a load.
TEST_F(CodeGenTest, TasksReturnTheirStateWhenOptimised) {
  ASSERT_TRUE(check({{"m", R"(requires "io"

task count(int n)
    yield n + 1

func main()
    count(1)
    io::printi(int(taskState(count)))
    io::printi(int(taskState(count)))
)"}}));
  struct Case {
    const TargetCase &Target;
    unsigned OptLevel;
    bool Probes;
    bool Returns, ReadsResult;
  };
  for (const Case &K : {Case{Targets[1], 1, false, true, true},
                        Case{Targets[1], 0, false, false, false},
                        Case{Targets[1], 1, true, false, false},
                        Case{Targets[0], 2, false, true, false}}) {
    SCOPED_TRACE(K.Target.Triple + std::string(" -O") +
                 std::to_string(K.OptLevel) + (K.Probes ? " probes" : ""));
    CodeGenOptions Opts;
    Opts.OptLevel = K.OptLevel;
    Opts.Probes = K.Probes;
    BehaviorLayout L;
    std::unique_ptr<llvm::Module> M = emit(K.Target, L, Opts);
    EXPECT_FALSE(llvm::verifyModule(*M, &llvm::errs()));
    const llvm::Function *Count = M->getFunction("bs.m.count");
    ASSERT_TRUE(Count);
    EXPECT_EQ(Count->getReturnType()->isIntegerTy(32), K.Returns);
    // main: the first print gets the call's result or a load; the second
    // always a load (a call came between).
    const llvm::CallInst *TaskCall = nullptr;
    std::vector<const llvm::Value *> Printed;
    const llvm::Function *Main = M->getFunction("bs.m.main");
    for (const llvm::Instruction &I : llvm::instructions(*Main))
      if (const auto *Call = llvm::dyn_cast<llvm::CallInst>(&I)) {
        if (Call->getCalledFunction() == Count)
          TaskCall = Call;
        else if (Call->arg_size() == 1 &&
                 Call->getArgOperand(0)->getType()->isIntegerTy(32))
          Printed.push_back(Call->getArgOperand(0));
      }
    ASSERT_TRUE(TaskCall);
    ASSERT_EQ(Printed.size(), 2u);
    EXPECT_EQ(Printed[0] == TaskCall, K.ReadsResult);
    EXPECT_TRUE(llvm::isa<llvm::LoadInst>(Printed[1]));
  }
}

TEST_F(CodeGenTest, ExportsAreWhatTheOptionsName) {
  ASSERT_TRUE(check(getPrograms().at("multi")));
  CodeGenOptions Opts;
  Opts.Exports = std::vector<const CallableDecl *>{
      findDecl("helper", "twice"), findDecl("helper", "step"),
      findDecl("multi", "main")};
  BehaviorLayout L;
  std::unique_ptr<llvm::Module> M = emit(Targets[0], L, Opts);
  std::vector<std::string> Symbols;
  for (const BehaviorLayout::Entry &E : L.Entries)
    Symbols.push_back(E.Symbol);
  // In the order given.
  EXPECT_EQ(Symbols, (std::vector<std::string>{"bs_B__helper__twice",
                                               "bs_B__helper__step",
                                               "bs_B__multi__main"}));
  Opts.Exports->clear();
  BehaviorLayout None;
  M = emit(Targets[0], None, Opts);
  EXPECT_TRUE(None.Entries.empty());
  for (const llvm::Function &F : *M) {
    if (!F.isDeclaration()) {
      EXPECT_TRUE(F.hasInternalLinkage()) << F.getName().str();
    }
  }
}

TEST_F(CodeGenTest, BoolEntriesTravelAsInt32) {
  ASSERT_TRUE(check({{"m", R"(func flip(bool b, int i, float f) : bool
    return !b
func str(string s)
    return
)"}}));
  BehaviorLayout L;
  std::unique_ptr<llvm::Module> M = emit(Targets[0], L);
  const llvm::Function *F = M->getFunction("bs_B__m__flip");
  ASSERT_TRUE(F);
  EXPECT_TRUE(F->getReturnType()->isIntegerTy(32));
  ASSERT_EQ(F->arg_size(), 4u);
  EXPECT_TRUE(F->getArg(0)->getType()->isPointerTy());
  EXPECT_TRUE(F->getArg(1)->getType()->isIntegerTy(32));
  EXPECT_TRUE(F->getArg(2)->getType()->isIntegerTy(32));
  EXPECT_TRUE(F->getArg(3)->getType()->isFloatTy());
  // A string parameter cannot come from C: no entry.
  EXPECT_FALSE(M->getFunction("bs_B__m__str"));
}

TEST_F(CodeGenTest, ProgramMainRunsTheCycles) {
  ASSERT_TRUE(check(getPrograms().at("fib")));
  BehaviorLayout L;
  CodeGenOptions Opts;
  Opts.ProgramEntry = findDecl("fib", "main");
  Opts.ProgramCycles = 5;
  std::unique_ptr<llvm::Module> M = emit(Targets[0], L, Opts);
  const llvm::Function *Main = M->getFunction("main");
  ASSERT_TRUE(Main);
  EXPECT_TRUE(Main->getReturnType()->isIntegerTy(32));
  bool CallsInit = false, CallsBegin = false, DestroysAtTheEnd = false;
  for (const llvm::BasicBlock &BB : *Main)
    for (const llvm::Instruction &I : BB)
      if (const auto *Call = llvm::dyn_cast<llvm::CallInst>(&I)) {
        if (const llvm::Function *Callee = Call->getCalledFunction()) {
          CallsInit |= Callee->getName() == "bs_state_init";
          CallsBegin |= Callee->getName() == "bs_begin_cycle";
          // bs_state_destroy(state, &info) right before `ret i32 0`.
          if (Callee->getName() == "bs_state_destroy") {
            const auto *Ret = llvm::dyn_cast_or_null<llvm::ReturnInst>(
                Call->getNextNode());
            DestroysAtTheEnd = Ret && llvm::isa<llvm::ConstantInt>(
                                          Ret->getReturnValue()) &&
                               Call->getArgOperand(1) ==
                                   M->getNamedGlobal(L.InfoSymbol);
          }
        }
      } else if (const auto *A = llvm::dyn_cast<llvm::AllocaInst>(&I)) {
        EXPECT_EQ(A->getAlign().value(), L.StateAlign);
      }
  EXPECT_TRUE(CallsInit);
  EXPECT_TRUE(CallsBegin);
  EXPECT_TRUE(DestroysAtTheEnd);
  // A refused state returns the runtime's report (status 1) at once: the
  // block that calls bs_report_init_failure returns its result.
  const llvm::CallInst *Report = nullptr;
  for (const llvm::BasicBlock &BB : *Main)
    for (const llvm::Instruction &I : BB)
      if (const auto *Call = llvm::dyn_cast<llvm::CallInst>(&I))
        if (const llvm::Function *Callee = Call->getCalledFunction())
          if (Callee->getName() == "bs_report_init_failure")
            Report = Call;
  ASSERT_TRUE(Report);
  const auto *Ret =
      llvm::dyn_cast<llvm::ReturnInst>(Report->getParent()->getTerminator());
  ASSERT_TRUE(Ret);
  EXPECT_EQ(Ret->getReturnValue(), Report);
  // Without ProgramEntry there is no main.
  BehaviorLayout L2;
  EXPECT_FALSE(emit(Targets[0], L2)->getFunction("main"));
}


TEST_F(CodeGenTest, ExplainedModulesVerify) {
  // The JIT's options with the conditions' log (`:why`), with and without
  // -g, unoptimised and optimised: every module verifies (the records'
  // calls need lines where the function has debug information).
  for (const auto &[Name, Files] : getPrograms()) {
    SCOPED_TRACE(Name);
    ASSERT_TRUE(check(Files));
    for (bool Debug : {false, true})
      for (unsigned Level : {0u, 2u}) {
        CodeGenOptions Opts;
        Opts.Probes = Opts.ExternalFunctions = Opts.Explain = true;
        Opts.DebugInfo = Debug;
        Opts.Sources = &C->SM;
        Opts.OptLevel = Level;
        BehaviorLayout L;
        std::unique_ptr<llvm::Module> M = emit(Targets[1], L, Opts);
        optimize(*M, Level);
        std::string Err;
        llvm::raw_string_ostream OS(Err);
        EXPECT_FALSE(llvm::verifyModule(*M, &OS)) << Err;
        EXPECT_EQ(findForbidden(*M), "");
        EXPECT_TRUE(M->getNamedGlobal(ExplainLogSymbol));
      }
  }
}

TEST_F(CodeGenTest, ExplainSitesDescribeTheRecords) {
  ASSERT_TRUE(check({{"m", R"(task t(int n)
    for(int i = 0; i < n && (i + 1) * 2 != n || !(n > 3); i += 1)
        if(-i < 3)
            yield
    for(; true; yield)
        t2()

task t2()
    yield
)"}}));
  // Without the option: no table, no log.
  BehaviorLayout Plain;
  EXPECT_FALSE(emit(Targets[1], Plain)->getNamedGlobal(ExplainLogSymbol));
  EXPECT_TRUE(Plain.ExplainSites.empty());

  CodeGenOptions Opts;
  Opts.Probes = Opts.Explain = true;
  Opts.Sources = &C->SM;
  BehaviorLayout L;
  std::unique_ptr<llvm::Module> M = emit(Targets[1], L, Opts);
  ASSERT_TRUE(M->getNamedGlobal(ExplainLogSymbol));
  // t's two conditions (not `true`), then its start and end; t2's.
  ASSERT_EQ(L.ExplainSites.size(), 6u);
  const ExplainSite &For = L.ExplainSites[0];
  EXPECT_EQ(For.Kind, ExplainSite::For);
  EXPECT_EQ(For.File, "m.bs");
  EXPECT_EQ(For.Line, 2u);
  // Pre-order, each under the nearest operand that encloses it; the
  // parentheses are those the structure needs; literals are not operands.
  std::vector<std::pair<std::string, int>> Expected = {
      {"i < n && (i + 1) * 2 != n || !(n > 3)", -1},
      {"i < n && (i + 1) * 2 != n", 0},
      {"i < n", 1},
      {"i", 2},
      {"n", 2},
      {"(i + 1) * 2 != n", 1},
      {"(i + 1) * 2", 5},
      {"i + 1", 6},
      {"i", 7},
      {"n", 5},
      {"!(n > 3)", 0},
      {"n > 3", 10},
      {"n", 11}};
  ASSERT_EQ(For.Operands.size(), Expected.size());
  for (size_t I = 0; I < Expected.size(); ++I) {
    SCOPED_TRACE(I);
    EXPECT_EQ(For.Operands[I].Text, Expected[I].first);
    EXPECT_EQ(For.Operands[I].Parent, Expected[I].second);
    // Scalars, 4 bytes each after the 16-byte header.
    EXPECT_EQ(For.Operands[I].Offset, ExplainRecordHeaderSize + 4 * I);
  }
  EXPECT_EQ(For.RecordSize, 72u); // 68, rounded up to 8.
  const ExplainSite &If = L.ExplainSites[1];
  EXPECT_EQ(If.Kind, ExplainSite::If);
  EXPECT_EQ(If.Line, 3u);
  ASSERT_EQ(If.Operands.size(), 3u);
  EXPECT_EQ(If.Operands[0].Text, "-i < 3");
  EXPECT_EQ(If.Operands[1].Text, "-i");
  EXPECT_EQ(If.Operands[2].Text, "i");
  EXPECT_EQ(L.ExplainSites[2].Kind, ExplainSite::TaskStart);
  EXPECT_EQ(L.ExplainSites[3].Kind, ExplainSite::TaskEnd);
  EXPECT_EQ(L.ExplainSites[3].RecordSize, 24u);
  EXPECT_EQ(L.ExplainSites[4].In, findDecl("m", "t2"));
}

} // namespace
