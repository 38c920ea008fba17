//===- ParseHabits.cpp - constructs of other languages --------------------===//
//
// People write b-script with the habits of C, C++ and Python. Where one of
// those spellings would otherwise surface as a puzzling "expected end of
// line", the parser names the b-script spelling instead, at the habit:
//   while (...)          -> for(; condition;)
//   elif                 -> else if
//   and, or, not         -> &&, ||, !
//   x++, x--, ++x, --x   -> x += 1, x -= 1
//   a trailing ';'       -> nothing: a statement ends with its line
// Sema adds the habits it alone can see (`True`, `==` between tasks).
// Each check looks at the current token and at most the next one, and only
// where the token could not start anything valid, so a program that is
// right never reaches them.
//
//===----------------------------------------------------------------------===//
#include "ParserImpl.h"

using namespace bsc;

/// Whether the rest of the line after `P` is empty (or a comment or `)`).
static bool restOfLineIsEmpty(const char *P, const char *End) {
  while (P != End && (*P == ' ' || *P == '\t' || *P == '\r'))
    ++P;
  return P == End || *P == '\n' || *P == '#' || *P == ')' || *P == ';';
}

bool Parser::diagnoseStatementHabit() {
  if (Tok.is(tok::identifier)) {
    // `while` / `elif` followed by a condition; a variable of that name
    // would be followed by an assignment, `.`, `(`-less text or the end.
    bool IsWhile = Tok.Text == "while";
    bool IsElif = Tok.Text == "elif" || Tok.Text == "elsif" ||
                  Tok.Text == "elseif";
    if (!IsWhile && !IsElif)
      return false;
    const Token &Next = peek();
    if (Next.isNot(tok::l_paren) && Next.isNot(tok::identifier) &&
        Next.isNot(tok::int_literal) && Next.isNot(tok::kw_true) &&
        Next.isNot(tok::kw_false) && Next.isNot(tok::exclaim))
      return false;
    if (IsWhile)
      diag(Tok.Loc, diag::err_habit_while);
    else
      diag(Tok.Loc, diag::err_habit_elif) << Tok.Text;
    return true;
  }
  // `++x` / `--x` as a statement.
  if ((Tok.is(tok::plus) || Tok.is(tok::minus)) &&
      Tok.Loc.getPointer()[1] == Tok.Text[0])
    return reportIncrementHabit();
  return false;
}

bool Parser::reportIncrementHabit() {
  bool Plus = Tok.is(tok::plus);
  diag(Tok.Loc, diag::err_habit_increment)
      << (Plus ? "++" : "--") << (Plus ? "+=" : "-=");
  return true;
}

bool Parser::diagnoseOperatorHabit() {
  if (Tok.is(tok::identifier) && (Tok.Text == "and" || Tok.Text == "or")) {
    diag(Tok.Loc, diag::err_habit_word_operator)
        << Tok.Text << (Tok.Text == "and" ? "&&" : "||");
    return true;
  }
  // `x++` (b-script has no unary plus, so `++` is never valid) and `x--`
  // at the end of the line (`a--b` is a minus a negation).
  if (Tok.is(tok::plus) || Tok.is(tok::minus)) {
    const char *P = Tok.Loc.getPointer();
    if (P[1] != P[0])
      return false;
    if (Tok.is(tok::minus) &&
        !restOfLineIsEmpty(P + 2, Source.data() + Source.size()))
      return false;
    return reportIncrementHabit();
  }
  return false;
}

bool Parser::diagnoseOperandHabit() {
  if (Tok.isNot(tok::identifier) || Tok.Text != "not")
    return false;
  const Token &Next = peek();
  if (Next.isNot(tok::identifier) && Next.isNot(tok::l_paren) &&
      Next.isNot(tok::kw_true) && Next.isNot(tok::kw_false) &&
      Next.isNot(tok::kw_taskState))
    return false;
  diag(Tok.Loc, diag::err_habit_word_operator) << "not" << "!";
  return true;
}

bool Parser::diagnoseEndOfLineHabit() {
  if (Tok.isNot(tok::semi) ||
      !restOfLineIsEmpty(Tok.Loc.getPointer() + 1,
                         Source.data() + Source.size()))
    return false;
  diag(Tok.Loc, diag::err_habit_semicolon);
  return true;
}
