//===- ConstantFoldingTest.cpp - every operator folded as at run time -----===//
//
// Sema computes module constants itself (SemaConst.cpp), so code generation
// only emits the result; the values must be the ones the generated code
// would compute (docs/language.md: int wraps, x / 0 == 0, x % 0 == x,
// IEEE single floats). One constant per operator and operand type, with
// the expected values worked out by hand, pins each case of the folding
// switches, including the ones a `default:` used to stand for.
//
//===----------------------------------------------------------------------===//
#include "ParsedModule.h"
#include "llvm/Support/FormatVariadic.h"
#include "gtest/gtest.h"
#include <cmath>
#include <cstdint>
#include <limits>

using namespace bsc;

namespace {

/// Reads the folded values of a checked module's constants by name.
class ConstantFoldingTest : public ::testing::Test {
protected:
  const ConstDecl *get(const ParsedModule &P, llvm::StringRef Name) {
    for (const ConstDecl *C : P.M->Consts)
      if (C->getName().Name == Name)
        return C;
    ADD_FAILURE() << "no constant " << Name.str();
    return nullptr;
  }
  int32_t intOf(const ParsedModule &P, llvm::StringRef Name) {
    const ConstDecl *C = get(P, Name);
    return C ? C->Value.Int : 0;
  }
  float floatOf(const ParsedModule &P, llvm::StringRef Name) {
    const ConstDecl *C = get(P, Name);
    return C ? C->Value.Float : 0;
  }
  bool boolOf(const ParsedModule &P, llvm::StringRef Name) {
    const ConstDecl *C = get(P, Name);
    return C ? C->Value.Bool : false;
  }
  /// The constants of comparisons(): `X` holds, `NX` does not.
  void expectComparisons(const ParsedModule &P) {
    for (llvm::StringRef Holds : {"LT", "LE", "GT", "GE", "EQ", "NE"}) {
      EXPECT_TRUE(boolOf(P, Holds)) << Holds.str();
      EXPECT_FALSE(boolOf(P, ("N" + Holds).str())) << "N" << Holds.str();
    }
  }
};

TEST_F(ConstantFoldingTest, IntArithmeticWrapsAndDividesWithoutTraps) {
  ParsedModule P("const int ADD = 7 + 2\n"
                 "const int SUB = 2 - 7\n"
                 "const int MUL = 7 * 3\n"
                 "const int DIV = 7 / 2\n"
                 "const int DIVNEG = -7 / 2\n"
                 "const int DIV0 = 7 / 0\n"
                 "const int DIVMIN = (-2147483647 - 1) / -1\n"
                 "const int REM = 7 % 3\n"
                 "const int REMNEG = -7 % 3\n"
                 "const int REM0 = 7 % 0\n"
                 "const int REMMIN = (-2147483647 - 1) % -1\n"
                 "const int WRAP = 2147483647 + 1\n"
                 "const int WRAPMUL = 65536 * 65536\n"
                 "const int NEG = -(3)\n"
                 "const int NEGMIN = -(-2147483647 - 1)\n");
  ASSERT_TRUE(P.OK);
  EXPECT_EQ(intOf(P, "ADD"), 9);
  EXPECT_EQ(intOf(P, "SUB"), -5);
  EXPECT_EQ(intOf(P, "MUL"), 21);
  EXPECT_EQ(intOf(P, "DIV"), 3);
  EXPECT_EQ(intOf(P, "DIVNEG"), -3); // Truncates toward zero.
  EXPECT_EQ(intOf(P, "DIV0"), 0);
  EXPECT_EQ(intOf(P, "DIVMIN"), INT32_MIN);
  EXPECT_EQ(intOf(P, "REM"), 1);
  EXPECT_EQ(intOf(P, "REMNEG"), -1); // The dividend's sign.
  EXPECT_EQ(intOf(P, "REM0"), 7);
  EXPECT_EQ(intOf(P, "REMMIN"), 0);
  EXPECT_EQ(intOf(P, "WRAP"), INT32_MIN);
  EXPECT_EQ(intOf(P, "WRAPMUL"), 0);
  EXPECT_EQ(intOf(P, "NEG"), -3);
  EXPECT_EQ(intOf(P, "NEGMIN"), INT32_MIN);
}

TEST_F(ConstantFoldingTest, FloatArithmeticIsIEEESingle) {
  ParsedModule P("const float ADD = 7.0 + 0.5\n"
                 "const float SUB = 0.5 - 7.0\n"
                 "const float MUL = 1.5 * 3.0\n"
                 "const float DIV = 1.0 / 4.0\n"
                 "const float DIV0 = 1.0 / 0.0\n"
                 "const float NEGDIV0 = -1.0 / 0.0\n"
                 "const float NAN0 = 0.0 / 0.0\n"
                 "const float NEAR = 1.5 - 0.1\n"
                 "const float NEG = -(2.5)\n"
                 "const float MIXED = 1 / 2.0\n");
  ASSERT_TRUE(P.OK);
  EXPECT_EQ(floatOf(P, "ADD"), 7.5f);
  EXPECT_EQ(floatOf(P, "SUB"), -6.5f);
  EXPECT_EQ(floatOf(P, "MUL"), 4.5f);
  EXPECT_EQ(floatOf(P, "DIV"), 0.25f);
  EXPECT_EQ(floatOf(P, "DIV0"), std::numeric_limits<float>::infinity());
  EXPECT_EQ(floatOf(P, "NEGDIV0"), -std::numeric_limits<float>::infinity());
  EXPECT_TRUE(std::isnan(floatOf(P, "NAN0")));
  EXPECT_EQ(floatOf(P, "NEAR"), 1.5f - 0.1f); // In single precision.
  EXPECT_EQ(floatOf(P, "NEG"), -2.5f);
  EXPECT_EQ(floatOf(P, "MIXED"), 0.5f);
}

TEST_F(ConstantFoldingTest, FloatRemainderIsNoConstant) {
  ParsedModule P("const float R = 7.0 % 2.0\n");
  EXPECT_FALSE(P.OK);
}

/// Constants `LT`, `LE`, `GT`, `GE`, `EQ`, `NE` that hold and `NLT`, ...
/// that do not, comparing `Lo` and `Hi` (Lo < Hi): each operator both ways.
std::string comparisons(llvm::StringRef Lo, llvm::StringRef Hi) {
  struct Row {
    const char *Name, *Op;
    llvm::StringRef HoldsL, HoldsR, FailsL, FailsR;
  } Rows[] = {{"LT", "<", Lo, Hi, Hi, Lo},  {"LE", "<=", Lo, Lo, Hi, Lo},
              {"GT", ">", Hi, Lo, Lo, Hi},  {"GE", ">=", Lo, Lo, Lo, Hi},
              {"EQ", "==", Lo, Lo, Lo, Hi}, {"NE", "!=", Lo, Hi, Lo, Lo}};
  std::string S;
  for (const Row &R : Rows)
    S += llvm::formatv("const bool {0} = {1} {2} {3}\n"
                       "const bool N{0} = {4} {2} {5}\n",
                       R.Name, R.HoldsL, R.Op, R.HoldsR, R.FailsL, R.FailsR)
             .str();
  return S;
}

TEST_F(ConstantFoldingTest, IntComparisons) {
  ParsedModule P(comparisons("1", "2"));
  ASSERT_TRUE(P.OK);
  expectComparisons(P);
}

TEST_F(ConstantFoldingTest, FloatComparisons) {
  ParsedModule P(comparisons("1.5", "2.5") +
                 "const bool NANNE = 0.0 / 0.0 != 0.0 / 0.0\n"
                 "const bool NANEQ = 0.0 / 0.0 == 0.0 / 0.0\n"
                 "const bool MIXED = 1 < 1.5\n");
  ASSERT_TRUE(P.OK);
  expectComparisons(P);
  EXPECT_TRUE(boolOf(P, "NANNE"));  // NaN is unequal to everything...
  EXPECT_FALSE(boolOf(P, "NANEQ")); // ...itself included.
  EXPECT_TRUE(boolOf(P, "MIXED"));
}

TEST_F(ConstantFoldingTest, BoolAndStringOperators) {
  ParsedModule P("const bool AND = true && false\n"
                 "const bool OR = false || true\n"
                 "const bool NOT = !false\n"
                 "const bool BEQ = true == true\n"
                 "const bool BNE = true != false\n"
                 "const bool SEQ = \"ab\" == \"ab\"\n"
                 "const bool SNE = \"ab\" != \"ab\"\n");
  ASSERT_TRUE(P.OK);
  EXPECT_FALSE(boolOf(P, "AND"));
  EXPECT_TRUE(boolOf(P, "OR"));
  EXPECT_TRUE(boolOf(P, "NOT"));
  EXPECT_TRUE(boolOf(P, "BEQ"));
  EXPECT_TRUE(boolOf(P, "BNE"));
  EXPECT_TRUE(boolOf(P, "SEQ"));
  EXPECT_FALSE(boolOf(P, "SNE"));
}

TEST_F(ConstantFoldingTest, TaskStatesCompareByKind) {
  // `== TaskState::running` and `failure` test the kind of the other side's
  // state, on either side; `done` and named states compare by number.
  ParsedModule P("enum Kick : TaskState\n"
                 "    aiming\n"
                 "const bool RUNS = Kick::aiming == TaskState::running\n"
                 "const bool NFAILS = TaskState::failure != Kick::aiming\n"
                 "const bool FAILS = TaskState::failure == TaskState::failure\n"
                 "const bool DONE = TaskState::done == TaskState::done\n"
                 "const bool NDONE = Kick::aiming == TaskState::done\n");
  ASSERT_TRUE(P.OK);
  EXPECT_TRUE(boolOf(P, "RUNS"));
  EXPECT_TRUE(boolOf(P, "NFAILS"));
  EXPECT_TRUE(boolOf(P, "FAILS"));
  EXPECT_TRUE(boolOf(P, "DONE"));
  EXPECT_FALSE(boolOf(P, "NDONE"));
}

TEST_F(ConstantFoldingTest, Conversions) {
  ParsedModule P("const int TRUNC = int(-3.7)\n"
                 "const int SAT = int(1.0 / 0.0)\n"
                 "const int NEGSAT = int(-1.0 / 0.0)\n"
                 "const int NAN = int(0.0 / 0.0)\n"
                 "const int FROMBOOL = int(true)\n"
                 "const float FROMINT = float(3)\n");
  ASSERT_TRUE(P.OK);
  EXPECT_EQ(intOf(P, "TRUNC"), -3);
  EXPECT_EQ(intOf(P, "SAT"), INT32_MAX);
  EXPECT_EQ(intOf(P, "NEGSAT"), INT32_MIN);
  EXPECT_EQ(intOf(P, "NAN"), 0);
  EXPECT_EQ(intOf(P, "FROMBOOL"), 1);
  EXPECT_EQ(floatOf(P, "FROMINT"), 3.0f);
}

} // namespace
