//===- ParseExpr.cpp - expressions -----------------------------------------===//
//
// Binary operators are parsed by precedence climbing driven by the table in
// OperatorKinds.def (C precedence, all left-associative), so adding an
// operator is one line there and one token in TokenKinds.def. There is no
// assignment inside expressions.
//
// Unary minus applied directly to a literal is folded into the literal; this
// is also how `-2147483648` (INT_MIN) is written, the one decimal literal
// above INT_MAX that is accepted.
//
//===----------------------------------------------------------------------===//
#include "ParserImpl.h"
#include <climits>

using namespace bsc;

namespace {
/// Token kind -> binary operator, built once from the two .def tables by
/// matching spellings.
struct BinaryOpTable {
  bool Valid[tok::NumKinds] = {};
  BinaryOp Ops[tok::NumKinds] = {};
  BinaryOpTable() {
    for (unsigned K = 0; K != tok::NumKinds; ++K) {
      llvm::StringRef Spelling = tok::getSpelling(tok::Kind(K));
#define BINARY_OP(Name, S, Prec)                                               \
  if (!Spelling.empty() && Spelling == S) {                                    \
    Valid[K] = true;                                                           \
    Ops[K] = BinaryOp::Name;                                                   \
  }
#include "bsc/AST/OperatorKinds.def"
    }
  }
};
} // namespace

static bool getBinaryOp(tok::Kind K, BinaryOp &Op) {
  static const BinaryOpTable Table;
  if (!Table.Valid[K])
    return false;
  Op = Table.Ops[K];
  return true;
}

Expr *Parser::makeError(llvm::SMLoc Start) {
  return make<ErrorExpr>(llvm::SMRange(Start, Start == Tok.Loc ? Start : PrevEnd));
}

unsigned Parser::heightOf(const Expr *E) const {
  auto It = Heights.find(E);
  return It == Heights.end() ? 0 : It->second;
}

Expr *Parser::withHeight(Expr *E,
                         std::initializer_list<const Expr *> Children) {
  unsigned Height = 0;
  for (const Expr *C : Children)
    Height = std::max(Height, heightOf(C));
  return withHeight(E, Height + 1);
}

Expr *Parser::withHeight(Expr *E, unsigned Height) {
  if (Height > MaxNestingDepth) {
    reportTooDeep(E->getLoc());
    skipToLineEnd();
    return make<ErrorExpr>(E->getRange());
  }
  Heights[E] = Height;
  return E;
}

/// expr ::= unary (binary-op unary)*
Expr *Parser::parseExpr() {
  NestingScope Scope(*this);
  if (Scope.tooDeep()) {
    llvm::SMLoc Start = Tok.Loc;
    reportTooDeep(Start);
    skipToLineEnd();
    return make<ErrorExpr>(rangeFrom(Start));
  }
  return parseBinaryRHS(1, parseUnary());
}

/// An expression whose leading qualified name was already parsed (the
/// statement parser needed it to tell declarations from expressions).
Expr *Parser::parseExprAfterName(QualifiedName Name) {
  NestingScope Scope(*this);
  Expr *E = parsePostfix(parseNameOrConversion(std::move(Name)));
  return parseBinaryRHS(1, E);
}

/// Precedence climbing: extends LHS with operators binding at least MinPrec.
Expr *Parser::parseBinaryRHS(unsigned MinPrec, Expr *LHS) {
  while (true) {
    BinaryOp Op;
    if (InError || diagnoseOperatorHabit() || !getBinaryOp(Tok.Kind, Op) ||
        getPrecedence(Op) < MinPrec)
      return LHS;
    unsigned Prec = getPrecedence(Op);
    consume();
    Expr *RHS = parseUnary();
    BinaryOp Next;
    while (!InError && getBinaryOp(Tok.Kind, Next) &&
           getPrecedence(Next) > Prec)
      RHS = parseBinaryRHS(Prec + 1, RHS);
    llvm::SMRange R(LHS->getLoc(), PrevEnd);
    LHS = withHeight(make<BinaryExpr>(R, Op, LHS, RHS), {LHS, RHS});
  }
}

/// unary ::= ('-' | '!') unary | postfix
Expr *Parser::parseUnary() {
  if (diagnoseOperandHabit())
    return makeError(Tok.Loc);
  if (Tok.isNot(tok::minus) && Tok.isNot(tok::exclaim))
    return parsePostfix(parsePrimary());
  llvm::SMLoc Start = Tok.Loc;
  bool IsNeg = Tok.is(tok::minus);
  consume();
  NestingScope Scope(*this);
  if (Scope.tooDeep()) {
    reportTooDeep(Start);
    skipToLineEnd();
    return make<ErrorExpr>(rangeFrom(Start));
  }
  // Fold `-literal`, unless a postfix operator binds to the literal first.
  if (IsNeg && (Tok.is(tok::int_literal) || Tok.is(tok::float_literal))) {
    Token Lit = Tok;
    consume();
    if (Tok.isNot(tok::period) && Tok.isNot(tok::l_paren)) {
      if (Lit.is(tok::float_literal))
        return make<FloatLiteralExpr>(rangeFrom(Start), -Lit.FloatValue);
      uint32_t Bits = uint32_t(Lit.IntValue);
      return make<IntLiteralExpr>(rangeFrom(Start), int32_t(0u - Bits));
    }
    // `-5.abs()` and the like: the literal alone, then the postfix part.
    Expr *Operand;
    if (Lit.is(tok::float_literal)) {
      Operand = make<FloatLiteralExpr>(Lit.getRange(), Lit.FloatValue);
    } else if (!Lit.IsHex && Lit.IntValue > uint64_t(INT32_MAX)) {
      diag(Lit.Loc, diag::err_int_literal_too_large) << Lit.Text;
      Operand = make<ErrorExpr>(Lit.getRange());
    } else {
      Operand = make<IntLiteralExpr>(Lit.getRange(), int32_t(Lit.IntValue));
    }
    Operand = parsePostfix(Operand);
    return withHeight(
        make<UnaryExpr>(rangeFrom(Start), UnaryOp::Neg, Operand), {Operand});
  }
  Expr *Operand = parseUnary();
  return withHeight(make<UnaryExpr>(rangeFrom(Start),
                                    IsNeg ? UnaryOp::Neg : UnaryOp::Not,
                                    Operand),
                    {Operand});
}

/// postfix ::= primary ('.' identifier | '(' (expr (',' expr)*)? ')'
///                     | '[' expr ']')*
Expr *Parser::parsePostfix(Expr *E) {
  while (!InError) {
    if (consumeIf(tok::l_square)) {
      Expr *Index = parseExpr();
      expect(tok::r_square, "']'");
      E = withHeight(make<IndexExpr>(llvm::SMRange(E->getLoc(), PrevEnd), E,
                                     Index),
                     {E, Index});
      continue;
    }
    if (consumeIf(tok::period)) {
      if (Tok.isNot(tok::identifier)) {
        diag(Tok.Loc, diag::err_expected_after) << "a member name" << "'.'";
        return make<ErrorExpr>(llvm::SMRange(E->getLoc(), PrevEnd));
      }
      Ident Member{Tok.Text, Tok.Loc};
      consume();
      E = withHeight(
          make<MemberExpr>(llvm::SMRange(E->getLoc(), PrevEnd), E, Member),
          {E});
      continue;
    }
    if (Tok.isNot(tok::l_paren))
      return E;
    consume();
    std::vector<Expr *> Args;
    unsigned Height = heightOf(E);
    if (Tok.isNot(tok::r_paren)) {
      while (true) {
        Args.push_back(parseExpr());
        Height = std::max(Height, heightOf(Args.back()));
        if (InError || !consumeIf(tok::comma))
          break;
      }
    }
    expect(tok::r_paren, "')'");
    E = withHeight(make<CallExpr>(llvm::SMRange(E->getLoc(), PrevEnd), E,
                                  std::move(Args)),
                   Height + 1);
  }
  return E;
}

/// primary ::= int-literal | float-literal | string-literal | 'true'
///           | 'false' | qualified-name | conversion | task-state
///           | '(' expr ')'
Expr *Parser::parsePrimary() {
  llvm::SMLoc Start = Tok.Loc;
  if (Tok.is(tok::int_literal)) {
    Token Lit = Tok;
    consume();
    if (!Lit.IsHex && Lit.IntValue > uint64_t(INT32_MAX)) {
      // Only `-2147483648` may go above INT_MAX (folded in parseUnary).
      diag(Start, diag::err_int_literal_too_large) << Lit.Text;
      return make<ErrorExpr>(Lit.getRange());
    }
    return make<IntLiteralExpr>(Lit.getRange(),
                                int32_t(uint32_t(Lit.IntValue)));
  }
  if (Tok.is(tok::float_literal)) {
    auto *E = make<FloatLiteralExpr>(Tok.getRange(), Tok.FloatValue);
    consume();
    return E;
  }
  if (Tok.is(tok::string_literal)) {
    auto *E = make<StringLiteralExpr>(Tok.getRange(), Tok.StringValue);
    consume();
    return E;
  }
  if (Tok.is(tok::kw_true) || Tok.is(tok::kw_false)) {
    auto *E = make<BoolLiteralExpr>(Tok.getRange(), Tok.is(tok::kw_true));
    consume();
    return E;
  }
  if (Tok.is(tok::identifier)) {
    QualifiedName Name;
    if (!parseQualifiedName(Name))
      return makeError(Start);
    return parseNameOrConversion(std::move(Name));
  }
  if (Tok.is(tok::kw_taskState))
    return parseTaskState();
  if (Tok.is(tok::l_paren))
    return parseParenExpr();
  diag(Start, diag::err_expected_expression);
  return makeError(Start);
}

/// conversion ::= ('int' | 'float' | 'bool') '(' expr ')'
/// A name followed by anything else is a NameExpr.
Expr *Parser::parseNameOrConversion(QualifiedName Name) {
  llvm::SMRange R = Name.getRange();
  if (InError)
    return make<ErrorExpr>(R);
  bool IsConversion = !Name.isQualified() && Tok.is(tok::l_paren) &&
                      (Name.Parts[0].Name == "int" ||
                       Name.Parts[0].Name == "float" ||
                       Name.Parts[0].Name == "bool");
  if (!IsConversion)
    return make<NameExpr>(R, std::move(Name));
  Expr *Operand = parseParenExpr();
  return withHeight(make<ConversionExpr>(llvm::SMRange(R.Start, PrevEnd),
                                         std::move(Name), Operand, false),
                    {Operand});
}

/// paren-expr ::= '(' expr ')'
Expr *Parser::parseParenExpr() {
  consume();
  Expr *E = parseExpr();
  expect(tok::r_paren, "')'");
  return E;
}

/// task-state ::= 'taskState' '(' qualified-name ')'
Expr *Parser::parseTaskState() {
  llvm::SMLoc Start = Tok.Loc;
  consume();
  if (Tok.isNot(tok::l_paren)) {
    diag(Tok.Loc, diag::err_expected_after) << "'('" << "'taskState'";
    return makeError(Start);
  }
  consume();
  llvm::SMLoc OperandLoc = Tok.Loc;
  QualifiedName Name;
  if (Tok.isNot(tok::identifier) || !parseQualifiedName(Name) ||
      Tok.isNot(tok::r_paren)) {
    diag(OperandLoc, diag::err_task_state_operand);
    skipToLineEnd();
    return make<ErrorExpr>(rangeFrom(Start));
  }
  consume();
  return make<TaskStateExpr>(rangeFrom(Start), std::move(Name));
}
