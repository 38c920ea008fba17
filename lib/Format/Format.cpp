//===- Format.cpp - a buffer in the canonical layout ----------------------===//
//
// The entry (formatBuffer): check the syntax, cut the buffer into items,
// decide the blank lines between them, write each, and check that the
// result is the same program.
//
//===----------------------------------------------------------------------===//
#include "bsc/Format/Format.h"
#include "FormatImpl.h"
#include "bsc/Parse/Lexer.h"
#include "bsc/Parse/Parser.h"
#include "llvm/Support/MemoryBuffer.h"

using namespace bsc;
using namespace bsc::format;

/// Whether a module-level statement declares something that stands apart:
/// a task, a func or an enum.
static bool isDeclaration(const Item &I) {
  return !I.IsComment && I.Depth == 0 &&
         (I.Tokens[0].Tok.is(tok::kw_task) || I.Tokens[0].Tok.is(tok::kw_func) ||
          I.Tokens[0].Tok.is(tok::kw_enum));
}

/// The blank lines before each item: the author's, at most one, none at
/// the start of the file or of a block, and one before a declaration and
/// the comment lines directly above it.
static std::vector<unsigned> decideBlankLines(const std::vector<Item> &Items) {
  std::vector<unsigned> Blank(Items.size(), 0);
  for (size_t I = 1; I < Items.size(); ++I) {
    const Item &Prev = Items[I - 1];
    bool OpensBlock = !Prev.IsComment && Items[I].Depth > Prev.Depth;
    Blank[I] = !OpensBlock && Items[I].First > Prev.Last + 1;
  }
  for (size_t I = 1; I < Items.size(); ++I) {
    if (!isDeclaration(Items[I]))
      continue;
    size_t J = I;
    while (J > 0 && Items[J - 1].IsComment && Items[J - 1].Depth == 0 &&
           !Blank[J])
      --J;
    if (J > 0)
      Blank[J] = 1;
  }
  return Blank;
}

/// The tokens (kind and text) and comments of a text, to compare two.
static std::pair<std::vector<std::string>, std::vector<std::string>>
readProgram(llvm::StringRef Text) {
  llvm::SourceMgr SM;
  unsigned ID = SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBuffer(Text, "", false), llvm::SMLoc());
  DiagnosticEngine Quiet;
  std::vector<llvm::StringRef> Comments;
  Lexer L(SM, ID, Quiet);
  L.keepComments(&Comments);
  std::vector<std::string> Tokens, CommentTexts;
  for (Token T = L.lex(); T.isNot(tok::eof); T = L.lex())
    Tokens.push_back((tok::getName(T.Kind) + " " + T.Text).str());
  if (Quiet.hasErrors())
    Tokens.push_back("(lexical errors)");
  for (llvm::StringRef C : Comments)
    // Trailing blanks, carriage returns among them, are no part of it.
    CommentTexts.push_back(C.rtrim(" \t\r").str());
  return {Tokens, CommentTexts};
}

llvm::Error format::checkSameProgram(llvm::StringRef Before,
                                     llvm::StringRef After) {
  auto [TokensBefore, CommentsBefore] = readProgram(Before);
  auto [TokensAfter, CommentsAfter] = readProgram(After);
  auto FirstDifference = [](const std::vector<std::string> &A,
                            const std::vector<std::string> &B) {
    size_t I = 0;
    while (I < A.size() && I < B.size() && A[I] == B[I])
      ++I;
    return I;
  };
  size_t T = FirstDifference(TokensBefore, TokensAfter);
  if (T != TokensBefore.size() || T != TokensAfter.size())
    return llvm::createStringError(
        "token %zu differs: '%s' became '%s'", T + 1,
        T < TokensBefore.size() ? TokensBefore[T].c_str() : "(end)",
        T < TokensAfter.size() ? TokensAfter[T].c_str() : "(end)");
  size_t C = FirstDifference(CommentsBefore, CommentsAfter);
  if (C != CommentsBefore.size() || C != CommentsAfter.size())
    return llvm::createStringError(
        "comment %zu differs: '%s' became '%s'", C + 1,
        C < CommentsBefore.size() ? CommentsBefore[C].c_str() : "(end)",
        C < CommentsAfter.size() ? CommentsAfter[C].c_str() : "(end)");
  return llvm::Error::success();
}

llvm::Expected<std::optional<FormattedFile>>
format::formatBuffer(const llvm::SourceMgr &SM, unsigned BufferID,
                     DiagnosticEngine &Diags) {
  unsigned ErrorsBefore = Diags.getNumErrors();
  ASTContext Ctx;
  parseModule(SM, BufferID, "formatted", Ctx, Diags);
  if (Diags.getNumErrors() != ErrorsBefore)
    return std::nullopt;

  std::vector<Item> Items = splitItems(SM, BufferID);
  std::vector<unsigned> Blank = decideBlankLines(Items);
  FormattedFile F;
  // A byte-order mark stays: the layout is not the encoding's business.
  llvm::StringRef Source = SM.getMemoryBuffer(BufferID)->getBuffer();
  if (Source.starts_with("\xEF\xBB\xBF"))
    F.Text = "\xEF\xBB\xBF";
  for (size_t I = 0; I < Items.size(); ++I) {
    const Item &It = Items[I];
    std::string Text(Blank[I], '\n');
    if (It.IsComment)
      Text += std::string(It.Depth * IndentWidth, ' ') + It.Comment.str() +
              "\n";
    else
      Text += layoutStatement(It);
    F.Text += Text;
    F.Pieces.push_back({It.First, It.Last, std::move(Text)});
  }
  if (llvm::Error E = checkSameProgram(Source, F.Text))
    return llvm::createStringError(
        "formatting '%s' would change the program (%s)",
        SM.getMemoryBuffer(BufferID)->getBufferIdentifier().str().c_str(),
        llvm::toString(std::move(E)).c_str());
  return F;
}

std::optional<RangeEdit> format::formatLines(const FormattedFile &F,
                                             unsigned First, unsigned Last) {
  std::optional<RangeEdit> Edit;
  for (const FormattedFile::Piece &P : F.Pieces) {
    if (P.Last < First || P.First > Last)
      continue;
    if (!Edit) {
      // The blank lines before the first piece stay as they are.
      Edit = RangeEdit{P.First, P.Last,
                       llvm::StringRef(P.Text).ltrim('\n').str()};
      continue;
    }
    Edit->ToLine = P.Last;
    Edit->Text += P.Text;
  }
  return Edit;
}
