//===- Index.cpp - one walk over the checked tree -------------------------===//
//
// Every name the source writes becomes an Occurrence: declarations where
// they are declared, uses where Sema resolved them (NameExpr's Local,
// Param, Callable, ...; MemberExpr's Resolved; a type name's Ty). The
// qualifiers of `M::name` and `M::Enum::value` name their module and enum.
//
//===----------------------------------------------------------------------===//
#include "bsc/LSP/Index.h"

using namespace bsc;
using namespace bsc::lsp;

namespace {
class IndexBuilder {
public:
  explicit IndexBuilder(Index &Out) : Out(Out) {}

  void module(const ModuleAST &M);

private:
  void add(llvm::SMRange R, Symbol S, bool Def = false) {
    if (S && R.isValid())
      Out.Occurrences.push_back({R, S, Def});
  }
  void add(const Ident &I, Symbol S, bool Def = false) {
    add(I.getRange(), S, Def);
  }
  static Symbol decl(const Decl *D) { return {Symbol::Decl, D, 0}; }
  Symbol moduleNamed(llvm::StringRef Name) const;
  Symbol enumSymbol(const NativeEnum *E) const;
  Symbol typeSymbol(const Type *Ty) const;
  /// `Q`, whose last part stands for `Last`: the parts before it name a
  /// module or, before an enum value, its enum.
  void qualified(const QualifiedName &Q, Symbol Last,
                 const NativeEnum *EnumOfLast = nullptr);
  void callable(const CallableDecl &C);
  void param(const ParamDecl &P);
  void stmt(const Stmt *S);
  void expr(const Expr *E);
  void name(const NameExpr &N);
  /// The enum of a named task state `Enum::value` or `M::Enum::value`.
  const NativeEnum *namedStateEnum(const QualifiedName &Q) const;

  Index &Out;
  const ModuleAST *Current = nullptr;
};
} // namespace

Symbol IndexBuilder::moduleNamed(llvm::StringRef Name) const {
  if (Current->Name == Name)
    return {Symbol::ScriptModule, Current, 0};
  for (const RequireDecl &R : Current->Requires)
    if (R.Name == Name) {
      if (R.Script)
        return {Symbol::ScriptModule, R.Script, 0};
      if (R.Native)
        return {Symbol::NativeModule, R.Native, 0};
    }
  return {};
}

Symbol IndexBuilder::enumSymbol(const NativeEnum *E) const {
  if (const EnumDecl *D = Out.getScriptEnum(E))
    return decl(D);
  return E ? Symbol{Symbol::NativeEnum, E, 0} : Symbol{};
}

Symbol IndexBuilder::typeSymbol(const Type *Ty) const {
  if (!Ty)
    return {};
  if (Ty->isEnum())
    return enumSymbol(Ty->getEnum());
  if (Ty->isClass() && Ty->getClass())
    return {Symbol::NativeClass, Ty->getClass(), 0};
  return {};
}

void IndexBuilder::qualified(const QualifiedName &Q, Symbol Last,
                             const NativeEnum *EnumOfLast) {
  if (Q.Parts.empty())
    return;
  size_t N = Q.Parts.size();
  add(Q.Parts[N - 1], Last);
  for (size_t I = 0; I + 1 < N; ++I) {
    if (EnumOfLast && I + 2 == N)
      add(Q.Parts[I], enumSymbol(EnumOfLast));
    else
      add(Q.Parts[I], moduleNamed(Q.Parts[I].Name));
  }
}

void IndexBuilder::module(const ModuleAST &M) {
  Current = &M;
  for (const RequireDecl &R : M.Requires)
    add(R.Range, moduleNamed(R.Name));
  for (const EnumDecl *E : M.Enums) {
    add(E->getName(), decl(E), true);
    for (unsigned I = 0; I < E->Enumerators.size(); ++I)
      add(E->Enumerators[I].Name, {Symbol::Enumerator, E, I}, true);
  }
  for (const ConstDecl *C : M.Consts) {
    add(C->getName(), decl(C), true);
    qualified(C->TypeName, typeSymbol(C->Ty));
    expr(C->Init);
  }
  for (const CallableDecl *C : M.Decls)
    callable(*C);
}

void IndexBuilder::callable(const CallableDecl &C) {
  add(C.getName(), decl(&C), true);
  for (const ParamDecl *P : C.Params)
    param(*P);
  if (const auto *F = llvm::dyn_cast<FuncDecl>(&C))
    qualified(F->ResultTypeName, typeSymbol(F->ResultTy));
  stmt(C.Body);
}

void IndexBuilder::param(const ParamDecl &P) {
  add(P.getName(), decl(&P), true);
  qualified(P.TypeName, typeSymbol(P.Ty));
  expr(P.Default);
}

void IndexBuilder::stmt(const Stmt *S) {
  if (!S)
    return;
  if (const auto *D = llvm::dyn_cast<DeclStmt>(S)) {
    const VarDecl *V = D->Var;
    add(V->getName(), decl(V), true);
    qualified(V->TypeName, typeSymbol(V->Ty));
    expr(V->Init);
    return;
  }
  if (const auto *F = llvm::dyn_cast<FuncDeclStmt>(S)) {
    callable(*F->Func);
    return;
  }
  // Every other statement only holds statements and expressions.
  forEachChild(*S, [&](const Node &C) {
    if (const auto *E = llvm::dyn_cast<Expr>(&C))
      expr(E);
    else
      stmt(llvm::cast<Stmt>(&C));
  });
}

void IndexBuilder::name(const NameExpr &N) {
  switch (N.Kind) {
  case NameKind::Local:
    qualified(N.Name, decl(N.Local));
    return;
  case NameKind::Param:
    qualified(N.Name, decl(N.Param));
    return;
  case NameKind::Callable:
    qualified(N.Name, decl(N.Callable));
    return;
  case NameKind::NativeFunction:
    qualified(N.Name, {Symbol::NativeFunction, N.NativeFn, 0});
    return;
  case NameKind::Constant:
    qualified(N.Name, decl(N.Const));
    return;
  case NameKind::EnumValue: {
    if (N.BuiltinState || N.Name.Parts.size() < 2)
      return;
    // A named task state has type TaskState: its enum is found by name.
    const NativeEnum *E = N.Ty && N.Ty->isEnum() ? N.Ty->getEnum()
                                                 : namedStateEnum(N.Name);
    if (!E)
      return;
    llvm::StringRef Value = N.Name.Parts.back().Name;
    Symbol S;
    if (const EnumDecl *D = Out.getScriptEnum(E)) {
      for (unsigned I = 0; I < D->Enumerators.size(); ++I)
        if (D->Enumerators[I].Name.Name == Value)
          S = {Symbol::Enumerator, D, I};
    } else if (E) {
      for (unsigned I = 0; I < E->Values.size(); ++I)
        if (E->Values[I].Name == Value)
          S = {Symbol::NativeEnumValue, E, I};
    }
    qualified(N.Name, S, E);
    return;
  }
  case NameKind::Input:
  case NameKind::Output:
    add(N.Name.Parts.back(),
        {Symbol::Global, nullptr, N.Kind == NameKind::Output ? 1u : 0u});
    return;
  case NameKind::Unresolved:
    return;
  }
}

const NativeEnum *IndexBuilder::namedStateEnum(const QualifiedName &Q) const {
  size_t N = Q.Parts.size();
  llvm::StringRef Enum = Q.Parts[N - 2].Name;
  Symbol In = N >= 3 ? moduleNamed(Q.Parts[N - 3].Name)
                     : Symbol{Symbol::ScriptModule, Current, 0};
  for (const EnumDecl *D : Out.ScriptEnums)
    if (D->getName().Name == Enum && D->Module == In.Ptr)
      return &D->Values;
  return nullptr;
}

void IndexBuilder::expr(const Expr *E) {
  if (!E)
    return;
  if (E->Ty && E->getRange().isValid())
    Out.Expressions.push_back({E->getRange(), E->Ty});
  switch (E->getKind()) {
  case NodeKind::NameExpr:
    name(*llvm::cast<NameExpr>(E));
    return;
  case NodeKind::MemberExpr: {
    const auto *M = llvm::cast<MemberExpr>(E);
    expr(M->Base);
    if (M->Resolved)
      add(M->Member, {Symbol::NativeFunction, M->Resolved, 0});
    return;
  }
  case NodeKind::IndexExpr:
    expr(llvm::cast<IndexExpr>(E)->Base);
    expr(llvm::cast<IndexExpr>(E)->Index);
    return;
  case NodeKind::CallExpr: {
    const auto *C = llvm::cast<CallExpr>(E);
    expr(C->Callee);
    // The arguments Sema appended from defaults are not in the source.
    for (size_t I = 0; I + C->NumDefaultArgs < C->Args.size(); ++I)
      expr(C->Args[I]);
    return;
  }
  case NodeKind::UnaryExpr:
    expr(llvm::cast<UnaryExpr>(E)->Operand);
    return;
  case NodeKind::BinaryExpr:
    expr(llvm::cast<BinaryExpr>(E)->LHS);
    expr(llvm::cast<BinaryExpr>(E)->RHS);
    return;
  case NodeKind::TaskStateExpr: {
    const auto *T = llvm::cast<TaskStateExpr>(E);
    qualified(T->TaskName, T->Task ? decl(T->Task) : Symbol());
    return;
  }
  case NodeKind::ConversionExpr:
    expr(llvm::cast<ConversionExpr>(E)->Operand);
    return;
  case NodeKind::IntLiteralExpr:
  case NodeKind::FloatLiteralExpr:
  case NodeKind::BoolLiteralExpr:
  case NodeKind::StringLiteralExpr:
  case NodeKind::ErrorExpr:
    return;
#define EXPR(Class)
#define NODE(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    llvm_unreachable("not an expression");
  }
}

const Occurrence *Index::findAt(llvm::SMLoc Loc) const {
  const char *P = Loc.getPointer();
  for (const Occurrence &O : Occurrences)
    if (O.Range.Start.getPointer() <= P && P <= O.Range.End.getPointer())
      return &O;
  return nullptr;
}

const TypedRange *Index::findExpressionAt(llvm::SMLoc Loc) const {
  const char *P = Loc.getPointer();
  const TypedRange *Best = nullptr;
  for (const TypedRange &T : Expressions)
    if (T.Range.Start.getPointer() <= P && P <= T.Range.End.getPointer() &&
        // Equal ranges: the later is inside (an implicit conversion's
        // operand), and shows the type as written.
        (!Best || T.Range.End.getPointer() - T.Range.Start.getPointer() <=
                      Best->Range.End.getPointer() -
                          Best->Range.Start.getPointer()))
      Best = &T;
  return Best;
}

const EnumDecl *Index::getScriptEnum(const bsc::NativeEnum *E) const {
  for (const EnumDecl *D : ScriptEnums)
    if (&D->Values == E)
      return D;
  return nullptr;
}

Index lsp::buildIndex(llvm::ArrayRef<ModuleAST *> Modules) {
  Index Out;
  for (const ModuleAST *M : Modules)
    for (const EnumDecl *E : M->Enums)
      Out.ScriptEnums.push_back(E);
  IndexBuilder B(Out);
  for (const ModuleAST *M : Modules)
    B.module(*M);
  return Out;
}
