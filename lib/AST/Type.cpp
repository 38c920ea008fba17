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
