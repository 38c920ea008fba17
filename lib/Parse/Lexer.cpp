//===- Lexer.cpp - b-script source to tokens ------------------------------===//
//
// A hand-written, single-pass lexer: one pointer walks the buffer once, so
// lexing is linear in the size of the file whatever it contains. The
// indentation rules and literal forms are documented in Lexer.h; this file
// only implements them. Every error is reported here exactly once and the
// offending text becomes an `error` token, so the parser stays quiet.
//
//===----------------------------------------------------------------------===//
#include "bsc/Parse/Lexer.h"
#include "llvm/ADT/APFloat.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSwitch.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;

/// Tabs advance to the next multiple of this (CPython's rule).
static constexpr unsigned TabWidth = 8;

Lexer::Lexer(const llvm::SourceMgr &SM, unsigned BufferID,
             DiagnosticEngine &Diags)
    : Diags(Diags) {
  const llvm::MemoryBuffer *Buf = SM.getMemoryBuffer(BufferID);
  BufStart = Buf->getBufferStart();
  BufEnd = Buf->getBufferEnd();
  Cur = BufStart;
  // A UTF-8 byte-order mark, which some Windows editors write, is not text.
  if (llvm::StringRef(BufStart, BufEnd - BufStart).starts_with("\xEF\xBB\xBF"))
    Cur += 3;
}

void Lexer::makeToken(Token &Result, tok::Kind K, const char *Start) {
  Result.Kind = K;
  Result.Loc = llvm::SMLoc::getFromPointer(Start);
  Result.Text = llvm::StringRef(Start, Cur - Start);
}

void Lexer::makeMarker(Token &Result, tok::Kind K, const char *At) {
  Result.Kind = K;
  Result.Loc = llvm::SMLoc::getFromPointer(At);
  Result.Text = llvm::StringRef(At, 0);
}

static bool isIdentStart(char C) { return llvm::isAlpha(C) || C == '_'; }
static bool isIdentChar(char C) { return llvm::isAlnum(C) || C == '_'; }

/// Shows a byte in a diagnostic: `'$'`, `'\x00'`, `'\xC3'`.
static std::string showChar(char C) {
  std::string S = "'";
  if (C == '\'' || C == '\\') {
    S += '\\';
    S += C;
  } else if (llvm::isPrint(C)) {
    S += C;
  } else {
    S += "\\x";
    S += llvm::hexdigit((unsigned char)C >> 4);
    S += llvm::hexdigit((unsigned char)C & 15);
  }
  return S + "'";
}

/// Skips blank and comment-only lines and measures the indentation of the
/// next line with tokens, leaving Cur at its first token. Returns false at
/// the end of the buffer.
bool Lexer::measureIndentation(unsigned &Column) {
  while (true) {
    const char *LineStart = Cur;
    Column = 0;
    bool HasTab = false, HasSpace = false;
    for (; Cur != BufEnd; ++Cur) {
      if (*Cur == ' ') {
        HasSpace = true;
        ++Column;
      } else if (*Cur == '\t') {
        HasTab = true;
        // In a file indented with spaces, a stray tab most likely stands
        // for one level: tab stops at that width keep the block structure
        // (and the errors) to the one about mixing.
        unsigned Stop = SawSpaceIndent && SpaceIndentUnit ? SpaceIndentUnit
                                                          : TabWidth;
        Column = (Column / Stop + 1) * Stop;
      } else if (*Cur != '\r') {
        break;
      }
    }
    if (Cur == BufEnd)
      return false;
    if (*Cur == '#')
      skipComment();
    if (Cur == BufEnd)
      return false;
    if (*Cur == '\n') {
      ++Cur;
      continue;
    }
    if (!ReportedMixed && ((HasTab && HasSpace) || (HasTab && SawSpaceIndent) ||
                           (HasSpace && SawTabIndent))) {
      ReportedMixed = true;
      report(LineStart, diag::err_mixed_tabs_spaces);
    }
    SawTabIndent |= HasTab;
    SawSpaceIndent |= HasSpace;
    if (HasSpace && !HasTab && !SpaceIndentUnit && Column)
      SpaceIndentUnit = Column;
    return true;
  }
}

Token Lexer::lex() {
  Token Result;
  while (true) {
    if (PendingDedents != 0) {
      --PendingDedents;
      makeMarker(Result, tok::dedent, DedentLoc);
      return Result;
    }
    if (PendingBadDedent) {
      PendingBadDedent = false;
      LineHasTokens = true;
      makeMarker(Result, tok::error, DedentLoc);
      return Result;
    }

    if (AtLineStart && OpenParens.empty() && !ReachedEnd) {
      unsigned Column;
      if (!measureIndentation(Column)) {
        ReachedEnd = true;
        continue;
      }
      AtLineStart = false;
      if (Column > Indents.back()) {
        Indents.push_back(Column);
        makeMarker(Result, tok::indent, Cur);
        return Result;
      }
      if (Column < Indents.back()) {
        while (Column < Indents.back()) {
          Indents.pop_back();
          ++PendingDedents;
        }
        DedentLoc = Cur;
        // A column never opened: continue at the enclosing level, and let
        // an error token keep the parser from reporting the line again.
        if (Column != Indents.back()) {
          report(Cur, diag::err_inconsistent_dedent);
          PendingBadDedent = true;
        }
        continue;
      }
    }

    // Whitespace and comments between tokens.
    while (Cur != BufEnd && (*Cur == ' ' || *Cur == '\t' || *Cur == '\r'))
      ++Cur;
    if (Cur != BufEnd && *Cur == '#')
      skipComment();

    if (Cur == BufEnd) {
      ReachedEnd = true;
      if (!OpenParens.empty()) {
        reportUnclosed();
        LineHasTokens = true;
        makeMarker(Result, tok::error, Cur);
        return Result;
      }
      if (LineHasTokens) {
        LineHasTokens = false;
        makeMarker(Result, tok::newline, Cur);
        return Result;
      }
      if (Indents.size() > 1) {
        PendingDedents = Indents.size() - 1;
        Indents.resize(1);
        DedentLoc = Cur;
        continue;
      }
      makeMarker(Result, tok::eof, Cur);
      return Result;
    }

    if (*Cur == '\n') {
      if (!OpenParens.empty() && !nextLineStartsStatement()) {
        ++Cur;
        continue;
      }
      if (!OpenParens.empty()) {
        // A statement keyword cannot continue an expression: the `(` was
        // never closed. End the line here, with an error token so that
        // the parser does not report the missing `)` again.
        reportUnclosed();
        makeMarker(Result, tok::error, Cur);
        return Result;
      }
      ++Cur;
      AtLineStart = true;
      if (LineHasTokens) {
        LineHasTokens = false;
        makeMarker(Result, tok::newline, Cur - 1);
        return Result;
      }
      continue;
    }

    LineHasTokens = true;
    char C = *Cur;
    if (isIdentStart(C)) {
      const char *Start = Cur;
      while (Cur != BufEnd && isIdentChar(*Cur))
        ++Cur;
      llvm::StringRef Text(Start, Cur - Start);
      tok::Kind K = llvm::StringSwitch<tok::Kind>(Text)
#define KEYWORD(Spelling) .Case(#Spelling, tok::kw_##Spelling)
#include "bsc/Parse/TokenKinds.def"
                        .Default(tok::identifier);
      makeToken(Result, K, Start);
      return Result;
    }
    if (llvm::isDigit(C) ||
        (C == '.' && Cur + 1 != BufEnd && llvm::isDigit(Cur[1]))) {
      lexNumber(Result);
      return Result;
    }
    if (C == '"') {
      lexString(Result);
      return Result;
    }
    if (lexPunctuator(Result))
      return Result;
    lexInvalidRun(Result);
    return Result;
  }
}

namespace {
struct Punctuator {
  tok::Kind Kind;
  llvm::StringLiteral Spelling;
};
const Punctuator Punctuators[] = {
#define PUNCT(Name, Spelling) {tok::Name, Spelling},
#include "bsc/Parse/TokenKinds.def"
};
} // namespace

/// Longest match against the PUNCT entries of TokenKinds.def.
static const Punctuator *matchPunctuator(const char *P, const char *End) {
  const Punctuator *Best = nullptr;
  llvm::StringRef Rest(P, std::min<size_t>(End - P, 2));
  for (const Punctuator &Punct : Punctuators)
    if (Rest.starts_with(Punct.Spelling) &&
        (!Best || Punct.Spelling.size() > Best->Spelling.size()))
      Best = &Punct;
  return Best;
}

void Lexer::reportUnclosed() {
  // Errors reported since the `(` opened (a parser error on the same
  // statement) already cover this mistake.
  if (Diags.getNumErrors() == ErrorsAtOpenParen)
    report(OpenParens.front(), diag::err_unclosed_bracket) << "(";
  OpenParens.clear();
}

/// Moves Cur from a `#` to the end of its line, keeping the comment.
void Lexer::skipComment() {
  const char *Start = Cur;
  while (Cur != BufEnd && *Cur != '\n')
    ++Cur;
  if (Comments)
    Comments->push_back(llvm::StringRef(Start, Cur - Start).rtrim(" \t\r"));
}

bool Lexer::nextLineStartsStatement() {
  // Blank lines are looked at once, whatever number of newlines ask.
  if (Cur < PeekEnd)
    return PeekResult;
  const char *P = Cur + 1;
  while (P != BufEnd) {
    while (P != BufEnd && (*P == ' ' || *P == '\t' || *P == '\r'))
      ++P;
    if (P != BufEnd && *P == '#')
      while (P != BufEnd && *P != '\n')
        ++P;
    if (P == BufEnd || *P != '\n')
      break;
    ++P;
  }
  PeekEnd = P;
  const char *WordEnd = P;
  while (WordEnd != BufEnd && isIdentChar(*WordEnd))
    ++WordEnd;
  PeekResult = llvm::StringSwitch<bool>(llvm::StringRef(P, WordEnd - P))
                   .Cases("func", "task", "requires", "if", "else", true)
                   .Cases("for", "break", "continue", "return", "yield", true)
                   .Cases("assert", "assume", true)
                   .Default(false);
  return PeekResult;
}

bool Lexer::lexPunctuator(Token &Result) {
  const Punctuator *P = matchPunctuator(Cur, BufEnd);
  if (!P)
    return false;
  const char *Start = Cur;
  Cur += P->Spelling.size();
  makeToken(Result, P->Kind, Start);
  if (P->Kind == tok::l_paren) {
    if (OpenParens.empty())
      ErrorsAtOpenParen = Diags.getNumErrors();
    OpenParens.push_back(Start);
  } else if (P->Kind == tok::r_paren) {
    if (OpenParens.empty()) {
      report(Start, diag::err_unmatched_bracket) << ")";
      Result.Kind = tok::error;
    } else {
      OpenParens.pop_back();
    }
  }
  return true;
}

void Lexer::lexInvalidRun(Token &Result) {
  const char *Start = Cur;
  auto IsInvalid = [&](const char *P) {
    char C = *P;
    if (isIdentChar(C) || C == '.' || C == '"' || C == '#' || C == ' ' ||
        C == '\t' || C == '\r' || C == '\n')
      return false;
    return matchPunctuator(P, BufEnd) == nullptr;
  };
  while (Cur != BufEnd && IsInvalid(Cur))
    ++Cur;
  if (static_cast<unsigned char>(*Start) >= 0x80)
    report(Start, diag::err_non_ascii_character) << showChar(*Start);
  else
    report(Start, diag::err_invalid_character) << showChar(*Start);
  makeToken(Result, tok::error, Start);
}

void Lexer::lexNumber(Token &Result) {
  const char *Start = Cur;
  bool Valid = true, IsFloat = false, IsHex = false;
  if (*Cur == '0' && Cur + 1 != BufEnd && (Cur[1] == 'x' || Cur[1] == 'X')) {
    IsHex = true;
    Cur += 2;
    const char *Digits = Cur;
    while (Cur != BufEnd && llvm::isHexDigit(*Cur))
      ++Cur;
    Valid = Cur != Digits;
  } else if (*Cur == '.') {
    Valid = false; // `.5`: the run below takes the digits.
    ++Cur;
  } else {
    while (Cur != BufEnd && llvm::isDigit(*Cur))
      ++Cur;
    if (Cur != BufEnd && *Cur == '.') {
      IsFloat = true;
      ++Cur;
      Valid = Cur != BufEnd && llvm::isDigit(*Cur);
      while (Cur != BufEnd && llvm::isDigit(*Cur))
        ++Cur;
    }
    if (Valid && Cur != BufEnd && (*Cur == 'e' || *Cur == 'E')) {
      IsFloat = true;
      ++Cur;
      if (Cur != BufEnd && (*Cur == '+' || *Cur == '-') && Cur + 1 != BufEnd &&
          llvm::isDigit(Cur[1]))
        ++Cur;
      Valid = Cur != BufEnd && llvm::isDigit(*Cur);
      while (Cur != BufEnd && llvm::isDigit(*Cur))
        ++Cur;
    }
  }
  // A number that runs into letters, digits or dots is one bad token:
  // `12abc`, `1.2.3`, `0xfg`.
  while (Cur != BufEnd && (isIdentChar(*Cur) || *Cur == '.')) {
    Valid = false;
    ++Cur;
  }
  makeToken(Result, tok::error, Start);
  if (!Valid) {
    report(Start, diag::err_invalid_number) << Result.Text;
    return;
  }

  if (IsFloat) {
    llvm::APFloat F(llvm::APFloat::IEEEsingle());
    auto Status =
        F.convertFromString(Result.Text, llvm::APFloat::rmNearestTiesToEven);
    if (!Status || (*Status & llvm::APFloat::opOverflow) || !F.isFinite()) {
      if (!Status)
        llvm::consumeError(Status.takeError());
      report(Start, diag::err_float_literal_range) << Result.Text;
      return;
    }
    Result.Kind = tok::float_literal;
    Result.FloatValue = F.convertToFloat();
    return;
  }

  // Saturating accumulation: anything above Limit is too large anyway.
  uint64_t Limit = IsHex ? 0xFFFFFFFFull : 2147483648ull;
  uint64_t Value = 0;
  bool TooLarge = false;
  for (char D : Result.Text.drop_front(IsHex ? 2 : 0)) {
    Value = Value * (IsHex ? 16 : 10) + llvm::hexDigitValue(D);
    if (Value > Limit) {
      TooLarge = true;
      break;
    }
  }
  if (TooLarge) {
    report(Start, diag::err_int_literal_too_large) << Result.Text;
    return;
  }
  Result.Kind = tok::int_literal;
  Result.IntValue = Value;
  Result.IsHex = IsHex;
}

void Lexer::lexString(Token &Result) {
  const char *Start = Cur++;
  std::string Value;
  while (true) {
    if (Cur == BufEnd || *Cur == '\n') {
      report(Start, diag::err_unterminated_string);
      // The quote probably was forgotten; do not let an open `(` before it
      // swallow the following lines.
      OpenParens.clear();
      makeToken(Result, tok::error, Start);
      return;
    }
    char C = *Cur;
    if (C == '"') {
      ++Cur;
      break;
    }
    if (C != '\\') {
      Value += C;
      ++Cur;
      continue;
    }
    if (Cur + 1 == BufEnd || Cur[1] == '\n') {
      ++Cur; // Reported as unterminated above.
      continue;
    }
    char E = Cur[1];
    switch (E) {
    case 'n':
      Value += '\n';
      break;
    case 't':
      Value += '\t';
      break;
    case '\\':
      Value += '\\';
      break;
    case '"':
      Value += '"';
      break;
    case '0':
      Value += '\0';
      break;
    default: {
      std::string Shown = showChar(E);
      // Without the quotes of showChar: the format adds `'\`...`'`.
      report(Cur, diag::err_invalid_escape) << Shown.substr(1, Shown.size() - 2);
      Value += E;
      break;
    }
    }
    Cur += 2;
  }
  makeToken(Result, tok::string_literal, Start);
  Result.StringValue = std::move(Value);
}

void bsc::dumpTokens(const llvm::SourceMgr &SM, unsigned BufferID,
                     DiagnosticEngine &Diags, llvm::raw_ostream &OS) {
  Lexer L(SM, BufferID, Diags);
  while (true) {
    Token T = L.lex();
    auto LineCol = SM.getLineAndColumn(T.Loc, BufferID);
    OS << LineCol.first << ':' << LineCol.second << ' ' << tok::getName(T.Kind);
    if (!T.Text.empty()) {
      OS << " '";
      for (char C : T.Text) {
        if (llvm::isPrint(C))
          OS << C;
        else
          OS << "\\x" << llvm::hexdigit((unsigned char)C >> 4)
             << llvm::hexdigit((unsigned char)C & 15);
      }
      OS << '\'';
    }
    OS << '\n';
    if (T.is(tok::eof))
      return;
  }
}
