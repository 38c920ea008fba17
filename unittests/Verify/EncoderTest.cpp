//===- EncoderTest.cpp - one cycle's IR as Z3 terms -----------------------===//
//
// The encoder (lib/Verify/Encoder.h) on IR written here: values, branches
// and phis, memory by bytes with computed indices, floats bit-precise,
// registered C++ as fresh values, checks and assumptions, and refusals.
//
//===----------------------------------------------------------------------===//
#include "Encoder.h"
#include "llvm/AsmParser/Parser.h"
#include "llvm/IR/LLVMContext.h"
#include "llvm/IR/Module.h"
#include "llvm/Support/SourceMgr.h"
#include "gtest/gtest.h"

using namespace bsc::verify;

namespace {

class EncoderTest : public ::testing::Test {
protected:
  /// Parses `IR`, whose function @f takes the state (16 bytes, symbolic
  /// `s0`..`s15`) and, if it has two parameters, `input` (8 bytes `i0`..).
  void encode(const char *IR, unsigned InputBytes = 8) {
    llvm::SMDiagnostic Err;
    M = llvm::parseAssemblyString(IR, Err, Ctx);
    ASSERT_TRUE(M) << Err.getMessage().str();
    std::vector<z3::expr> State, Input;
    for (unsigned I = 0; I < 16; ++I)
      State.push_back(Z.bv_const(("s" + std::to_string(I)).c_str(), 8));
    for (unsigned I = 0; I < InputBytes; ++I)
      Input.push_back(Z.bv_const(("i" + std::to_string(I)).c_str(), 8));
    Mem = Memory();
    unsigned S = Mem.add("the state", State);
    unsigned In = Mem.add("input", Input);
    E = std::make_unique<Encoder>(Z, M->getDataLayout(), &Natives);
    llvm::Function *F = M->getFunction("f");
    std::vector<Pointer> Args = {Pointer::into(S, Z.bv_val(0, 64)),
                                 Pointer::into(In, Z.bv_val(0, 64))};
    Encoded = E->encode(*F, llvm::ArrayRef(Args).take_front(F->arg_size()), Mem,
                        "c1");
  }
  /// The 32-bit little-endian word at `Offset` of the state after the call.
  z3::expr word(unsigned Offset) {
    const std::vector<z3::expr> &B = Mem.Bytes[0];
    return z3::concat(z3::concat(B[Offset + 3], B[Offset + 2]),
                      z3::concat(B[Offset + 1], B[Offset]));
  }
  z3::expr inputWord(unsigned Offset) {
    return z3::concat(
        z3::concat(Z.bv_const(("i" + std::to_string(Offset + 3)).c_str(), 8),
                   Z.bv_const(("i" + std::to_string(Offset + 2)).c_str(), 8)),
        z3::concat(Z.bv_const(("i" + std::to_string(Offset + 1)).c_str(), 8),
                   Z.bv_const(("i" + std::to_string(Offset)).c_str(), 8)));
  }
  /// Whether `Claim` holds for every value of the symbols (and the
  /// encoder's assumptions).
  bool proves(const z3::expr &Claim) {
    z3::solver S(Z);
    S.add(E->getAssumed());
    S.add(!Claim);
    return S.check() == z3::unsat;
  }

  /// The thunks the IR calls (BehaviorLayout::NativeCalls).
  std::map<std::string, bsc::BehaviorLayout::NativeCall> Natives;
  llvm::LLVMContext Ctx;
  std::unique_ptr<llvm::Module> M;
  z3::context Z;
  Memory Mem;
  std::unique_ptr<Encoder> E;
  bool Encoded = false;
};

TEST_F(EncoderTest, ArithmeticBranchesAndPhis) {
  // state[0] = input[0] > 10 ? input[0] * 2 : 7 - input[0]
  encode(R"(
define void @f(ptr %s, ptr %in) {
entry:
  %x = load i32, ptr %in
  %big = icmp sgt i32 %x, 10
  br i1 %big, label %then, label %else
then:
  %d = mul i32 %x, 2
  br label %join
else:
  %e = sub i32 7, %x
  br label %join
join:
  %r = phi i32 [ %d, %then ], [ %e, %else ]
  store i32 %r, ptr %s
  ret void
}
)");
  ASSERT_TRUE(Encoded) << E->getUnsupported();
  z3::expr X = inputWord(0);
  EXPECT_TRUE(proves(word(0) == z3::ite(X > 10, X * 2, 7 - X)));
  EXPECT_FALSE(proves(word(0) == X * 2));
  // The bytes the cycle did not write are as they were.
  EXPECT_TRUE(proves(Mem.Bytes[0][4] == Z.bv_const("s4", 8)));
}

TEST_F(EncoderTest, StoresOnOnePathMergeWithTheOther) {
  encode(R"(
define void @f(ptr %s, ptr %in) {
entry:
  %x = load i8, ptr %in
  %p = getelementptr inbounds i8, ptr %s, i64 8
  %c = icmp eq i8 %x, 0
  br i1 %c, label %write, label %done
write:
  store i16 513, ptr %p
  br label %done
done:
  ret void
}
)");
  ASSERT_TRUE(Encoded) << E->getUnsupported();
  z3::expr I0 = Z.bv_const("i0", 8);
  EXPECT_TRUE(proves(
      z3::implies(I0 == 0, Mem.Bytes[0][8] == 1 && Mem.Bytes[0][9] == 2)));
  EXPECT_TRUE(
      proves(z3::implies(I0 != 0, Mem.Bytes[0][8] == Z.bv_const("s8", 8))));
}

TEST_F(EncoderTest, AComputedIndexReadsAndWritesThePlaceItNames) {
  // state[4 + 4 * (input[0] & 1)] = 5; a read through the same index.
  encode(R"(
define void @f(ptr %s, ptr %in) {
  %x = load i32, ptr %in
  %k = and i32 %x, 1
  %a = getelementptr inbounds [2 x i32], ptr %s, i64 0, i64 1
  %p = getelementptr inbounds i32, ptr %a, i32 %k
  store i32 5, ptr %p
  %v = load i32, ptr %p
  %q = getelementptr inbounds i8, ptr %s, i64 0
  store i32 %v, ptr %q
  ret void
}
)");
  ASSERT_TRUE(Encoded) << E->getUnsupported();
  z3::expr Odd = (inputWord(0) & 1) == 1;
  EXPECT_TRUE(proves(word(0) == 5));
  EXPECT_TRUE(proves(z3::implies(Odd, word(8) == 5)));
  EXPECT_TRUE(proves(z3::implies(!Odd, word(4) == 5)));
}

TEST_F(EncoderTest, FloatsAreIEEEBitPrecise) {
  // 0.1f + 0.2f == 0.3f is false in floats; x * 1.0 == x fails for NaN.
  encode(R"(
define void @f(ptr %s, ptr %in) {
  %sum = fadd float 0x3FB99999A0000000, 0x3FC99999A0000000
  %eq = fcmp oeq float %sum, 0x3FD3333340000000
  %b = zext i1 %eq to i32
  store i32 %b, ptr %s
  %x = load float, ptr %in
  %y = fmul float %x, 1.0
  %same = fcmp oeq float %x, %y
  %c = zext i1 %same to i32
  %p = getelementptr inbounds i8, ptr %s, i64 4
  store i32 %c, ptr %p
  %k = fptosi float 2.75 to i32
  %q = getelementptr inbounds i8, ptr %s, i64 8
  store i32 %k, ptr %q
  ret void
}
)");
  ASSERT_TRUE(Encoded) << E->getUnsupported();
  EXPECT_TRUE(proves(word(0) == 1));  // 0.1f + 0.2f rounds to 0.3f.
  EXPECT_FALSE(proves(word(4) == 1)); // NaN.
  EXPECT_TRUE(proves(word(8) == 2));  // Towards zero.
}

TEST_F(EncoderTest, ChecksAssumptionsAndNatives) {
  Natives["native"].Pure = true;
  encode(R"(
declare i32 @native(i32)
declare void @bs.verify.check(i1, i32, i1)
define void @f(ptr %s, ptr %in) {
  %x = load i32, ptr %in
  %pos = icmp sgt i32 %x, 0
  call void @bs.verify.check(i1 %pos, i32 0, i1 true)
  %a = call i32 @native(i32 %x)
  %b = call i32 @native(i32 %x)
  %same = icmp eq i32 %a, %b
  call void @bs.verify.check(i1 %same, i32 1, i1 false)
  %big = icmp sgt i32 %x, -5
  call void @bs.verify.check(i1 %big, i32 2, i1 false)
  %small = icmp slt i32 %x, 100
  call void @bs.verify.check(i1 %small, i32 3, i1 false)
  ret void
}
)");
  ASSERT_TRUE(Encoded) << E->getUnsupported();
  ASSERT_EQ(E->getChecks().size(), 3u);
  ASSERT_EQ(E->getNativeResults().size(), 2u);
  EXPECT_EQ(E->getNativeResults()[0].Callee, "native");
  // A pure native gives the same result for the same argument; the
  // assumption x > 0 makes x > -5 hold; x < 100 can fail.
  EXPECT_TRUE(proves(!E->getChecks()[0].Fails));
  EXPECT_TRUE(proves(!E->getChecks()[1].Fails));
  EXPECT_FALSE(proves(!E->getChecks()[2].Fails));
  EXPECT_EQ(E->getChecks()[2].Index, 3u);
}

TEST_F(EncoderTest, ConstantGlobalsAreObjectsOfTheirBytes) {
  // A string's bytes read through its pointer; two strings are at two
  // addresses; the saturating conversion of a NaN is 0.
  encode(R"(
@a = private unnamed_addr constant [3 x i8] c"hi\00"
@b = private unnamed_addr constant [3 x i8] c"ho\00"
declare i32 @llvm.fptosi.sat.i32.f32(float)
define void @f(ptr %s, ptr %in) {
  %p = getelementptr inbounds i8, ptr @a, i64 1
  %c = load i8, ptr %p
  %w = zext i8 %c to i32
  store i32 %w, ptr %s
  %same = icmp eq ptr @a, @b
  %x = zext i1 %same to i32
  %q = getelementptr inbounds i8, ptr %s, i64 4
  store i32 %x, ptr %q
  %f = load float, ptr %in
  %k = call i32 @llvm.fptosi.sat.i32.f32(float %f)
  %r = getelementptr inbounds i8, ptr %s, i64 8
  store i32 %k, ptr %r
  ret void
}
)");
  ASSERT_TRUE(Encoded) << E->getUnsupported();
  EXPECT_TRUE(proves(word(0) == 'i'));
  EXPECT_TRUE(proves(word(4) == 0));
  z3::expr F(Z, Z3_mk_fpa_to_fp_bv(Z, inputWord(0), Z.fpa_sort<32>()));
  EXPECT_TRUE(
      proves(z3::implies(z3::expr(Z, Z3_mk_fpa_is_nan(Z, F)), word(8) == 0)));
  // 3e9 saturates to the largest int.
  EXPECT_TRUE(proves(z3::implies(inputWord(0) == Z.bv_val(0x4F32D05E, 32),
                                 word(8) == 0x7FFFFFFF)));
}

TEST_F(EncoderTest, NativesWriteWhatTheyMayAndPureOnesReadTheirObjects) {
  // A method that may write its object (`Writes`) leaves any bytes there,
  // which the counterexample records; a pure one that reads an object
  // gives the same result for the same bytes, not for the same address.
  Natives["touch"].Writes = {{0, 4}};
  Natives["touch"].Name = "V::touch";
  Natives["norm"].Pure = true;
  Natives["norm"].Reads = {{0, 4}};
  encode(R"(
declare void @touch(ptr)
declare i32 @norm(ptr)
define void @f(ptr %s, ptr %in) {
  store i32 7, ptr %s
  call void @touch(ptr %s)
  %a = call i32 @norm(ptr %in)
  %b = call i32 @norm(ptr %in)
  %same = icmp eq i32 %a, %b
  %x = zext i1 %same to i32
  %q = getelementptr inbounds i8, ptr %s, i64 4
  store i32 %x, ptr %q
  store i32 1, ptr %in
  %c = call i32 @norm(ptr %in)
  %same2 = icmp eq i32 %a, %c
  %y = zext i1 %same2 to i32
  %r = getelementptr inbounds i8, ptr %s, i64 8
  store i32 %y, ptr %r
  ret void
}
)");
  ASSERT_TRUE(Encoded) << E->getUnsupported();
  EXPECT_FALSE(proves(word(0) == 7));
  ASSERT_EQ(E->getNativeResults().size(), 4u);
  EXPECT_TRUE(E->getNativeResults()[0].Recorded);
  EXPECT_FALSE(E->getNativeResults()[1].Recorded);
  ASSERT_EQ(E->getNativeResults()[0].Ptrs.size(), 1u);
  EXPECT_EQ(E->getNativeResults()[0].Ptrs[0].size(), 4u);
  EXPECT_TRUE(proves(word(4) == 1));
  EXPECT_FALSE(proves(word(8) == 1)); // Other bytes, maybe another result.
}

TEST_F(EncoderTest, APointerChosenByABranchReadsTheObjectChosen) {
  // The string of one branch or the other (two objects): a read through
  // the pointer the phi chose, a write through one a select chose, and
  // a comparison of the two.
  encode(R"(
@a = private unnamed_addr constant [3 x i8] c"hi\00"
@b = private unnamed_addr constant [4 x i8] c"ho!\00"
define void @f(ptr %s, ptr %in) {
entry:
  %x = load i32, ptr %in
  %c = icmp sgt i32 %x, 0
  br i1 %c, label %then, label %join
then:
  br label %join
join:
  %p = phi ptr [ @a, %then ], [ @b, %entry ]
  %q = getelementptr inbounds i8, ptr %p, i64 1
  %ch = load i8, ptr %q
  %w = zext i8 %ch to i32
  store i32 %w, ptr %s
  %t = getelementptr inbounds i8, ptr %s, i64 8
  %u = getelementptr inbounds i8, ptr %in, i64 4
  %dst = select i1 %c, ptr %t, ptr %u
  store i32 5, ptr %dst
  %eq = icmp eq ptr %p, @a
  %e = zext i1 %eq to i32
  %r = getelementptr inbounds i8, ptr %s, i64 4
  store i32 %e, ptr %r
  ret void
}
)");
  ASSERT_TRUE(Encoded) << E->getUnsupported();
  z3::expr Positive = inputWord(0) > 0;
  EXPECT_TRUE(proves(z3::implies(Positive, word(0) == 'i')));
  EXPECT_TRUE(proves(z3::implies(!Positive, word(0) == 'o')));
  EXPECT_TRUE(proves(z3::implies(Positive, word(8) == 5)));
  EXPECT_TRUE(proves(z3::implies(Positive, word(4) == 1)));
  EXPECT_TRUE(proves(z3::implies(!Positive, word(4) == 0)));
  EXPECT_FALSE(proves(word(8) == 5));
}

TEST_F(EncoderTest, ALoopIsAnEscapeAndUnknownConstructsAreRefused) {
  // What is left of a loop after peeling (Verify.cpp) is not encoded:
  // reaching its head is an escape, here when the input is positive.
  encode(R"(
define void @f(ptr %s, ptr %in) {
entry:
  %x = load i32, ptr %in
  %c0 = icmp sgt i32 %x, 0
  br i1 %c0, label %loop, label %done
loop:
  %i = phi i32 [ 0, %entry ], [ %j, %loop ]
  %j = add i32 %i, 1
  %c = icmp slt i32 %j, %x
  br i1 %c, label %loop, label %done
done:
  ret void
}
)");
  ASSERT_TRUE(Encoded) << E->getUnsupported();
  ASSERT_EQ(E->getEscapes().size(), 1u);
  EXPECT_TRUE(proves(E->getEscapes()[0].Reached == (inputWord(0) > 0)));
  encode(R"(
define void @f(ptr %s, ptr %in) {
  %v = load <2 x float>, ptr %in
  ret void
}
)");
  EXPECT_FALSE(Encoded);
  EXPECT_NE(E->getUnsupported().find("<2 x float>"), std::string::npos);
}

} // namespace
