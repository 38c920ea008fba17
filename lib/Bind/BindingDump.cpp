//===- BindingDump.cpp - print what binding objects register --------------===//
//
// The text of `bsc --dump-bindings OBJ`: one line per module, class, member
// and enum, with the b-script signature first (what a script author needs)
// and the target facts after it (size, alignment, offsets, thunk symbols:
// what someone debugging a binding needs). Stable, so tests can FileCheck
// it.
//
//===----------------------------------------------------------------------===//
#include "bsc/Bind/Bind.h"
#include <cstring>
#include "llvm/Support/Format.h"
#include "llvm/Support/raw_ostream.h"

using namespace llvm;
using namespace bsc;
using namespace bsc::bind;

namespace {

std::string typeName(const BindingModel &Model, const BoundType &T) {
  std::string S;
  switch (T.Code) {
  case TypeCode::Void:
    return "void";
  case TypeCode::Context:
    return "bs::Context&";
  case TypeCode::Bool:
    S = "bool";
    break;
  case TypeCode::Int:
    S = T.Flags & TF_Unsigned ? "int(unsigned)" : "int";
    break;
  case TypeCode::Float:
    S = "float";
    break;
  case TypeCode::String:
    S = "string";
    break;
  case TypeCode::Enum:
  case TypeCode::Class:
    S = Model.getQualifiedName(T);
    if (S.empty())
      S = "?" + T.Key;
    break;
  }
  // The C++ storage when it differs from the wire type (double, short...);
  // an array field shows its extents instead, and its element size below.
  unsigned Wire = T.Code == TypeCode::Bool ? 1 : 4;
  if (T.isArray()) {
    for (uint32_t Extent : T.Extents)
      S += "[" + std::to_string(Extent) + "]";
  } else if (T.isScalar() && T.Code != TypeCode::String &&
             T.StorageSize != Wire) {
    S += "[" + std::to_string(T.StorageSize) + "]";
  }
  if (T.Flags & TF_Ref)
    S += (T.Flags & TF_Const) ? " const&" : "&";
  return S;
}

const char *kindName(MemberKind K) {
  switch (K) {
  case MemberKind::Field:
    return "field";
  case MemberKind::Property:
    return "property";
  case MemberKind::Method:
    return "method";
  case MemberKind::Function:
    return "function";
  case MemberKind::Constructor:
    return "constructor";
  case MemberKind::Constant:
    return "constant";
  }
  return "?";
}

void dumpMember(const BindingModel &Model, const BoundMember &M,
                raw_ostream &OS) {
  std::string Unusable = getUnusableReason(M);
  OS << "    " << (Unusable.empty() ? "" : "skipped ") << kindName(M.Kind)
     << " " << M.Name;
  if (M.Kind == MemberKind::Constant) {
    OS << " : " << typeName(Model, M.Result) << " = ";
    if (M.Result.Code == TypeCode::Float) {
      float F;
      std::memcpy(&F, &M.Value, 4);
      OS << format("%g", double(F));
    } else {
      OS << int32_t(M.Value);
    }
  } else if (M.Kind == MemberKind::Field || M.Kind == MemberKind::Property) {
    OS << " : " << typeName(Model, M.Result);
    if (M.FieldOffset)
      OS << " offset " << *M.FieldOffset;
    OS << (M.Result.isArray() ? " element size " : " size ")
       << M.Result.StorageSize;
    OS << (M.isReadOnly() ? " read-only" : " read-write");
  } else {
    OS << "(";
    for (size_t I = 0; I < M.Params.size(); ++I) {
      const BoundParam &P = M.Params[I];
      if (I)
        OS << ", ";
      OS << typeName(Model, P.Type);
      if (!P.Name.empty())
        OS << " " << P.Name;
      if (P.Default == DefaultKind::Int)
        OS << " = " << P.DefaultInt;
      else if (P.Default == DefaultKind::Float)
        OS << " = " << format("%g", double(P.DefaultFloat));
    }
    OS << ")";
    if (M.Result.Code != TypeCode::Void)
      OS << " : " << typeName(Model, M.Result);
    if (M.Kind == MemberKind::Method)
      OS << (M.isConstSelf() ? " const" : " mutating");
  }
  if (M.resultViaOut())
    OS << " out";
  if (M.isPure())
    OS << " pure";
  if (!M.CppName.empty())
    OS << " = " << M.CppName;
  if (!Unusable.empty())
    OS << "\n      unusable: " << Unusable;
  OS << "\n";
  if (!M.Thunk.empty()) // Array fields have none: reached by offset.
    OS << "      thunk " << M.Thunk << "\n";
  if (!M.Setter.empty())
    OS << "      setter " << M.Setter << "\n";
}

} // namespace

std::string bind::getUnusableReason(const BoundMember &M) {
  for (size_t I = 0; I < M.Params.size(); ++I) {
    const BoundType &T = M.Params[I].Type;
    if (!T.isOutPointer())
      continue;
    const char *Name = T.Code == TypeCode::Bool    ? "bool&"
                       : T.Code == TypeCode::Float ? "float&"
                       : T.Code == TypeCode::Enum  ? "an enum&"
                                                   : "int&";
    return "parameter " + std::to_string(I + 1) + " is '" + Name +
           "', an out-parameter, and b-script passes scalars by value; "
           "register a function that returns the value instead";
  }
  return "";
}

void bind::dumpBindings(const BindingModel &Model, raw_ostream &OS) {
  for (const BoundModule &M : Model.Modules) {
    OS << "module " << M.Name << " (" << M.File << ", version " << M.Version
       << ", hash " << format_hex(M.Hash, 18) << ")\n";
    for (size_t CI = 0; CI < M.Classes.size(); ++CI) {
      const BoundClass &C = M.Classes[CI];
      OS << "  class " << C.Name;
      if (!C.CppName.empty())
        OS << " = " << C.CppName;
      OS << " size " << C.Size << " align " << C.Align;
      static const struct {
        unsigned Flag;
        const char *Name;
      } Flags[] = {{CF_TriviallyCopyable, "trivially-copyable"},
                   {CF_TriviallyDestructible, "trivially-destructible"},
                   {CF_DefaultConstructible, "default-constructible"},
                   {CF_CopyConstructible, "copy-constructible"},
                   {CF_CopyAssignable, "copy-assignable"},
                   {CF_StandardLayout, "standard-layout"},
                   {CF_CopyAsBytes, "copy-as-bytes"}};
      for (const auto &F : Flags)
        if (C.Flags & F.Flag)
          OS << " " << F.Name;
      if (int(CI) == M.InputClass)
        OS << " input";
      if (int(CI) == M.OutputClass)
        OS << " output";
      OS << "\n      key " << C.Key << "\n";
      const std::pair<const char *, const std::string *> Life[] = {
          {"construct", &C.Construct},
          {"copy", &C.Copy},
          {"assign", &C.Assign},
          {"destroy", &C.Destroy}};
      for (const auto &[Name, Sym] : Life)
        if (!Sym->empty())
          OS << "      " << Name << " " << *Sym << "\n";
      for (const BoundMember &Mb : C.Members)
        dumpMember(Model, Mb, OS);
    }
    for (const BoundEnum &E : M.Enums) {
      OS << "  enum " << E.Name;
      if (!E.CppName.empty())
        OS << " = " << E.CppName;
      OS << " size " << E.Size << (E.Scoped ? " scoped" : "")
         << (E.Signed ? " signed" : " unsigned") << ":";
      for (const BoundEnum::Value &V : E.Values)
        OS << " " << V.Name << "=" << V.Number;
      OS << "\n      key " << E.Key << "\n";
    }
    for (const auto *List : {&M.Functions, &M.Constants})
      for (const BoundMember &F : *List) {
        std::string S;
        raw_string_ostream SS(S);
        dumpMember(Model, F, SS);
        OS << "  " << StringRef(S).drop_front(4);
      }
  }
}
