//===- LexerTest.cpp - indentation and literals of the lexer ---------------===//
//
// The lexer's indentation rules are easiest to pin down as token-kind
// sequences; each test lexes a small buffer and compares the kinds (and, for
// errors, the diagnostic kinds).
//
//===----------------------------------------------------------------------===//
#include "bsc/Parse/Lexer.h"
#include "llvm/Support/MemoryBuffer.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {
struct Lexed {
  llvm::SourceMgr SM;
  DiagnosticEngine Diags;
  std::vector<Token> Tokens;
  std::string Kinds; // "kw_task identifier ... eof"

  explicit Lexed(llvm::StringRef Src) {
    unsigned ID = SM.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(Src, "t.bs"), llvm::SMLoc());
    Lexer L(SM, ID, Diags);
    while (true) {
      Tokens.push_back(L.lex());
      if (!Kinds.empty())
        Kinds += ' ';
      Kinds += tok::getName(Tokens.back().Kind).str();
      if (Tokens.back().is(tok::eof) || Tokens.size() > 10000)
        break;
    }
  }
  std::vector<diag::Kind> diags() const {
    std::vector<diag::Kind> R;
    for (const Diagnostic &D : Diags.getDiagnostics())
      R.push_back(D.Kind);
    return R;
  }
};
} // namespace

TEST(LexerTest, IndentDedent) {
  Lexed L("task t()\n    a\n        b\n    c\nd\n");
  EXPECT_EQ(L.Kinds, "kw_task identifier l_paren r_paren newline indent "
                     "identifier newline indent identifier newline dedent "
                     "identifier newline dedent identifier newline eof");
  EXPECT_TRUE(L.diags().empty());
}

TEST(LexerTest, BlankAndCommentLinesProduceNothing) {
  Lexed L("a\n\n   \n  # comment\n\t\n    b # trailing\n#x\n");
  EXPECT_EQ(L.Kinds, "identifier newline indent identifier newline dedent eof");
}

TEST(LexerTest, NoFinalNewline) {
  Lexed L("a\n    b");
  EXPECT_EQ(L.Kinds, "identifier newline indent identifier newline dedent eof");
  Lexed Empty("");
  EXPECT_EQ(Empty.Kinds, "eof");
  Lexed OnlyComment("# nothing");
  EXPECT_EQ(OnlyComment.Kinds, "eof");
}

TEST(LexerTest, MultipleDedentsAtOnce) {
  Lexed L("a\n  b\n    c\nd\n");
  EXPECT_EQ(L.Kinds, "identifier newline indent identifier newline indent "
                     "identifier newline dedent dedent identifier newline eof");
}

TEST(LexerTest, NewlinesIgnoredInsideParens) {
  Lexed L("f(a,\n        b,\n  c)\nd\n");
  EXPECT_EQ(L.Kinds, "identifier l_paren identifier comma identifier comma "
                     "identifier r_paren newline identifier newline eof");
  EXPECT_TRUE(L.diags().empty());
}

TEST(LexerTest, UnmatchedAndUnclosedBrackets) {
  Lexed L("a)\n");
  EXPECT_EQ(L.Kinds, "identifier error newline eof");
  EXPECT_EQ(L.diags(), std::vector<diag::Kind>{diag::err_unmatched_bracket});
  Lexed U("f((a\n");
  EXPECT_EQ(U.diags(), std::vector<diag::Kind>{diag::err_unclosed_bracket});
  EXPECT_EQ(U.Kinds.substr(U.Kinds.size() - 17), "error newline eof");
  Lexed K("f(a,\n\n  # c\n  if(x)\n");
  EXPECT_EQ(K.diags(), std::vector<diag::Kind>{diag::err_unclosed_bracket});
  EXPECT_EQ(K.Kinds, "identifier l_paren identifier comma error newline "
                     "indent kw_if l_paren identifier r_paren newline dedent eof");
}

TEST(LexerTest, MixedTabsAndSpacesReportedOnce) {
  Lexed L("a\n    b\nc\n\tb\n\td\n \te\n");
  EXPECT_EQ(L.diags(), std::vector<diag::Kind>{diag::err_mixed_tabs_spaces});
  Lexed Tabs("a\n\tb\n\t\tc\n");
  EXPECT_TRUE(Tabs.diags().empty());
  EXPECT_EQ(Tabs.Kinds, "identifier newline indent identifier newline indent "
                        "identifier newline dedent dedent eof");
}

TEST(LexerTest, InconsistentDedent) {
  Lexed L("a\n    b\n  c\n");
  EXPECT_EQ(L.diags(), std::vector<diag::Kind>{diag::err_inconsistent_dedent});
  // Back at level 0; the line starts with an error token.
  EXPECT_EQ(L.Kinds, "identifier newline indent identifier newline dedent "
                     "error identifier newline eof");
}

TEST(LexerTest, IntLiterals) {
  Lexed L("0 42 2147483647 2147483648 0x7fffffff 0xFFFFFFFF\n");
  ASSERT_EQ(L.Tokens.size(), 8u);
  EXPECT_EQ(L.Tokens[1].IntValue, 42u);
  EXPECT_EQ(L.Tokens[3].IntValue, 2147483648u); // Only valid after '-'.
  EXPECT_TRUE(L.Tokens[5].IsHex);
  EXPECT_EQ(L.Tokens[5].IntValue, 0xFFFFFFFFu);
  EXPECT_TRUE(L.diags().empty());
  Lexed Big("2147483649 0x100000000\n");
  EXPECT_EQ(Big.Kinds, "error error newline eof");
  EXPECT_EQ(Big.diags(),
            (std::vector<diag::Kind>{diag::err_int_literal_too_large,
                                     diag::err_int_literal_too_large}));
}

TEST(LexerTest, FloatLiterals) {
  Lexed L("1.5 0.75 1e3 2.5E-2 1e-60\n");
  EXPECT_EQ(L.Kinds, "float_literal float_literal float_literal "
                     "float_literal float_literal newline eof");
  EXPECT_FLOAT_EQ(L.Tokens[0].FloatValue, 1.5f);
  EXPECT_FLOAT_EQ(L.Tokens[2].FloatValue, 1000.0f);
  EXPECT_FLOAT_EQ(L.Tokens[3].FloatValue, 0.025f);
  EXPECT_TRUE(L.diags().empty());
  Lexed Big("1e39\n");
  EXPECT_EQ(Big.diags(),
            std::vector<diag::Kind>{diag::err_float_literal_range});
}

TEST(LexerTest, InvalidNumbers) {
  for (const char *Src : {"1.\n", ".5\n", "1e\n", "0x\n", "12abc\n", "1.2.3\n"}) {
    Lexed L(Src);
    EXPECT_EQ(L.Kinds, "error newline eof") << Src;
    EXPECT_EQ(L.diags(), std::vector<diag::Kind>{diag::err_invalid_number})
        << Src;
  }
}

TEST(LexerTest, Strings) {
  Lexed L("\"a\\n\\t\\\\\\\"\\0b\"\n");
  ASSERT_EQ(L.Tokens[0].Kind, tok::string_literal);
  EXPECT_EQ(L.Tokens[0].StringValue, std::string("a\n\t\\\"\0b", 7));
  Lexed Bad("\"\\q\"\n");
  EXPECT_EQ(Bad.Tokens[0].Kind, tok::string_literal);
  EXPECT_EQ(Bad.diags(), std::vector<diag::Kind>{diag::err_invalid_escape});
  Lexed Open("f(\"abc\nx\n");
  EXPECT_EQ(Open.diags(),
            std::vector<diag::Kind>{diag::err_unterminated_string});
  // The open '(' is forgotten, so the next line is a line of its own.
  EXPECT_EQ(Open.Kinds,
            "identifier l_paren error newline identifier newline eof");
}

TEST(LexerTest, InvalidCharactersOnePerRun) {
  Lexed L(llvm::StringRef("a $$@ b \0\x01 c \xC3\xA9\n", 16));
  EXPECT_EQ(L.Kinds,
            "identifier error identifier error identifier error newline eof");
  ASSERT_EQ(L.Diags.getDiagnostics().size(), 3u);
  EXPECT_EQ(L.Diags.getDiagnostics()[0].Message,
            "invalid character '$' in source");
  EXPECT_EQ(L.Diags.getDiagnostics()[1].Message,
            "invalid character '\\x00' in source");
  EXPECT_EQ(L.Diags.getDiagnostics()[2].Message,
            "non-ASCII byte '\\xC3': b-script names and operators are "
            "ASCII; UTF-8 text belongs in strings and comments");
  // Raw bytes are fine in comments and strings.
  Lexed Ok("a # \xff\xfe\n\"\xC3\xA9\xff\"\n");
  EXPECT_TRUE(Ok.diags().empty());
}

TEST(LexerTest, KeywordsAndPunctuators) {
  Lexed L("taskState int :: : <= < == = != ! && || += %=\n");
  EXPECT_EQ(L.Kinds, "kw_taskState identifier coloncolon colon lessequal less "
                     "equalequal equal exclaimequal exclaim ampamp pipepipe "
                     "plusequal percentequal newline eof");
}
