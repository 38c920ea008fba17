//===- Presentation.cpp - semantic tokens and folding ranges --------------===//
//
// Both read the lexer's tokens of the document (with its comments); a
// name is coloured by what the index says it stands for, so a task, a
// registered method and an enum value differ even where the grammar alone
// cannot tell them apart.
//
//===----------------------------------------------------------------------===//
#include "Features.h"
#include "bsc/Parse/Lexer.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSwitch.h"

using namespace bsc;
using namespace bsc::lsp;

const char *const lsp::TokenTypes[14] = {
    "namespace", "type",     "enum",    "enumMember", "function",
    "method",    "property", "variable", "parameter", "keyword",
    "comment",   "string",   "number",  "operator"};
const char *const lsp::TokenModifiers[4] = {"declaration", "readonly",
                                           "defaultLibrary", "task"};

namespace {
enum TokenType {
  Namespace,
  TypeName,
  EnumType,
  EnumMember,
  Function,
  Method,
  Property,
  Variable,
  Parameter,
  Keyword,
  Comment,
  String,
  Number,
  Operator,
};
enum TokenModifier {
  Declaration = 1,
  ReadOnly = 2,
  DefaultLibrary = 4,
  Task = 8,
};
} // namespace

/// The token type and modifiers of a name that stands for `S`.
static std::pair<int, int> classify(const Symbol &S) {
  switch (S.K) {
  case Symbol::Decl: {
    const auto *D = static_cast<const Decl *>(S.Ptr);
    switch (D->getKind()) {
    case NodeKind::TaskDecl:
      return {Function, Task};
    case NodeKind::FuncDecl:
      return {Function, 0};
    case NodeKind::ParamDecl:
      return {Parameter, 0};
    case NodeKind::VarDecl:
      return {Variable, 0};
    case NodeKind::ConstDecl:
      return {Variable, ReadOnly};
    case NodeKind::EnumDecl:
      return {EnumType, 0};
    default:
      return {-1, 0};
    }
  }
  case Symbol::Enumerator:
    return {EnumMember, 0};
  case Symbol::NativeFunction: {
    const auto *F = static_cast<const NativeFunction *>(S.Ptr);
    if (F->isData())
      return {Property, F->ReadOnly ? ReadOnly : 0};
    return {F->hasSelf() ? Method : Function, DefaultLibrary};
  }
  case Symbol::NativeClass:
    return {TypeName, DefaultLibrary};
  case Symbol::NativeEnum:
    return {EnumType, DefaultLibrary};
  case Symbol::NativeEnumValue:
    return {EnumMember, DefaultLibrary};
  case Symbol::NativeConstant:
    return {Variable, ReadOnly | DefaultLibrary};
  case Symbol::ScriptModule:
  case Symbol::NativeModule:
    return {Namespace, 0};
  case Symbol::Global:
    return {Variable, DefaultLibrary};
  case Symbol::None:
    break;
  }
  return {-1, 0};
}

/// The type of a token the grammar alone classifies, or -1.
static int classify(const Token &T) {
  switch (T.Kind) {
  case tok::int_literal:
  case tok::float_literal:
    return Number;
  case tok::string_literal:
    return String;
  case tok::identifier:
    return llvm::StringSwitch<int>(T.Text)
        .Cases("int", "float", "bool", "string", "TaskState", TypeName)
        .Default(-1);
  case tok::l_paren:
  case tok::r_paren:
  case tok::l_square:
  case tok::r_square:
  case tok::comma:
  case tok::period:
  case tok::colon:
  case tok::coloncolon:
  case tok::semi:
    return -1; // Punctuation: the editor's grammar colours it.
  default:
    if (!tok::getSpelling(T.Kind).empty())
      return llvm::isAlpha(tok::getSpelling(T.Kind)[0]) ? Keyword : Operator;
    return -1;
  }
}

llvm::json::Value lsp::semanticTokens(const Analysis &A, unsigned BufferID) {
  llvm::DenseMap<const char *, const Occurrence *> Names;
  for (const Occurrence &O : A.Idx.Occurrences)
    Names[O.Range.Start.getPointer()] = &O;
  DiagnosticEngine Quiet;
  std::vector<llvm::StringRef> Comments;
  Lexer L(A.C->SM, BufferID, Quiet);
  L.keepComments(&Comments);
  // (start, length, type, modifiers) in source order.
  std::vector<std::tuple<const char *, size_t, int, int>> Spans;
  for (Token T = L.lex(); T.isNot(tok::eof); T = L.lex()) {
    if (T.Text.empty())
      continue;
    int Type = classify(T), Mods = 0;
    if (T.is(tok::identifier) || T.is(tok::string_literal))
      if (const Occurrence *O = Names.lookup(T.Text.data())) {
        std::tie(Type, Mods) = classify(O->Sym);
        if (O->IsDefinition)
          Mods |= Declaration;
        if (Type < 0 && T.is(tok::string_literal))
          Type = String;
      }
    if (Type >= 0)
      Spans.emplace_back(T.Text.data(), T.Text.size(), Type, Mods);
  }
  for (llvm::StringRef C : Comments)
    Spans.emplace_back(C.data(), C.size(), Comment, 0);
  llvm::sort(Spans, [](const auto &X, const auto &Y) {
    return std::get<0>(X) < std::get<0>(Y);
  });
  llvm::json::Array Data;
  int64_t PrevLine = 0, PrevChar = 0;
  for (auto &[Start, Length, Type, Mods] : Spans) {
    llvm::SMLoc Loc = llvm::SMLoc::getFromPointer(Start);
    llvm::json::Object P = A.getPosition(Loc);
    llvm::json::Object E = A.getPosition(llvm::SMLoc::getFromPointer(Start + Length));
    int64_t Line = *P.getInteger("line"), Char = *P.getInteger("character");
    int64_t EndChar = *E.getInteger("character");
    if (*E.getInteger("line") != Line)
      continue; // Tokens never span lines.
    Data.push_back(Line - PrevLine);
    Data.push_back(Line == PrevLine ? Char - PrevChar : Char);
    Data.push_back(EndChar - Char);
    Data.push_back(Type);
    Data.push_back(Mods);
    PrevLine = Line;
    PrevChar = Char;
  }
  return llvm::json::Object{{"data", std::move(Data)}};
}

llvm::json::Value lsp::foldingRanges(const Analysis &A, unsigned BufferID) {
  DiagnosticEngine Quiet;
  Lexer L(A.C->SM, BufferID, Quiet);
  auto LineOf = [&](llvm::SMLoc Loc) {
    return int64_t(A.C->SM.getLineAndColumn(Loc, BufferID).first) - 1;
  };
  llvm::json::Array Ranges;
  std::vector<int64_t> Open;
  int64_t StatementLine = 0, LastLine = 0;
  bool AtStatementStart = true;
  for (Token T = L.lex(); T.isNot(tok::eof); T = L.lex()) {
    switch (T.Kind) {
    case tok::indent:
      Open.push_back(StatementLine);
      break;
    case tok::dedent:
      if (!Open.empty()) {
        if (LastLine > Open.back())
          Ranges.push_back(llvm::json::Object{{"startLine", Open.back()},
                                              {"endLine", LastLine}});
        Open.pop_back();
      }
      break;
    case tok::newline:
      AtStatementStart = true;
      break;
    default:
      if (AtStatementStart)
        StatementLine = LineOf(T.Loc);
      AtStatementStart = false;
      LastLine = LineOf(T.Loc);
      break;
    }
  }
  return Ranges;
}
