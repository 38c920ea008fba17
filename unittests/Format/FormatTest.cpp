//===- FormatTest.cpp - the canonical layout, rule by rule ----------------===//
#include "bsc/Format/Format.h"
#include "llvm/Support/MemoryBuffer.h"
#include "gtest/gtest.h"

using namespace bsc;
using namespace bsc::format;

namespace {

/// Formats `Text`; "error" if it was refused.
std::string fmt(llvm::StringRef Text) {
  llvm::SourceMgr SM;
  unsigned ID = SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(Text, "t.bs"), llvm::SMLoc());
  DiagnosticEngine Diags;
  auto F = formatBuffer(SM, ID, Diags);
  EXPECT_TRUE(bool(F)) << llvm::toString(F.takeError());
  if (!F || !*F)
    return "error";
  return (*F)->Text;
}

/// The formatted statement `S` in a func body.
std::string stmt(llvm::StringRef S) {
  std::string Out = fmt(("func f()\n    " + S + "\n").str());
  llvm::StringRef Body = llvm::StringRef(Out).drop_front(strlen("func f()\n"));
  return Body.trim().str();
}

TEST(FormatTest, SpacesAroundBinaryOperatorsNotUnaryOnes) {
  EXPECT_EQ(stmt("x=a+b*-c"), "x = a + b * -c");
  EXPECT_EQ(stmt("x=-a- -b"), "x = -a - -b");
  EXPECT_EQ(stmt("b=!(a&&c)||!d"), "b = !(a && c) || !d");
  EXPECT_EQ(stmt("x%=f(-1)-(2)"), "x %= f(-1) - (2)");
  EXPECT_EQ(stmt("return -1"), "return -1");
  EXPECT_EQ(stmt("x = ( a )*( -b )"), "x = (a) * (-b)");
}

TEST(FormatTest, CallsMembersQualifiersAndIndexes) {
  EXPECT_EQ(stmt("M :: f ( a ,b )"), "M::f(a, b)");
  EXPECT_EQ(stmt("x = input . ball . position . abs ( )"),
            "x = input.ball.position.abs()");
  EXPECT_EQ(stmt("output.wide [ 3 ] [ i ] = 1"), "output.wide[3][i] = 1");
  EXPECT_EQ(stmt("x = int ( y )"), "x = int(y)");
}

TEST(FormatTest, HeadsOfIfAndForAsThePaperWritesThem) {
  EXPECT_EQ(fmt("task t()\n    for ( ; ; yield )\n        if (true)\n"
                "            break\n        else  if (x)\n            break\n"),
            "task t()\n    for(;; yield)\n        if(true)\n            break\n"
            "        else if(x)\n            break\n");
  EXPECT_EQ(stmt("for(int i=0;i<3;i+=1)\n        yield"),
            "for(int i = 0; i < 3; i += 1)\n        yield");
  EXPECT_EQ(stmt("for(;;)\n        yield"), "for(;;)\n        yield");
}

TEST(FormatTest, DeclarationsAndResultTypes) {
  EXPECT_EQ(fmt("func g( int a,float b=2.0 ):int\n    return a\n"),
            "func g(int a, float b = 2.0) : int\n    return a\n");
  EXPECT_EQ(fmt("enum E:TaskState\n    a=1\n    b\n"),
            "enum E : TaskState\n    a = 1\n    b\n");
  EXPECT_EQ(fmt("const   float K=1.5e3\n"), "const float K = 1.5e3\n");
}

TEST(FormatTest, IndentationBecomesFourSpaces) {
  EXPECT_EQ(fmt("task t()\n  if(x)\n        yield\n  yield\n"),
            "task t()\n    if(x)\n        yield\n    yield\n");
  EXPECT_EQ(fmt("task t()\n\tyield\n"), "task t()\n    yield\n");
}

TEST(FormatTest, BlankLines) {
  // At most one; none at the start of a block or the file or at its end.
  EXPECT_EQ(fmt("\n\ntask t()\n\n    yield\n\n\n\n    yield\n\n\n"),
            "task t()\n    yield\n\n    yield\n");
  // One before a declaration, above the comments that belong to it.
  EXPECT_EQ(fmt("func a()\n    return\n# doc\n# more\nfunc b()\n    return\n"),
            "func a()\n    return\n\n# doc\n# more\nfunc b()\n    return\n");
  // A nested func keeps what the author wrote.
  EXPECT_EQ(fmt("task t()\n    func k() : bool\n        return true\n"
                "    yield\n"),
            "task t()\n    func k() : bool\n        return true\n    yield\n");
}

TEST(FormatTest, CommentsKeepTheirTextAndFindTheirDepth) {
  EXPECT_EQ(fmt("task t()\n    yield   #  two   spaces  \n"),
            "task t()\n    yield  #  two   spaces\n");
  // Before a dedent: the deepest block the comment is indented into.
  EXPECT_EQ(fmt("task t()\n    if(x)\n        yield\n      # in if\n"
                "    # in t\n# top\n    yield\n"),
            "task t()\n    if(x)\n        yield\n        # in if\n"
            "    # in t\n    # top\n    yield\n");
  EXPECT_EQ(fmt("task t()\n    if(x)\n        yield\n        # in if\n"
                "  # in t\n# top\nfunc f()\n    return\n"),
            "task t()\n    if(x)\n        yield\n        # in if\n    # in t\n"
            "\n# top\nfunc f()\n    return\n");
  // A comment line first in a block is indented as the block.
  EXPECT_EQ(fmt("task t()\n# c\n    yield\n"), "task t()\n    # c\n    yield\n");
  EXPECT_EQ(fmt("# only a comment"), "# only a comment\n");
  EXPECT_EQ(fmt(""), "");
}

TEST(FormatTest, LongCallsBreakAfterTheOutermostParen) {
  std::string Long = "Motion::walkTo(input.ball.position.x + 100.0, "
                     "input.ball.position.y - 100.0, Motion::fast, 1)";
  EXPECT_EQ(stmt(Long), "Motion::walkTo(\n"
                        "            input.ball.position.x + 100.0,\n"
                        "            input.ball.position.y - 100.0,\n"
                        "            Motion::fast,\n"
                        "            1)");
  // Short enough: one line, even if the author broke it.
  EXPECT_EQ(stmt("f(a,\n        b)"), "f(a, b)");
  // Several calls side by side: no call holds the line, so it stays long.
  std::string Sum = "x = aaaaaaaaaaaa(1, 2) + bbbbbbbbbbbbbbbbbb(3, 4) + "
                    "cccccccccccccccccc(5, 6) + d(7)";
  EXPECT_EQ(stmt(Sum), Sum);
}

TEST(FormatTest, CommentsInsideParenthesesBreakTheLine) {
  EXPECT_EQ(stmt("f(a,  # first\n      # own line\n      b)"),
            "f(a,  # first\n            # own line\n            b)");
}

TEST(FormatTest, SyntaxErrorsAreRefused) {
  EXPECT_EQ(fmt("task t(\n    yield\n"), "error");
  EXPECT_EQ(fmt("task t()\n    x = = 1\n"), "error");
  EXPECT_EQ(fmt("\x01\x02"), "error");
}

TEST(FormatTest, TheFormattedProgramIsChecked) {
  EXPECT_FALSE(bool(checkSameProgram("x = 1 # c\n", "x=1   # c   \n")));
  llvm::Error E = checkSameProgram("x = 1\n", "x = 2\n");
  EXPECT_EQ(llvm::toString(std::move(E)),
            "token 3 differs: 'int_literal 1' became 'int_literal 2'");
  llvm::Error C = checkSameProgram("x = 1 # a\n", "x = 1 # b\n");
  EXPECT_EQ(llvm::toString(std::move(C)),
            "comment 1 differs: '# a' became '# b'");
  llvm::Error L = checkSameProgram("f(a,\n  b)\n", "f(a\n  b)\n");
  EXPECT_TRUE(bool(L));
  llvm::consumeError(std::move(L));
}

TEST(FormatTest, ARangeFormatsTheLinesItTouches) {
  llvm::SourceMgr SM;
  unsigned ID = SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(
          "task t()\n    x=1\n    f(a,\n      b)\n    y=2\n", "t.bs"),
      llvm::SMLoc());
  DiagnosticEngine Diags;
  auto F = formatBuffer(SM, ID, Diags);
  ASSERT_TRUE(F && *F);
  std::optional<RangeEdit> E = formatLines(**F, 4, 4);
  ASSERT_TRUE(E);
  EXPECT_EQ(E->FromLine, 3u);
  EXPECT_EQ(E->ToLine, 4u);
  EXPECT_EQ(E->Text, "    f(a, b)\n");
  E = formatLines(**F, 1, 2);
  ASSERT_TRUE(E);
  EXPECT_EQ(E->FromLine, 1u);
  EXPECT_EQ(E->ToLine, 2u);
  EXPECT_EQ(E->Text, "task t()\n    x = 1\n");
  EXPECT_FALSE(formatLines(**F, 9, 12));
}

} // namespace
