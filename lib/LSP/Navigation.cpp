//===- Navigation.cpp - definitions, references, renames, outlines --------===//
//
// A script symbol is the same across analyses when its definition is at
// the same place (definitionKey): so references and renames gather the
// occurrences of every analysis the server hands over, each checking the
// behavior from another file, and find the uses in modules that the
// renamed one does not require.
//
//===----------------------------------------------------------------------===//
#include "Describe.h"
#include "Features.h"
#include "bsc/Parse/Lexer.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSet.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include <map>

using namespace bsc;
using namespace bsc::lsp;

/// Where a script symbol is declared; empty for the others.
static llvm::SMRange definitionRange(const Symbol &S) {
  switch (S.K) {
  case Symbol::Decl:
    return static_cast<const Decl *>(S.Ptr)->getName().getRange();
  case Symbol::Enumerator:
    return static_cast<const EnumDecl *>(S.Ptr)
        ->Enumerators[S.Index]
        .Name.getRange();
  default:
    return {};
  }
}

std::string lsp::definitionKey(const Analysis &A, const Symbol &S) {
  if (S.K == Symbol::ScriptModule)
    return "module " + static_cast<const ModuleAST *>(S.Ptr)->Name;
  llvm::SMRange R = definitionRange(S);
  unsigned ID = R.isValid() ? A.C->SM.FindBufferContainingLoc(R.Start) : 0;
  if (!ID)
    return "";
  const char *Start = A.C->SM.getMemoryBuffer(ID)->getBufferStart();
  return A.getPath(ID) + ":" + std::to_string(R.Start.getPointer() - Start);
}

/// The source file a binding module's descriptor names (its __FILE__): as
/// given if absolute, else beside the binding object or from here.
static std::string placeFile(const NativeModule &M) {
  if (M.PlaceFile.empty() || llvm::sys::path::is_absolute(M.PlaceFile))
    return M.PlaceFile;
  llvm::StringRef Object = llvm::StringRef(M.File).split('(').first;
  llvm::SmallString<256> Beside = llvm::sys::path::parent_path(Object);
  llvm::sys::path::append(Beside, M.PlaceFile);
  if (llvm::sys::fs::exists(Beside))
    return std::string(Beside);
  llvm::SmallString<256> Here(M.PlaceFile);
  llvm::sys::fs::make_absolute(Here);
  return std::string(Here);
}

/// The place of a registration in C++: the string literal `"Name"` after
/// the module's BS_MODULE (and after `"Owner"`, the class or enum it is a
/// member of), else BS_MODULE's line. A descriptor records where BS_MODULE
/// is; compilers give every line of a macro's arguments one line number,
/// so the registration itself is found by its name.
static llvm::json::Value registrationPlace(const NativeModule &M,
                                           llvm::StringRef Owner,
                                           llvm::StringRef Name) {
  std::string File = placeFile(M);
  if (File.empty())
    return nullptr;
  auto Buf = llvm::MemoryBuffer::getFile(File);
  if (!Buf)
    return nullptr;
  llvm::StringRef Text = (*Buf)->getBuffer();
  // BS_MODULE(Name, with any spaces.
  size_t At = llvm::StringRef::npos;
  for (size_t P = Text.find("BS_MODULE("); P != llvm::StringRef::npos;
       P = Text.find("BS_MODULE(", P + 1))
    if (Text.substr(P + 10).ltrim().starts_with(M.Name + ",") ||
        Text.substr(P + 10).ltrim().starts_with(M.Name + " ")) {
      At = P;
      break;
    }
  size_t Found = At;
  if (At != llvm::StringRef::npos) {
    size_t From = At;
    if (!Owner.empty())
      From = Text.find(("\"" + Owner + "\"").str(), From);
    if (From != llvm::StringRef::npos && !Name.empty())
      From = Text.find(("\"" + Name + "\"").str(), From);
    if (From != llvm::StringRef::npos)
      Found = From + (Name.empty() ? 0 : 1);
  }
  int64_t Line, Char;
  if (Found == llvm::StringRef::npos) {
    Line = M.PlaceLine ? int64_t(M.PlaceLine) - 1 : 0;
    Char = 0;
  } else {
    Line = Text.take_front(Found).count('\n');
    Char = Found - (Text.rfind('\n', Found) + 1);
    if (Text.rfind('\n', Found) == llvm::StringRef::npos)
      Char = Found;
  }
  int64_t Length = Found == llvm::StringRef::npos || Name.empty()
                       ? 0
                       : int64_t(Name.size());
  return llvm::json::Object{
      {"uri", pathToURI(File)},
      {"range",
       llvm::json::Object{
           {"start", llvm::json::Object{{"line", Line}, {"character", Char}}},
           {"end", llvm::json::Object{{"line", Line},
                                      {"character", Char + Length}}}}}};
}

/// Where registered C++ is registered, if the descriptor says.
static llvm::json::Value nativeDefinition(const Analysis &A, const Symbol &S) {
  const Compilation &C = *A.C;
  auto ModuleNamed = [&](llvm::StringRef Name) {
    return C.Natives.find(Name);
  };
  switch (S.K) {
  case Symbol::NativeFunction: {
    const auto *F = static_cast<const NativeFunction *>(S.Ptr);
    const NativeModule *M = ModuleNamed(moduleOf(C, *F));
    return M ? registrationPlace(*M, F->Owner ? F->Owner->Name : "", F->Name)
             : nullptr;
  }
  case Symbol::NativeClass: {
    const auto *K = static_cast<const NativeClass *>(S.Ptr);
    return K->Module ? registrationPlace(*K->Module, "", K->Name) : nullptr;
  }
  case Symbol::NativeEnum: {
    const auto *E = static_cast<const NativeEnum *>(S.Ptr);
    return E->Module ? registrationPlace(*E->Module, "", E->Name) : nullptr;
  }
  case Symbol::NativeEnumValue: {
    const auto *E = static_cast<const NativeEnum *>(S.Ptr);
    return E->Module ? registrationPlace(*E->Module, E->Name,
                                         E->Values[S.Index].Name)
                     : nullptr;
  }
  case Symbol::NativeModule:
    return registrationPlace(*static_cast<const NativeModule *>(S.Ptr), "", "");
  case Symbol::Global: {
    const NativeModule *World = C.Checked.World;
    const NativeClass *K =
        World ? (S.Index ? World->Output : World->Input) : nullptr;
    return K ? registrationPlace(*World, "", K->Name) : nullptr;
  }
  default:
    return nullptr;
  }
}

llvm::json::Value lsp::definition(const Analysis &A, llvm::SMLoc Loc) {
  const Occurrence *O = A.Idx.findAt(Loc);
  if (!O)
    return nullptr;
  if (!O->Sym.isScript())
    return nativeDefinition(A, O->Sym);
  if (O->Sym.K == Symbol::ScriptModule) {
    const auto *M = static_cast<const ModuleAST *>(O->Sym.Ptr);
    llvm::SMLoc Start = llvm::SMLoc::getFromPointer(
        A.C->SM.getMemoryBuffer(M->BufferID)->getBufferStart());
    return A.getLocation({Start, Start});
  }
  llvm::SMRange R = definitionRange(O->Sym);
  if (!R.isValid())
    return nullptr;
  return A.getLocation(R);
}

/// Registered C++'s identity across analyses (each reads the binding
/// objects anew): its module, class or enum and name; empty for what has
/// none here (a constant).
static std::string nativeKey(const Analysis &A, const Symbol &S) {
  switch (S.K) {
  case Symbol::NativeFunction: {
    const auto *F = static_cast<const NativeFunction *>(S.Ptr);
    return "fn " + moduleOf(*A.C, *F) + "::" +
           (F->Owner ? F->Owner->Name + "." : "") + F->Name;
  }
  case Symbol::NativeClass:
    return "class " + static_cast<const NativeClass *>(S.Ptr)->QualifiedName;
  case Symbol::NativeEnum:
  case Symbol::NativeEnumValue: {
    const auto *E = static_cast<const NativeEnum *>(S.Ptr);
    std::string Key =
        "enum " + (E->Module ? E->Module->Name : std::string()) + "::" + E->Name;
    if (S.K == Symbol::NativeEnumValue && S.Index < E->Values.size())
      Key += "::" + E->Values[S.Index].Name;
    return Key;
  }
  case Symbol::NativeModule:
    return "native module " + static_cast<const NativeModule *>(S.Ptr)->Name;
  case Symbol::Global:
    return "global " + std::to_string(S.Index);
  default:
    return "";
  }
}

std::vector<Location>
lsp::findOccurrences(llvm::ArrayRef<const Analysis *> All, const Analysis &A,
                     llvm::SMLoc Loc, bool IncludeDeclaration) {
  std::vector<Location> Out;
  const Occurrence *O = A.Idx.findAt(Loc);
  if (!O)
    return Out;
  std::string Key = definitionKey(A, O->Sym);
  llvm::StringSet<> Seen;
  auto AddFrom = [&](const Analysis &From, const Occurrence &Occ) {
    if (Occ.IsDefinition && !IncludeDeclaration)
      return;
    unsigned ID = From.C->SM.FindBufferContainingLoc(Occ.Range.Start);
    if (!ID)
      return;
    const char *Start = From.C->SM.getMemoryBuffer(ID)->getBufferStart();
    Location L{From.getPath(ID),
               unsigned(Occ.Range.Start.getPointer() - Start),
               unsigned(Occ.Range.End.getPointer() - Start),
               From.getRange(Occ.Range)};
    if (Seen.insert(L.Path + ":" + std::to_string(L.Begin)).second)
      Out.push_back(std::move(L));
  };
  if (Key.empty()) {
    // Registered C++: its uses in every analysis, by its name there.
    std::string Native = nativeKey(A, O->Sym);
    if (Native.empty()) {
      for (const Occurrence &Occ : A.Idx.Occurrences)
        if (Occ.Sym == O->Sym)
          AddFrom(A, Occ);
      return Out;
    }
    for (const Analysis *From : All)
      for (const Occurrence &Occ : From->Idx.Occurrences)
        if (!Occ.Sym.isScript() && Occ.Sym.K == O->Sym.K &&
            nativeKey(*From, Occ.Sym) == Native)
          AddFrom(*From, Occ);
    return Out;
  }
  for (const Analysis *From : All)
    for (const Occurrence &Occ : From->Idx.Occurrences)
      if (Occ.Sym.isScript() && definitionKey(*From, Occ.Sym) == Key)
        AddFrom(*From, Occ);
  return Out;
}

llvm::json::Value lsp::references(llvm::ArrayRef<const Analysis *> All,
                                  const Analysis &A, llvm::SMLoc Loc,
                                  bool IncludeDeclaration) {
  llvm::json::Array Result;
  for (Location &L : findOccurrences(All, A, Loc, IncludeDeclaration))
    Result.push_back(llvm::json::Object{{"uri", pathToURI(L.Path)},
                                        {"range", std::move(L.Range)}});
  return Result;
}

llvm::json::Value lsp::documentHighlights(const Analysis &A, unsigned Buffer,
                                          llvm::SMLoc Loc) {
  // Without a kind (Text): the index does not tell an assignment's target
  // from a read.
  llvm::json::Array Result;
  std::string Path = A.getPath(Buffer);
  for (Location &L : findOccurrences({&A}, A, Loc, true))
    if (L.Path == Path)
      Result.push_back(llvm::json::Object{{"range", std::move(L.Range)}});
  return Result;
}

/// A renamable symbol under the cursor, or an error saying why not.
static llvm::Expected<const Occurrence *> renamable(const Analysis &A,
                                                    llvm::SMLoc Loc) {
  const Occurrence *O = A.Idx.findAt(Loc);
  if (!O)
    return llvm::createStringError("no name of the behavior here");
  if (O->Sym.K == Symbol::ScriptModule)
    return llvm::createStringError(
        "a module is named by its file: rename the file");
  if (!O->Sym.isScript())
    return llvm::createStringError(
        "'%s' is registered in C++: rename it where it is registered",
        std::string(O->Range.Start.getPointer(),
                     O->Range.End.getPointer())
            .c_str());
  return O;
}

llvm::json::Value lsp::prepareRename(const Analysis &A, llvm::SMLoc Loc) {
  llvm::Expected<const Occurrence *> O = renamable(A, Loc);
  if (!O) {
    llvm::consumeError(O.takeError());
    return nullptr;
  }
  return A.getRange((*O)->Range);
}

/// Whether `Name` can name a declaration: an identifier, not a keyword.
static bool isNewName(llvm::StringRef Name) {
  if (Name.empty() || !(llvm::isAlpha(Name[0]) || Name[0] == '_'))
    return false;
  if (!llvm::all_of(Name, [](char C) { return llvm::isAlnum(C) || C == '_'; }))
    return false;
#define KEYWORD(Spelling)                                                      \
  if (Name == #Spelling)                                                       \
    return false;
#include "bsc/Parse/TokenKinds.def"
  return Name != "input" && Name != "output";
}

llvm::Expected<llvm::json::Value>
lsp::rename(llvm::ArrayRef<const Analysis *> All, const Analysis &A,
            llvm::SMLoc Loc, llvm::StringRef NewName) {
  llvm::Expected<const Occurrence *> O = renamable(A, Loc);
  if (!O)
    return O.takeError();
  if (!isNewName(NewName))
    return llvm::createStringError(
        "'%s' is not a name b-script can declare (an identifier, not a "
        "keyword)",
        NewName.str().c_str());
  std::map<std::string, llvm::json::Array> Edits;
  for (Location &L : findOccurrences(All, A, Loc, true))
    Edits[pathToURI(L.Path)].push_back(llvm::json::Object{
        {"range", std::move(L.Range)}, {"newText", NewName.str()}});
  llvm::json::Object Changes;
  for (auto &[URI, List] : Edits)
    Changes[URI] = std::move(List);
  return llvm::json::Object{{"changes", std::move(Changes)}};
}

llvm::json::Value lsp::renameModuleFile(llvm::ArrayRef<const Analysis *> All,
                                        llvm::StringRef OldPath,
                                        llvm::StringRef NewPath) {
  llvm::StringRef OldName = llvm::sys::path::stem(OldPath);
  llvm::StringRef NewName = llvm::sys::path::stem(NewPath);
  // A file that is no module before or after: nothing names it.
  if (llvm::sys::path::extension(OldPath) != ".bs" ||
      llvm::sys::path::extension(NewPath) != ".bs" || !isNewName(NewName) ||
      OldName == NewName)
    return nullptr;
  std::map<std::string, llvm::json::Array> Edits;
  llvm::StringSet<> Seen;
  for (const Analysis *A : All)
    for (const Occurrence &O : A->Idx.Occurrences) {
      if (O.Sym.K != Symbol::ScriptModule)
        continue;
      const auto *M = static_cast<const ModuleAST *>(O.Sym.Ptr);
      if (M->Name != OldName || A->getPath(M->BufferID) != OldPath)
        continue;
      unsigned ID = A->C->SM.FindBufferContainingLoc(O.Range.Start);
      if (!ID)
        continue;
      std::string Path = A->getPath(ID);
      const char *Start = A->C->SM.getMemoryBuffer(ID)->getBufferStart();
      if (!Seen.insert(Path + ":" +
                       std::to_string(O.Range.Start.getPointer() - Start))
               .second)
        continue;
      // `requires "Moves"` names it in a string; `Moves::step` bare.
      bool Quoted = *O.Range.Start.getPointer() == '"';
      Edits[pathToURI(Path)].push_back(llvm::json::Object{
          {"range", A->getRange(O.Range)},
          {"newText", Quoted ? "\"" + NewName.str() + "\"" : NewName.str()}});
    }
  if (Edits.empty())
    return nullptr;
  llvm::json::Object Changes;
  for (auto &[URI, List] : Edits)
    Changes[URI] = std::move(List);
  return llvm::json::Object{{"changes", std::move(Changes)}};
}

//===----------------------------------------------------------------------===//
// Outlines
//===----------------------------------------------------------------------===//

namespace {
/// LSP's SymbolKind numbers.
enum SymbolKind {
  Module = 2,
  Class = 5,
  Method = 6,
  Enum = 10,
  Function = 12,
  Variable = 13,
  Constant = 14,
  EnumMember = 22,
  Event = 24,
};
} // namespace

static llvm::json::Object symbolOf(const Analysis &A, llvm::StringRef Name,
                                   llvm::StringRef Detail, int Kind,
                                   llvm::SMRange Whole, llvm::SMRange Sel) {
  if (!Whole.isValid() || Whole.End.getPointer() < Sel.End.getPointer())
    Whole = Sel;
  return llvm::json::Object{{"name", Name.str()},
                            {"detail", Detail.str()},
                            {"kind", Kind},
                            {"range", A.getRange(Whole)},
                            {"selectionRange", A.getRange(Sel)}};
}

/// Where the last statement of a block ends (a block's own range runs to
/// the next line's first token).
static llvm::SMLoc endOfBlock(const Stmt *S) {
  while (S) {
    if (const auto *B = llvm::dyn_cast<BlockStmt>(S)) {
      if (B->Stmts.empty())
        return B->getRange().End;
      S = B->Stmts.back();
    } else if (const auto *If = llvm::dyn_cast<IfStmt>(S)) {
      S = If->Else ? If->Else : If->Then;
    } else if (const auto *F = llvm::dyn_cast<ForStmt>(S)) {
      S = F->Body;
    } else if (const auto *D = llvm::dyn_cast<FuncDeclStmt>(S)) {
      S = D->Func->Body;
    } else {
      return S->getRange().End;
    }
  }
  return {};
}

static llvm::json::Object callableSymbol(const Analysis &A,
                                         const CallableDecl &C) {
  bool IsTask = llvm::isa<TaskDecl>(C);
  llvm::SMRange Whole = C.getRange();
  if (llvm::SMLoc End = endOfBlock(C.Body); End.isValid())
    Whole.End = End;
  llvm::json::Object S =
      symbolOf(A, C.getName().Name, headerOf(A.C->SM, C),
               IsTask ? Event : Function, Whole, C.getName().getRange());
  llvm::json::Array Children;
  if (const auto *T = llvm::dyn_cast<TaskDecl>(&C))
    for (const FuncDecl *F : T->NestedFuncs)
      Children.push_back(callableSymbol(A, *F));
  if (!Children.empty())
    S["children"] = std::move(Children);
  return S;
}

static llvm::json::Object enumSymbol(const Analysis &A, const EnumDecl &E) {
  llvm::SMRange Whole = E.getRange();
  if (!E.Enumerators.empty())
    Whole.End = E.Enumerators.back().ValueRange.isValid()
                    ? E.Enumerators.back().ValueRange.End
                    : E.Enumerators.back().Name.getRange().End;
  llvm::json::Object S =
      symbolOf(A, E.getName().Name, E.IsTaskState ? "enum : TaskState" : "enum",
               Enum, Whole, E.getName().getRange());
  llvm::json::Array Children;
  for (size_t I = 0; I < E.Enumerators.size(); ++I) {
    const Ident &N = E.Enumerators[I].Name;
    std::string Value; // By name: an enum with errors has fewer values.
    for (const NativeEnum::Value &V : E.Values.Values)
      if (V.Name == N.Name)
        Value = std::to_string(V.Number);
    Children.push_back(symbolOf(A, N.Name, Value, EnumMember, N.getRange(),
                                N.getRange()));
  }
  S["children"] = std::move(Children);
  return S;
}

llvm::json::Value lsp::documentSymbols(const Analysis &A, unsigned BufferID) {
  llvm::json::Array Result;
  for (const ModuleAST *M : A.C->Modules) {
    if (M->BufferID != BufferID)
      continue;
    for (const EnumDecl *E : M->Enums)
      Result.push_back(enumSymbol(A, *E));
    for (const ConstDecl *K : M->Consts)
      Result.push_back(symbolOf(A, K->getName().Name,
                                K->Ty ? K->Ty->getName() : "", Constant,
                                K->getRange(), K->getName().getRange()));
    for (const CallableDecl *C : M->Decls)
      Result.push_back(callableSymbol(A, *C));
  }
  return Result;
}

llvm::json::Value lsp::workspaceSymbols(llvm::ArrayRef<const Analysis *> All,
                                        llvm::StringRef Query) {
  llvm::json::Array Result;
  llvm::StringSet<> Seen;
  auto Add = [&](const Analysis &A, const ModuleAST &M, const Decl &D,
                 int Kind) {
    std::string Name = M.Name + "::" + D.getName().Name.str();
    if (!D.getName().Name.contains_insensitive(Query) ||
        !Seen.insert(Name).second)
      return;
    Result.push_back(llvm::json::Object{
        {"name", D.getName().Name.str()},
        {"containerName", M.Name},
        {"kind", Kind},
        {"location", A.getLocation(D.getName().getRange())}});
  };
  for (const Analysis *A : All)
    for (const ModuleAST *M : A->C->Modules) {
      for (const EnumDecl *E : M->Enums)
        Add(*A, *M, *E, Enum);
      for (const ConstDecl *K : M->Consts)
        Add(*A, *M, *K, Constant);
      for (const CallableDecl *C : M->Decls)
        Add(*A, *M, *C, llvm::isa<TaskDecl>(C) ? Event : Function);
    }
  // Registered C++ of the binding objects, where each is registered.
  auto AddNative = [&](const NativeModule &M, llvm::StringRef Container,
                       llvm::StringRef Owner, llvm::StringRef Name, int Kind) {
    if (!Name.contains_insensitive(Query) ||
        !Seen.insert("native " + Container.str() + "::" + Name.str()).second)
      return;
    llvm::json::Value Place = registrationPlace(M, Owner, Name);
    if (Place.kind() == llvm::json::Value::Null)
      return;
    Result.push_back(llvm::json::Object{{"name", Name.str()},
                                        {"containerName", Container.str()},
                                        {"kind", Kind},
                                        {"location", std::move(Place)}});
  };
  for (const Analysis *A : All)
    for (const NativeModule *M : A->C->Checked.BindingModules) {
      for (const NativeFunction &F : M->Functions)
        AddNative(*M, M->Name, "", F.Name, Function);
      for (const NativeEnum &E : M->Enums)
        AddNative(*M, M->Name, "", E.Name, Enum);
      for (const NativeClass &K : M->Classes) {
        AddNative(*M, M->Name, "", K.Name, Class);
        for (const NativeFunction &F : K.Members)
          AddNative(*M, K.QualifiedName, K.Name, F.Name, Method);
      }
    }
  return Result;
}
