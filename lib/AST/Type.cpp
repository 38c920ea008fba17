//===- Type.cpp - the static types of b-script ----------------------------===//
#include "bsc/AST/Type.h"
#include "bsc/AST/Native.h"

using namespace bsc;

TypeContext::TypeContext()
    : ErrorTy(TypeKind::Error, "<error>"), VoidTy(TypeKind::Void, "void"),
      IntTy(TypeKind::Int, "int"), FloatTy(TypeKind::Float, "float"),
      BoolTy(TypeKind::Bool, "bool"), StringTy(TypeKind::String, "string"),
      TaskStateTy(TypeKind::TaskState, "TaskState") {}

const Type *TypeContext::getEnum(const NativeEnum *E,
                                 llvm::StringRef QualifiedName) {
  std::unique_ptr<Type> &Slot = Enums[E];
  if (!Slot)
    Slot = std::make_unique<Type>(TypeKind::Enum, QualifiedName.str(), E);
  return Slot.get();
}

const Type *TypeContext::getClass(const NativeClass *C) {
  std::unique_ptr<Type> &Slot = Classes[C];
  if (!Slot)
    Slot = std::make_unique<Type>(TypeKind::Class, C->QualifiedName, nullptr, C);
  return Slot.get();
}

const Type *TypeContext::getArray(const Type *Element, uint32_t Extent) {
  std::unique_ptr<Type> &Slot = Arrays[{Element, Extent}];
  if (!Slot) {
    // The extent goes before the element's own: an array of 3 `float[3]`
    // is `float[3][3]`.
    std::string Name = Element->getName().str();
    size_t Bracket = std::min(Name.find('['), Name.size());
    Name.insert(Bracket, "[" + std::to_string(Extent) + "]");
    Slot = std::make_unique<Type>(std::move(Name), Element, Extent);
  }
  return Slot.get();
}
