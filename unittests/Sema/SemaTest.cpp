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
#include "ParsedModule.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {

/// A hand-made `io` with the signatures of the runtime's io_module.cpp
/// (printi, printf, printb, prints, each taking one scalar and returning
/// nothing), named `io_<f>` instead of by thunk. The real module is read
/// from the runtime archive (FrontendTest).
NativeRegistry makeIORegistry() {
  NativeRegistry R;
  auto IO = std::make_unique<NativeModule>();
  IO->Name = "io";
  const std::pair<const char *, NativeType::Code> Prints[] = {
      {"printi", NativeType::Int},
      {"printf", NativeType::Float},
      {"printb", NativeType::Bool},
      {"prints", NativeType::String}};
  for (const auto &[Name, Param] : Prints) {
    NativeFunction F;
    F.Name = Name;
    F.Symbol = std::string("io_") + Name;
    F.Params.emplace_back().TheCode = Param;
    IO->Functions.push_back(std::move(F));
  }
  R.Modules.push_back(std::move(IO));
  return R;
}

class SemaTest : public ::testing::Test {
protected:
  ASTContext Ctx;
  DiagnosticEngine Diags;
  Behavior Out;
  ModuleAST *M = nullptr;
  NativeRegistry Natives = makeIORegistry();

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
  bool check() { return checkBehavior({M}, Ctx, Diags, Out, &Natives); }
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

TEST_F(SemaTest, StringsCompareOnlyForEquality) {
  BinaryExpr *Eq = bin(BinaryOp::Ne, str("a"), str("b"));
  func("f", "", {var("bool", "b", Eq),
                 var("bool", "c", bin(BinaryOp::Lt, str("a"), str("a")))});
  EXPECT_FALSE(check());
  EXPECT_TRUE(Eq->Ty->isBool());
  EXPECT_EQ(messages(),
            Msgs{"invalid operands to binary '<' ('string' and 'string')"});
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
  EXPECT_EQ(Good->NativeFn->Symbol, "io_printf");
  EXPECT_TRUE(llvm::isa<ConversionExpr>(Good->Args[0]));
  EXPECT_EQ(messages(),
            (Msgs{"argument 1 of 'io::printi' must be 'int', not 'float'",
                  "'io::printi' is registered as 'printi(int)'",
                  "'io::prints' takes 1 argument(s), but 0 were given",
                  "'io::prints' is registered as 'prints(string)'"}));
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
  // `endless` never returns, which is no error but is worth a warning.
  EXPECT_EQ(messages(),
            (Msgs{"this loop never reaches a 'return' or 'break': a call that "
                  "enters it never returns (-Wno-yield-loop)",
                  "function 'g' does not return a value on every path"}));
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

TEST_F(SemaTest, RedeclarationIsAnError) {
  // A local may take a func's name; a second `x` in the same scope is a
  // redefinition (shadowing across scopes: test/Sema/names.bs).
  func("f", "", {var("int", "x", lit(0)), var("int", "f", lit(0)),
                 var("float", "x", lit(0))},
       {{"int", "p"}});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(),
            (Msgs{"redefinition of 'x'", "previous definition is here"}));
}

TEST_F(SemaTest, InputHasNoTypeYet) {
  auto *Member = Ctx.create<MemberExpr>(llvm::SMRange(), name("input"),
                                        id("time"));
  func("f", "", {var("int", "t", Member),
                 assign(AssignOp::Assign, name("input"), lit(1))});
  EXPECT_FALSE(check());
  EXPECT_EQ(messages(),
            (Msgs{"no input type registered; 'input' needs a binding module "
                  "that declares it: pass its object with --bind",
                  "'input' is read-only"}));
}

} // namespace

namespace {

using Parsed = ParsedModule;

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

//===----------------------------------------------------------------------===//
// Registered classes, from a hand-made Native.h registry (no binding object)
//===----------------------------------------------------------------------===//

namespace {

NativeType scalar(NativeType::Code C) {
  NativeType T;
  T.TheCode = C;
  return T;
}

NativeType classType(const NativeClass &C) {
  NativeType T;
  T.TheCode = NativeType::Class;
  T.Name = C.QualifiedName;
  T.TheClass = &C;
  return T;
}

NativeFunction member(NativeFunction::MemberKind K, const char *Name,
                      const NativeClass &Owner, NativeType Result,
                      std::vector<NativeType> Params = {},
                      bool ConstSelf = true) {
  NativeFunction F;
  F.Kind = K;
  F.Name = Name;
  F.Symbol = std::string("thunk_") + Name;
  F.Owner = &Owner;
  F.Result = std::move(Result);
  F.Params = std::move(Params);
  F.ConstSelf = ConstSelf;
  return F;
}

/// A world module `W` with class `Vec` (field x, const method len, non-const
/// method move(float, float = 2), operators _plus_ and _eq_) and the input
/// and output classes `In` and `Out`, each with a field `v : W::Vec`.
NativeRegistry makeWorld() {
  NativeRegistry R = makeIORegistry();
  auto W = std::make_unique<NativeModule>();
  W->Name = "W";
  W->Classes.resize(3);
  const char *Names[] = {"Vec", "In", "Out"};
  for (int I = 0; I != 3; ++I) {
    W->Classes[I].Name = Names[I];
    W->Classes[I].QualifiedName = std::string("W::") + Names[I];
    W->Classes[I].Module = W.get();
    W->Classes[I].Size = 8;
    W->Classes[I].Align = 4;
    // Plain structs: copied as bytes, nothing to destroy.
    W->Classes[I].CopiesAsBytes = true;
    W->Classes[I].TriviallyDestructible = true;
  }
  NativeClass &Vec = W->Classes[0];
  NativeType Float = scalar(NativeType::Float);
  Vec.Members.push_back(member(NativeFunction::Field, "x", Vec, Float));
  Vec.Members.back().FieldOffset = 0;
  Vec.Members.push_back(member(NativeFunction::Method, "len", Vec, Float));
  Vec.Members.push_back(member(NativeFunction::Method, "move", Vec,
                               scalar(NativeType::Void), {Float, Float},
                               /*ConstSelf=*/false));
  NativeDefault Two;
  Two.IsFloat = true;
  Two.Float = 2;
  Vec.Members.back().Defaults.push_back(Two);
  Vec.Members.push_back(member(NativeFunction::Method, "_plus_", Vec,
                               classType(Vec), {classType(Vec)}));
  Vec.Members.push_back(member(NativeFunction::Method, "_eq_", Vec,
                               scalar(NativeType::Bool), {classType(Vec)}));
  for (int I = 1; I != 3; ++I)
    W->Classes[I].Members.push_back(
        member(NativeFunction::Field, "v", W->Classes[I], classType(Vec)));
  W->Input = &W->Classes[1];
  W->Output = &W->Classes[2];
  R.Modules.push_back(std::move(W));
  return R;
}

/// Parses and checks one module against the world registry.
struct ParsedWithWorld {
  llvm::SourceMgr SM;
  ASTContext Ctx;
  DiagnosticEngine Diags;
  Behavior Out;
  NativeRegistry Natives = makeWorld();
  ModuleAST *M = nullptr;
  bool OK = false;

  /// `Adjust` may change the world before the check.
  explicit ParsedWithWorld(
      llvm::StringRef Source,
      llvm::function_ref<void(NativeRegistry &)> Adjust = nullptr) {
    if (Adjust)
      Adjust(Natives);
    unsigned ID = SM.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(Source, "P.bs"), llvm::SMLoc());
    M = parseModule(SM, ID, "P", Ctx, Diags);
    OK = !Diags.hasErrors() && checkBehavior({M}, Ctx, Diags, Out, &Natives);
  }
  std::vector<std::string> messages() const {
    std::vector<std::string> Result;
    for (const Diagnostic &D : Diags.getDiagnostics())
      Result.push_back(D.Message);
    return Result;
  }
  /// The statements of the first declaration's body.
  std::vector<Stmt *> &body() { return M->Decls[0]->Body->Stmts; }
};

TEST(SemaClassTest, FieldChainsResolveToMembersAndTypes) {
  ParsedWithWorld P("task t()\n"
                    "    float f = input.v.x\n"
                    "    output.v.x = f\n");
  ASSERT_TRUE(P.OK) << P.messages().front();
  EXPECT_TRUE(P.Out.UsesClasses);
  EXPECT_EQ(P.Out.World, P.Natives.getWorld());
  auto *D = llvm::cast<DeclStmt>(P.body()[0]);
  auto *X = llvm::cast<MemberExpr>(D->Var->Init);
  auto *V = llvm::cast<MemberExpr>(X->Base);
  auto *In = llvm::cast<NameExpr>(V->Base);
  EXPECT_EQ(In->Kind, NameKind::Input);
  ASSERT_TRUE(In->Ty->isClass());
  EXPECT_EQ(In->Ty->getClass(), P.Natives.getWorld()->Input);
  EXPECT_EQ(V->Ty->getName(), "W::Vec");
  EXPECT_EQ(V->Resolved->Name, "v");
  EXPECT_EQ(X->Resolved->Kind, NativeFunction::Field);
  EXPECT_TRUE(X->Ty->isFloat());
  // Types are uniqued: the field's class type is the one of the class.
  EXPECT_EQ(V->Ty, P.Ctx.getTypes().getClass(V->Ty->getClass()));
}

TEST(SemaClassTest, MethodCallsRecordTheMemberAndFillInDefaults) {
  ParsedWithWorld P("func f(Vec a) : float\n"
                    "    Vec b = a\n"
                    "    b.move(1)\n"
                    "    return b.len()\n");
  ASSERT_TRUE(P.OK) << P.messages().front();
  auto *S = llvm::cast<ExprStmt>(P.body()[1]);
  auto *Move = llvm::cast<CallExpr>(S->E);
  EXPECT_EQ(Move->Kind, CallKind::Method);
  EXPECT_EQ(Move->NativeFn->Name, "move");
  ASSERT_EQ(Move->Args.size(), 2u);
  EXPECT_EQ(Move->NumDefaultArgs, 1u);
  // The written int argument is promoted; the default is a float literal.
  EXPECT_TRUE(llvm::isa<ConversionExpr>(Move->Args[0]));
  auto *Default = llvm::dyn_cast<FloatLiteralExpr>(Move->Args[1]);
  ASSERT_NE(Default, nullptr);
  EXPECT_EQ(Default->Value, 2.0f);
  EXPECT_TRUE(Default->Ty->isFloat());
  auto *Ret = llvm::cast<ReturnStmt>(P.body()[2]);
  EXPECT_EQ(llvm::cast<CallExpr>(Ret->Value)->Kind, CallKind::Method);
}

TEST(SemaClassTest, OperatorsCallTheirMethodsAndNotEqualFallsBack) {
  ParsedWithWorld P("func f(Vec a, Vec b) : bool\n"
                    "    Vec c = a + b\n"
                    "    return c != a\n");
  ASSERT_TRUE(P.OK) << P.messages().front();
  auto *Sum = llvm::cast<BinaryExpr>(llvm::cast<DeclStmt>(P.body()[0])->Var->Init);
  ASSERT_NE(Sum->Operator, nullptr);
  EXPECT_EQ(Sum->Operator->Name, "_plus_");
  EXPECT_FALSE(Sum->NegateOperator);
  auto *Ne = llvm::cast<BinaryExpr>(llvm::cast<ReturnStmt>(P.body()[1])->Value);
  EXPECT_EQ(Ne->Operator->Name, "_eq_");
  EXPECT_TRUE(Ne->NegateOperator);
  EXPECT_TRUE(Ne->Ty->isBool());
}

TEST(SemaClassTest, CopiesOfClassesThatCannotBeCopiedAreErrors) {
  // Vec without copy thunk and not byte-copyable; only the assign thunk.
  auto NotCopyable = [](NativeRegistry &R) {
    auto &Vec = const_cast<NativeClass &>(*R.getWorld()->findClass("Vec"));
    Vec.CopiesAsBytes = false;
    Vec.Assign = "assign";
    Vec.DefaultConstructible = true;
  };
  ParsedWithWorld P("func f(Vec a) : Vec\n"
                    "    Vec b\n"
                    "    Vec c = b\n"
                    "    b = c\n"
                    "    b.move(1)\n"
                    "    return b\n"
                    "task t()\n"
                    "    Vec d\n"
                    "    Vec e = d\n",
                    NotCopyable);
  EXPECT_FALSE(P.OK);
  std::string Head =
      "class 'W::Vec' cannot be copied: register a copy constructor for it "
      "(or .copyAsBytes()); ";
  // The assignment and the task's initialiser assign: the assign thunk
  // does. The parameter, the func's initialiser and `return` construct.
  EXPECT_EQ(P.messages(), (Msgs{Head + "a parameter is a copy",
                                Head + "an initialiser is a copy",
                                Head + "a returned value is a copy"}));
}

TEST(SemaClassTest, DefaultConstructionNeedsADefaultConstructor) {
  const char *Source = "func f(Vec a) : Vec\n"
                       "    Vec b\n"
                       "    Vec c = a\n"
                       "    return c\n"
                       "task t(Vec p)\n"
                       "    Vec d = p\n";
  // Without default constructor and with a destructor: the func's local
  // without initial value and everything the task holds are errors.
  auto NoDefault = [](NativeRegistry &R) {
    auto &Vec = const_cast<NativeClass &>(*R.getWorld()->findClass("Vec"));
    Vec.DefaultConstructible = false;
    Vec.TriviallyDestructible = false;
    Vec.Destroy = "destroy";
  };
  ParsedWithWorld P(Source, NoDefault);
  EXPECT_FALSE(P.OK);
  std::string Head = "class 'W::Vec' has no default constructor: ";
  std::string InTask = Head + "a task constructs its parameters and locals "
                              "when it starts, so register a default "
                              "constructor for it, or pass it to a func "
                              "instead";
  // Signatures are checked before bodies: the task's parameter first.
  EXPECT_EQ(P.messages(),
            (Msgs{InTask, Head + "give 'b' an initial value", InTask}));
  // Byte-copyable and trivially destructible: zero bytes are a value.
  auto ZeroIsAValue = [](NativeRegistry &R) {
    auto &Vec = const_cast<NativeClass &>(*R.getWorld()->findClass("Vec"));
    Vec.DefaultConstructible = false;
    Vec.CopiesAsBytes = true;
    Vec.TriviallyDestructible = true;
  };
  ParsedWithWorld Q(Source, ZeroIsAValue);
  EXPECT_TRUE(Q.OK) << Q.messages().front();
}

TEST(SemaClassTest, InputIsReadOnlyAndOutputWriteOnly) {
  ParsedWithWorld P("task t()\n"
                    "    input.v.move(1)\n"
                    "    float a = input.v.len()\n"
                    "    float b = output.v.len()\n"
                    "    input.v = output.v\n"
                    "    a = input.v - input.v\n");
  EXPECT_FALSE(P.OK);
  EXPECT_EQ(P.messages(),
            (Msgs{"'input' is read-only; method 'move' is not const and may "
                  "modify it",
                  "'output' is write-only; its value cannot be read",
                  "'input' is read-only",
                  "'output' is write-only; its value cannot be read",
                  "invalid operands to binary '-' ('W::Vec' and 'W::Vec')"}));
}

} // namespace
