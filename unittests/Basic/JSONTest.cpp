//===- JSONTest.cpp - parseJSON: the depth limit and error places ---------===//
#include "bsc/Basic/JSON.h"
#include "gtest/gtest.h"
#include <string>

using namespace bsc;

namespace {

/// What parseJSON gives for `Text`: "ok", or "LINE:COLUMN@OFFSET: MESSAGE".
std::string read(llvm::StringRef Text) {
  llvm::Expected<llvm::json::Value> V = parseJSON(Text);
  if (V)
    return "ok";
  std::string Result;
  llvm::handleAllErrors(V.takeError(), [&](const JSONReadError &E) {
    Result = std::to_string(E.Line) + ":" + std::to_string(E.Column) + "@" +
             std::to_string(E.Offset) + ": " + E.Message;
  });
  return Result;
}

std::string repeat(llvm::StringRef S, unsigned N) {
  std::string R;
  for (unsigned I = 0; I < N; ++I)
    R += S;
  return R;
}

const std::string TooDeep =
    "nesting deeper than " + std::to_string(MaxJSONDepth) + " levels";

TEST(JSONTest, ALineOfBracketsIsRefusedWithoutRecursing) {
  // llvm::json::parse overflows the stack on this.
  EXPECT_EQ(read(std::string(100000, '[')), "1:257@256: " + TooDeep);
}

TEST(JSONTest, TheLimitItselfIsRead) {
  std::string Arrays = std::string(MaxJSONDepth, '[') +
                       std::string(MaxJSONDepth, ']');
  EXPECT_EQ(read(Arrays), "ok");
  EXPECT_EQ(read("[" + Arrays + "]"), "1:257@256: " + TooDeep);
}

TEST(JSONTest, ObjectsAndArraysCountAlike) {
  std::string Objects = repeat("{\"a\":", MaxJSONDepth) + "1" +
                        std::string(MaxJSONDepth, '}');
  EXPECT_EQ(read(Objects), "ok");
  std::string Deeper = repeat("{\"a\":[", 200);
  // Level 257 is the 129th '{'; each "{\"a\":[" is 6 bytes.
  EXPECT_EQ(read(Deeper), "1:769@768: " + TooDeep);
}

TEST(JSONTest, BracketsInStringsDoNotCount) {
  std::string Quoted = "[\"" + std::string(100000, '[') + "\"]";
  EXPECT_EQ(read(Quoted), "ok");
  // An escaped quote does not end the string...
  EXPECT_EQ(read("[\"\\\"" + std::string(1000, '{') + "\"]"), "ok");
  // ...but an escaped backslash before the quote does.
  std::string AfterBackslash = "[\"\\\\\"," + std::string(1000, '[');
  EXPECT_EQ(read(AfterBackslash), "1:262@261: " + TooDeep);
}

TEST(JSONTest, StrayClosersDoNotMakeRoom) {
  std::string Text = std::string(10, ']') + std::string(300, '[');
  EXPECT_EQ(read(Text), "1:267@266: " + TooDeep);
}

TEST(JSONTest, DepthErrorsHaveLineAndColumn) {
  std::string Text = "{\"a\":\n  " + std::string(300, '[');
  // The '{' is level 1, so the 256th '[' is one too many: byte 8 + 255.
  EXPECT_EQ(read(Text), "2:258@263: " + TooDeep);
}

TEST(JSONTest, ParserErrorsKeepTheirPlace) {
  // llvm::json points just past the character it could not take.
  EXPECT_EQ(read("{\"input\":{,}}"), "1:12@11: Expected object key");
  EXPECT_EQ(read("{\"a\":1,\n \"b\":}"), "2:7@14: Invalid JSON value");
  EXPECT_EQ(read("[1] x"), "1:5@4: Text after end of document");
  EXPECT_EQ(read("[\"\xff\"]"), "1:3@2: Invalid UTF-8 sequence");
}

TEST(JSONTest, ErrorsPrintWithTheirPlace) {
  llvm::Expected<llvm::json::Value> V = parseJSON("[[");
  ASSERT_FALSE(bool(V));
  EXPECT_EQ(llvm::toString(V.takeError()), "1:3: Unexpected EOF");
}

TEST(JSONTest, IsJSONAgreesWithTheParser) {
  // isJSON checks without building values; it must accept exactly what
  // parseJSON accepts.
  const char *Texts[] = {
      "{}", "[]", "0", "-0", "1.5e-3", "-12E+4", "true", "false", "null",
      "\"a\\u00e9\\n\"", "{\"a\":[1,{\"b\":null}],\"c\":\"x\"}",
      " { \"a\" : 1 } ", "\"\xc3\xa9\"",
      // llvm::json's numbers: what strtoll/strtod read whole.
      "01", "1.", ".5", "+1", "+.5e-1", "-.5", "1E+2", "99999999999999999999",
      "1e", "e5", "-", "--1", "1-", "1.5.5", "0x10",
      // Not JSON:
      "", "{", "}", "[1,]", "{\"a\"}", "{\"a\":}", "{a:1}",
      "tru", "nul", "\"\\x\"", "\"\\u12\"",
      "\"a\tb\"", "\"\xff\"", "[1] 2", "{\"a\":1,}", "[1 2]",
      "{\"a\":1 \"b\":2}", "\"open", "[\"a\"]]"};
  for (const char *T : Texts) {
    llvm::Expected<llvm::json::Value> V = parseJSON(T);
    bool Parsed = bool(V);
    if (!V)
      llvm::consumeError(V.takeError());
    EXPECT_EQ(isJSON(T), Parsed) << T;
  }
  EXPECT_FALSE(isJSON(std::string(300, '[') + std::string(300, ']')));
}

TEST(JSONTest, IsJSONHandsOverTheTopLevelMembers) {
  std::vector<std::string> Seen;
  auto Collect = [&](llvm::StringRef K, llvm::StringRef V) {
    Seen.push_back((K + "=" + V).str());
  };
  EXPECT_TRUE(isJSON(R"( {"a" : [1, {"b":2}], "c:" :"x" ,"d":{}} )", Collect));
  EXPECT_EQ(Seen, (std::vector<std::string>{"a=[1, {\"b\":2}]", "c:=\"x\"",
                                            "d={}"}));
  Seen.clear();
  EXPECT_TRUE(isJSON("[{\"a\":1}]", Collect)); // Not an object: none.
  EXPECT_TRUE(Seen.empty());
}

} // namespace
