//===- Completion.cpp - what may be written here, and a call's signature --===//
//
// Half-typed text does not parse, so both read the text before the cursor
// (`Motion::`, `input.ball.`, `walkTo(a, `) and look the words up in the
// checked behavior of the last analysis: modules and their members, the
// classes of `input`, `output` and typed names, enums, and the names in
// scope at the cursor.
//
//===----------------------------------------------------------------------===//
#include "Describe.h"
#include "Features.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSet.h"

using namespace bsc;
using namespace bsc::lsp;

namespace {
/// LSP's CompletionItemKind numbers.
enum ItemKind {
  Method = 2,
  Function = 3,
  Field = 5,
  Variable = 6,
  Class = 7,
  Module = 9,
  Enum = 13,
  Keyword = 14,
  EnumMember = 20,
  Constant = 21,
  Event = 23,
};

class Completer {
public:
  Completer(const Analysis &A, unsigned BufferID, llvm::SMLoc Loc)
      : A(A), Loc(Loc) {
    for (const ModuleAST *M : A.C->Modules)
      if (M->BufferID == BufferID)
        Here = M;
    llvm::StringRef Buf = A.C->SM.getMemoryBuffer(BufferID)->getBuffer();
    const char *LineStart = Loc.getPointer();
    while (LineStart != Buf.begin() && LineStart[-1] != '\n')
      --LineStart;
    Before = llvm::StringRef(LineStart, Loc.getPointer() - LineStart);
  }

  llvm::json::Value complete();
  llvm::json::Value signature();

private:
  void item(llvm::StringRef Label, int Kind, llvm::StringRef Detail = "") {
    if (Seen.insert(Label).second)
      Items.push_back(llvm::json::Object{
          {"label", Label.str()}, {"kind", Kind}, {"detail", Detail.str()}});
  }
  /// The words of the chain ending before the cursor (`a::b.c.`): each
  /// with the separator after it.
  std::vector<std::pair<std::string, std::string>> chain(llvm::StringRef Text);
  const ModuleAST *scriptModule(llvm::StringRef Name) const;
  const NativeModule *nativeModule(llvm::StringRef Name) const;
  const NativeClass *classOfChain(
      const std::vector<std::pair<std::string, std::string>> &Words) const;
  const Type *typeOfName(llvm::StringRef Name) const;
  void moduleMembers(llvm::StringRef Name);
  void classMembers(const NativeClass &K);
  void inScope();

  const Analysis &A;
  llvm::SMLoc Loc;
  const ModuleAST *Here = nullptr;
  llvm::StringRef Before;
  llvm::json::Array Items;
  llvm::StringSet<> Seen;
};
} // namespace

std::vector<std::pair<std::string, std::string>>
Completer::chain(llvm::StringRef Text) {
  std::vector<std::pair<std::string, std::string>> Words;
  // Drop the word being typed, then read `word sep` pairs backwards.
  Text = Text.rtrim(llvm::StringRef("abcdefghijklmnopqrstuvwxyz"
                                    "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_"));
  while (true) {
    std::string Sep;
    if (Text.ends_with("::"))
      Sep = "::";
    else if (Text.ends_with("."))
      Sep = ".";
    else
      break;
    Text = Text.drop_back(Sep.size());
    size_t Start = Text.size();
    while (Start && (llvm::isAlnum(Text[Start - 1]) || Text[Start - 1] == '_'))
      --Start;
    if (Start == Text.size())
      break; // `f().x` and `a[1].x`: not followed.
    Words.insert(Words.begin(), {Text.substr(Start).str(), Sep});
    Text = Text.take_front(Start);
  }
  return Words;
}

const ModuleAST *Completer::scriptModule(llvm::StringRef Name) const {
  if (Here && Here->Name == Name)
    return Here;
  for (const ModuleAST *M : A.C->Modules)
    if (M->Name == Name)
      return M;
  return nullptr;
}

const NativeModule *Completer::nativeModule(llvm::StringRef Name) const {
  return A.C->Natives.find(Name);
}

/// The type of a parameter or local named `Name` declared before the
/// cursor in this file (the nearest), or of a module constant.
const Type *Completer::typeOfName(llvm::StringRef Name) const {
  const Type *Found = nullptr;
  for (const Occurrence &O : A.Idx.Occurrences) {
    if (!O.IsDefinition || O.Sym.K != Symbol::Decl ||
        O.Range.Start.getPointer() > Loc.getPointer() ||
        llvm::StringRef(O.Range.Start.getPointer(),
                        O.Range.End.getPointer() - O.Range.Start.getPointer()) !=
            Name)
      continue;
    const auto *D = static_cast<const Decl *>(O.Sym.Ptr);
    if (const auto *V = llvm::dyn_cast<VarDecl>(D))
      Found = V->Ty;
    else if (const auto *P = llvm::dyn_cast<ParamDecl>(D))
      Found = P->Ty;
  }
  return Found;
}

const NativeClass *Completer::classOfChain(
    const std::vector<std::pair<std::string, std::string>> &Words) const {
  const NativeClass *K = nullptr;
  for (size_t I = 0; I < Words.size(); ++I) {
    const auto &[Word, Sep] = Words[I];
    if (Sep != ".")
      return nullptr;
    if (I == 0) {
      const NativeModule *World = A.C->Checked.World;
      if (Word == "input" && World)
        K = World->Input;
      else if (Word == "output" && World)
        K = World->Output;
      else if (const Type *Ty = typeOfName(Word))
        K = Ty->isClass() ? Ty->getClass() : nullptr;
    } else if (K) {
      const NativeFunction *M = K->findMember(Word);
      K = M && M->Result.TheCode == NativeType::Class && !M->Result.isArray()
              ? M->Result.TheClass
              : nullptr;
    }
    if (!K)
      return nullptr;
  }
  return K;
}

void Completer::classMembers(const NativeClass &K) {
  for (const NativeFunction &M : K.Members) {
    if (M.Name.empty() || M.Name[0] == '_')
      continue; // Operators (`_plus_`) are written as operators.
    item(M.Name, M.isData() ? Field : Method, signatureOf(M, ""));
  }
}

void Completer::moduleMembers(llvm::StringRef Name) {
  if (Name == "TaskState") {
    for (const char *S : {"done", "running", "failure"})
      item(S, EnumMember, "TaskState");
    return;
  }
  if (const ModuleAST *M = scriptModule(Name)) {
    for (const CallableDecl *C : M->Decls)
      item(C->getName().Name, llvm::isa<TaskDecl>(C) ? Event : Function,
           headerOf(A.C->SM, *C));
    for (const ConstDecl *K : M->Consts)
      item(K->getName().Name, Constant, K->Ty ? K->Ty->getName() : "");
    for (const EnumDecl *E : M->Enums)
      item(E->getName().Name, Enum, "enum");
    return;
  }
  if (const NativeModule *N = nativeModule(Name)) {
    for (const NativeFunction &F : N->Functions)
      item(F.Name, Function, signatureOf(F, N->Name));
    for (const NativeClass &K : N->Classes)
      item(K.Name, Class, K.CppName);
    for (const NativeEnum &E : N->Enums)
      item(E.Name, Enum, "enum");
    for (const NativeConstant &K : N->Constants)
      item(K.Name, Constant, typeName(K.Type));
    return;
  }
  // An enum: `Phase::`, `M::Phase::`, a registered `MotionType::`.
  for (const EnumDecl *E : A.Idx.ScriptEnums)
    if (E->getName().Name == Name)
      for (const NativeEnum::Value &V : E->Values.Values)
        item(V.Name, EnumMember, std::to_string(V.Number));
  for (const auto &M : A.C->Natives.Modules)
    if (const NativeEnum *E = M->findEnum(Name))
      for (const NativeEnum::Value &V : E->Values)
        item(V.Name, EnumMember, std::to_string(V.Number));
}

void Completer::inScope() {
#define KEYWORD(Spelling) item(#Spelling, Keyword);
#include "bsc/Parse/TokenKinds.def"
  for (const char *T : {"int", "float", "bool", "string", "TaskState"})
    item(T, Class, "built-in type");
  item("input", Variable, "the world's input");
  item("output", Variable, "the world's output");
  // Parameters and locals declared before the cursor in the callable
  // around it.
  for (const Occurrence &O : A.Idx.Occurrences) {
    if (!O.IsDefinition || O.Sym.K != Symbol::Decl ||
        O.Range.Start.getPointer() > Loc.getPointer())
      continue;
    const auto *D = static_cast<const Decl *>(O.Sym.Ptr);
    const CallableDecl *Owner = nullptr;
    const Type *Ty = nullptr;
    if (const auto *V = llvm::dyn_cast<VarDecl>(D))
      Owner = V->Owner, Ty = V->Ty;
    else if (const auto *P = llvm::dyn_cast<ParamDecl>(D))
      Owner = P->Owner, Ty = P->Ty;
    if (!Owner || !Owner->Body)
      continue;
    llvm::SMRange Body = Owner->Body->getRange();
    if (Body.End.getPointer() >= Loc.getPointer() || !Body.End.isValid())
      item(D->getName().Name, Variable, Ty ? Ty->getName() : "");
  }
  if (Here) {
    for (const CallableDecl *C : Here->Decls) {
      item(C->getName().Name, llvm::isa<TaskDecl>(C) ? Event : Function,
           headerOf(A.C->SM, *C));
      if (const auto *T = llvm::dyn_cast<TaskDecl>(C))
        for (const FuncDecl *F : T->NestedFuncs)
          item(F->getName().Name, Function, headerOf(A.C->SM, *F));
    }
    for (const ConstDecl *K : Here->Consts)
      item(K->getName().Name, Constant, K->Ty ? K->Ty->getName() : "");
    for (const EnumDecl *E : Here->Enums)
      item(E->getName().Name, Enum, "enum");
    for (const RequireDecl &R : Here->Requires)
      item(R.Name, Module, R.Script ? "module" : "module registered in C++");
  }
  // The world module's names are visible unqualified.
  if (const NativeModule *World = A.C->Checked.World) {
    for (const NativeFunction &F : World->Functions)
      item(F.Name, Function, signatureOf(F, World->Name));
    for (const NativeClass &K : World->Classes)
      item(K.Name, Class, K.CppName);
    for (const NativeEnum &E : World->Enums)
      item(E.Name, Enum, "enum");
  }
}

llvm::json::Value Completer::complete() {
  auto Words = chain(Before);
  if (!Words.empty() && Words.back().second == "::")
    moduleMembers(Words.back().first);
  else if (!Words.empty()) {
    if (const NativeClass *K = classOfChain(Words))
      classMembers(*K);
  } else {
    inScope();
  }
  return llvm::json::Object{{"isIncomplete", false},
                            {"items", std::move(Items)}};
}

llvm::json::Value Completer::signature() {
  // The open `(` before the cursor, and the commas since at its depth.
  int Depth = 0;
  unsigned Commas = 0;
  size_t Open = llvm::StringRef::npos;
  for (size_t I = Before.size(); I-- > 0;) {
    char C = Before[I];
    if (C == ')')
      ++Depth;
    else if (C == '(' && Depth-- == 0) {
      Open = I;
      break;
    } else if (C == ',' && Depth == 0)
      ++Commas;
  }
  if (Open == llvm::StringRef::npos || Open == 0)
    return nullptr;
  llvm::StringRef Callee = Before.take_front(Open).rtrim();
  size_t Start = Callee.size();
  while (Start && (llvm::isAlnum(Callee[Start - 1]) || Callee[Start - 1] == '_'))
    --Start;
  std::string Name = Callee.substr(Start).str();
  auto Words = chain(Callee.take_front(Start));
  std::string Label;
  std::vector<std::string> Params;
  std::string Doc;
  const NativeModule *NM = nullptr;
  const ModuleAST *SM = Here;
  if (!Words.empty() && Words.back().second == "::") {
    SM = scriptModule(Words.back().first);
    NM = SM ? nullptr : nativeModule(Words.back().first);
  } else if (!Words.empty()) {
    if (const NativeClass *K = classOfChain(Words))
      if (const NativeFunction *F = K->findMember(Name)) {
        Label = signatureOf(*F, "");
        Params = parameterLabels(*F);
      }
  }
  if (Label.empty() && SM)
    for (const CallableDecl *C : SM->Decls)
      if (C->getName().Name == Name) {
        Label = headerOf(A.C->SM, *C);
        Params = parameterLabels(*C);
        Doc = docCommentOf(A.C->SM, *C);
      }
  if (Label.empty() && NM)
    if (const NativeFunction *F = NM->findFunction(Name)) {
      Label = signatureOf(*F, NM->Name);
      Params = parameterLabels(*F);
    }
  if (Label.empty())
    return nullptr;
  llvm::json::Array ParamInfos;
  for (const std::string &P : Params)
    ParamInfos.push_back(llvm::json::Object{{"label", P}});
  llvm::json::Object Sig{{"label", Label}, {"parameters", std::move(ParamInfos)}};
  if (!Doc.empty())
    Sig["documentation"] = Doc;
  return llvm::json::Object{
      {"signatures", llvm::json::Array{std::move(Sig)}},
      {"activeSignature", 0},
      {"activeParameter", int64_t(Commas)}};
}

llvm::json::Value lsp::completion(const Analysis &A, unsigned BufferID,
                                  llvm::SMLoc Loc) {
  return Completer(A, BufferID, Loc).complete();
}

llvm::json::Value lsp::signatureHelp(const Analysis &A, unsigned BufferID,
                                     llvm::SMLoc Loc) {
  return Completer(A, BufferID, Loc).signature();
}
