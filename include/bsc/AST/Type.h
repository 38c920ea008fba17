//===- Type.h - the static types of b-script -------------------*- C++ -*-===//
//
// Types are uniqued in a TypeContext, so they compare by pointer. The error
// type is poison: an expression of error type has already been diagnosed,
// and every check that sees it stays silent (one mistake, one message).
//
// Registered enums and classes point at their Native.h description, which
// is where Sema finds enum values and class members and CodeGen finds sizes,
// alignments and thunks; the type itself only adds identity and a name.
// A script's own `enum` (EnumDecl) carries its values in the same form.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_AST_TYPE_H
#define BSC_AST_TYPE_H

#include "llvm/ADT/StringRef.h"
#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace bsc {

struct NativeClass;
struct NativeEnum;

enum class TypeKind {
  Error,
  Void,
  Int,
  Float,
  Bool,
  String,
  TaskState,
  Enum,  ///< A registered or script enum (getEnum()).
  Class, ///< A registered C++ class, a value type (getClass()).
  /// An array field of a registered class (`float m[3][3]` is an array of
  /// 3 arrays of 3 floats): getElement(), getExtent(). Only the base of an
  /// index expression has this type; b-script has no array values.
  Array,
};

class Type {
public:
  TypeKind getKind() const { return Kind; }
  /// The name as the user writes it (`int`, `TaskState`, `MotionType`).
  llvm::StringRef getName() const { return Name; }
  const NativeEnum *getEnum() const { return Enum; }
  const NativeClass *getClass() const { return Class; }
  const Type *getElement() const { return Element; }
  uint32_t getExtent() const { return Extent; }

  bool isError() const { return Kind == TypeKind::Error; }
  bool isVoid() const { return Kind == TypeKind::Void; }
  bool isInt() const { return Kind == TypeKind::Int; }
  bool isFloat() const { return Kind == TypeKind::Float; }
  bool isBool() const { return Kind == TypeKind::Bool; }
  bool isString() const { return Kind == TypeKind::String; }
  bool isTaskState() const { return Kind == TypeKind::TaskState; }
  bool isEnum() const { return Kind == TypeKind::Enum; }
  bool isClass() const { return Kind == TypeKind::Class; }
  bool isArray() const { return Kind == TypeKind::Array; }
  bool isArithmetic() const { return isInt() || isFloat(); }

  Type(TypeKind K, std::string Name, const NativeEnum *E = nullptr,
       const NativeClass *C = nullptr)
      : Kind(K), Name(std::move(Name)), Enum(E), Class(C) {}
  Type(std::string Name, const Type *Element, uint32_t Extent)
      : Kind(TypeKind::Array), Name(std::move(Name)), Element(Element),
        Extent(Extent) {}

private:
  TypeKind Kind;
  std::string Name;
  const NativeEnum *Enum = nullptr;
  const NativeClass *Class = nullptr;
  const Type *Element = nullptr;
  uint32_t Extent = 0;
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
  /// The type of a registered class (named by its QualifiedName).
  const Type *getClass(const NativeClass *C);
  /// An array of `Extent` elements (named as C declares it: `float[3][3]`).
  const Type *getArray(const Type *Element, uint32_t Extent);

private:
  Type ErrorTy, VoidTy, IntTy, FloatTy, BoolTy, StringTy, TaskStateTy;
  std::map<const NativeEnum *, std::unique_ptr<Type>> Enums;
  std::map<const NativeClass *, std::unique_ptr<Type>> Classes;
  std::map<std::pair<const Type *, uint32_t>, std::unique_ptr<Type>> Arrays;
};

} // namespace bsc

#endif
