//===- ParseStmt.cpp - statements ------------------------------------------===//
//
// One statement per line. A statement that starts with a name is decided
// after its qualified name: another identifier makes it a declaration
// (`Math::Vector2f v = ...`), anything else continues it as an expression,
// which an assignment operator may then turn into an assignment. Sema, not
// the parser, checks that a target is assignable and that an expression
// statement is a call.
//
//===----------------------------------------------------------------------===//
#include "ParserImpl.h"

using namespace bsc;

static bool getAssignOp(tok::Kind K, AssignOp &Op) {
  // Matched by spelling, so OperatorKinds.def and TokenKinds.def stay the
  // only lists of operators.
  llvm::StringRef Spelling = tok::getSpelling(K);
  if (Spelling.empty())
    return false;
#define ASSIGN_OP(Name, S, Bin)                                                \
  if (Spelling == S) {                                                         \
    Op = AssignOp::Name;                                                       \
    return true;                                                               \
  }
#include "bsc/AST/OperatorKinds.def"
  return false;
}

/// Whether a token can begin an expression (and so a simple statement).
static bool startsExpression(tok::Kind K) {
  return K == tok::identifier || K == tok::int_literal ||
         K == tok::float_literal || K == tok::string_literal ||
         K == tok::kw_true || K == tok::kw_false || K == tok::kw_taskState ||
         K == tok::l_paren || K == tok::minus || K == tok::exclaim ||
         K == tok::error;
}

/// statement ::= if-stmt | for-stmt | 'break' NEWLINE | 'continue' NEWLINE
///             | ('return' | 'yield') expr? NEWLINE
///             | ('assert' | 'assume') '(' expr (',' string-literal)? ')'
///               NEWLINE
///             | func-decl (top level of a task body only)
///             | simple-stmt NEWLINE
Stmt *Parser::parseStatement() {
  InError = false;
  Heights.clear();
  llvm::SMLoc Start = Tok.Loc;
  if (Tok.is(tok::kw_if))
    return parseIf();
  if (Tok.is(tok::kw_for))
    return parseFor();
  if (Tok.is(tok::kw_break)) {
    consume();
    return finishLine(make<BreakStmt>(rangeFrom(Start)), Start);
  }
  if (Tok.is(tok::kw_continue)) {
    consume();
    return finishLine(make<ContinueStmt>(rangeFrom(Start)), Start);
  }
  if (Tok.is(tok::kw_return)) {
    consume();
    Expr *Value = parseOptionalValue();
    return finishLine(make<ReturnStmt>(rangeFrom(Start), Value), Start);
  }
  if (Tok.is(tok::kw_yield)) {
    consume();
    Expr *Value = parseOptionalValue();
    return finishLine(make<YieldStmt>(rangeFrom(Start), Value), Start);
  }
  if (Tok.is(tok::kw_assert) || Tok.is(tok::kw_assume))
    return parseAssert();
  if (Tok.is(tok::kw_func))
    return parseNestedFunc();
  if (Tok.is(tok::kw_task)) {
    diag(Start, diag::err_nested_task);
    return recoverStatement(nullptr, Start);
  }
  if (Tok.is(tok::kw_else)) {
    diag(Start, diag::err_else_without_if);
    return recoverStatement(nullptr, Start);
  }
  if (Tok.is(tok::kw_requires)) {
    diag(Start, diag::err_requires_after_decl);
    return recoverStatement(nullptr, Start);
  }
  if (Tok.is(tok::kw_const)) {
    diag(Start, diag::err_const_in_body);
    return recoverStatement(nullptr, Start);
  }
  if (Tok.is(tok::kw_enum)) {
    diag(Start, diag::err_enum_in_body);
    return recoverStatement(nullptr, Start);
  }
  if (diagnoseStatementHabit())
    return recoverStatement(nullptr, Start);
  if (!startsExpression(Tok.Kind)) {
    diag(Start, diag::err_expected_statement);
    return recoverStatement(nullptr, Start);
  }
  return finishLine(parseSimpleStatement(), Start);
}

/// assert-stmt ::= ('assert' | 'assume') '(' expr (',' string-literal)? ')'
///                 NEWLINE
Stmt *Parser::parseAssert() {
  llvm::SMLoc Start = Tok.Loc;
  bool IsAssume = Tok.is(tok::kw_assume);
  consume();
  if (Tok.isNot(tok::l_paren)) {
    diag(Tok.Loc, diag::err_expected_after)
        << "'('" << (IsAssume ? "'assume'" : "'assert'");
    return recoverStatement(nullptr, Start);
  }
  consume();
  Expr *Cond = parseExpr();
  StringLiteralExpr *Message = nullptr;
  if (!InError && consumeIf(tok::comma)) {
    // A literal, so that the message costs nothing where it is not shown.
    llvm::SMLoc MessageLoc = Tok.Loc;
    if (Tok.is(tok::string_literal)) {
      Message = make<StringLiteralExpr>(Tok.getRange(), Tok.StringValue);
      consume();
    }
    if (!Message || Tok.isNot(tok::r_paren)) // `"a" + b` is not one either.
      diag(MessageLoc, diag::err_assert_message_not_literal);
  }
  if (!InError)
    expect(tok::r_paren, "')'");
  return finishLine(
      make<AssertStmt>(rangeFrom(Start), Cond, Message, IsAssume), Start);
}

/// The value of `return` / `yield`, if the line has one.
Expr *Parser::parseOptionalValue() {
  // `;` too: `return;` is a habit finishLine reports.
  if (Tok.is(tok::newline) || Tok.is(tok::r_paren) || Tok.is(tok::eof) ||
      Tok.is(tok::semi))
    return nullptr;
  return parseExpr();
}

/// Ends a one-line statement at its NEWLINE.
Stmt *Parser::finishLine(Stmt *S, llvm::SMLoc Start) {
  // `x = 1;`: the statement itself is whole, so it stays (no follow-on
  // errors from a missing declaration or return).
  if (!InError && diagnoseEndOfLineHabit()) {
    skipLineAndBlock();
    return S;
  }
  if (!InError && Tok.isNot(tok::newline))
    diag(Tok.Loc, diag::err_expected) << "end of line";
  if (!InError) {
    consume();
    return S;
  }
  return recoverStatement(S, Start);
}

/// Skips the rest of a bad statement and any block under it. A declaration
/// survives (with an ErrorExpr initializer, say), so that its later uses do
/// not report a second error; anything else becomes an ErrorStmt.
Stmt *Parser::recoverStatement(Stmt *Partial, llvm::SMLoc Start) {
  skipLineAndBlock();
  if (Partial && llvm::isa<DeclStmt>(Partial))
    return Partial;
  return make<ErrorStmt>(rangeFrom(Start));
}

/// simple-stmt ::= qualified-name identifier ('=' expr)?
///               | expr (assign-op expr)?
Stmt *Parser::parseSimpleStatement() {
  llvm::SMLoc Start = Tok.Loc;
  Expr *E;
  if (Tok.is(tok::identifier)) {
    QualifiedName Name;
    if (!parseQualifiedName(Name))
      return make<ErrorStmt>(rangeFrom(Start));
    if (Tok.is(tok::identifier))
      return parseDeclRest(std::move(Name));
    E = parseExprAfterName(std::move(Name));
  } else {
    E = parseExpr();
  }
  AssignOp Op;
  if (!InError && getAssignOp(Tok.Kind, Op)) {
    consume();
    Expr *Value = parseExpr();
    return make<AssignStmt>(rangeFrom(Start), Op, E, Value);
  }
  return make<ExprStmt>(rangeFrom(Start), E);
}

/// The rest of `Type name [= expr]` once the type was parsed.
Stmt *Parser::parseDeclRest(QualifiedName TypeName) {
  llvm::SMLoc Start = TypeName.getLoc();
  Ident Name{Tok.Text, Tok.Loc};
  consume();
  Expr *Init = nullptr;
  if (consumeIf(tok::equal))
    Init = parseExpr();
  auto *Var = make<VarDecl>(rangeFrom(Start), Name, std::move(TypeName), Init);
  return make<DeclStmt>(rangeFrom(Start), Var);
}

/// if-stmt ::= 'if' '(' expr ')' block ('else' (if-stmt | block))?
Stmt *Parser::parseIf() {
  llvm::SMLoc Start = Tok.Loc;
  consume();
  Expr *Cond;
  if (Tok.isNot(tok::l_paren)) {
    diag(Tok.Loc, diag::err_expected_after) << "'('" << "'if'";
    Cond = makeError(Tok.Loc);
  } else {
    Cond = parseParenExpr();
  }
  BlockStmt *Then = parseBlock("'if'");
  Stmt *Else = nullptr;
  llvm::SMLoc ElseLoc;
  if (Tok.is(tok::kw_else)) {
    InError = false;
    Heights.clear();
    ElseLoc = Tok.Loc;
    consume();
    // An `else if` chain nests in the tree, so it counts as nesting too.
    NestingScope Scope(*this);
    if (Scope.tooDeep()) {
      reportTooDeep(Tok.Loc);
      recoverStatement(nullptr, Tok.Loc);
    } else if (Tok.is(tok::kw_if))
      Else = parseIf();
    else
      Else = parseBlock("'else'");
  }
  auto *If = make<IfStmt>(rangeFrom(Start), Cond, Then, Else);
  If->ElseLoc = ElseLoc;
  return If;
}

/// for-stmt  ::= 'for' '(' for-init? ';' expr? ';' for-step? ')' block
/// for-init  ::= simple-stmt
/// for-step  ::= 'yield' expr? | simple-stmt (not a declaration)
Stmt *Parser::parseFor() {
  llvm::SMLoc Start = Tok.Loc;
  consume();
  Stmt *Init = nullptr, *Step = nullptr;
  Expr *Cond = nullptr;
  if (Tok.isNot(tok::l_paren)) {
    diag(Tok.Loc, diag::err_expected_after) << "'('" << "'for'";
  } else {
    consume();
    if (Tok.isNot(tok::semi))
      Init = parseSimpleStatement();
    expect(tok::semi, "';'");
    if (!InError && Tok.isNot(tok::semi))
      Cond = parseExpr();
    expect(tok::semi, "';'");
    if (!InError && Tok.isNot(tok::r_paren))
      Step = parseForStep();
    expect(tok::r_paren, "')'");
    if (InError) {
      Init = Init && llvm::isa<DeclStmt>(Init) ? Init : nullptr;
      Step = nullptr;
      if (Cond && llvm::isa<ErrorExpr>(Cond))
        Cond = nullptr;
    }
  }
  BlockStmt *Body = parseBlock("'for'");
  return make<ForStmt>(rangeFrom(Start), Init, Cond, Step, Body);
}

Stmt *Parser::parseForStep() {
  llvm::SMLoc Start = Tok.Loc;
  if (Tok.is(tok::kw_yield)) {
    consume();
    Expr *Value = parseOptionalValue();
    return make<YieldStmt>(rangeFrom(Start), Value);
  }
  if (Tok.is(tok::kw_break) || Tok.is(tok::kw_continue) ||
      Tok.is(tok::kw_return) || Tok.is(tok::kw_if) || Tok.is(tok::kw_for) ||
      Tok.is(tok::kw_else) || Tok.is(tok::kw_func) || Tok.is(tok::kw_task) ||
      Tok.is(tok::kw_requires) || Tok.is(tok::kw_const)) {
    diag(Start, diag::err_invalid_for_step);
    return nullptr;
  }
  Stmt *S = parseSimpleStatement();
  if (llvm::isa<DeclStmt>(S)) {
    diag(Start, diag::err_invalid_for_step);
    return nullptr;
  }
  return S;
}

/// A `func` in a body: allowed only at the top level of a task body, where
/// it becomes a FuncDeclStmt and one of the task's NestedFuncs.
Stmt *Parser::parseNestedFunc() {
  llvm::SMLoc Start = Tok.Loc;
  auto *Task = llvm::dyn_cast_or_null<TaskDecl>(CurCallable);
  if (!Task) {
    diag(Start, diag::err_func_in_func);
    return recoverStatement(nullptr, Start);
  }
  if (!AtTaskTopLevel) {
    diag(Start, diag::err_nested_func_placement);
    return recoverStatement(nullptr, Start);
  }
  CallableDecl *D = parseCallable(Task);
  if (!D)
    return make<ErrorStmt>(rangeFrom(Start));
  auto *F = llvm::cast<FuncDecl>(D);
  Task->NestedFuncs.push_back(F);
  return make<FuncDeclStmt>(rangeFrom(Start), F);
}
