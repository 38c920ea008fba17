//===- ReplCheckerTest.cpp - checking the REPL's lines --------------------===//
#include "ParsedModule.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {

/// A behavior, and lines checked against it as `bsc repl` checks them.
struct Session : ParsedModule {
  ReplChecker Checker;
  unsigned Number = 0;

  explicit Session(llvm::StringRef Source)
      : ParsedModule(Source), Checker(Ctx, Diags, Out, nullptr, M) {}

  std::optional<ReplChecker::Line> line(llvm::StringRef Text) {
    Diags.clear();
    unsigned ID = SM.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(Text, "<repl>"), llvm::SMLoc());
    BlockStmt *Body = parseReplLine(SM, ID, Ctx, Diags);
    if (Diags.hasErrors())
      return std::nullopt;
    return Checker.check(Body, ++Number);
  }
};

const char *const Behavior = "func twice(int x) : int\n"
                             "    return 2 * x\n"
                             "task main()\n"
                             "    yield\n";

TEST(ReplCheckerTest, AnExpressionBecomesTheLinesResult) {
  Session S(Behavior);
  ASSERT_TRUE(S.OK);
  std::optional<ReplChecker::Line> L = S.line("twice(3) + 1");
  ASSERT_TRUE(L);
  ASSERT_TRUE(L->Result);
  EXPECT_TRUE(L->Result->Ty->isInt());
  EXPECT_TRUE(L->NewVars.empty());
  EXPECT_EQ(L->Func->Module, S.M);
  // A call of a task or a void func shows nothing.
  L = S.line("main()");
  ASSERT_TRUE(L);
  EXPECT_FALSE(L->Result);
}

TEST(ReplCheckerTest, VariablesOutliveTheirLine) {
  Session S(Behavior);
  ASSERT_TRUE(S.OK);
  std::optional<ReplChecker::Line> L = S.line("float k = 2.5");
  ASSERT_TRUE(L);
  ASSERT_EQ(L->NewVars.size(), 1u);
  EXPECT_FALSE(L->Result);
  L = S.line("k * 2");
  ASSERT_TRUE(L);
  ASSERT_TRUE(L->Result);
  EXPECT_TRUE(L->Result->Ty->isFloat());
  EXPECT_EQ(S.Checker.getVariables().size(), 1u);
  // A line with an error declares nothing.
  EXPECT_FALSE(S.line("int j = true"));
  EXPECT_FALSE(S.line("j"));
  EXPECT_EQ(S.Checker.getVariables().size(), 1u);
}

TEST(ReplCheckerTest, TheRulesOfFuncBodiesStillHold) {
  Session S(Behavior);
  ASSERT_TRUE(S.OK);
  EXPECT_FALSE(S.line("yield"));
  EXPECT_FALSE(S.line("nope(1)"));
  EXPECT_FALSE(S.line("twice(1, 2)"));
  EXPECT_TRUE(S.line("twice(1)"));
}

} // namespace
