//===- Type.h - the static types of b-script -------------------*- C++ -*-===//
//
// Types are uniqued in a TypeContext, so they compare by pointer. The error
// type is poison: an expression of error type has already been diagnosed,
// and every check that sees it stays silent (one mistake, one message).
//
//===----------------------------------------------------------------------===//
#ifndef BSC_AST_TYPE_H
#define BSC_AST_TYPE_H

#include "llvm/ADT/StringRef.h"
#include <map>
#include <memory>
#include <string>

namespace bsc {

struct NativeEnum;

enum class TypeKind { Error, Void, Int, Float, Bool, String, TaskState, Enum };

class Type {
public:
  TypeKind getKind() const { return Kind; }
  /// The name as the user writes it (`int`, `TaskState`, `MotionType`).
  llvm::StringRef getName() const { return Name; }
  const NativeEnum *getEnum() const { return Enum; }

  bool isError() const { return Kind == TypeKind::Error; }
  bool isVoid() const { return Kind == TypeKind::Void; }
  bool isInt() const { return Kind == TypeKind::Int; }
  bool isFloat() const { return Kind == TypeKind::Float; }
  bool isBool() const { return Kind == TypeKind::Bool; }
  bool isString() const { return Kind == TypeKind::String; }
  bool isTaskState() const { return Kind == TypeKind::TaskState; }
  bool isEnum() const { return Kind == TypeKind::Enum; }
  bool isArithmetic() const { return isInt() || isFloat(); }

  Type(TypeKind K, std::string Name, const NativeEnum *E = nullptr)
      : Kind(K), Name(std::move(Name)), Enum(E) {}

private:
  TypeKind Kind;
  std::string Name;
  const NativeEnum *Enum;
};

/// Owns and uniques every type of one compilation.
class TypeContext {
public:
  TypeContext();
  const Type *getError() const { return &ErrorTy; }
  const Type *getVoid() const { return &VoidTy; }
  const Type *getInt() const { return &IntTy; }
  const Type *getFloat() const { return &FloatTy; }
  const Type *getBool() const { return &BoolTy; }
  const Type *getString() const { return &StringTy; }
  const Type *getTaskState() const { return &TaskStateTy; }
  /// The type of a registered enum, named by its qualified b-script name.
  const Type *getEnum(const NativeEnum *E, llvm::StringRef QualifiedName);

private:
  Type ErrorTy, VoidTy, IntTy, FloatTy, BoolTy, StringTy, TaskStateTy;
  std::map<const NativeEnum *, std::unique_ptr<Type>> Enums;
};

} // namespace bsc

#endif
