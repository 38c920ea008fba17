//===- Hover.cpp - what a name or an expression is ------------------------===//
//
// A name shows its declaration (a script's as written, with the doc
// comment above it; registered C++ as b-script sees it, with the C++ it
// binds and, for a class, its fields); any other expression its type.
//
//===----------------------------------------------------------------------===//
#include "Describe.h"
#include "Features.h"

using namespace bsc;
using namespace bsc::lsp;

/// The C++ name a registered member was bound to (the descriptor's), if
/// the registration gave one.
static std::string cppNameOf(const Compilation &C, const NativeFunction &F) {
  for (const bind::BoundModule &M : C.Bindings.Modules) {
    for (const bind::BoundMember &B : M.Functions)
      if (B.Thunk == F.Symbol)
        return B.CppName;
    for (const bind::BoundClass &K : M.Classes)
      for (const bind::BoundMember &B : K.Members)
        if (B.Thunk == F.Symbol)
          return B.CppName;
  }
  return "";
}

static std::string fence(llvm::StringRef Code) {
  return "```bscript\n" + Code.str() + "\n```";
}

static std::string describeClass(const NativeClass &K) {
  std::string S = fence("class " + K.QualifiedName);
  if (!K.CppName.empty())
    S += "\n\nC++ `" + K.CppName + "`, " + std::to_string(K.Size) + " bytes";
  std::string Fields;
  for (const NativeFunction &M : K.Members)
    if (M.isData())
      Fields += "\n- `" + typeName(M.Result) + " " + M.Name + "`" +
                (M.ReadOnly ? " (read-only)" : "");
  if (!Fields.empty())
    S += "\n\nFields:" + Fields;
  return S;
}

static std::string describeDecl(const Analysis &A, const Decl &D) {
  const llvm::SourceMgr &SM = A.C->SM;
  std::string Code, What;
  if (const auto *C = llvm::dyn_cast<CallableDecl>(&D)) {
    Code = headerOf(SM, *C);
    if (C->Module)
      What = "in module `" + C->Module->Name + "`";
  } else if (const auto *P = llvm::dyn_cast<ParamDecl>(&D)) {
    Code = (P->Ty ? P->Ty->getName().str() : P->TypeName.str()) + " " +
           P->getName().Name.str();
    if (P->Owner)
      What = "parameter of `" + P->Owner->getQualifiedName() + "`";
  } else if (const auto *V = llvm::dyn_cast<VarDecl>(&D)) {
    Code = (V->Ty ? V->Ty->getName().str() : V->TypeName.str()) + " " +
           V->getName().Name.str();
    if (V->Owner)
      What = "local of `" + V->Owner->getQualifiedName() + "`";
  } else if (const auto *K = llvm::dyn_cast<ConstDecl>(&D)) {
    Code = "const " + (K->Ty ? K->Ty->getName().str() : K->TypeName.str()) +
           " " + K->getName().Name.str();
  } else if (const auto *E = llvm::dyn_cast<EnumDecl>(&D)) {
    Code = "enum " + E->getName().Name.str() +
           (E->IsTaskState ? " : TaskState" : "");
    for (const NativeEnum::Value &V : E->Values.Values)
      Code += "\n    " + V.Name + " = " + std::to_string(V.Number);
  }
  std::string S = fence(Code);
  if (!What.empty())
    S += "\n\n" + What;
  // Module-level declarations have doc comments; a parameter's line is
  // its task's, whose comment is not about it.
  bool Documented = llvm::isa<CallableDecl, ConstDecl, EnumDecl>(D);
  std::string Doc = Documented ? docCommentOf(SM, D) : "";
  if (!Doc.empty())
    S += "\n\n" + Doc;
  return S;
}

static std::string describe(const Analysis &A, const Symbol &S) {
  const Compilation &C = *A.C;
  switch (S.K) {
  case Symbol::Decl:
    return describeDecl(A, *static_cast<const Decl *>(S.Ptr));
  case Symbol::Enumerator: {
    // An enum with errors (a name given twice) has fewer values than
    // enumerators: the value is looked up by name.
    const auto *E = static_cast<const EnumDecl *>(S.Ptr);
    llvm::StringRef Name = E->Enumerators[S.Index].Name.Name;
    std::string Text = E->getName().Name.str() + "::" + Name.str();
    for (const NativeEnum::Value &V : E->Values.Values)
      if (V.Name == Name)
        return fence(Text + " = " + std::to_string(V.Number));
    return fence(Text);
  }
  case Symbol::NativeFunction: {
    const auto *F = static_cast<const NativeFunction *>(S.Ptr);
    std::string Text = fence(signatureOf(*F, moduleOf(C, *F)));
    std::string Cpp = cppNameOf(C, *F);
    if (!Cpp.empty())
      Text += "\n\nC++ `" + Cpp + "`";
    if (F->Owner && !F->isData() && !F->hasSelf())
      Text += "\n\nconstructor of `" + F->Owner->QualifiedName + "`";
    return Text;
  }
  case Symbol::NativeClass:
    return describeClass(*static_cast<const NativeClass *>(S.Ptr));
  case Symbol::NativeEnum: {
    const auto *E = static_cast<const NativeEnum *>(S.Ptr);
    std::string Code =
        "enum " + (E->Module ? E->Module->Name + "::" : "") + E->Name;
    for (const NativeEnum::Value &V : E->Values)
      Code += "\n    " + V.Name + " = " + std::to_string(V.Number);
    return fence(Code);
  }
  case Symbol::NativeEnumValue: {
    const auto *E = static_cast<const NativeEnum *>(S.Ptr);
    return fence(E->Name + "::" + E->Values[S.Index].Name + " = " +
                 std::to_string(E->Values[S.Index].Number));
  }
  case Symbol::NativeConstant:
    return fence("const " + static_cast<const NativeConstant *>(S.Ptr)->Name);
  case Symbol::ScriptModule: {
    const auto *M = static_cast<const ModuleAST *>(S.Ptr);
    return fence("module " + M->Name) + "\n\n`" + M->Path + "`";
  }
  case Symbol::NativeModule: {
    const auto *M = static_cast<const NativeModule *>(S.Ptr);
    return fence("module " + M->Name) + "\n\nregistered in C++" +
           (M->File.empty() ? "" : " (`" + M->File + "`)");
  }
  case Symbol::Global: {
    const NativeModule *World = C.Checked.World;
    const NativeClass *K =
        World ? (S.Index ? World->Output : World->Input) : nullptr;
    std::string Name = S.Index ? "output" : "input";
    if (!K)
      return fence(Name);
    return fence(K->QualifiedName + " " + Name) + "\n\n" + describeClass(*K);
  }
  case Symbol::None:
    break;
  }
  return "";
}

llvm::json::Value lsp::hover(const Analysis &A, llvm::SMLoc Loc) {
  std::string Text;
  llvm::SMRange Range;
  if (const Occurrence *O = A.Idx.findAt(Loc)) {
    Text = describe(A, O->Sym);
    Range = O->Range;
  } else if (const TypedRange *T = A.Idx.findExpressionAt(Loc)) {
    if (T->Ty && !T->Ty->isError())
      Text = fence(T->Ty->getName().str());
    Range = T->Range;
  }
  if (Text.empty())
    return nullptr;
  return llvm::json::Object{
      {"contents",
       llvm::json::Object{{"kind", "markdown"}, {"value", Text}}},
      {"range", A.getRange(Range)}};
}
