//===- ParserImpl.h - the recursive-descent parser of b-script -*- C++ -*-===//
//
// One Parser object parses one buffer; its methods are split by construct
// over Parser.cpp (module, declarations, blocks, recovery), ParseStmt.cpp
// and ParseExpr.cpp. It reads tokens one at a time from the Lexer with no
// lookahead: a statement that starts with a name parses the qualified name
// first and then decides between a declaration (`Math::Vector2f v`) and an
// expression.
//
// Error recovery is panic mode per statement: the first error of a statement
// is reported, later ones in the same statement are swallowed (InError), the
// rest of the line and any block indented under it are skipped, and an
// ErrorStmt/ErrorExpr takes the construct's place. Errors at `error` tokens
// were already reported by the lexer and are never repeated.
//
// Nesting (blocks, parenthesised and unary expressions, calls) is counted in
// Depth, and the height of every expression tree is tracked, so that neither
// this parser nor any later phase that recurses over the tree can exhaust
// the stack: beyond MaxNestingDepth the construct is reported once and
// skipped without recursing further.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_PARSE_PARSERIMPL_H
#define BSC_LIB_PARSE_PARSERIMPL_H

#include "bsc/Parse/Lexer.h"
#include "bsc/Parse/Parser.h"
#include "llvm/ADT/DenseMap.h"
#include <optional>

namespace bsc {

class Parser {
public:
  Parser(const llvm::SourceMgr &SM, unsigned BufferID, ASTContext &Ctx,
         DiagnosticEngine &Diags);

  ModuleAST *parseModule(llvm::StringRef Name);
  BlockStmt *parseReplLine();

private:
  //--- Parser.cpp: tokens, diagnostics, recovery, declarations ------------
  void consume();
  bool consumeIf(tok::Kind K);
  /// The token after Tok (lexed once, then consumed as usual).
  const Token &peek();
  /// Consumes a token of kind K or reports `expected What`.
  bool expect(tok::Kind K, llvm::StringRef What);
  /// Reports unless this statement already has an error or the current
  /// token is a lexer error; either way the statement is now in error.
  DiagnosticBuilder diag(llvm::SMLoc Loc, diag::Kind K);
  void reportTooDeep(llvm::SMLoc Loc);
  llvm::SMRange rangeFrom(llvm::SMLoc Start) const { return {Start, PrevEnd}; }

  void skipToLineEnd();
  void skipBlock();
  void skipLineAndBlock();

  void parseRequires(bool AfterDecl);
  ConstDecl *parseConst();
  EnumDecl *parseEnum();
  void parseEnumerator(EnumDecl &D);
  CallableDecl *parseCallable(TaskDecl *Enclosing);
  void parseParams(CallableDecl *D);
  bool parseQualifiedName(QualifiedName &QN);
  BlockStmt *parseBlock(llvm::StringRef After, bool IsTaskBody = false);
  BlockStmt *parseBlockBody(bool IsTaskBody);
  /// The end of a block's head line: reports anything left on it (once)
  /// and consumes the newline. Returns whether an INDENT follows (not
  /// consumed); else reports err_expected_block at the line's end,
  /// `LineEnd`.
  bool startBlock(llvm::StringRef After, llvm::SMLoc &LineEnd);

  //--- ParseStmt.cpp -------------------------------------------------------
  Stmt *parseStatement();
  Stmt *parseSimpleStatement();
  Stmt *parseDeclRest(QualifiedName TypeName);
  Stmt *finishLine(Stmt *S, llvm::SMLoc Start);
  Stmt *recoverStatement(Stmt *Partial, llvm::SMLoc Start);
  Stmt *parseIf();
  Stmt *parseFor();
  Stmt *parseForStep();
  Stmt *parseNestedFunc();
  Stmt *parseAssert();
  Expr *parseOptionalValue();

  //--- ParseHabits.cpp: spellings of other languages ---------------------
  // Each reports the habit at the current token and returns true, or
  // returns false without consuming anything.
  /// At the start of a statement: `while`, `elif`, `++x`.
  bool diagnoseStatementHabit();
  /// After an operand: `and`, `or`, `x++`, `x--`.
  bool diagnoseOperatorHabit();
  /// Where an operand starts: `not`.
  bool diagnoseOperandHabit();
  /// Where a statement should end: a trailing `;`.
  bool diagnoseEndOfLineHabit();
  /// Reports `++`/`--` at Tok (`+=`/`-=` in b-script); returns true.
  bool reportIncrementHabit();

  //--- ParseExpr.cpp -------------------------------------------------------
  Expr *parseExpr();
  Expr *parseExprAfterName(QualifiedName Name);
  Expr *parseBinaryRHS(unsigned MinPrec, Expr *LHS);
  Expr *parseUnary();
  Expr *parsePostfix(Expr *E);
  Expr *parsePrimary();
  Expr *parseNameOrConversion(QualifiedName Name);
  Expr *parseTaskState();
  Expr *parseParenExpr();
  Expr *makeError(llvm::SMLoc Start);
  /// Records the height of a new composite node; too tall trees become an
  /// ErrorExpr (and the rest of the line is skipped).
  Expr *withHeight(Expr *E, std::initializer_list<const Expr *> Children);
  Expr *withHeight(Expr *E, unsigned Height);
  unsigned heightOf(const Expr *E) const;

  template <typename T, typename... Args> T *make(Args &&...A) {
    return Ctx.create<T>(std::forward<Args>(A)...);
  }

  /// Counts one level of nesting for the lifetime of a parse function.
  class NestingScope {
  public:
    explicit NestingScope(Parser &P) : P(P) { ++P.Depth; }
    ~NestingScope() { --P.Depth; }
    bool tooDeep() const { return P.Depth > MaxNestingDepth; }

  private:
    Parser &P;
  };

  Lexer Lex;
  Token Tok;
  std::optional<Token> Peeked;
  /// End of the last consumed token: the end of the node being finished.
  llvm::SMLoc PrevEnd;
  ASTContext &Ctx;
  DiagnosticEngine &Diags;
  unsigned BufferID;
  llvm::StringRef Source;
  ModuleAST *Module = nullptr;

  /// The func or task whose body is being parsed, and whether the current
  /// block is the top level of a task body (where a `func` may appear).
  CallableDecl *CurCallable = nullptr;
  bool AtTaskTopLevel = false;

  unsigned Depth = 0;
  bool InError = false;
  bool ReportedTooDeep = false;
  /// Heights of the composite expressions of the current statement.
  llvm::DenseMap<const Expr *, unsigned> Heights;
};

} // namespace bsc

#endif
