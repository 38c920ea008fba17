//===- NativeConversion.cpp - binding model -> Native.h registry ----------===//
//
// Sema consumes native modules through Native.h (NativeModule, NativeEnum,
// NativeFunction). That description can say today what the built-in `io`
// needs: module functions whose parameters and result are scalars or enums
// passed by value. This adds exactly that part of a binding model, so that
// `requires "Math"` with `Math::fabs` works before Sema learns classes; the
// rest (classes, members, out parameters, defaults, input/output) stays in
// the BindingModel for the Sema/CodeGen integration.
//
//===----------------------------------------------------------------------===//
#include "bsc/AST/Native.h"
#include "bsc/Bind/Bind.h"

using namespace bsc;
using namespace bsc::bind;

namespace {

/// The Native.h form of a by-value scalar or enum, or false.
bool convertType(const BindingModel &Model, const BoundType &T,
                 NativeType &Out) {
  if (T.Flags & TF_Pointer)
    return false;
  switch (T.Code) {
  case TypeCode::Void:
    Out.TheCode = NativeType::Void;
    return true;
  case TypeCode::Bool:
    Out.TheCode = NativeType::Bool;
    return true;
  case TypeCode::Int:
    Out.TheCode = NativeType::Int;
    return true;
  case TypeCode::Float:
    Out.TheCode = NativeType::Float;
    return true;
  case TypeCode::String:
    Out.TheCode = NativeType::String;
    return true;
  case TypeCode::Enum:
    Out.TheCode = NativeType::Enum;
    Out.Name = Model.getQualifiedName(T);
    return !Out.Name.empty();
  case TypeCode::Class:
    return false;
  }
  return false;
}

} // namespace

std::vector<std::string> bind::addToNativeRegistry(const BindingModel &Model,
                                                   NativeRegistry &Registry) {
  std::vector<std::string> Skipped;
  for (const BoundModule &M : Model.Modules) {
    auto NM = std::make_unique<NativeModule>();
    NM->Name = M.Name;
    for (const BoundEnum &E : M.Enums) {
      NativeEnum NE;
      NE.Name = E.Name;
      for (const BoundEnum::Value &V : E.Values)
        NE.Values.push_back({V.Name, V.Number});
      NM->Enums.push_back(std::move(NE));
    }
    for (const BoundMember &F : M.Functions) {
      NativeFunction NF;
      NF.Name = F.Name;
      NF.Symbol = F.Thunk;
      bool Ok = !F.resultViaOut() && convertType(Model, F.Result, NF.Result);
      for (const BoundParam &P : F.Params) {
        NativeType T;
        Ok = Ok && P.Default == DefaultKind::None &&
             convertType(Model, P.Type, T);
        NF.Params.push_back(std::move(T));
      }
      if (Ok)
        NM->Functions.push_back(std::move(NF));
      else
        Skipped.push_back(M.Name + "::" + F.Name);
    }
    for (const BoundClass &C : M.Classes)
      for (const BoundMember &Mb : C.Members)
        Skipped.push_back(M.Name + "::" + C.Name + "." + Mb.Name);
    Registry.Modules.push_back(std::move(NM));
  }
  return Skipped;
}
