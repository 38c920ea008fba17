//===- Items.cpp - a buffer as statement lines and comment lines ----------===//
//
// The lexer gives the tokens and, on request, the comments it skips; this
// file puts each comment where the layout needs it: after the token it
// follows on its line, before the token it precedes inside a continued
// line, or as a line of its own between statements, at the depth of the
// code it stands in.
//
//===----------------------------------------------------------------------===//
#include "FormatImpl.h"
#include "bsc/Parse/Lexer.h"

using namespace bsc;
using namespace bsc::format;

namespace {
/// Cuts one buffer into items, token by token.
class ItemSplitter {
public:
  ItemSplitter(const llvm::SourceMgr &SM, unsigned BufferID)
      : SM(SM), BufferID(BufferID) {}

  std::vector<Item> split();

private:
  struct Position {
    unsigned Line, Column;
  };
  Position where(const char *P) const {
    auto [Line, Column] =
        SM.getLineAndColumn(llvm::SMLoc::getFromPointer(P), BufferID);
    return {Line, Column};
  }
  void addComment(llvm::StringRef Text);
  void addToken(const Token &T);
  void endStatement();
  /// The comment lines seen since the last statement, placed before the
  /// next one (at depth `NextDepth`).
  void flushCommentLines(unsigned NextDepth);

  const llvm::SourceMgr &SM;
  unsigned BufferID;
  std::vector<Item> Items;
  /// The statement being read, if one is open.
  Item Statement;
  bool StatementOpen = false;
  unsigned LastTokenLine = 0;
  std::vector<llvm::StringRef> PendingLeading;
  /// Comment lines between statements: their text and position.
  std::vector<std::pair<llvm::StringRef, Position>> PendingLines;
  unsigned Depth = 0;
  /// The depth of the last statement and the source column of each depth
  /// open there, to place a comment line before a dedent.
  unsigned LastDepth = 0;
  std::vector<unsigned> ColumnAt{1};
};
} // namespace

std::vector<Item> ItemSplitter::split() {
  DiagnosticEngine Quiet; // The caller has checked the syntax.
  std::vector<llvm::StringRef> Comments;
  Lexer L(SM, BufferID, Quiet);
  L.keepComments(&Comments);
  std::vector<Token> Tokens;
  for (Token T = L.lex(); T.isNot(tok::eof); T = L.lex())
    Tokens.push_back(std::move(T));

  size_t NextComment = 0;
  for (const Token &T : Tokens) {
    for (; NextComment < Comments.size() &&
           Comments[NextComment].data() < T.Loc.getPointer();
         ++NextComment)
      addComment(Comments[NextComment]);
    addToken(T);
  }
  for (; NextComment < Comments.size(); ++NextComment)
    addComment(Comments[NextComment]);
  if (StatementOpen)
    endStatement();
  flushCommentLines(0);
  return std::move(Items);
}

void ItemSplitter::addComment(llvm::StringRef Text) {
  Position P = where(Text.data());
  if (StatementOpen && P.Line == LastTokenLine)
    Statement.Tokens.back().Trailing = Text.rtrim(" \t");
  else if (StatementOpen)
    PendingLeading.push_back(Text.rtrim(" \t"));
  else
    PendingLines.push_back({Text.rtrim(" \t"), P});
}

void ItemSplitter::addToken(const Token &T) {
  switch (T.Kind) {
  case tok::newline:
    endStatement();
    return;
  case tok::indent:
    ++Depth;
    return;
  case tok::dedent:
    --Depth;
    return;
  default:
    break;
  }
  Position P = where(T.Loc.getPointer());
  if (!StatementOpen) {
    flushCommentLines(Depth);
    Statement = Item();
    Statement.Depth = Depth;
    Statement.First = P.Line;
    StatementOpen = true;
    ColumnAt.resize(Depth + 1);
    ColumnAt[Depth] = P.Column;
    LastDepth = Depth;
  }
  Statement.Tokens.push_back({T, std::move(PendingLeading), {}});
  PendingLeading.clear();
  LastTokenLine = P.Line;
}

void ItemSplitter::endStatement() {
  if (!StatementOpen)
    return;
  Statement.Last = LastTokenLine;
  Items.push_back(std::move(Statement));
  StatementOpen = false;
}

void ItemSplitter::flushCommentLines(unsigned NextDepth) {
  for (auto &[Text, P] : PendingLines) {
    // Into a block that opens: its depth. Before a dedent: the deepest
    // block still open that the comment is indented into (right of the
    // code around the block), so that a comment closing a block stays in
    // it.
    unsigned D = NextDepth;
    if (NextDepth <= LastDepth)
      for (unsigned Level = LastDepth; Level > NextDepth; --Level)
        if (ColumnAt[Level - 1] < P.Column) {
          D = Level;
          break;
        }
    Item C;
    C.IsComment = true;
    C.Depth = D;
    C.First = C.Last = P.Line;
    C.Comment = Text;
    Items.push_back(std::move(C));
  }
  PendingLines.clear();
}

std::vector<Item> format::splitItems(const llvm::SourceMgr &SM,
                                     unsigned BufferID) {
  return ItemSplitter(SM, BufferID).split();
}
