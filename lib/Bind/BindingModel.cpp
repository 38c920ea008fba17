//===- BindingModel.cpp - lookups in what the binding objects register ----===//
//
// The queries of BindingModel and its modules (bsc/Bind/Bind.h): by name,
// and from a resolved type back to its class or enum.
//
//===----------------------------------------------------------------------===//
#include "bsc/Bind/Bind.h"

using namespace llvm;
using namespace bsc;
using namespace bsc::bind;


/// The element of `Range` whose Name is `N`, or null: every model lookup.
template <typename RangeT>
static auto findNamed(const RangeT &Range, StringRef N)
    -> decltype(&*std::begin(Range)) {
  for (const auto &Element : Range)
    if (Element.Name == N)
      return &Element;
  return nullptr;
}

const BoundMember *BoundClass::findMember(StringRef N) const {
  return findNamed(Members, N);
}

const BoundClass *BoundModule::findClass(StringRef N) const {
  return findNamed(Classes, N);
}

const BoundEnum *BoundModule::findEnum(StringRef N) const {
  return findNamed(Enums, N);
}

const BoundMember *BoundModule::findFunction(StringRef N) const {
  return findNamed(Functions, N);
}

const BoundModule *BindingModel::findModule(StringRef N) const {
  return findNamed(Modules, N);
}

const BoundModule *BindingModel::getWorldModule() const {
  for (const BoundModule &M : Modules)
    if (M.InputClass >= 0)
      return &M;
  for (const BoundModule &M : Modules)
    if (M.OutputClass >= 0)
      return &M;
  return nullptr;
}

const BoundClass *BindingModel::getClass(const BoundType &T) const {
  if (T.Code != TypeCode::Class || T.Module < 0)
    return nullptr;
  return &Modules[T.Module].Classes[T.Index];
}

const BoundEnum *BindingModel::getEnum(const BoundType &T) const {
  if (T.Code != TypeCode::Enum || T.Module < 0)
    return nullptr;
  return &Modules[T.Module].Enums[T.Index];
}

std::string BindingModel::getQualifiedName(const BoundType &T) const {
  if (const BoundClass *C = getClass(T))
    return Modules[T.Module].Name + "::" + C->Name;
  if (const BoundEnum *E = getEnum(T))
    return Modules[T.Module].Name + "::" + E->Name;
  return "";
}
