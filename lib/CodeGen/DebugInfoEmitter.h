//===- DebugInfoEmitter.h - the DWARF of -g ---------------------*- C++ -*-===//
//
// DebugInfoEmitter: the DWARF of `-g` (CodeGenOptions::DebugInfo), defined
// in CGDebugInfo.cpp; CodeGenImpl.h gives the overview of the generator.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_CODEGEN_DEBUGINFOEMITTER_H
#define BSC_LIB_CODEGEN_DEBUGINFOEMITTER_H

#include "CodeGenImpl.h"

namespace bsc {
namespace codegen {

class ModuleEmitter;

/// The DWARF of `-g` (CodeGenOptions::DebugInfo), as Clang's CGDebugInfo:
/// one compile unit per behavior, a namespace per module (so gdb's
/// `break Motion::walk` works: the CU's language is C++), a subprogram per
/// func and task and for the generated glue, b-script types as DWARF base,
/// enumeration and structure types. Where a variable lives decides how it
/// is described: an alloca by itself; a frame field as the `state`
/// argument plus the field's offset (DW_OP_plus_uconst), which holds
/// wherever the function runs, also after a resume.
class DebugInfoEmitter {
public:
  DebugInfoEmitter(ModuleEmitter &CGM, const llvm::SourceMgr &SM);

  /// The subprogram of the function of a func or task.
  llvm::DISubprogram *createFunction(const CallableDecl &D,
                                     llvm::Function &Fn);
  /// An artificial subprogram for generated glue (entries, `main`, destroy
  /// functions) whose code is attributed to line `Loc` (invalid: line 0).
  /// Every instruction gets that location, so that the calls into the
  /// b-script functions inlined there have one (the verifier insists).
  void createGlueFunction(llvm::Function &Fn, llvm::SMLoc Loc);
  /// Line and column of `Loc` in `Scope`.
  llvm::DILocation *getLocation(llvm::SMLoc Loc, llvm::DIScope *Scope);
  /// A lexical block (a block statement, a `for` head) at `Loc`.
  llvm::DILexicalBlock *createBlock(llvm::DIScope *Parent, llvm::SMLoc Loc);
  /// Describes parameter or local `D` of type `Ty` in `Scope`, which lives
  /// in the alloca `Slot`. `ArgNo`: 0 for locals, else the DWARF argument
  /// number. The dbg.declare goes before `Before`.
  void declareVariable(const Decl &D, const Type *Ty, llvm::DIScope *Scope,
                       llvm::AllocaInst *Slot, unsigned ArgNo,
                       llvm::Instruction *Before);
  /// The same for a task's parameter or local kept in its frame, `Offset`
  /// bytes into the state. Unoptimised code reads the state pointer from
  /// its stack slot `StateSlot` (alive all along); optimised code has it
  /// in `State`, the argument, whose value LLVM tracks through registers.
  void declareFrameVariable(const Decl &D, const Type *Ty,
                            llvm::DIScope *Scope, llvm::Value *State,
                            llvm::AllocaInst *StateSlot, uint64_t Offset,
                            unsigned ArgNo, llvm::Instruction *Before);
  /// Describes the `state` argument, spilled to `Slot`: argument 1, of
  /// type `struct bs_state *` (the header and every frame), so that
  /// `print *state` shows the whole behavior.
  void declareState(llvm::DISubprogram *SP, llvm::Value *Slot,
                    llvm::Instruction *Before);
  /// Completes the types and subprograms.
  void finalize();

private:
  llvm::DIFile *getFile(llvm::SMLoc Loc);
  /// Line and column of `Loc`; 0, 0 where it has none.
  std::pair<unsigned, unsigned> getLineAndColumn(llvm::SMLoc Loc);
  unsigned getLine(llvm::SMLoc Loc);
  llvm::DINamespace *getNamespace(llvm::StringRef Name,
                                  llvm::DIScope *Parent = nullptr);
  llvm::DIType *getType(const Type *T);
  /// A registered C++ field's type as C++ declares it (short, double,
  /// float[3][3], ...), and one element of it.
  llvm::DIType *getNativeType(const NativeType &NT);
  llvm::DIType *getNativeElementType(const NativeType &NT);
  llvm::DIType *getBasicType(llvm::StringRef Name, uint64_t Bits,
                             unsigned Encoding);
  llvm::DIType *getEnumType(const NativeEnum *E);
  /// TaskState of 32 bits (values, frames) or 8 (a narrow task state,
  /// bscript.h bs_task_info): the same enumeration by name.
  llvm::DIType *getTaskStateType(unsigned Bits = 32);
  llvm::DIType *getClassType(const NativeClass *C);
  /// A property's value as its getter thunk returns it (bindings.md, "wire"):
  /// integers as 32 bits, floats as float; null for a class (returned
  /// through an out pointer) or void.
  llvm::DIType *getWireType(const NativeType &NT);
  /// The properties of class `C`, whose DWARF is `Struct`: a member function
  /// per scalar property whose linkage name is its getter thunk (`print
  /// v.x()`), and the union `__bs_properties` that lists every property for
  /// the pretty-printer (tools/gdb/bscript_printers.py); appended to
  /// `Members`.
  void addProperties(const NativeClass *C, llvm::DICompositeType *Struct,
                     llvm::SmallVectorImpl<llvm::Metadata *> &Members);
  llvm::DIType *getStringType();
  llvm::DIType *getStatePointerType();
  /// A member of `Scope` of `Bits` bits at byte `Offset`.
  llvm::DIDerivedType *createMember(llvm::DIScope *Scope, llvm::StringRef Name,
                                    uint64_t Bits, uint64_t Offset,
                                    llvm::DIType *Ty);
  /// The state's member for the frames of the tasks [Begin, End) of the
  /// layout, one module's.
  llvm::DIDerivedType *createModuleFramesMember(llvm::DICompositeType *State,
                                                size_t Begin, size_t End);
  /// A task's frame: its own words and the fields it keeps.
  llvm::DICompositeType *createFrameType(llvm::DIScope *ModStruct,
                                         const BehaviorLayout::Task &Task);
  /// The state's member `headers`: per task with a narrow resume point or
  /// state (bscript.h bs_task_info), a structure of them; null if none.
  llvm::DIDerivedType *createTaskHeadersMember(llvm::DICompositeType *State);
  llvm::DISubroutineType *getSubroutineType(const CallableDecl &D);
  llvm::DILocalVariable *createVariable(const Decl &D, const Type *Ty,
                                        llvm::DIScope *Scope, unsigned ArgNo);

  ModuleEmitter &CGM;
  const llvm::SourceMgr &SM;
  llvm::DIBuilder DIB;
  llvm::DICompileUnit *CU = nullptr;
  llvm::DenseMap<unsigned, llvm::DIFile *> Files; ///< By buffer ID.
  llvm::StringMap<llvm::DINamespace *> Namespaces;
  llvm::StringMap<llvm::DIType *> BasicTypes;
  llvm::DenseMap<const NativeEnum *, llvm::DIType *> Enums;
  llvm::DenseMap<const NativeClass *, llvm::DIType *> Classes;
  llvm::DIType *TaskStateTy = nullptr, *TaskState8Ty = nullptr;
  llvm::DIType *StringTy = nullptr;
  llvm::DIType *StatePtrTy = nullptr;
  bool Optimized; ///< CodeGenOptions::OptLevel > 0.
};

} // namespace codegen
} // namespace bsc

#endif
