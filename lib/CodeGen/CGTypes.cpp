//===- CGTypes.cpp - b-script types as LLVM types -------------------------===//
//
// How values are represented: a b-script type in registers (getValueType:
// bool is i1) and in memory (getMemoryType: bool is i8, a registered class
// its own storage with the class's size and alignment), the C ABI types of
// native parameters and results, which class values need destroying, and
// the zero value every local starts with.
//
//===----------------------------------------------------------------------===//
#include "ModuleEmitter.h"
#include "llvm/IR/Constants.h"
#include "llvm/IR/DerivedTypes.h"
#include "llvm/Support/ErrorHandling.h"

using namespace bsc;
using namespace bsc::codegen;

llvm::Type *ModuleEmitter::getValueType(const Type *T) {
  switch (T->getKind()) {
  case TypeKind::Void:
    return llvm::Type::getVoidTy(Ctx);
  case TypeKind::Int:
  case TypeKind::TaskState:
  case TypeKind::Enum:
    return llvm::Type::getInt32Ty(Ctx);
  case TypeKind::Float:
    return llvm::Type::getFloatTy(Ctx);
  case TypeKind::Bool:
    return llvm::Type::getInt1Ty(Ctx);
  case TypeKind::String:
    return llvm::PointerType::getUnqual(Ctx);
  case TypeKind::Class:
    // A pointer to the value's storage (CodeGenImpl.h).
    return llvm::PointerType::getUnqual(Ctx);
  case TypeKind::Error:
  case TypeKind::Array: // Only indexed (IndexExpr), never a value.
    break;
  }
  llvm_unreachable("the error type never reaches code generation");
}

llvm::Type *ModuleEmitter::getMemoryType(const Type *T) {
  if (T->isBool())
    return llvm::Type::getInt8Ty(Ctx);
  if (T->isClass())
    return getClassMemoryType(T->getClass());
  return getValueType(T);
}

llvm::Type *ModuleEmitter::getClassMemoryType(const NativeClass *C) {
  uint64_t Align = C->Align ? C->Align : 1;
  if (Align == 1 || C->Size % Align != 0)
    return llvm::ArrayType::get(llvm::Type::getInt8Ty(Ctx), C->Size);
  // A unit of Align bytes whose ABI alignment on this target is Align, so
  // that frames, the state and allocas get the class's alignment from the
  // DataLayout (i64 is only 4-aligned on i586; vectors are size-aligned).
  const llvm::DataLayout &DL = M.getDataLayout();
  llvm::Type *Unit = nullptr;
  for (unsigned Bits : {16u, 32u, 64u, 128u}) {
    llvm::Type *I = llvm::Type::getIntNTy(Ctx, Bits);
    if (Bits / 8 == Align && DL.getABITypeAlign(I).value() == Align &&
        DL.getTypeAllocSize(I) == Align) {
      Unit = I;
      break;
    }
  }
  if (!Unit)
    Unit = llvm::FixedVectorType::get(llvm::Type::getInt8Ty(Ctx), Align);
  return llvm::ArrayType::get(Unit, C->Size / Align);
}

bool ModuleEmitter::returnsClass(const CallableDecl &D) {
  const auto *F = llvm::dyn_cast<FuncDecl>(&D);
  return F && F->ResultTy && F->ResultTy->isClass();
}

bool ModuleEmitter::needsDestroy(const NativeClass *C) {
  return C && !C->TriviallyDestructible && !C->Destroy.empty();
}

bool ModuleEmitter::needsDestroy(const Type *T) {
  return T && T->isClass() && needsDestroy(T->getClass());
}

llvm::Constant *ModuleEmitter::getZeroValue(const Type *T) {
  // A string local without initialiser is "" rather than null: it may be
  // passed to C code that expects a valid `const char *`.
  if (T->isString())
    return getString("");
  return llvm::Constant::getNullValue(getMemoryType(T));
}

llvm::Type *ModuleEmitter::getNativeType(const NativeType &NT) {
  switch (NT.TheCode) {
  case NativeType::Void:
    return llvm::Type::getVoidTy(Ctx);
  case NativeType::Bool: // C ABI: bool travels as a 0/1 int32 (bscript.h).
  case NativeType::Int:
  case NativeType::Enum:
    return llvm::Type::getInt32Ty(Ctx);
  case NativeType::Float:
    return llvm::Type::getFloatTy(Ctx);
  case NativeType::String:
    return llvm::PointerType::getUnqual(Ctx);
  case NativeType::Class: // const T * / T *.
    return llvm::PointerType::getUnqual(Ctx);
  }
  llvm_unreachable("unknown native type");
}
