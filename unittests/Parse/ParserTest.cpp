//===- ParserTest.cpp - shapes of the trees the parser builds --------------===//
#include "bsc/Parse/Parser.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/raw_ostream.h"
#include "gtest/gtest.h"
#include <functional>

using namespace bsc;
using llvm::cast;
using llvm::isa;

namespace {
struct Parsed {
  llvm::SourceMgr SM;
  DiagnosticEngine Diags;
  ASTContext Ctx;
  ModuleAST *M;
  explicit Parsed(llvm::StringRef Src) {
    unsigned ID = SM.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(Src, "m.bs"), llvm::SMLoc());
    M = parseModule(SM, ID, "m", Ctx, Diags);
  }
  std::vector<diag::Kind> diags() const {
    std::vector<diag::Kind> R;
    for (const Diagnostic &D : Diags.getDiagnostics())
      R.push_back(D.Kind);
    return R;
  }
  /// The statements of the body of the first declaration.
  std::vector<Stmt *> &body() { return M->Decls.at(0)->Body->Stmts; }
  std::string dump() {
    std::string S;
    llvm::raw_string_ostream OS(S);
    dumpAST(*M, OS);
    return S;
  }
};
} // namespace

TEST(ParserTest, ModuleAndDeclarations) {
  Parsed P("requires \"io\"\ntask t(int a, Math::Vector2f v)\n    yield\n"
           "func f() : bool\n    return true\n");
  EXPECT_TRUE(P.diags().empty());
  ASSERT_EQ(P.M->Requires.size(), 1u);
  EXPECT_EQ(P.M->Requires[0].Name, "io");
  ASSERT_EQ(P.M->Decls.size(), 2u);
  auto *T = cast<TaskDecl>(P.M->Decls[0]);
  EXPECT_EQ(T->getName().Name, "t");
  EXPECT_EQ(T->Module, P.M);
  ASSERT_EQ(T->Params.size(), 2u);
  EXPECT_EQ(T->Params[1]->TypeName.str(), "Math::Vector2f");
  EXPECT_EQ(T->Params[1]->Owner, T);
  EXPECT_EQ(T->Params[1]->Index, 1u);
  auto *F = cast<FuncDecl>(P.M->Decls[1]);
  EXPECT_EQ(F->ResultTypeName.str(), "bool");
  EXPECT_EQ(F->EnclosingTask, nullptr);
}

TEST(ParserTest, NestedFunc) {
  Parsed P("task t()\n    func g() : int\n        return 1\n    g()\n");
  EXPECT_TRUE(P.diags().empty());
  auto *T = cast<TaskDecl>(P.M->Decls[0]);
  ASSERT_EQ(T->NestedFuncs.size(), 1u);
  auto *FS = cast<FuncDeclStmt>(P.body()[0]);
  EXPECT_EQ(FS->Func, T->NestedFuncs[0]);
  EXPECT_EQ(FS->Func->EnclosingTask, T);
  EXPECT_EQ(FS->Func->Module, P.M);
}

TEST(ParserTest, DeclarationAssignmentExpression) {
  Parsed P("func f()\n    Math::Vector2f v = g(1)\n    int i\n"
           "    a.b += 2\n    io::printi(i)\n");
  EXPECT_TRUE(P.diags().empty());
  auto *D = cast<DeclStmt>(P.body()[0]);
  EXPECT_EQ(D->Var->TypeName.str(), "Math::Vector2f");
  EXPECT_TRUE(isa<CallExpr>(D->Var->Init));
  EXPECT_EQ(cast<DeclStmt>(P.body()[1])->Var->Init, nullptr);
  auto *A = cast<AssignStmt>(P.body()[2]);
  EXPECT_EQ(A->Op, AssignOp::AddAssign);
  EXPECT_TRUE(isa<MemberExpr>(A->Target));
  EXPECT_TRUE(isa<CallExpr>(cast<ExprStmt>(P.body()[3])->E));
}

TEST(ParserTest, Precedence) {
  Parsed P("func f()\n    x = 1 + 2 * 3 < 4 && !a || b == c\n");
  EXPECT_TRUE(P.diags().empty());
  auto *Or = cast<BinaryExpr>(cast<AssignStmt>(P.body()[0])->Value);
  EXPECT_EQ(Or->Op, BinaryOp::Or);
  auto *And = cast<BinaryExpr>(Or->LHS);
  EXPECT_EQ(And->Op, BinaryOp::And);
  auto *Lt = cast<BinaryExpr>(And->LHS);
  EXPECT_EQ(Lt->Op, BinaryOp::Lt);
  auto *Add = cast<BinaryExpr>(Lt->LHS);
  EXPECT_EQ(Add->Op, BinaryOp::Add);
  EXPECT_EQ(cast<BinaryExpr>(Add->RHS)->Op, BinaryOp::Mul);
  EXPECT_TRUE(isa<UnaryExpr>(And->RHS));
  EXPECT_EQ(cast<BinaryExpr>(Or->RHS)->Op, BinaryOp::Eq);
  Parsed L("func f()\n    x = 1 - 2 - 3\n");
  auto *Sub = cast<BinaryExpr>(cast<AssignStmt>(L.body()[0])->Value);
  EXPECT_TRUE(isa<BinaryExpr>(Sub->LHS)); // Left-associative.
}

TEST(ParserTest, LiteralsAndFolding) {
  Parsed P("func f()\n    x = -2147483648\n    y = 0xFFFFFFFF\n"
           "    z = -1.5\n    w = float(x)\n    s = taskState(M::t)\n");
  EXPECT_TRUE(P.diags().empty());
  auto Val = [&](unsigned I) { return cast<AssignStmt>(P.body()[I])->Value; };
  EXPECT_EQ(cast<IntLiteralExpr>(Val(0))->Value, INT32_MIN);
  EXPECT_EQ(cast<IntLiteralExpr>(Val(1))->Value, -1);
  EXPECT_FLOAT_EQ(cast<FloatLiteralExpr>(Val(2))->Value, -1.5f);
  auto *C = cast<ConversionExpr>(Val(3));
  EXPECT_EQ(C->TargetName.str(), "float");
  EXPECT_FALSE(C->Implicit);
  EXPECT_EQ(cast<TaskStateExpr>(Val(4))->TaskName.str(), "M::t");
  Parsed Big("func f()\n    x = 2147483648\n");
  EXPECT_EQ(Big.diags(),
            std::vector<diag::Kind>{diag::err_int_literal_too_large});
}

TEST(ParserTest, IfElseChainAndFor) {
  Parsed P("task t()\n    if(a)\n        x()\n    else if(b)\n        y()\n"
           "    else\n        z()\n    for(int i = 0; i < 3; i += 1)\n"
           "        x()\n    for(;;yield)\n        x()\n");
  EXPECT_TRUE(P.diags().empty());
  auto *If = cast<IfStmt>(P.body()[0]);
  auto *ElseIf = cast<IfStmt>(If->Else);
  EXPECT_TRUE(isa<BlockStmt>(ElseIf->Else));
  auto *For = cast<ForStmt>(P.body()[1]);
  EXPECT_TRUE(isa<DeclStmt>(For->Init));
  EXPECT_TRUE(isa<AssignStmt>(For->Step));
  auto *Loop = cast<ForStmt>(P.body()[2]);
  EXPECT_EQ(Loop->Init, nullptr);
  EXPECT_EQ(Loop->Cond, nullptr);
  EXPECT_TRUE(isa<YieldStmt>(Loop->Step));
}

TEST(ParserTest, OneErrorPerMistake) {
  Parsed P("task t()\n    x = (1 +\n    y = 2 3\n    else\n        z()\n"
           "    a()\n        b()\n    task u()\n        c()\n");
  EXPECT_EQ(P.diags(),
            (std::vector<diag::Kind>{
                // `(1 +` runs into the next line; `else` ends it.
                diag::err_expected, diag::err_else_without_if, diag::err_unexpected_indent,
                diag::err_nested_task}));
  Parsed M("x = 1\n    y\nfunc f()\n    a()\nrequires \"a\"\n");
  EXPECT_EQ(M.diags(), (std::vector<diag::Kind>{
                           diag::err_expected_declaration,
                           diag::err_requires_after_decl}));
  EXPECT_EQ(M.M->Decls.size(), 1u);
}

TEST(ParserTest, FuncPlacement) {
  Parsed P("func f()\n    func g()\n        a()\ntask t()\n    if(x)\n"
           "        func h()\n            a()\n");
  EXPECT_EQ(P.diags(), (std::vector<diag::Kind>{
                           diag::err_func_in_func,
                           diag::err_nested_func_placement}));
}

TEST(ParserTest, MissingBlock) {
  Parsed P("task t()\n    if(x)\n    y()\n    for(;;) z()\n");
  EXPECT_EQ(P.diags(), (std::vector<diag::Kind>{diag::err_expected_block,
                                                diag::err_expected_block}));
}

TEST(ParserTest, DeepNesting) {
  std::string Src = "task t()\n";
  for (unsigned I = 0; I != 500; ++I)
    Src += std::string(4 * (I + 1), ' ') + "if(x)\n";
  Src += std::string(4 * 501, ' ') + "y()\n";
  Parsed Ok(Src);
  EXPECT_TRUE(Ok.diags().empty());

  Parsed Parens("func f()\n    x = " + std::string(100000, '(') + "1" +
                std::string(100000, ')') + "\n");
  EXPECT_EQ(Parens.diags(),
            std::vector<diag::Kind>{diag::err_nesting_too_deep});
  std::string Chain = "func f()\n    x = 1";
  for (unsigned I = 0; I != 5000; ++I)
    Chain += " + 1";
  Parsed Long(Chain + "\n");
  EXPECT_EQ(Long.diags(), std::vector<diag::Kind>{diag::err_nesting_too_deep});
}

TEST(ParserTest, DumpFormat) {
  Parsed P("task fib()\n    int a = 0\n    io::printi(a)\n");
  EXPECT_EQ(P.dump(), "Module 'm'\n"
                      "  TaskDecl 'fib' <1:1>\n"
                      "    BlockStmt <2:5>\n"
                      "      DeclStmt <2:5>\n"
                      "        VarDecl 'a' 'int' <2:5>\n"
                      "          IntLiteralExpr 0 <2:13>\n"
                      "      ExprStmt <3:5>\n"
                      "        CallExpr <3:5>\n"
                      "          NameExpr 'io::printi' <3:5>\n"
                      "          NameExpr 'a' <3:16>\n");
}

/// Random text (a third of it random bytes) never crashes the parser, is
/// always reported as an error, and every diagnostic points into the text
/// with its ranges inside it.
TEST(ParserTest, GarbageIsReportedInsideTheText) {
  uint32_t Seed = 12345;
  for (unsigned Round = 0; Round != 200; ++Round) {
    std::string Src;
    for (unsigned I = 0; I != 300; ++I) {
      Seed = Seed * 1103515245 + 12345;
      static const char Alphabet[] = "tf(),.:;+-*/%!<>=&|[]\"\\#\n\n    \t0x9e.ab";
      Src += (Seed >> 16) % 3 == 0 ? char(Seed >> 8)
                                   : Alphabet[(Seed >> 16) % (sizeof(Alphabet) - 1)];
    }
    Parsed P(Src);
    SCOPED_TRACE("round " + std::to_string(Round));
    EXPECT_GT(P.Diags.getNumErrors(), 0u);
    const char *Begin = P.SM.getMemoryBuffer(1)->getBufferStart();
    const char *End = P.SM.getMemoryBuffer(1)->getBufferEnd();
    auto Inside = [&](llvm::SMLoc L) {
      return L.getPointer() >= Begin && L.getPointer() <= End;
    };
    for (const Diagnostic &D : P.Diags.getDiagnostics()) {
      EXPECT_TRUE(Inside(D.Loc)) << D.Message;
      for (const llvm::SMRange &R : D.Ranges)
        EXPECT_TRUE(Inside(R.Start) && Inside(R.End) &&
                    R.Start.getPointer() <= R.End.getPointer())
            << D.Message;
    }
    EXPECT_FALSE(P.dump().empty());
  }
}

// forEachChild (AST.h) visits every child in source order; a walk that only
// recurses sees the whole tree.
TEST(ParserTest, ForEachChildWalksTheTreeInSourceOrder) {
  Parsed P("task t(int a = 2)\n"
           "    int x = a + 1\n"
           "    if(x > 0)\n"
           "        x = -x\n"
           "    else\n"
           "        yield\n"
           "    assert(x != 3, \"not three\")\n");
  ASSERT_TRUE(P.diags().empty());
  std::vector<std::string> Kinds;
  std::function<void(const Node &)> Walk = [&](const Node &N) {
    Kinds.push_back(getNodeKindName(N.getKind()).str());
    forEachChild(N, Walk);
  };
  Walk(*P.M->Decls.at(0));
  std::vector<std::string> Want = {
      "TaskDecl",     "ParamDecl",     "IntLiteralExpr",   "BlockStmt",
      "DeclStmt",     "VarDecl",       "BinaryExpr",       "NameExpr",
      "IntLiteralExpr", "IfStmt",      "BinaryExpr",       "NameExpr",
      "IntLiteralExpr", "BlockStmt",   "AssignStmt",       "NameExpr",
      "UnaryExpr",    "NameExpr",      "BlockStmt",        "YieldStmt",
      "AssertStmt",   "BinaryExpr",    "NameExpr",         "IntLiteralExpr",
      "StringLiteralExpr"};
  EXPECT_EQ(Kinds, Want);
}
