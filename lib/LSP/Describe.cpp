//===- Describe.cpp - names and signatures as the editor shows them -------===//
//
// Script declarations are shown as their source writes them (the header
// line, whitespace collapsed); registered C++ as b-script would declare it.
//
//===----------------------------------------------------------------------===//
#include "Describe.h"

using namespace bsc;
using namespace bsc::lsp;

std::string lsp::typeName(const NativeType &T) {
  std::string Base;
  switch (T.TheCode) {
  case NativeType::Void:
    Base = "void";
    break;
  case NativeType::Bool:
    Base = "bool";
    break;
  case NativeType::Int:
    Base = "int";
    break;
  case NativeType::Float:
    Base = "float";
    break;
  case NativeType::String:
    Base = "string";
    break;
  case NativeType::Enum:
  case NativeType::Class:
    Base = T.Name;
    break;
  }
  for (uint32_t E : T.Extents)
    Base += "[" + std::to_string(E) + "]";
  return Base;
}

std::vector<std::string> lsp::parameterLabels(const NativeFunction &F) {
  std::vector<std::string> Labels;
  for (size_t I = 0; I < F.Params.size(); ++I) {
    std::string L = typeName(F.Params[I]);
    if (I < F.ParamNames.size() && !F.ParamNames[I].empty())
      L += " " + F.ParamNames[I];
    size_t FirstDefault = F.Params.size() - F.Defaults.size();
    if (I >= FirstDefault) {
      const NativeDefault &D = F.Defaults[I - FirstDefault];
      L += " = " + (D.IsFloat ? std::to_string(D.Float) : std::to_string(D.Int));
    }
    Labels.push_back(L);
  }
  return Labels;
}

std::string lsp::signatureOf(const NativeFunction &F, llvm::StringRef Module) {
  std::string Owner = F.Owner ? F.Owner->QualifiedName
                              : (Module.empty() ? "" : Module.str() + "::");
  if (F.isData())
    return typeName(F.Result) + " " + Owner + "." + F.Name +
           (F.ReadOnly ? "  (read-only)" : "");
  std::string S = "func " + Owner + (F.Owner ? "." : "") + F.Name + "(";
  std::vector<std::string> Labels = parameterLabels(F);
  for (size_t I = 0; I < Labels.size(); ++I)
    S += (I ? ", " : "") + Labels[I];
  S += ")";
  if (F.Result.TheCode != NativeType::Void)
    S += " : " + typeName(F.Result);
  return S;
}

/// The buffer holding `Loc`.
static llvm::StringRef bufferOf(const llvm::SourceMgr &SM, llvm::SMLoc Loc) {
  unsigned ID = Loc.isValid() ? SM.FindBufferContainingLoc(Loc) : 0;
  return ID ? SM.getMemoryBuffer(ID)->getBuffer() : llvm::StringRef();
}

/// The source text from `Loc` to the end of its line, continued while a
/// `(` is open, with runs of whitespace as one space.
static std::string headerText(const llvm::SourceMgr &SM, llvm::SMLoc Loc) {
  llvm::StringRef Buf = bufferOf(SM, Loc);
  if (Buf.empty())
    return "";
  std::string Out;
  int Open = 0;
  bool Space = false;
  for (const char *P = Loc.getPointer();
       P != Buf.end() && !(*P == '\n' && Open <= 0) && Out.size() < 400; ++P) {
    char C = *P;
    if (C == '#' && Open <= 0)
      break;
    Open += C == '(' ? 1 : C == ')' ? -1 : 0;
    if (C == ' ' || C == '\t' || C == '\n' || C == '\r') {
      Space = !Out.empty();
      continue;
    }
    if (Space && !(C == ')' || C == ',' || Out.back() == '('))
      Out += ' ';
    Space = false;
    Out += C;
  }
  return Out;
}

std::string lsp::headerOf(const llvm::SourceMgr &SM, const CallableDecl &D) {
  return headerText(SM, D.getLoc());
}

std::vector<std::string> lsp::parameterLabels(const CallableDecl &D) {
  std::vector<std::string> Labels;
  for (const ParamDecl *P : D.Params) {
    const char *Start = P->getRange().Start.getPointer();
    const char *End = P->getRange().End.getPointer();
    Labels.push_back(Start && End > Start ? std::string(Start, End)
                                          : P->getName().Name.str());
  }
  return Labels;
}

std::string lsp::docCommentOf(const llvm::SourceMgr &SM, const Decl &D) {
  llvm::StringRef Buf = bufferOf(SM, D.getLoc());
  if (Buf.empty())
    return "";
  size_t LineStart = Buf.rfind('\n', D.getLoc().getPointer() - Buf.data());
  std::vector<std::string> Lines;
  // The comment lines right above the declaration's line, nearest first.
  while (LineStart != llvm::StringRef::npos && LineStart > 0) {
    size_t Prev = Buf.rfind('\n', LineStart - 1);
    size_t From = Prev == llvm::StringRef::npos ? 0 : Prev + 1;
    llvm::StringRef Text = Buf.slice(From, LineStart).trim();
    if (!Text.starts_with("#"))
      break;
    Lines.push_back(Text.drop_front().trim().str());
    if (Prev == llvm::StringRef::npos)
      break;
    LineStart = Prev;
  }
  std::string Doc;
  for (auto It = Lines.rbegin(); It != Lines.rend(); ++It)
    Doc += (Doc.empty() ? "" : "\n") + *It;
  return Doc;
}

std::string lsp::moduleOf(const Compilation &C, const NativeFunction &F) {
  if (F.Owner && F.Owner->Module)
    return F.Owner->Module->Name;
  for (const auto &M : C.Natives.Modules)
    for (const NativeFunction &G : M->Functions)
      if (&G == &F)
        return M->Name;
  return "";
}
