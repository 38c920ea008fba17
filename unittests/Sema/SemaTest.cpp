//===- SemaTest.cpp - the typing and task rules of Sema -------------------===//
//
// Most tests build small trees by hand instead of parsing source, so they
// pin down Sema's rules (types, implicit conversions, poison, resume
// points, the call graph) independently of the parser; a few parse source
// for what is tedious to build by hand (nested funcs, locals). The lit tests in
// test/Sema cover the same rules end to end with source positions.
//
//===----------------------------------------------------------------------===//
#include "bsc/Parse/Parser.h"
#include "bsc/Sema/Sema.h"
#include "llvm/Support/MemoryBuffer.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {

class SemaTest : public ::testing::Test {
protected:
  ASTContext Ctx;
  DiagnosticEngine Diags;
  Behavior Out;
  ModuleAST *M = nullptr;
  NativeRegistry Natives = makeBuiltinNativeRegistry();

  void SetUp() override {
    M = Ctx.createModule();
    M->Name = "M";
  }

  static Ident id(llvm::StringRef N) {
    return {N, llvm::SMLoc::getFromPointer(N.data())};
  }
  static QualifiedName qn(llvm::StringRef A, llvm::StringRef B = "") {
    QualifiedName Q;
    Q.Parts.push_back(id(A));
    if (!B.empty())
      Q.Parts.push_back(id(B));
    return Q;
  }
  Expr *lit(int V) { return Ctx.create<IntLiteralExpr>(llvm::SMRange(), V); }
  Expr *flt(float V) {
    return Ctx.create<FloatLiteralExpr>(llvm::SMRange(), V);
  }
  Expr *boolean(bool V) {
    return Ctx.create<BoolLiteralExpr>(llvm::SMRange(), V);
  }
  Expr *str(const char *V) {
    return Ctx.create<StringLiteralExpr>(llvm::SMRange(), V);
  }
  NameExpr *name(llvm::StringRef A, llvm::StringRef B = "") {
    return Ctx.create<NameExpr>(llvm::SMRange(), qn(A, B));
  }
  BinaryExpr *bin(BinaryOp Op, Expr *L, Expr *R) {
    return Ctx.create<BinaryExpr>(llvm::SMRange(), Op, L, R);
  }
  CallExpr *call(Expr *Callee, std::vector<Expr *> Args = {}) {
    return Ctx.create<CallExpr>(llvm::SMRange(), Callee, std::move(Args));
  }
  Stmt *exprStmt(Expr *E) { return Ctx.create<ExprStmt>(llvm::SMRange(), E); }
  DeclStmt *var(llvm::StringRef Ty, llvm::StringRef Name, Expr *Init) {
    auto *V = Ctx.create<VarDecl>(llvm::SMRange(), id(Name), qn(Ty), Init);
    return Ctx.create<DeclStmt>(llvm::SMRange(), V);
  }
  Stmt *assign(AssignOp Op, Expr *T, Expr *V) {
    return Ctx.create<AssignStmt>(llvm::SMRange(), Op, T, V);
  }
  YieldStmt *yield(Expr *V = nullptr) {
    return Ctx.create<YieldStmt>(llvm::SMRange(), V);
  }
  Stmt *ret(Expr *V = nullptr) {
    return Ctx.create<ReturnStmt>(llvm::SMRange(), V);
  }
  BlockStmt *block(std::vector<Stmt *> Stmts) {
    auto *B = Ctx.create<BlockStmt>(llvm::SMRange());
    B->Stmts = std::move(Stmts);
    return B;
  }
  void addParams(CallableDecl *C,
                 std::vector<std::pair<llvm::StringRef, llvm::StringRef>> Ps) {
    for (auto [Ty, Name] : Ps) {
      auto *P = Ctx.create<ParamDecl>(llvm::SMRange(), id(Name), qn(Ty));
      P->Owner = C;
      P->Index = C->Params.size();
      C->Params.push_back(P);
    }
  }
  FuncDecl *func(llvm::StringRef Name, llvm::StringRef Result,
                 std::vector<Stmt *> Body,
                 std::vector<std::pair<llvm::StringRef, llvm::StringRef>> Ps = {}) {
    auto *F = Ctx.create<FuncDecl>(llvm::SMRange(), id(Name));
    if (!Result.empty())
      F->ResultTypeName = qn(Result);
    F->Module = M;
    addParams(F, Ps);
    F->Body = block(std::move(Body));
    M->Decls.push_back(F);
    return F;
  }
  TaskDecl *task(llvm::StringRef Name, std::vector<Stmt *> Body,
                 std::vector<std::pair<llvm::StringRef, llvm::StringRef>> Ps = {}) {
    auto *T = Ctx.create<TaskDecl>(llvm::SMRange(), id(Name));
    T->Module = M;
    addParams(T, Ps);
    T->Body = block(std::move(Body));
    M->Decls.push_back(T);
    return T;
  }
  void require(const char *Name) {
    RequireDecl R;
    R.Name = Name;
    R.Native = Natives.find(Name);
    M->Requires.push_back(R);
  }
  bool check() { return checkBehavior({M}, Ctx, Diags, Out); }
  std::vector<std::string> messages() const {
    std::vector<std::string> Result;
    for (const Diagnostic &D : Diags.getDiagnostics())
      Result.push_back(D.Message);
    return Result;
  }
};

using Msgs = std::vector<std::string>;

TEST_F(SemaTest, MixedArithmeticPromotesTheIntSide) {
  BinaryExpr *Add = bin(BinaryOp::Add, lit(1), flt(2.0f));
  func("f", "", {var("float", "x", Add)});
  ASSERT_TRUE(check()) << messages().front();
  EXPECT_TRUE(Add->Ty->isFloat());
  auto *Conv = llvm::dyn_cast<ConversionExpr>(Add->LHS);
  ASSERT_NE(Conv, nullptr);
  EXPECT_TRUE(Conv->Implicit);
  EXPECT_TRUE(Conv->Ty->isFloat());
  EXPECT_TRUE(llvm::isa<FloatLiteralExpr>(Add->RHS));
}

TEST_F(SemaTest, IntInitialisationOfFloatIsPromoted) {
  DeclStmt *D = var("float", "x", lit(3));
  func("f", "", {D});
  ASSERT_TRUE(check());
  EXPECT_TRUE(llvm::isa<ConversionExpr>(D->Var->Init));
  EXPECT_TRUE(D->Var->Ty->isFloat());
}

TEST_F(SemaTest, FloatDoesNotConvertToInt) {
  func("f", "", {var("int", "x", flt(1.5f))});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(), Msgs{"cannot initialize 'x' of type 'int' with a "
                             "value of type 'float'"});
}

TEST_F(SemaTest, RemainderNeedsInts) {
  func("f", "", {var("float", "x", bin(BinaryOp::Rem, flt(1), lit(2)))});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(),
            Msgs{"invalid operands to binary '%' ('float' and 'int')"});
}

TEST_F(SemaTest, ComparisonsGiveBool) {
  BinaryExpr *Lt = bin(BinaryOp::Lt, lit(1), flt(2));
  BinaryExpr *Eq = bin(BinaryOp::Eq, name("TaskState", "done"),
                       name("TaskState", "failure"));
  func("f", "", {var("bool", "a", Lt), var("bool", "b", Eq)});
  ASSERT_TRUE(check());
  EXPECT_TRUE(Lt->Ty->isBool());
  EXPECT_TRUE(Eq->Ty->isBool());
  EXPECT_EQ(llvm::cast<NameExpr>(Eq->RHS)->EnumValue, -1);
  EXPECT_TRUE(Eq->LHS->Ty->isTaskState());
}

TEST_F(SemaTest, TaskStateAndIntDoNotMix) {
  func("f", "",
       {var("bool", "b", bin(BinaryOp::Eq, name("TaskState", "done"), lit(0)))});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(),
            Msgs{"invalid operands to binary '==' ('TaskState' and 'int')"});
}

TEST_F(SemaTest, StringsAreNeverCompared) {
  func("f", "", {var("bool", "b", bin(BinaryOp::Eq, str("a"), str("a")))});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(),
            Msgs{"invalid operands to binary '==' ('string' and 'string')"});
}

TEST_F(SemaTest, ErrorTypeIsPoison) {
  // `undeclared + 1.5 < true` reports only the unknown name.
  func("f", "", {var("bool", "b",
                     bin(BinaryOp::Lt, bin(BinaryOp::Add, name("nope"), flt(1)),
                         boolean(true)))});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(), Msgs{"use of undeclared name 'nope'"});
}

TEST_F(SemaTest, ExplicitConversions) {
  auto Conv = [&](llvm::StringRef To, Expr *E) {
    return Ctx.create<ConversionExpr>(llvm::SMRange(), qn(To), E, false);
  };
  ConversionExpr *ToInt = Conv("int", flt(2.5f));
  ConversionExpr *FromState = Conv("int", name("TaskState", "running"));
  func("f", "", {var("int", "a", ToInt), var("int", "b", FromState),
                 var("bool", "c", Conv("bool", lit(1)))});
  EXPECT_FALSE(check());
  EXPECT_TRUE(ToInt->Ty->isInt());
  EXPECT_TRUE(FromState->Ty->isInt());
  EXPECT_EQ(messages(), Msgs{"cannot convert 'int' to 'bool'"});
}

TEST_F(SemaTest, CompoundAssignmentFollowsBinaryRules) {
  func("f", "", {var("int", "i", lit(0)), var("float", "x", lit(0)),
                 assign(AssignOp::AddAssign, name("i"), flt(1.5f)),
                 assign(AssignOp::AddAssign, name("x"), lit(1)),
                 assign(AssignOp::RemAssign, name("x"), lit(1))});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(),
            (Msgs{"cannot assign a value of type 'float' to 'i' of type 'int'",
                  "invalid operands to binary '%=' ('float' and 'int')"}));
}

TEST_F(SemaTest, CallsCheckArityAndArgumentTypes) {
  require("io");
  CallExpr *Good = call(name("io", "printf"), {lit(1)});
  func("f", "",
       {exprStmt(Good), exprStmt(call(name("io", "printi"), {flt(1)})),
        exprStmt(call(name("io", "prints"), {}))});
  EXPECT_FALSE(check());
  EXPECT_EQ(Good->Kind, CallKind::NativeFunction);
  ASSERT_NE(Good->NativeFn, nullptr);
  EXPECT_EQ(Good->NativeFn->Symbol, "bs_io_printf");
  EXPECT_TRUE(llvm::isa<ConversionExpr>(Good->Args[0]));
  EXPECT_EQ(messages(),
            (Msgs{"argument 1 of 'io::printi' must be 'int', not 'float'",
                  "'io::prints' takes 1 argument(s), but 0 were given"}));
  ASSERT_EQ(Out.NativeModules.size(), 1u);
}

TEST_F(SemaTest, TaskCallsAreStatementsOnly) {
  task("t", {});
  CallExpr *Stmt = call(name("t"));
  func("f", "", {exprStmt(Stmt), var("int", "x", call(name("t")))});
  EXPECT_FALSE(check());
  EXPECT_EQ(Stmt->Kind, CallKind::Task);
  EXPECT_EQ(messages(), Msgs{"a task call is a statement and has no value; "
                             "read its state with 'taskState(t)'"});
}

TEST_F(SemaTest, YieldsAreNumberedInSourceOrder) {
  YieldStmt *Y1 = yield(), *Y2 = yield(name("TaskState", "failure"));
  TaskDecl *T = task("t", {Y1, var("int", "a", lit(1)), Y2});
  ASSERT_TRUE(check());
  ASSERT_EQ(T->Yields.size(), 2u);
  EXPECT_EQ(Y1->ResumePoint, 1u);
  EXPECT_EQ(Y2->ResumePoint, 2u);
  ASSERT_EQ(T->Locals.size(), 1u);
  EXPECT_EQ(T->Locals[0]->Owner, T);
  EXPECT_EQ(Out.Tasks, std::vector<TaskDecl *>{T});
}

TEST_F(SemaTest, TaskParametersAreReadOnly) {
  task("t", {assign(AssignOp::Assign, name("p"), lit(1))}, {{"int", "p"}});
  func("f", "", {assign(AssignOp::Assign, name("p"), lit(1))}, {{"int", "p"}});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(), Msgs{"cannot assign to 'p': the parameters of task "
                             "'t' are read-only"});
}

TEST_F(SemaTest, MissingReturn) {
  auto *For = Ctx.create<ForStmt>(llvm::SMRange(), nullptr, boolean(true),
                                  nullptr, block({}));
  func("endless", "int", {For});
  func("g", "int", {var("int", "x", lit(1))});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(),
            Msgs{"function 'g' does not return a value on every path"});
}

TEST_F(SemaTest, CallCyclesAreReportedOnceWithTheirEdges) {
  task("a", {exprStmt(call(name("b")))});
  task("b", {exprStmt(call(name("c"))), exprStmt(call(name("a")))});
  task("c", {});
  func("f", "", {exprStmt(call(name("f")))});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(),
            (Msgs{"task 'M::a' can reach itself: M::a -> M::b -> M::a",
                  "'M::a' calls 'M::b' here", "'M::b' calls 'M::a' here",
                  "function 'M::f' can reach itself: M::f -> M::f",
                  "'M::f' calls 'M::f' here"}));
}

TEST_F(SemaTest, ShadowingIsAnError) {
  func("f", "", {var("int", "x", lit(0)), var("int", "f", lit(0)),
                 var("float", "x", lit(0))},
       {{"int", "p"}});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(),
            (Msgs{"declaration of 'x' shadows an earlier declaration",
                  "previous definition is here"}));
}

TEST_F(SemaTest, BuiltinIoModule) {
  const NativeModule *IO = Natives.find("io");
  ASSERT_NE(IO, nullptr);
  ASSERT_EQ(IO->Functions.size(), 4u);
  const NativeFunction *P = IO->findFunction("prints");
  ASSERT_NE(P, nullptr);
  EXPECT_EQ(P->Symbol, "bs_io_prints");
  ASSERT_EQ(P->Params.size(), 1u);
  EXPECT_EQ(P->Params[0].TheCode, NativeType::String);
  EXPECT_EQ(P->Result.TheCode, NativeType::Void);
}

TEST_F(SemaTest, InputHasNoTypeYet) {
  auto *Member = Ctx.create<MemberExpr>(llvm::SMRange(), name("input"),
                                        id("time"));
  func("f", "", {var("int", "t", Member),
                 assign(AssignOp::Assign, name("input"), lit(1))});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(),
            (Msgs{"no input type registered; 'input' needs a binding module "
                  "that declares it",
                  "'input' is read-only"}));
}

} // namespace

namespace {

/// Parses and checks one module from source text.
struct Parsed {
  llvm::SourceMgr SM;
  ASTContext Ctx;
  DiagnosticEngine Diags;
  Behavior Out;
  ModuleAST *M = nullptr;
  bool OK = false;

  explicit Parsed(llvm::StringRef Source) {
    unsigned ID = SM.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(Source, "P.bs"), llvm::SMLoc());
    M = parseModule(SM, ID, "P", Ctx, Diags);
    OK = !Diags.hasErrors() && checkBehavior({M}, Ctx, Diags, Out);
  }
};

TEST(SemaParsedTest, NestedFuncsOwnTheirLocalsAndComeInSourceOrder) {
  Parsed P("func first()\n"
           "    return\n"
           "task t(int p)\n"
           "    int a = p\n"
           "    func inner() : int\n"
           "        int b = a\n"
           "        return b\n"
           "    for(int i = 0; i < inner(); i += 1)\n"
           "        int c = i\n"
           "func last()\n"
           "    t(1)\n");
  ASSERT_TRUE(P.OK);
  ASSERT_EQ(P.Out.Funcs.size(), 3u);
  EXPECT_EQ(P.Out.Funcs[0]->getName().Name, "first");
  FuncDecl *Inner = P.Out.Funcs[1];
  EXPECT_EQ(Inner->getName().Name, "inner");
  EXPECT_EQ(P.Out.Funcs[2]->getName().Name, "last");
  ASSERT_EQ(P.Out.Tasks.size(), 1u);
  TaskDecl *T = P.Out.Tasks[0];

  std::vector<llvm::StringRef> TaskLocals;
  for (VarDecl *V : T->Locals) {
    TaskLocals.push_back(V->getName().Name);
    EXPECT_EQ(V->Owner, T);
  }
  EXPECT_EQ(TaskLocals, (std::vector<llvm::StringRef>{"a", "i", "c"}));
  ASSERT_EQ(Inner->Locals.size(), 1u);
  EXPECT_EQ(Inner->Locals[0]->Owner, Inner);
  EXPECT_TRUE(Inner->ResultTy->isInt());
}

TEST(SemaParsedTest, RecursionThroughATaskIsReported) {
  Parsed P("task a()\n"
           "    b()\n"
           "task b()\n"
           "    a()\n");
  EXPECT_FALSE(P.OK);
  std::vector<std::string> Msgs;
  for (const Diagnostic &D : P.Diags.getDiagnostics())
    Msgs.push_back(D.Message);
  EXPECT_EQ(Msgs, (std::vector<std::string>{
                      "task 'P::a' can reach itself: P::a -> P::b -> P::a",
                      "'P::a' calls 'P::b' here", "'P::b' calls 'P::a' here"}));
}

} // namespace
