//===- Parser.cpp - modules, declarations and blocks ----------------------===//
//
// The module and declaration level of the parser, the block structure that
// the lexer's indent/dedent tokens describe, and the recovery helpers every
// construct shares. Statements are in ParseStmt.cpp, expressions in
// ParseExpr.cpp; ParserImpl.h explains the recovery and nesting strategy.
//
//===----------------------------------------------------------------------===//
#include "ParserImpl.h"

using namespace bsc;

Parser::Parser(const llvm::SourceMgr &SM, unsigned BufferID, ASTContext &Ctx,
               DiagnosticEngine &Diags)
    : Lex(SM, BufferID, Diags), Ctx(Ctx), Diags(Diags), BufferID(BufferID),
      Source(SM.getMemoryBuffer(BufferID)->getBuffer()) {
  Tok = Lex.lex();
  PrevEnd = Tok.Loc;
}

void Parser::consume() {
  if (Tok.is(tok::eof))
    return;
  PrevEnd = Tok.getEndLoc();
  if (Peeked) {
    Tok = *Peeked;
    Peeked.reset();
    return;
  }
  Tok = Lex.lex();
}

const Token &Parser::peek() {
  if (!Peeked)
    Peeked = Lex.lex();
  return *Peeked;
}

bool Parser::consumeIf(tok::Kind K) {
  if (Tok.isNot(K))
    return false;
  consume();
  return true;
}

bool Parser::expect(tok::Kind K, llvm::StringRef What) {
  if (consumeIf(K))
    return true;
  diag(Tok.Loc, diag::err_expected) << What;
  return false;
}

DiagnosticBuilder Parser::diag(llvm::SMLoc Loc, diag::Kind K) {
  bool Quiet = InError || Tok.is(tok::error);
  InError = true;
  return DiagnosticBuilder(Quiet ? nullptr : &Diags, K, Loc);
}

void Parser::reportTooDeep(llvm::SMLoc Loc) {
  // Once per declaration: the constructs around the first one that is too
  // deep are just as deep.
  if (ReportedTooDeep) {
    InError = true;
    return;
  }
  ReportedTooDeep = true;
  diag(Loc, diag::err_nesting_too_deep) << MaxNestingDepth;
}

void Parser::skipToLineEnd() {
  while (Tok.isNot(tok::newline) && Tok.isNot(tok::eof))
    consume();
}

void Parser::skipBlock() {
  unsigned Level = 0;
  do {
    if (Tok.is(tok::indent))
      ++Level;
    else if (Tok.is(tok::dedent))
      --Level;
    consume();
  } while (Level != 0 && Tok.isNot(tok::eof));
}

void Parser::skipLineAndBlock() {
  skipToLineEnd();
  consumeIf(tok::newline);
  if (Tok.is(tok::indent))
    skipBlock();
}

/// qualified-name ::= identifier ('::' identifier)*
bool Parser::parseQualifiedName(QualifiedName &QN) {
  if (Tok.isNot(tok::identifier)) {
    diag(Tok.Loc, diag::err_expected_type);
    return false;
  }
  QN.Parts.push_back({Tok.Text, Tok.Loc});
  consume();
  while (consumeIf(tok::coloncolon)) {
    if (Tok.isNot(tok::identifier)) {
      diag(Tok.Loc, diag::err_expected_after) << "a name" << "'::'";
      return false;
    }
    QN.Parts.push_back({Tok.Text, Tok.Loc});
    consume();
  }
  return true;
}

/// module ::= requires* (func-decl | task-decl)*
ModuleAST *Parser::parseModule(llvm::StringRef Name) {
  Module = Ctx.createModule();
  Module->Name = Name.str();
  Module->BufferID = BufferID;
  Module->Source = Source;
  bool SeenDecl = false;
  while (Tok.isNot(tok::eof) && !Diags.tooManyErrors()) {
    InError = false;
    ReportedTooDeep = false;
    Heights.clear();
    const char *Before = Tok.Loc.getPointer();
    tok::Kind BeforeKind = Tok.Kind;
    if (Tok.is(tok::kw_requires)) {
      parseRequires(SeenDecl);
    } else if (Tok.is(tok::kw_func) || Tok.is(tok::kw_task)) {
      SeenDecl = true;
      if (CallableDecl *D = parseCallable(nullptr))
        Module->Decls.push_back(D);
    } else if (Tok.is(tok::kw_const)) {
      SeenDecl = true;
      if (ConstDecl *D = parseConst())
        Module->Consts.push_back(D);
    } else if (Tok.is(tok::kw_enum)) {
      SeenDecl = true;
      if (EnumDecl *D = parseEnum())
        Module->Enums.push_back(D);
    } else if (Tok.is(tok::indent)) {
      diag(Tok.Loc, diag::err_unexpected_indent);
      skipBlock();
    } else {
      diag(Tok.Loc, diag::err_expected_declaration);
      skipLineAndBlock();
    }
    // Never loop without progress, whatever the token stream looks like.
    if (Tok.Loc.getPointer() == Before && Tok.Kind == BeforeKind)
      consume();
  }
  return Module;
}

/// const-decl ::= 'const' qualified-name identifier '=' expr NEWLINE
ConstDecl *Parser::parseConst() {
  llvm::SMLoc Start = Tok.Loc;
  consume();
  QualifiedName TypeName;
  if (Tok.isNot(tok::identifier)) {
    diag(Tok.Loc, diag::err_expected_after) << "a type" << "'const'";
    skipLineAndBlock();
    return nullptr;
  }
  if (!parseQualifiedName(TypeName) || Tok.isNot(tok::identifier)) {
    if (!InError)
      diag(Tok.Loc, diag::err_expected_after) << "a name" << "the type";
    skipLineAndBlock();
    return nullptr;
  }
  Ident Name{Tok.Text, Tok.Loc};
  consume();
  if (Tok.isNot(tok::equal)) {
    diag(Tok.Loc, diag::err_const_without_value) << Name.Name;
    skipLineAndBlock();
    return nullptr;
  }
  consume();
  Expr *Init = parseExpr();
  if (!InError && Tok.isNot(tok::newline))
    diag(Tok.Loc, diag::err_expected) << "end of line";
  skipLineAndBlock();
  auto *D = make<ConstDecl>(rangeFrom(Start), Name, std::move(TypeName), Init);
  D->Module = Module;
  return D;
}

/// enum-decl  ::= 'enum' identifier (':' 'TaskState')? NEWLINE
///                INDENT enumerator+ DEDENT
/// enumerator ::= identifier ('=' '-'? int-literal)? NEWLINE
EnumDecl *Parser::parseEnum() {
  llvm::SMLoc Start = Tok.Loc;
  consume();
  if (Tok.isNot(tok::identifier)) {
    diag(Tok.Loc, diag::err_expected_after) << "a name" << "'enum'";
    skipLineAndBlock();
    return nullptr;
  }
  Ident Name{Tok.Text, Tok.Loc};
  consume();
  bool IsTaskState = false;
  if (consumeIf(tok::colon)) {
    if (Tok.isNot(tok::identifier) || Tok.Text != "TaskState") {
      diag(Tok.Loc, diag::err_enum_base_not_task_state) << Name.Name;
      skipLineAndBlock();
      return nullptr;
    }
    IsTaskState = true;
    consume();
  }
  auto *D = make<EnumDecl>(rangeFrom(Start), Name, IsTaskState);
  D->Module = Module;
  llvm::SMLoc LineEnd;
  if (!startBlock("'enum'", LineEnd))
    return D;
  consume();
  while (Tok.isNot(tok::dedent) && Tok.isNot(tok::eof)) {
    const char *Before = Tok.Loc.getPointer();
    parseEnumerator(*D);
    if (Tok.Loc.getPointer() == Before)
      consume();
  }
  consumeIf(tok::dedent);
  return D;
}

void Parser::parseEnumerator(EnumDecl &D) {
  InError = false; // Each line is a declaration of its own.
  if (Tok.isNot(tok::identifier)) {
    diag(Tok.Loc, diag::err_expected_enumerator) << D.getName().Name;
    skipLineAndBlock();
    return;
  }
  Enumerator E{{Tok.Text, Tok.Loc}, std::nullopt, {}};
  consume();
  if (Tok.is(tok::equal)) {
    llvm::SMLoc ValueStart = Tok.Loc;
    consume();
    bool Negative = consumeIf(tok::minus);
    if (Tok.isNot(tok::int_literal)) {
      diag(Tok.Loc, diag::err_expected_after) << "an integer" << "'='";
      skipLineAndBlock();
      return;
    }
    E.Explicit = Negative ? -int64_t(Tok.IntValue) : int64_t(Tok.IntValue);
    consume();
    E.ValueRange = rangeFrom(ValueStart);
  }
  if (Tok.isNot(tok::newline)) {
    diag(Tok.Loc, diag::err_expected) << "end of line";
    skipLineAndBlock();
  } else {
    consume();
  }
  D.Enumerators.push_back(E);
}

/// requires ::= 'requires' string-literal NEWLINE
void Parser::parseRequires(bool AfterDecl) {
  llvm::SMLoc KwLoc = Tok.Loc;
  consume();
  if (Tok.isNot(tok::string_literal)) {
    diag(Tok.Loc, diag::err_expected_after)
        << "a module name in quotes" << "'requires'";
    skipLineAndBlock();
    return;
  }
  if (AfterDecl)
    diag(KwLoc, diag::err_requires_after_decl);
  // Recorded even when misplaced, so that uses of the module do not cascade.
  Module->Requires.push_back(RequireDecl{Tok.StringValue, Tok.getRange()});
  consume();
  if (Tok.isNot(tok::newline))
    diag(Tok.Loc, diag::err_expected) << "end of line";
  skipLineAndBlock();
}

/// func-decl ::= 'func' identifier params (':' qualified-name)? block
/// task-decl ::= 'task' identifier params block
CallableDecl *Parser::parseCallable(TaskDecl *Enclosing) {
  bool IsTask = Tok.is(tok::kw_task);
  llvm::StringRef Keyword = IsTask ? "'task'" : "'func'";
  llvm::SMLoc Start = Tok.Loc;
  consume();
  if (Tok.isNot(tok::identifier)) {
    diag(Tok.Loc, diag::err_expected_after) << "a name" << Keyword;
    skipLineAndBlock();
    return nullptr;
  }
  Ident Name{Tok.Text, Tok.Loc};
  consume();

  CallableDecl *D;
  if (IsTask) {
    D = make<TaskDecl>(rangeFrom(Start), Name);
  } else {
    auto *F = make<FuncDecl>(rangeFrom(Start), Name);
    F->EnclosingTask = Enclosing;
    D = F;
  }
  D->Module = Module;
  parseParams(D);
  if (!InError && Tok.is(tok::colon)) {
    if (IsTask) {
      diag(Tok.Loc, diag::err_task_result_type);
    } else {
      consume();
      parseQualifiedName(llvm::cast<FuncDecl>(D)->ResultTypeName);
    }
  }

  CallableDecl *SavedCallable = CurCallable;
  bool SavedTop = AtTaskTopLevel;
  CurCallable = D;
  D->Body = parseBlock(Keyword, IsTask);
  CurCallable = SavedCallable;
  AtTaskTopLevel = SavedTop;
  D->setRange(rangeFrom(Start));
  return D;
}

/// params ::= '(' (param (',' param)*)? ')'
/// param  ::= qualified-name identifier ('=' expr)?
void Parser::parseParams(CallableDecl *D) {
  if (Tok.isNot(tok::l_paren)) {
    diag(Tok.Loc, diag::err_expected_after)
        << "'('" << ("'" + D->getName().Name + "'").str();
    return;
  }
  consume();
  if (consumeIf(tok::r_paren))
    return;
  while (true) {
    llvm::SMLoc Start = Tok.Loc;
    QualifiedName TypeName;
    if (!parseQualifiedName(TypeName))
      return;
    if (Tok.isNot(tok::identifier)) {
      diag(Tok.Loc, diag::err_expected) << "a parameter name";
      return;
    }
    Ident Name{Tok.Text, Tok.Loc};
    consume();
    auto *P = make<ParamDecl>(rangeFrom(Start), Name, std::move(TypeName));
    P->Owner = D;
    P->Index = D->Params.size();
    D->Params.push_back(P);
    if (consumeIf(tok::equal)) {
      P->Default = parseExpr();
      P->setRange(rangeFrom(Start));
    }
    if (consumeIf(tok::comma))
      continue;
    expect(tok::r_paren, "')'");
    return;
  }
}

/// block ::= NEWLINE INDENT statement+ DEDENT
///
/// `After` names the construct for err_expected_block. A head that already
/// had an error is skipped to its end, and a block under it is still parsed
/// so that the errors inside it are found too.
BlockStmt *Parser::parseBlock(llvm::StringRef After, bool IsTaskBody) {
  llvm::SMLoc LineEnd;
  if (!startBlock(After, LineEnd))
    return make<BlockStmt>(llvm::SMRange(LineEnd, LineEnd));
  InError = false;
  return parseBlockBody(IsTaskBody);
}

bool Parser::startBlock(llvm::StringRef After, llvm::SMLoc &LineEnd) {
  if (Tok.isNot(tok::newline))
    diag(Tok.Loc, diag::err_expected_block) << After;
  skipToLineEnd();
  LineEnd = Tok.Loc;
  consumeIf(tok::newline);
  if (Tok.is(tok::indent))
    return true;
  diag(LineEnd, diag::err_expected_block) << After;
  return false;
}

/// The statements from INDENT to its DEDENT.
BlockStmt *Parser::parseBlockBody(bool IsTaskBody) {
  llvm::SMLoc Start = Tok.Loc;
  auto *Block = make<BlockStmt>(llvm::SMRange(Start, Start));
  NestingScope Scope(*this);
  if (Scope.tooDeep()) {
    reportTooDeep(Start);
    skipBlock();
    return Block;
  }
  consume();

  bool SavedTop = AtTaskTopLevel;
  AtTaskTopLevel = IsTaskBody;
  while (Tok.isNot(tok::dedent) && Tok.isNot(tok::eof) &&
         !Diags.tooManyErrors()) {
    const char *Before = Tok.Loc.getPointer();
    tok::Kind BeforeKind = Tok.Kind;
    if (Tok.is(tok::indent)) {
      // An indented line under a statement that opens no block: parse it as
      // if it belonged there (to find its errors) and drop it.
      InError = false;
      diag(Tok.Loc, diag::err_unexpected_indent);
      parseBlockBody(false);
      continue;
    }
    Block->Stmts.push_back(parseStatement());
    if (Tok.Loc.getPointer() == Before && Tok.Kind == BeforeKind)
      consume();
  }
  AtTaskTopLevel = SavedTop;
  consumeIf(tok::dedent);
  Block->setRange(llvm::SMRange(Start, PrevEnd));
  return Block;
}

/// repl-line ::= statement* EOF
BlockStmt *Parser::parseReplLine() {
  llvm::SMLoc Start = Tok.Loc;
  BlockStmt *Block = make<BlockStmt>(rangeFrom(Start));
  while (Tok.isNot(tok::eof) && !Diags.tooManyErrors()) {
    const char *Before = Tok.Loc.getPointer();
    tok::Kind BeforeKind = Tok.Kind;
    if (Tok.is(tok::indent)) {
      diag(Tok.Loc, diag::err_unexpected_indent);
      skipBlock();
    } else if (Stmt *S = parseStatement()) {
      Block->Stmts.push_back(S);
    }
    if (Tok.Loc.getPointer() == Before && Tok.Kind == BeforeKind)
      consume();
  }
  Block->setRange(rangeFrom(Start));
  return Block;
}

BlockStmt *bsc::parseReplLine(const llvm::SourceMgr &SM, unsigned BufferID,
                              ASTContext &Ctx, DiagnosticEngine &Diags) {
  Parser P(SM, BufferID, Ctx, Diags);
  return P.parseReplLine();
}

ModuleAST *bsc::parseModule(const llvm::SourceMgr &SM, unsigned BufferID,
                            llvm::StringRef ModuleName, ASTContext &Ctx,
                            DiagnosticEngine &Diags) {
  Parser P(SM, BufferID, Ctx, Diags);
  return P.parseModule(ModuleName);
}
