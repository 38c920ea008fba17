//===- NativeConversion.cpp - binding model -> Native.h registry ----------===//
//
// Sema and CodeGen consume native modules through Native.h. This converts a whole binding
// model into it: every module with its classes (sizes, alignments,
// life-cycle thunks, fields with offsets, properties, methods, class-scope
// functions), module functions, enums, and the `input`/`output` classes.
//
// It runs in two passes so that types can point at their classes and enums:
// first every module, class and enum is created (and the vectors are never
// resized afterwards), then members and functions are filled in with
// resolved pointers. The model's module/index pairs map one to one onto the
// new NativeModules.
//
// Left out (and returned by name): members with `int&`, `float&` or `bool&`
// out parameters, which b-script has no way to pass.
//
//===----------------------------------------------------------------------===//
#include "bsc/AST/Native.h"
#include "bsc/Bind/Bind.h"
#include <cstring>

using namespace bsc;
using namespace bsc::bind;

namespace {

class Converter {
public:
  Converter(const BindingModel &Model) : Model(Model) {}

  std::vector<std::string> run(NativeRegistry &Registry) {
    for (const BoundModule &M : Model.Modules)
      Mods.push_back(createModule(M));
    for (size_t I = 0; I != Model.Modules.size(); ++I)
      fillModule(Model.Modules[I], *Mods[I]);
    for (auto &M : Mods)
      Registry.Modules.push_back(std::move(M));
    return std::move(Skipped);
  }

private:
  std::unique_ptr<NativeModule> createModule(const BoundModule &M) {
    auto NM = std::make_unique<NativeModule>();
    NM->Name = M.Name;
    NM->File = M.File;
    NM->PlaceFile = M.PlaceFile;
    NM->PlaceLine = M.PlaceLine;
    NM->Hash = M.Hash;
    for (const BoundEnum &E : M.Enums) {
      NativeEnum NE;
      NE.Name = E.Name;
      NE.Module = NM.get();
      for (const BoundEnum::Value &V : E.Values)
        NE.Values.push_back({V.Name, V.Number});
      NM->Enums.push_back(std::move(NE));
    }
    for (const BoundClass &C : M.Classes) {
      NativeClass NC;
      NC.Name = C.Name;
      NC.QualifiedName = M.Name + "::" + C.Name;
      NC.CppName = C.CppName;
      NC.Module = NM.get();
      NC.Size = C.Size;
      NC.Align = C.Align;
      NC.DefaultConstructible = C.Flags & CF_DefaultConstructible;
      NC.TriviallyDestructible = C.Flags & CF_TriviallyDestructible;
      NC.CopiesAsBytes = C.copiesAsBytes();
      NC.Construct = C.Construct;
      NC.Copy = C.Copy;
      NC.Assign = C.Assign;
      NC.Destroy = C.Destroy;
      NM->Classes.push_back(std::move(NC));
    }
    if (M.InputClass >= 0)
      NM->Input = &NM->Classes[M.InputClass];
    if (M.OutputClass >= 0)
      NM->Output = &NM->Classes[M.OutputClass];
    return NM;
  }

  void fillModule(const BoundModule &M, NativeModule &NM) {
    for (const BoundMember &F : M.Functions) {
      NativeFunction NF;
      if (convertMember(F, nullptr, NF))
        NM.Functions.push_back(std::move(NF));
      else
        skip(M.Name + "::" + F.Name, F, NM.Unusable);
    }
    for (const BoundMember &B : M.Constants) {
      NativeConstant NC;
      NC.Name = B.Name;
      if (!convertType(B.Result, NC.Type))
        continue; // An enum of no loaded module: the reader reported it.
      NC.Int = int32_t(B.Value);
      std::memcpy(&NC.Float, &B.Value, 4);
      NM.Constants.push_back(std::move(NC));
    }
    for (size_t I = 0; I != M.Classes.size(); ++I) {
      NativeClass &NC = NM.Classes[I];
      for (const BoundMember &Mb : M.Classes[I].Members) {
        NativeFunction NF;
        bool Ok = convertMember(Mb, &NC, NF);
        std::vector<NativeFunction> &Into =
            Mb.Kind == MemberKind::Constructor ? NC.Constructors : NC.Members;
        if (Ok)
          Into.push_back(std::move(NF));
        else
          skip(NC.QualifiedName + "." + Mb.Name, Mb, NC.Unusable);
      }
    }
  }

  /// Records a member left out, with the reason Sema gives on its use.
  void skip(std::string Path, const BoundMember &B,
            std::vector<UnusableMember> &Into) {
    Skipped.push_back(std::move(Path));
    std::string Reason = getUnusableReason(B);
    if (Reason.empty())
      Reason = "its types are not registered"; // An enum or class of no module.
    Into.push_back({B.Name, std::move(Reason)});
  }

  /// False for what b-script cannot express (out parameters).
  bool convertType(const BoundType &T, NativeType &Out) {
    Out.StorageSize = T.StorageSize;
    Out.Unsigned = T.Flags & TF_Unsigned;
    Out.Extents = T.Extents;
    switch (T.Code) {
    case TypeCode::Void:
      Out.TheCode = NativeType::Void;
      return true;
    case TypeCode::Bool:
      Out.TheCode = NativeType::Bool;
      return !T.isOutPointer();
    case TypeCode::Int:
      Out.TheCode = NativeType::Int;
      return !T.isOutPointer();
    case TypeCode::Float:
      Out.TheCode = NativeType::Float;
      return !T.isOutPointer();
    case TypeCode::String:
      Out.TheCode = NativeType::String;
      return true;
    case TypeCode::Enum:
      Out.TheCode = NativeType::Enum;
      Out.Name = Model.getQualifiedName(T);
      if (T.Module < 0 || T.Index < 0)
        return false;
      Out.TheEnum = &Mods[T.Module]->Enums[T.Index];
      return !T.isOutPointer();
    case TypeCode::Context:
      return false; // Only as the first parameter (convertMember).
    case TypeCode::Class:
      Out.TheCode = NativeType::Class;
      Out.Name = Model.getQualifiedName(T);
      if (T.Module < 0 || T.Index < 0)
        return false;
      Out.TheClass = &Mods[T.Module]->Classes[T.Index];
      Out.MutableRef = (T.Flags & TF_Ref) && !(T.Flags & TF_Const);
      return true;
    }
    return false;
  }

  bool convertMember(const BoundMember &B, const NativeClass *Owner,
                     NativeFunction &NF) {
    switch (B.Kind) {
    case MemberKind::Field:
      NF.Kind = NativeFunction::Field;
      break;
    case MemberKind::Property:
      NF.Kind = NativeFunction::Property;
      break;
    case MemberKind::Method:
      NF.Kind = NativeFunction::Method;
      break;
    case MemberKind::Function:
    case MemberKind::Constructor:
      NF.Kind = NativeFunction::Function;
      break;
    case MemberKind::Constant:
      return false; // Not a member: NativeModule::Constants.
    }
    NF.Name = B.Name;
    NF.Symbol = B.Thunk;
    NF.Setter = B.Setter;
    NF.FieldOffset = B.FieldOffset;
    NF.Owner = Owner;
    NF.ConstSelf = B.isConstSelf();
    NF.ReadOnly = B.isReadOnly();
    NF.Pure = B.isPure();
    NF.ResultViaOut = B.resultViaOut();
    bool Ok = convertType(B.Result, NF.Result);
    for (const BoundParam &P : B.Params) {
      if (P.Type.Code == TypeCode::Context) {
        NF.TakesContext = true; // Generated code passes it; scripts do not.
        continue;
      }
      NativeType T;
      Ok = convertType(P.Type, T) && Ok;
      NF.Params.push_back(std::move(T));
      NF.ParamNames.push_back(P.Name);
      if (P.Default != DefaultKind::None) {
        NativeDefault D;
        D.IsFloat = P.Default == DefaultKind::Float;
        D.Int = P.DefaultInt;
        D.Float = P.DefaultFloat;
        NF.Defaults.push_back(D);
      }
    }
    return Ok;
  }

  const BindingModel &Model;
  std::vector<std::unique_ptr<NativeModule>> Mods;
  std::vector<std::string> Skipped;
};

} // namespace

std::vector<std::string> bind::addToNativeRegistry(const BindingModel &Model,
                                                   NativeRegistry &Registry) {
  return Converter(Model).run(Registry);
}
