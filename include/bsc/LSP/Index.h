//===- Index.h - what each name of a checked behavior stands for -*- C++ -*-===//
//
// The language server answers hover, go-to-definition, references, rename,
// semantic tokens and outlines from one table: every name written in the
// behavior's modules (a declaration or a use), with what Sema resolved it
// to, and every expression with its type. It is built by one walk over the
// checked tree after each edit; nothing in it outlives the Compilation.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LSP_INDEX_H
#define BSC_LSP_INDEX_H

#include "bsc/AST/AST.h"
#include "bsc/AST/Native.h"
#include "bsc/AST/Type.h"
#include "llvm/ADT/ArrayRef.h"
#include <vector>

namespace bsc {
namespace lsp {

/// What a name stands for: a declaration of the script, or something
/// registered in C++, or a module.
struct Symbol {
  enum Kind {
    None,
    Decl,          ///< Ptr: a bsc::Decl (task, func, param, local, const, enum).
    Enumerator,    ///< Ptr: the EnumDecl; Index: the enumerator.
    NativeFunction, ///< Ptr: a NativeFunction (function, method, field, property).
    NativeClass,   ///< Ptr: a NativeClass.
    NativeEnum,    ///< Ptr: a registered NativeEnum.
    NativeEnumValue, ///< Ptr: the NativeEnum; Index: the value.
    NativeConstant, ///< Ptr: a NativeConstant.
    ScriptModule,  ///< Ptr: a ModuleAST.
    NativeModule,  ///< Ptr: a NativeModule.
    Global,        ///< `input` (Index 0) or `output` (Index 1).
  };
  Kind K = None;
  const void *Ptr = nullptr;
  unsigned Index = 0;

  bool operator==(const Symbol &O) const {
    return K == O.K && Ptr == O.Ptr && Index == O.Index;
  }
  explicit operator bool() const { return K != None; }
  /// Whether the script declares it (so it can be renamed).
  bool isScript() const {
    return K == Decl || K == Enumerator || K == ScriptModule;
  }
};

/// One name in the source.
struct Occurrence {
  llvm::SMRange Range;
  Symbol Sym;
  bool IsDefinition = false;
};

/// An expression with its type, for hover.
struct TypedRange {
  llvm::SMRange Range;
  const Type *Ty;
};

struct Index {
  /// In source order within each buffer.
  std::vector<Occurrence> Occurrences;
  std::vector<TypedRange> Expressions;
  /// The script enums by their values (types refer to the NativeEnum
  /// inside the EnumDecl).
  std::vector<const EnumDecl *> ScriptEnums;

  /// The occurrence whose range holds `Loc` (end inclusive, so a cursor
  /// right after a name finds it), if any.
  const Occurrence *findAt(llvm::SMLoc Loc) const;
  /// The innermost expression holding `Loc`, if any.
  const TypedRange *findExpressionAt(llvm::SMLoc Loc) const;
  /// The EnumDecl whose values `E` are, or null for a registered enum.
  const EnumDecl *getScriptEnum(const bsc::NativeEnum *E) const;
};

/// Walks every module of a checked behavior.
Index buildIndex(llvm::ArrayRef<ModuleAST *> Modules);

} // namespace lsp
} // namespace bsc

#endif
