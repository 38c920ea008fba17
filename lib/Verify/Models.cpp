//===- Models.cpp - `bsc verify --model`: b-script funcs for C++ ----------===//
#include "Models.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSet.h"

using namespace bsc;
using namespace bsc::verify;

/// `float`, `Math::Vector2f` as b-script spells the type.
static std::string spell(const NativeType &T) {
  switch (T.TheCode) {
  case NativeType::Void:
    return "void";
  case NativeType::Bool:
    return "bool";
  case NativeType::Int:
    return "int";
  case NativeType::Float:
    return "float";
  case NativeType::String:
    return "string";
  case NativeType::Enum:
  case NativeType::Class:
    return T.Name;
  }
  return T.Name;
}

/// Whether the b-script type `T` is the registered `N`.
static bool sameType(const Type *T, const NativeType &N) {
  switch (N.TheCode) {
  case NativeType::Void:
    return T->isVoid();
  case NativeType::Bool:
    return T->isBool();
  case NativeType::Int:
    return T->getKind() == TypeKind::Int;
  case NativeType::Float:
    return T->getKind() == TypeKind::Float;
  case NativeType::String:
    return T->getKind() == TypeKind::String;
  case NativeType::Enum:
    return T->getKind() == TypeKind::Enum &&
           (N.TheEnum ? T->getEnum() == N.TheEnum : T->getName() == N.Name);
  case NativeType::Class:
    return T->isClass() && T->getClass() == N.TheClass;
  }
  return false;
}

namespace {
/// A registered function or member, as a model names it.
struct Modelled {
  const NativeFunction *F;
  std::string Name;               ///< `Math::abs`, `Math::Vector2f::norm`.
  std::vector<NativeType> Params; ///< The object first for a member.
};
} // namespace

bool bsc::verify::findModels(Compilation &C, ModelMap &Models) {
  llvm::StringMap<Modelled> ByName;
  llvm::StringSet<> ModulePrefixes;
  for (const auto &NM : C.Natives.Modules) {
    ModulePrefixes.insert(NM->Name + "_");
    for (const NativeFunction &F : NM->Functions)
      ByName[NM->Name + "_" + F.Name] = {&F, NM->Name + "::" + F.Name,
                                         F.Params};
    for (const NativeClass &NC : NM->Classes)
      for (const NativeFunction &F : NC.Members) {
        NativeType Self;
        Self.TheCode = NativeType::Class;
        Self.Name = NC.QualifiedName;
        Self.TheClass = &NC;
        std::vector<NativeType> Params = {Self};
        Params.insert(Params.end(), F.Params.begin(), F.Params.end());
        ByName[NM->Name + "_" + NC.Name + "_" + F.Name] = {
            &F, NC.QualifiedName + "::" + F.Name, std::move(Params)};
      }
  }
  bool OK = true;
  for (const ModuleAST *M : C.Checked.Modules) {
    if (!M->IsModel)
      continue;
    for (const CallableDecl *D : M->Decls) {
      const auto *F = llvm::dyn_cast<FuncDecl>(D);
      llvm::StringRef Name = D->getName().Name;
      if (!F || llvm::none_of(ModulePrefixes, [&](const auto &P) {
            return Name.starts_with(P.getKey());
          }))
        continue; // A helper.
      auto It = ByName.find(Name);
      if (It == ByName.end()) {
        C.Diags.report(D->getLoc(), diag::err_verify_model_unknown) << Name;
        OK = false;
        continue;
      }
      const Modelled &To = It->second;
      bool Same = F->Params.size() == To.Params.size() &&
                  sameType(F->ResultTy, To.F->Result);
      for (size_t I = 0; Same && I < To.Params.size(); ++I)
        Same = sameType(F->Params[I]->Ty, To.Params[I]);
      if (!Same) {
        std::string Params;
        for (const NativeType &P : To.Params)
          Params += (Params.empty() ? "" : ", ") + spell(P);
        C.Diags.report(D->getLoc(), diag::err_verify_model_signature)
            << Name << To.Name << Params << spell(To.F->Result);
        OK = false;
        continue;
      }
      Models[To.F] = F;
    }
  }
  return OK;
}
