//===- ASTDumper.cpp - the tree printed by `bsc --emit=ast` ----------------===//
//
// One node per line, children indented by two spaces, so that FileCheck
// tests can match a construct with CHECK-NEXT lines:
//
//   Module 'fib'
//     Requires 'io' <3:10>
//     TaskDecl 'fib' <5:1>
//       BlockStmt <6:5>
//         DeclStmt <6:5>
//           VarDecl 'a' 'int' <6:5>
//             IntLiteralExpr 0 <6:13>
//
// A line is the node kind, its key attributes (names in quotes, type names
// as written), what Sema filled in when it has run (`: int` for the type of
// an expression or declaration, `-> local` for a resolved name, the kind of
// a call, `resume 2` for a yield) and the location `<line:col>` of its first
// character. A missing part of a `for` head prints as `<<null>>`.
//
//===----------------------------------------------------------------------===//
#include "bsc/AST/AST.h"
#include "llvm/ADT/APFloat.h"
#include "llvm/ADT/SmallString.h"
#include "llvm/Support/ErrorHandling.h"
#include "llvm/Support/raw_ostream.h"
#include <algorithm>

using namespace bsc;

namespace {
class Dumper {
public:
  Dumper(const ModuleAST &M, llvm::raw_ostream &OS) : Source(M.Source), OS(OS) {
    LineStarts.push_back(0);
    for (size_t I = 0, E = Source.size(); I != E; ++I)
      if (Source[I] == '\n')
        LineStarts.push_back(I + 1);
  }

  void dumpModule(const ModuleAST &M);

private:
  void dumpDecl(const Decl *D);
  void dumpStmt(const Stmt *S);
  void dumpExpr(const Expr *E);
  void dumpNull() { line() << "<<null>>\n"; }

  llvm::raw_ostream &line() { return OS.indent(Indent * 2); }
  void loc(llvm::SMLoc L);
  void type(const Type *T) {
    if (T)
      OS << " : " << T->getName();
  }
  void children(std::initializer_list<const Node *> Nodes);
  void child(const Node *N);

  llvm::StringRef Source;
  llvm::raw_ostream &OS;
  std::vector<size_t> LineStarts;
  unsigned Indent = 0;
};
} // namespace

void Dumper::loc(llvm::SMLoc L) {
  const char *P = L.getPointer();
  if (!P || P < Source.begin() || P > Source.end()) {
    OS << " <invalid>\n";
    return;
  }
  size_t Offset = P - Source.begin();
  auto It = std::upper_bound(LineStarts.begin(), LineStarts.end(), Offset);
  size_t Line = It - LineStarts.begin();
  OS << " <" << Line << ':' << (Offset - LineStarts[Line - 1] + 1) << ">\n";
}

void Dumper::child(const Node *N) {
  ++Indent;
  if (!N)
    dumpNull();
  else if (auto *D = llvm::dyn_cast<Decl>(N))
    dumpDecl(D);
  else if (auto *S = llvm::dyn_cast<Stmt>(N))
    dumpStmt(S);
  else
    dumpExpr(llvm::cast<Expr>(N));
  --Indent;
}

void Dumper::children(std::initializer_list<const Node *> Nodes) {
  for (const Node *N : Nodes)
    child(N);
}

void Dumper::dumpModule(const ModuleAST &M) {
  line() << "Module '" << M.Name << "'\n";
  ++Indent;
  for (const RequireDecl &R : M.Requires) {
    line() << "Requires '" << R.Name << "'";
    loc(R.Range.Start);
  }
  for (const EnumDecl *D : M.Enums)
    dumpDecl(D);
  for (const ConstDecl *D : M.Consts)
    dumpDecl(D);
  for (const CallableDecl *D : M.Decls)
    dumpDecl(D);
  --Indent;
}

void Dumper::dumpDecl(const Decl *D) {
  line() << getNodeKindName(D->getKind()) << " '" << D->getName().Name << "'";
  switch (D->getKind()) {
  case NodeKind::FuncDecl: {
    auto *F = llvm::cast<FuncDecl>(D);
    if (!F->ResultTypeName.empty())
      OS << " '" << F->ResultTypeName.str() << "'";
    if (F->EnclosingTask)
      OS << " in '" << F->EnclosingTask->getName().Name << "'";
    if (F->ResultTy)
      type(F->ResultTy);
    break;
  }
  case NodeKind::TaskDecl:
    break;
  case NodeKind::ParamDecl: {
    auto *P = llvm::cast<ParamDecl>(D);
    OS << " '" << P->TypeName.str() << "'";
    type(P->Ty);
    loc(D->getLoc());
    if (P->Default)
      child(P->Default);
    return;
  }
  case NodeKind::VarDecl: {
    auto *V = llvm::cast<VarDecl>(D);
    OS << " '" << V->TypeName.str() << "'";
    type(V->Ty);
    if (V->ReadBeforeDeclared)
      OS << " zeroed-at-reset";
    loc(D->getLoc());
    if (V->Init)
      child(V->Init);
    return;
  }
  case NodeKind::EnumDecl: {
    auto *E = llvm::cast<EnumDecl>(D);
    if (E->IsTaskState)
      OS << " : TaskState";
    loc(D->getLoc());
    ++Indent;
    for (size_t I = 0; I != E->Enumerators.size(); ++I) {
      const Enumerator &En = E->Enumerators[I];
      line() << "Enumerator '" << En.Name.Name << "'";
      // After Sema the number it got, before it the one written.
      if (I < E->Values.Values.size())
        OS << " = " << E->Values.Values[I].Number;
      else if (En.Explicit)
        OS << " = " << *En.Explicit;
      loc(En.Name.Loc);
    }
    --Indent;
    return;
  }
  case NodeKind::ConstDecl: {
    auto *C = llvm::cast<ConstDecl>(D);
    OS << " '" << C->TypeName.str() << "'";
    type(C->Ty);
    loc(D->getLoc());
    if (C->Init)
      child(C->Init);
    return;
  }
#define DECL(Class)
#define NODE(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    llvm_unreachable("not a declaration");
  }
  loc(D->getLoc());
  auto *C = llvm::cast<CallableDecl>(D);
  for (const ParamDecl *P : C->Params)
    child(P);
  child(C->Body);
}

void Dumper::dumpStmt(const Stmt *S) {
  line() << getNodeKindName(S->getKind());
  switch (S->getKind()) {
  case NodeKind::BlockStmt: {
    loc(S->getLoc());
    for (const Stmt *Sub : llvm::cast<BlockStmt>(S)->Stmts)
      child(Sub);
    return;
  }
  case NodeKind::DeclStmt:
    loc(S->getLoc());
    child(llvm::cast<DeclStmt>(S)->Var);
    return;
  case NodeKind::FuncDeclStmt:
    loc(S->getLoc());
    child(llvm::cast<FuncDeclStmt>(S)->Func);
    return;
  case NodeKind::AssignStmt: {
    auto *A = llvm::cast<AssignStmt>(S);
    OS << " '" << getSpelling(A->Op) << "'";
    loc(S->getLoc());
    children({A->Target, A->Value});
    return;
  }
  case NodeKind::ExprStmt:
    loc(S->getLoc());
    child(llvm::cast<ExprStmt>(S)->E);
    return;
  case NodeKind::IfStmt: {
    auto *I = llvm::cast<IfStmt>(S);
    if (I->Else)
      OS << " has_else";
    loc(S->getLoc());
    children({I->Cond, I->Then});
    if (I->Else)
      child(I->Else);
    return;
  }
  case NodeKind::ForStmt: {
    auto *F = llvm::cast<ForStmt>(S);
    loc(S->getLoc());
    children({F->Init, F->Cond, F->Step, F->Body});
    return;
  }
  case NodeKind::BreakStmt:
  case NodeKind::ContinueStmt:
  case NodeKind::ErrorStmt:
    loc(S->getLoc());
    return;
  case NodeKind::ReturnStmt:
    loc(S->getLoc());
    if (auto *V = llvm::cast<ReturnStmt>(S)->Value)
      child(V);
    return;
  case NodeKind::AssertStmt: {
    auto *A = llvm::cast<AssertStmt>(S);
    if (A->IsAssume)
      OS << " assume";
    loc(S->getLoc());
    child(A->Cond);
    if (A->Message)
      child(A->Message);
    return;
  }
  case NodeKind::YieldStmt: {
    auto *Y = llvm::cast<YieldStmt>(S);
    if (Y->ResumePoint)
      OS << " resume " << Y->ResumePoint;
    loc(S->getLoc());
    if (Y->Value)
      child(Y->Value);
    return;
  }
#define STMT(Class)
#define NODE(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    llvm_unreachable("not a statement");
  }
}

static llvm::StringRef getNameKindName(NameKind K) {
  switch (K) {
  case NameKind::Unresolved:
    return "";
  case NameKind::Local:
    return "local";
  case NameKind::Param:
    return "param";
  case NameKind::Callable:
    return "callable";
  case NameKind::NativeFunction:
    return "native";
  case NameKind::EnumValue:
    return "enum";
  case NameKind::Constant:
    return "const";
  case NameKind::Input:
    return "input";
  case NameKind::Output:
    return "output";
  }
  llvm_unreachable("unknown name kind");
}

static llvm::StringRef getCallKindName(CallKind K) {
  switch (K) {
  case CallKind::Unresolved:
    return "";
  case CallKind::Func:
    return "func";
  case CallKind::Task:
    return "task";
  case CallKind::NativeFunction:
    return "native";
  case CallKind::Method:
    return "method";
  }
  llvm_unreachable("unknown call kind");
}

static llvm::StringRef getMemberKindName(NativeFunction::MemberKind K) {
  switch (K) {
  case NativeFunction::Function:
    return "function";
  case NativeFunction::Method:
    return "method";
  case NativeFunction::Field:
    return "field";
  case NativeFunction::Property:
    return "property";
  }
  llvm_unreachable("unknown member kind");
}

void Dumper::dumpExpr(const Expr *E) {
  line() << getNodeKindName(E->getKind());
  switch (E->getKind()) {
  case NodeKind::IntLiteralExpr:
    OS << ' ' << llvm::cast<IntLiteralExpr>(E)->Value;
    break;
  case NodeKind::FloatLiteralExpr: {
    llvm::SmallString<16> Str;
    llvm::APFloat(llvm::cast<FloatLiteralExpr>(E)->Value).toString(Str);
    OS << ' ' << Str;
    break;
  }
  case NodeKind::BoolLiteralExpr:
    OS << (llvm::cast<BoolLiteralExpr>(E)->Value ? " true" : " false");
    break;
  case NodeKind::StringLiteralExpr:
    OS << " \"";
    OS.write_escaped(llvm::cast<StringLiteralExpr>(E)->Value);
    OS << '"';
    break;
  case NodeKind::NameExpr: {
    auto *N = llvm::cast<NameExpr>(E);
    OS << " '" << N->Name.str() << "'";
    if (N->Kind != NameKind::Unresolved)
      OS << " -> " << getNameKindName(N->Kind);
    if (N->Kind == NameKind::EnumValue)
      OS << ' ' << N->EnumValue;
    break;
  }
  case NodeKind::MemberExpr: {
    auto *ME = llvm::cast<MemberExpr>(E);
    OS << " '." << ME->Member.Name << "'";
    if (ME->Resolved)
      OS << " -> " << getMemberKindName(ME->Resolved->Kind);
    break;
  }
  case NodeKind::IndexExpr: {
    auto *I = llvm::cast<IndexExpr>(E);
    if (I->Extent)
      OS << " of " << I->Extent << " stride " << I->Stride
         << (I->ConstIndex ? " constant" : " clamped");
    break;
  }
  case NodeKind::CallExpr: {
    auto *C = llvm::cast<CallExpr>(E);
    if (C->Kind != CallKind::Unresolved)
      OS << ' ' << getCallKindName(C->Kind);
    if (C->NumDefaultArgs)
      OS << " defaults " << C->NumDefaultArgs;
    break;
  }
  case NodeKind::UnaryExpr: {
    auto *U = llvm::cast<UnaryExpr>(E);
    OS << " '" << getSpelling(U->Op) << "'";
    if (U->Operator)
      OS << " -> " << U->Operator->Name;
    break;
  }
  case NodeKind::BinaryExpr: {
    auto *B = llvm::cast<BinaryExpr>(E);
    OS << " '" << getSpelling(B->Op) << "'";
    if (B->Operator)
      OS << " -> " << (B->NegateOperator ? "!" : "") << B->Operator->Name;
    if (B->StateTest == BinaryExpr::StateKindTest::Running)
      OS << " kind running";
    else if (B->StateTest == BinaryExpr::StateKindTest::Failure)
      OS << " kind failure";
    break;
  }
  case NodeKind::TaskStateExpr:
    OS << " '" << llvm::cast<TaskStateExpr>(E)->TaskName.str() << "'";
    break;
  case NodeKind::ConversionExpr: {
    auto *C = llvm::cast<ConversionExpr>(E);
    if (C->Implicit)
      OS << " implicit";
    else
      OS << " '" << C->TargetName.str() << "'";
    break;
  }
  case NodeKind::ErrorExpr:
    break;
#define EXPR(Class)
#define NODE(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    llvm_unreachable("not an expression");
  }
  type(E->Ty);
  loc(E->getLoc());

  switch (E->getKind()) {
  case NodeKind::MemberExpr:
    child(llvm::cast<MemberExpr>(E)->Base);
    return;
  case NodeKind::IndexExpr:
    children({llvm::cast<IndexExpr>(E)->Base, llvm::cast<IndexExpr>(E)->Index});
    return;
  case NodeKind::CallExpr: {
    auto *C = llvm::cast<CallExpr>(E);
    child(C->Callee);
    for (const Expr *A : C->Args)
      child(A);
    return;
  }
  case NodeKind::UnaryExpr:
    child(llvm::cast<UnaryExpr>(E)->Operand);
    return;
  case NodeKind::BinaryExpr:
    children({llvm::cast<BinaryExpr>(E)->LHS, llvm::cast<BinaryExpr>(E)->RHS});
    return;
  case NodeKind::ConversionExpr:
    child(llvm::cast<ConversionExpr>(E)->Operand);
    return;
  case NodeKind::IntLiteralExpr:
  case NodeKind::FloatLiteralExpr:
  case NodeKind::BoolLiteralExpr:
  case NodeKind::StringLiteralExpr:
  case NodeKind::NameExpr:
  case NodeKind::TaskStateExpr:
  case NodeKind::ErrorExpr:
    return;
#define EXPR(Class)
#define NODE(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    llvm_unreachable("not an expression");
  }
}

void bsc::dumpAST(const ModuleAST &M, llvm::raw_ostream &OS) {
  Dumper(M, OS).dumpModule(M);
}
