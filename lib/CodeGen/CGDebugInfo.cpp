//===- CGDebugInfo.cpp - DWARF for `-g` -----------------------------------===//
//
// What gdb needs to debug a behavior as the source reads (docs/repl.md,
// "gdb: -g"):
// - a line for every statement (FunctionEmitter sets the builder's location
//   per statement; the prologue of a task has the task's line);
// - a subprogram per func and task in a namespace per module, so
//   `break Motion::walk` works (the compile unit says C++, whose scoping
//   gdb then applies), and artificial ones for the glue bsc generates;
// - parameters and locals with their b-script types: int, float, bool,
//   `string` (a `const char *`), TaskState and registered enums as
//   enumerations, registered classes as structures with the C++ fields
//   and, for their properties, the getters as member functions (gdb calls
//   them; tools/gdb/bscript_printers.py shows them beside the fields);
// - `__bs_state`, argument 1 of every function, as `struct bs_state *`
//   whose members are the state header and every task's frame, module by
//   module (`print __bs_state->Motion.walk`), named so that a script's own
//   `state` does not hide it.
//
// A task's variable kept in its frame is described as the `__bs_state`
// argument plus the field's offset. That description holds at every point
// of the function: the code after a `yield` is entered from the resume
// switch, not from the block that declared the variable. Every dbg.declare
// therefore goes to the top of the entry block, whatever the scope.
//
//===----------------------------------------------------------------------===//
#include "FunctionEmitter.h"
#include "llvm/BinaryFormat/Dwarf.h"
#include "llvm/IR/InstIterator.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"

using namespace bsc;
using namespace bsc::codegen;

/// Whether a task's resume point or state lies in its frame (4 bytes) or
/// among the narrow headers after the frames.
static bool inFrame(const BehaviorLayout::Task &Task,
                    const BehaviorLayout::TaskWord &W) {
  return W.Offset >= Task.FrameOffset &&
         W.Offset < Task.FrameOffset + Task.FrameSize;
}

/// DWARF 4: the gdb and binutils of older robot toolchains read it.
constexpr unsigned DwarfVersion = 4;

DebugInfoEmitter::DebugInfoEmitter(ModuleEmitter &CGM,
                                   const llvm::SourceMgr &SM)
    : CGM(CGM), SM(SM), DIB(CGM.getModule()),
      Optimized(CGM.getOptions().OptLevel > 0) {
  llvm::Module &M = CGM.getModule();
  M.addModuleFlag(llvm::Module::Warning, "Dwarf Version", DwarfVersion);
  M.addModuleFlag(llvm::Module::Warning, "Debug Info Version",
                  llvm::DEBUG_METADATA_VERSION);
  const Behavior &B = CGM.getBehavior();
  llvm::DIFile *MainFile =
      B.Modules.empty()
          ? DIB.createFile(M.getSourceFileName(), ".")
          : getFile(llvm::SMLoc::getFromPointer(
                SM.getMemoryBuffer(B.Modules.front()->BufferID)
                    ->getBufferStart()));
  CU = DIB.createCompileUnit(llvm::dwarf::DW_LANG_C_plus_plus, MainFile,
                             "bsc", Optimized, "", /*RuntimeVersion=*/0);
}

//===----------------------------------------------------------------------===//
// Places
//===----------------------------------------------------------------------===//

llvm::DIFile *DebugInfoEmitter::getFile(llvm::SMLoc Loc) {
  unsigned ID = Loc.isValid() ? SM.FindBufferContainingLoc(Loc) : 0;
  if (!ID)
    return CU ? CU->getFile() : DIB.createFile("<unknown>", ".");
  llvm::DIFile *&F = Files[ID];
  if (F)
    return F;
  // As Clang does: the name as given, relative to the directory bsc ran in.
  llvm::StringRef Path = SM.getMemoryBuffer(ID)->getBufferIdentifier();
  llvm::SmallString<256> Dir;
  if (llvm::sys::path::is_absolute(Path))
    Dir = llvm::sys::path::parent_path(Path);
  else if (llvm::sys::fs::current_path(Dir))
    Dir = ".";
  llvm::StringRef Name = llvm::sys::path::is_absolute(Path)
                             ? llvm::sys::path::filename(Path)
                             : Path;
  F = DIB.createFile(Name, Dir);
  return F;
}

std::pair<unsigned, unsigned>
DebugInfoEmitter::getLineAndColumn(llvm::SMLoc Loc) {
  if (!Loc.isValid() || !SM.FindBufferContainingLoc(Loc))
    return {0, 0}; // DWARF's "no line".
  return SM.getLineAndColumn(Loc);
}

unsigned DebugInfoEmitter::getLine(llvm::SMLoc Loc) {
  return getLineAndColumn(Loc).first;
}

llvm::DILocation *DebugInfoEmitter::getLocation(llvm::SMLoc Loc,
                                                llvm::DIScope *Scope) {
  auto [Line, Col] = getLineAndColumn(Loc);
  return llvm::DILocation::get(CGM.getContext(), Line, Col, Scope);
}

llvm::DINamespace *DebugInfoEmitter::getNamespace(llvm::StringRef Name,
                                                  llvm::DIScope *Parent) {
  std::string Key = (Parent ? Parent->getName().str() + "::" : "") + Name.str();
  llvm::DINamespace *&NS = Namespaces[Key];
  if (!NS)
    NS = DIB.createNameSpace(Parent, Name, /*ExportSymbols=*/false);
  return NS;
}

llvm::DILexicalBlock *DebugInfoEmitter::createBlock(llvm::DIScope *Parent,
                                                    llvm::SMLoc Loc) {
  auto [Line, Col] = getLineAndColumn(Loc);
  return DIB.createLexicalBlock(Parent, getFile(Loc), Line, Col);
}

//===----------------------------------------------------------------------===//
// Types
//===----------------------------------------------------------------------===//

llvm::DIType *DebugInfoEmitter::getBasicType(llvm::StringRef Name,
                                             uint64_t Bits, unsigned Encoding) {
  llvm::DIType *&T = BasicTypes[Name];
  if (!T)
    T = DIB.createBasicType(Name, Bits, Encoding);
  return T;
}

llvm::DIType *DebugInfoEmitter::getStringType() {
  if (!StringTy) {
    const llvm::DataLayout &DL = CGM.getModule().getDataLayout();
    llvm::DIType *Char =
        getBasicType("char", 8, llvm::dwarf::DW_ATE_signed_char);
    llvm::DIType *ConstChar =
        DIB.createQualifiedType(llvm::dwarf::DW_TAG_const_type, Char);
    StringTy = DIB.createTypedef(
        DIB.createPointerType(ConstChar, DL.getPointerSizeInBits()), "string",
        nullptr, 0, CU);
  }
  return StringTy;
}

llvm::DIType *DebugInfoEmitter::getTaskStateType(unsigned Bits) {
  llvm::DIType *&Ty = Bits == 8 ? TaskState8Ty : TaskStateTy;
  if (!Ty) {
    llvm::DIType *Int =
        Bits == 8 ? getBasicType("signed char", 8, llvm::dwarf::DW_ATE_signed)
                  : getBasicType("int", 32, llvm::dwarf::DW_ATE_signed);
    // The named states; a custom state (`yield 3`) prints as its number.
    llvm::Metadata *Values[] = {DIB.createEnumerator("done", 0),
                                DIB.createEnumerator("running", 1),
                                DIB.createEnumerator("failure", -1)};
    Ty = DIB.createEnumerationType(CU, "TaskState", nullptr, 0, Bits, Bits,
                                   DIB.getOrCreateArray(Values), Int,
                                   /*RunTimeLang=*/0, "", /*IsScoped=*/true);
  }
  return Ty;
}

llvm::DIType *DebugInfoEmitter::getEnumType(const NativeEnum *E) {
  llvm::DIType *&T = Enums[E];
  if (T)
    return T;
  llvm::SmallVector<llvm::Metadata *, 8> Values;
  for (const NativeEnum::Value &V : E->Values)
    Values.push_back(DIB.createEnumerator(V.Name, V.Number));
  llvm::DIScope *Scope = E->Module ? getNamespace(E->Module->Name) : nullptr;
  T = DIB.createEnumerationType(
      Scope, E->Name, nullptr, 0, 32, 32, DIB.getOrCreateArray(Values),
      getBasicType("int", 32, llvm::dwarf::DW_ATE_signed), 0, "",
      /*IsScoped=*/true);
  return T;
}

llvm::DIType *DebugInfoEmitter::getNativeType(const NativeType &NT) {
  llvm::DIType *Element = getNativeElementType(NT);
  if (!NT.isArray() || !Element)
    return Element;
  // `float m[3][3]`: one array type with a subrange per dimension.
  llvm::SmallVector<llvm::Metadata *, 4> Ranges;
  uint64_t Bits = Element->getSizeInBits();
  for (uint32_t Extent : NT.Extents) {
    Ranges.push_back(DIB.getOrCreateSubrange(0, int64_t(Extent)));
    Bits *= Extent;
  }
  return DIB.createArrayType(Bits, 0, Element, DIB.getOrCreateArray(Ranges));
}

llvm::DIType *DebugInfoEmitter::getNativeElementType(const NativeType &NT) {
  unsigned Bits = NT.StorageSize * 8;
  switch (NT.TheCode) {
  case NativeType::Void:
    return nullptr;
  case NativeType::Bool:
    return getBasicType("bool", Bits ? Bits : 8, llvm::dwarf::DW_ATE_boolean);
  case NativeType::Int: {
    static const char *const Signed[] = {"signed char", "short", "int",
                                         "long long"};
    static const char *const Unsigned[] = {"unsigned char", "unsigned short",
                                           "unsigned int", "unsigned long long"};
    unsigned Size = Bits ? Bits : 32;
    unsigned Index = Size == 8 ? 0 : Size == 16 ? 1 : Size == 64 ? 3 : 2;
    return NT.Unsigned
               ? getBasicType(Unsigned[Index], Size,
                              Size == 8 ? llvm::dwarf::DW_ATE_unsigned_char
                                        : llvm::dwarf::DW_ATE_unsigned)
               : getBasicType(Signed[Index], Size,
                              Size == 8 ? llvm::dwarf::DW_ATE_signed_char
                                        : llvm::dwarf::DW_ATE_signed);
  }
  case NativeType::Float:
    return Bits == 64 ? getBasicType("double", 64, llvm::dwarf::DW_ATE_float)
                      : getBasicType("float", 32, llvm::dwarf::DW_ATE_float);
  case NativeType::String:
    return getStringType();
  case NativeType::Enum:
    return NT.TheEnum ? getEnumType(NT.TheEnum)
                      : getBasicType("int", 32, llvm::dwarf::DW_ATE_signed);
  case NativeType::Class:
    return NT.TheClass ? getClassType(NT.TheClass)
                       : DIB.createUnspecifiedType(NT.Name);
  }
  return nullptr;
}

llvm::DIType *DebugInfoEmitter::getClassType(const NativeClass *C) {
  llvm::DIType *&T = Classes[C];
  if (T)
    return T;
  llvm::DIScope *Scope = C->Module ? getNamespace(C->Module->Name) : nullptr;
  auto *Struct = DIB.createStructType(
      Scope, C->Name, nullptr, 0, C->Size * 8, C->Align * 8,
      llvm::DINode::FlagZero, nullptr, llvm::DINodeArray());
  T = Struct;
  // The fields bsc reads by offset, as C++ lays them out; properties and
  // private data stay out of sight, as in the script.
  llvm::SmallVector<llvm::Metadata *, 8> Members;
  for (const NativeFunction &F : C->Members) {
    if (F.Kind != NativeFunction::Field || !F.FieldOffset)
      continue;
    llvm::DIType *FieldTy = getNativeType(F.Result);
    if (!FieldTy)
      continue;
    uint64_t Bits = F.Result.StorageSize && !F.Result.isArray()
                        ? F.Result.StorageSize * 8
                        : FieldTy->getSizeInBits();
    Members.push_back(DIB.createMemberType(Struct, F.Name, nullptr, 0, Bits, 0,
                                           *F.FieldOffset * 8,
                                           llvm::DINode::FlagZero, FieldTy));
  }
  addProperties(C, Struct, Members);
  DIB.replaceArrays(Struct, DIB.getOrCreateArray(Members));
  return T;
}

llvm::DIType *DebugInfoEmitter::getWireType(const NativeType &NT) {
  switch (NT.TheCode) {
  case NativeType::Void:
  case NativeType::Class:
    return nullptr;
  case NativeType::Int:
    // Every integer up to 32 bits travels as one (a uint8_t 250 is 250).
    return NT.Unsigned
               ? getBasicType("unsigned int", 32, llvm::dwarf::DW_ATE_unsigned)
               : getBasicType("int", 32, llvm::dwarf::DW_ATE_signed);
  case NativeType::Float: // A double travels as float.
    return getBasicType("float", 32, llvm::dwarf::DW_ATE_float);
  case NativeType::Bool:
    // An i32 0 or 1: its low byte is the bool.
    return getBasicType("bool", 8, llvm::dwarf::DW_ATE_boolean);
  case NativeType::String:
  case NativeType::Enum:
    return getNativeElementType(NT);
  }
  return nullptr;
}

// A property has no place in the object, only a getter thunk, `wire(R)
// get(const T *self)`: the plain C ABI of a C++ member function of T that
// returns R, with `this` first. Declaring the thunk as such a member
// function (its symbol as the linkage name) lets gdb call it in a live
// process: `print v.x()`. A class-valued getter, `void get(R *out, const
// T *self)`, is no member function's shape (a C++ method returning R puts
// `this` first, or returns a small R in registers), so it is listed only.
//
// gdb's Python API does not list a type's member functions, so the
// pretty-printer finds the properties in a nested union, `T::__bs_properties`,
// one member per property with its type; a union takes no space in T and
// does not change how gdb prints T without the printer.
void DebugInfoEmitter::addProperties(
    const NativeClass *C, llvm::DICompositeType *Struct,
    llvm::SmallVectorImpl<llvm::Metadata *> &Members) {
  llvm::SmallVector<std::pair<const NativeFunction *, llvm::DIType *>, 8> Props;
  uint64_t Bits = 0, Align = 0;
  llvm::DIType *Self = nullptr;
  for (const NativeFunction &F : C->Members) {
    if (F.Kind != NativeFunction::Property || F.Symbol.empty())
      continue;
    llvm::DIType *Shown = F.Result.TheCode == NativeType::Class
                              ? getNativeType(F.Result)
                              : getWireType(F.Result);
    if (!Shown)
      continue;
    Props.push_back({&F, Shown});
    Bits = std::max(Bits, Shown->getSizeInBits());
    Align = std::max<uint64_t>(Align, Shown->getAlignInBits());
    llvm::DIType *Wire = getWireType(F.Result);
    if (!Wire)
      continue;
    if (!Self)
      Self = DIB.createObjectPointerType(DIB.createPointerType(
          DIB.createQualifiedType(llvm::dwarf::DW_TAG_const_type, Struct),
          CGM.getModule().getDataLayout().getPointerSizeInBits()));
    llvm::Metadata *Sig[] = {Wire, Self};
    Members.push_back(DIB.createMethod(
        Struct, F.Name, F.Symbol, nullptr, 0,
        DIB.createSubroutineType(DIB.getOrCreateTypeArray(Sig)),
        /*VTableIndex=*/0, /*ThisAdjustment=*/0, /*VTableHolder=*/nullptr,
        llvm::DINode::FlagPrototyped));
  }
  if (Props.empty())
    return;
  auto *List =
      DIB.createUnionType(Struct, "__bs_properties", nullptr, 0, Bits, Align,
                          llvm::DINode::FlagZero, llvm::DINodeArray());
  llvm::SmallVector<llvm::Metadata *, 8> Listed;
  for (auto [F, Ty] : Props)
    Listed.push_back(DIB.createMemberType(List, F->Name, nullptr, 0,
                                          Ty->getSizeInBits(), 0, 0,
                                          llvm::DINode::FlagZero, Ty));
  DIB.replaceArrays(List, DIB.getOrCreateArray(Listed));
  // Not referenced by any member: kept by the compile unit, emitted inside
  // its scope, T.
  DIB.retainType(List);
}

llvm::DIType *DebugInfoEmitter::getType(const Type *T) {
  switch (T->getKind()) {
  case TypeKind::Error:
  case TypeKind::Void:
  case TypeKind::Array: // Not a variable's type; fields: getClassType.
    return nullptr;
  case TypeKind::Int:
    return getBasicType("int", 32, llvm::dwarf::DW_ATE_signed);
  case TypeKind::Float:
    return getBasicType("float", 32, llvm::dwarf::DW_ATE_float);
  case TypeKind::Bool:
    // In memory a byte, 0 or 1 (CodeGenImpl.h).
    return getBasicType("bool", 8, llvm::dwarf::DW_ATE_boolean);
  case TypeKind::String:
    return getStringType();
  case TypeKind::TaskState:
    return getTaskStateType();
  case TypeKind::Enum:
    return getEnumType(T->getEnum());
  case TypeKind::Class:
    return getClassType(T->getClass());
  }
  return nullptr;
}

/// The bytes a task's narrow resume point and state take, [first, end);
/// empty if both are in its frame.
static std::pair<uint64_t, uint64_t>
getNarrowSpan(const BehaviorLayout::Task &Task) {
  uint64_t Start = ~0ull, End = 0;
  for (const BehaviorLayout::TaskWord &W : {Task.Resume, Task.State})
    if (!inFrame(Task, W)) {
      Start = std::min(Start, W.Offset);
      End = std::max(End, W.Offset + W.Bytes);
    }
  return {Start, End};
}

llvm::DIDerivedType *
DebugInfoEmitter::createTaskHeadersMember(llvm::DICompositeType *State) {
  const BehaviorLayout &Layout = CGM.getLayout();
  uint64_t HeadersStart = ~0ull, HeadersEnd = 0;
  for (const BehaviorLayout::Task &Task : Layout.Tasks) {
    auto [Start, End] = getNarrowSpan(Task);
    HeadersStart = std::min(HeadersStart, Start);
    HeadersEnd = std::max(HeadersEnd, End);
  }
  if (HeadersStart >= HeadersEnd)
    return nullptr;
  auto Member = [&](llvm::DIScope *Scope, llvm::StringRef Name, uint64_t Bits,
                    uint64_t Offset, llvm::DIType *Ty) {
    return DIB.createMemberType(Scope, Name, nullptr, 0, Bits, 0, Offset * 8,
                                llvm::DINode::FlagZero, Ty);
  };
  auto *Headers = DIB.createStructType(
      State, "task_headers", nullptr, 0, (HeadersEnd - HeadersStart) * 8, 0,
      llvm::DINode::FlagZero, nullptr, llvm::DINodeArray());
  llvm::SmallVector<llvm::Metadata *, 16> PerTask;
  for (const BehaviorLayout::Task &Task : Layout.Tasks) {
    auto [Start, End] = getNarrowSpan(Task);
    if (Start >= End)
      continue;
    // The task's name, with its module's where another module has a task
    // of that name.
    std::string TaskName = Task.Decl->getName().Name.str();
    if (llvm::count_if(Layout.Tasks, [&](const BehaviorLayout::Task &O) {
          return O.Decl->getName().Name == Task.Decl->getName().Name;
        }) > 1 &&
        Task.Decl->Module)
      TaskName = Task.Decl->Module->Name + "_" + TaskName;
    auto *Header = DIB.createStructType(
        Headers, TaskName + "_header", nullptr, 0, (End - Start) * 8, 0,
        llvm::DINode::FlagZero, nullptr, llvm::DINodeArray());
    llvm::SmallVector<llvm::Metadata *, 2> Words;
    // A bit field of an unsigned int: gdb prints a one-byte integer type as
    // a character too.
    if (!inFrame(Task, Task.Resume))
      Words.push_back(DIB.createBitFieldMemberType(
          Header, "resume", nullptr, 0, Task.Resume.Bytes * 8,
          (Task.Resume.Offset - Start) * 8, 0, llvm::DINode::FlagZero,
          getBasicType("unsigned int", 32, llvm::dwarf::DW_ATE_unsigned)));
    if (!inFrame(Task, Task.State))
      Words.push_back(Member(Header, "state", 8, Task.State.Offset - Start,
                             getTaskStateType(8)));
    DIB.replaceArrays(Header, DIB.getOrCreateArray(Words));
    PerTask.push_back(Member(Headers, TaskName, (End - Start) * 8,
                             Start - HeadersStart, Header));
  }
  DIB.replaceArrays(Headers, DIB.getOrCreateArray(PerTask));
  return Member(State, "headers", (HeadersEnd - HeadersStart) * 8,
                HeadersStart, Headers);
}

llvm::DIDerivedType *DebugInfoEmitter::createMember(llvm::DIScope *Scope,
                                                    llvm::StringRef Name,
                                                    uint64_t Bits,
                                                    uint64_t Offset,
                                                    llvm::DIType *Ty) {
  return DIB.createMemberType(Scope, Name, nullptr, 0, Bits, 0, Offset * 8,
                              llvm::DINode::FlagZero, Ty);
}

llvm::DIType *DebugInfoEmitter::getStatePointerType() {
  if (StatePtrTy)
    return StatePtrTy;
  const BehaviorLayout &Layout = CGM.getLayout();
  const llvm::DataLayout &DL = CGM.getModule().getDataLayout();
  unsigned PtrBits = DL.getPointerSizeInBits();
  llvm::DIType *U32 =
      getBasicType("unsigned int", 32, llvm::dwarf::DW_ATE_unsigned);
  llvm::DIType *VoidPtr = DIB.createPointerType(nullptr, PtrBits);
  auto *State = DIB.createStructType(CU, "bs_state", nullptr, 0,
                                     Layout.StateSize * 8,
                                     Layout.StateAlign * 8,
                                     llvm::DINode::FlagZero, nullptr,
                                     llvm::DINodeArray());
  // The header (bscript.h's bs_state_header): input and output point to
  // the world's classes when the behavior has a world.
  const NativeModule *World = CGM.getBehavior().World;
  auto WorldPtr = [&](const NativeClass *C) {
    return C ? DIB.createPointerType(getClassType(C), PtrBits) : VoidPtr;
  };
  const llvm::StructLayout *SL =
      DL.getStructLayout(CGM.getStateType());
  llvm::SmallVector<llvm::Metadata *, 16> Members = {
      createMember(State, "cycle", 32, SL->getElementOffset(StateCycle), U32),
      createMember(State, "input", PtrBits, SL->getElementOffset(StateInput),
                   WorldPtr(World ? World->Input : nullptr)),
      createMember(State, "output", PtrBits,
                   SL->getElementOffset(StateOutput),
                   WorldPtr(World ? World->Output : nullptr)),
      createMember(State, "user", PtrBits, SL->getElementOffset(StateUser),
                   VoidPtr)};
  // The frames, a structure per module holding its tasks' frames (tasks
  // are laid out module by module). The state type is made first, so that
  // the metadata keeps one order whichever frame uses it first.
  getTaskStateType();
  for (size_t I = 0; I < Layout.Tasks.size();) {
    const ModuleAST *Mod = Layout.Tasks[I].Decl->Module;
    size_t End = I;
    while (End < Layout.Tasks.size() && Layout.Tasks[End].Decl->Module == Mod)
      ++End;
    Members.push_back(createModuleFramesMember(State, I, End));
    I = End;
  }
  if (llvm::DIDerivedType *Headers = createTaskHeadersMember(State))
    Members.push_back(Headers);
  DIB.replaceArrays(State, DIB.getOrCreateArray(Members));
  StatePtrTy = DIB.createPointerType(State, PtrBits);
  return StatePtrTy;
}

llvm::DIDerivedType *
DebugInfoEmitter::createModuleFramesMember(llvm::DICompositeType *State,
                                           size_t Begin, size_t End) {
  const BehaviorLayout &Layout = CGM.getLayout();
  const ModuleAST *Mod = Layout.Tasks[Begin].Decl->Module;
  uint64_t ModStart = Layout.Tasks[Begin].FrameOffset;
  uint64_t ModEnd =
      Layout.Tasks[End - 1].FrameOffset + Layout.Tasks[End - 1].FrameSize;
  std::string ModName = Mod ? Mod->Name : "module";
  auto *ModStruct = DIB.createStructType(
      State, ModName + "_frames", nullptr, 0, (ModEnd - ModStart) * 8, 0,
      llvm::DINode::FlagZero, nullptr, llvm::DINodeArray());
  llvm::SmallVector<llvm::Metadata *, 8> Frames;
  for (size_t K = Begin; K < End; ++K) {
    const BehaviorLayout::Task &Task = Layout.Tasks[K];
    Frames.push_back(createMember(ModStruct, Task.Decl->getName().Name,
                                  Task.FrameSize * 8,
                                  Task.FrameOffset - ModStart,
                                  createFrameType(ModStruct, Task)));
  }
  DIB.replaceArrays(ModStruct, DIB.getOrCreateArray(Frames));
  return createMember(State, ModName, (ModEnd - ModStart) * 8, ModStart,
                      ModStruct);
}

llvm::DICompositeType *
DebugInfoEmitter::createFrameType(llvm::DIScope *ModStruct,
                                  const BehaviorLayout::Task &Task) {
  const llvm::DataLayout &DL = CGM.getModule().getDataLayout();
  llvm::DIType *U32 =
      getBasicType("unsigned int", 32, llvm::dwarf::DW_ATE_unsigned);
  std::string TaskName = Task.Decl->getName().Name.str();
  auto *Frame = DIB.createStructType(
      ModStruct, TaskName + "_frame", nullptr, 0, Task.FrameSize * 8, 0,
      llvm::DINode::FlagZero, nullptr, llvm::DINodeArray());
  // The frame's own words: the last call, the resume point and state if
  // they take 4 bytes. A kept variable of the same name (a task's `int
  // state`) keeps its name, and the word takes the `__bs_` prefix: gdb
  // would show one of two same-named members.
  auto WordName = [&](llvm::StringRef Name) {
    bool Taken =
        llvm::any_of(Task.Fields, [&](const BehaviorLayout::FrameField &F) {
          return F.D->getName().Name == Name;
        });
    return Taken ? ("__bs_" + Name).str() : Name.str();
  };
  llvm::SmallVector<llvm::Metadata *, 8> Fields = {
      createMember(Frame, WordName("last_call"), 32, 0, U32)};
  if (inFrame(Task, Task.Resume))
    Fields.push_back(createMember(Frame, WordName("resume"), 32,
                                  Task.Resume.Offset - Task.FrameOffset, U32));
  if (inFrame(Task, Task.State))
    Fields.push_back(createMember(Frame, WordName("state"), 32,
                                  Task.State.Offset - Task.FrameOffset,
                                  getTaskStateType()));
  // The fields kept (locals of disjoint scopes may share one).
  for (const BehaviorLayout::FrameField &F : Task.Fields) {
    llvm::DIType *Ty = getType(F.Ty);
    if (!Ty)
      continue;
    uint64_t Bits = Ty->getSizeInBits()
                        ? Ty->getSizeInBits()
                        : DL.getTypeAllocSizeInBits(CGM.getMemoryType(F.Ty));
    Fields.push_back(createMember(Frame, F.D->getName().Name, Bits,
                                  F.Offset - Task.FrameOffset, Ty));
  }
  DIB.replaceArrays(Frame, DIB.getOrCreateArray(Fields));
  return Frame;
}

llvm::DISubroutineType *
DebugInfoEmitter::getSubroutineType(const CallableDecl &D) {
  llvm::SmallVector<llvm::Metadata *, 8> Types;
  const auto *F = llvm::dyn_cast<FuncDecl>(&D);
  Types.push_back(F ? getType(F->ResultTy) : nullptr);
  Types.push_back(DIB.createArtificialType(getStatePointerType()));
  for (const ParamDecl *P : D.Params)
    Types.push_back(getType(P->Ty));
  return DIB.createSubroutineType(DIB.getOrCreateTypeArray(Types));
}

//===----------------------------------------------------------------------===//
// Functions and variables
//===----------------------------------------------------------------------===//

llvm::DISubprogram *DebugInfoEmitter::createFunction(const CallableDecl &D,
                                                     llvm::Function &Fn) {
  llvm::DIScope *Scope =
      D.Module ? getNamespace(D.Module->Name) : static_cast<llvm::DIScope *>(CU);
  // A nested func is `Module::task::f`.
  if (const auto *F = llvm::dyn_cast<FuncDecl>(&D))
    if (F->EnclosingTask)
      Scope = getNamespace(F->EnclosingTask->getName().Name, Scope);
  unsigned Line = getLine(D.getLoc());
  llvm::DISubprogram::DISPFlags SPFlags = llvm::DISubprogram::SPFlagDefinition;
  if (Fn.hasLocalLinkage())
    SPFlags |= llvm::DISubprogram::SPFlagLocalToUnit;
  // No linkage name: gdb would take `bs.M.f`, which no C++ demangler
  // reads, for the name, instead of `M::f` from the namespace.
  llvm::DISubprogram *SP = DIB.createFunction(
      Scope, D.getName().Name, /*LinkageName=*/"", getFile(D.getLoc()), Line,
      getSubroutineType(D), Line, llvm::DINode::FlagPrototyped, SPFlags);
  Fn.setSubprogram(SP);
  return SP;
}

void DebugInfoEmitter::createGlueFunction(llvm::Function &Fn,
                                          llvm::SMLoc Loc) {
  unsigned Line = getLine(Loc);
  llvm::DISubprogram *SP = DIB.createFunction(
      getFile(Loc), Fn.getName(), Fn.getName(), getFile(Loc), Line,
      DIB.createSubroutineType(DIB.getOrCreateTypeArray({})), Line,
      llvm::DINode::FlagArtificial | llvm::DINode::FlagPrototyped,
      llvm::DISubprogram::SPFlagDefinition |
          (Fn.hasLocalLinkage() ? llvm::DISubprogram::SPFlagLocalToUnit
                                : llvm::DISubprogram::SPFlagZero));
  Fn.setSubprogram(SP);
  llvm::DILocation *At = llvm::DILocation::get(CGM.getContext(), Line, 0, SP);
  for (llvm::Instruction &I : llvm::instructions(Fn))
    I.setDebugLoc(At);
}

llvm::DILocalVariable *DebugInfoEmitter::createVariable(const Decl &D,
                                                       const Type *Ty,
                                                       llvm::DIScope *Scope,
                                                       unsigned ArgNo) {
  llvm::DIType *DTy = getType(Ty);
  llvm::DIFile *File = getFile(D.getLoc());
  unsigned Line = getLine(D.getLoc());
  llvm::StringRef Name = D.getName().Name;
  if (ArgNo)
    return DIB.createParameterVariable(Scope, Name, ArgNo, File, Line, DTy,
                                       /*AlwaysPreserve=*/true);
  return DIB.createAutoVariable(Scope, Name, File, Line, DTy,
                                /*AlwaysPreserve=*/true);
}

void DebugInfoEmitter::declareVariable(const Decl &D, const Type *Ty,
                                       llvm::DIScope *Scope,
                                       llvm::AllocaInst *Slot, unsigned ArgNo,
                                       llvm::Instruction *Before) {
  DIB.insertDeclare(Slot, createVariable(D, Ty, Scope, ArgNo),
                    DIB.createExpression(), getLocation(D.getLoc(), Scope),
                    Before);
}

void DebugInfoEmitter::declareFrameVariable(
    const Decl &D, const Type *Ty, llvm::DIScope *Scope, llvm::Value *State,
    llvm::AllocaInst *StateSlot, uint64_t Offset, unsigned ArgNo,
    llvm::Instruction *Before) {
  llvm::DILocalVariable *Var = createVariable(D, Ty, Scope, ArgNo);
  llvm::DILocation *Loc = getLocation(D.getLoc(), Scope);
  if (!Optimized) {
    // At (slot) + Offset: a stack slot is valid in the whole function.
    DIB.insertDeclare(StateSlot, Var,
                      DIB.createExpression(llvm::ArrayRef<uint64_t>{
                          llvm::dwarf::DW_OP_deref,
                          llvm::dwarf::DW_OP_plus_uconst, Offset}),
                      Loc, Before);
    return;
  }
  // In memory at state + Offset (the trailing deref makes it a memory
  // location); mem2reg would drop the form above once the slot is gone.
  DIB.insertDbgValueIntrinsic(
      State, Var,
      DIB.createExpression(llvm::ArrayRef<uint64_t>{
          llvm::dwarf::DW_OP_plus_uconst, Offset, llvm::dwarf::DW_OP_deref}),
      Loc, Before);
}

void DebugInfoEmitter::declareState(llvm::DISubprogram *SP, llvm::Value *Slot,
                                    llvm::Instruction *Before) {
  llvm::DILocalVariable *Var = DIB.createParameterVariable(
      SP, StateParamName, 1, SP->getFile(), SP->getLine(),
      getStatePointerType(), /*AlwaysPreserve=*/true,
      llvm::DINode::FlagArtificial);
  DIB.insertDeclare(Slot, Var, DIB.createExpression(),
                    llvm::DILocation::get(CGM.getContext(), SP->getLine(), 0,
                                          SP),
                    Before);
}

void DebugInfoEmitter::finalize() {
  // Calls that no statement located (none should remain) get the function's
  // line 0: the verifier requires a location on every call of a function
  // with debug information.
  for (llvm::Function &F : CGM.getModule()) {
    llvm::DISubprogram *SP = F.getSubprogram();
    if (!SP)
      continue;
    for (llvm::Instruction &I : llvm::instructions(F))
      if (llvm::isa<llvm::CallBase>(I) && !I.getDebugLoc())
        I.setDebugLoc(llvm::DILocation::get(CGM.getContext(), 0, 0, SP));
  }
  DIB.finalize();
}

//===----------------------------------------------------------------------===//
// FunctionEmitter's side
//===----------------------------------------------------------------------===//

void FunctionEmitter::emitDebugPrologue() {
  DebugInfoEmitter *DI = CGM.getDebugInfo();
  DebugScopes = {DI->createFunction(D, *Fn)};
  // mem2reg removes these slots at -O1 and above.
  StateSlot = new llvm::AllocaInst(StatePtr->getType(), 0,
                                   StateParamName + ".addr",
                                   EntryPoint);
  Builder.CreateStore(StatePtr, StateSlot);
  DI->declareState(Fn->getSubprogram(), StateSlot, EntryPoint);
  if (!Task)
    return; // A func's parameters are in slots anyway (emitFuncPrologue).
  // A task's frame keeps a copy of a parameter for nested funcs, stored
  // only after the reset check; the argument is what the body reads.
  for (const ParamDecl *P : Task->Params) {
    if (!P->Ty->isClass()) {
      llvm::AllocaInst *Slot =
          createSlot(P->Ty, P->getName().Name + ".addr");
      emitStore(P->Ty, Fn->getArg(P->Index + 1), Slot);
      Slots[P] = Slot;
    }
    declareForDebugger(*P, P->Ty, P->Index + 2);
  }
}

void FunctionEmitter::setDebugLocation(llvm::SMLoc Loc) {
  if (DebugInfoEmitter *DI = CGM.getDebugInfo())
    Builder.SetCurrentDebugLocation(DI->getLocation(Loc, DebugScopes.back()));
}

void FunctionEmitter::pushDebugScope(llvm::SMLoc Loc) {
  if (DebugInfoEmitter *DI = CGM.getDebugInfo())
    DebugScopes.push_back(DI->createBlock(DebugScopes.back(), Loc));
}

void FunctionEmitter::popDebugScope() {
  if (CGM.getDebugInfo())
    DebugScopes.pop_back();
}

void FunctionEmitter::declareForDebugger(const Decl &Dcl, const Type *Ty,
                                         unsigned ArgNo) {
  DebugInfoEmitter *DI = CGM.getDebugInfo();
  if (!DI)
    return;
  // A stack slot (a func's variables, a task's scalar parameters with -g,
  // a task's locals that never outlive a call).
  if (auto *Slot =
          llvm::dyn_cast_or_null<llvm::AllocaInst>(Slots.lookup(&Dcl))) {
    DI->declareVariable(Dcl, Ty, DebugScopes.back(), Slot, ArgNo, EntryPoint);
    return;
  }
  // A task's parameter or local kept in its frame: `__bs_state` plus the
  // field's offset (the file comment says why not the field's address).
  const CallableDecl *Owner = nullptr;
  if (const auto *V = llvm::dyn_cast<VarDecl>(&Dcl))
    Owner = V->Owner;
  else
    Owner = llvm::cast<ParamDecl>(Dcl).Owner;
  if (const auto *T = llvm::dyn_cast_or_null<TaskDecl>(Owner))
    if (CGM.keepsInFrame(&Dcl)) {
      DI->declareFrameVariable(
          Dcl, Ty, DebugScopes.back(), StatePtr, StateSlot,
          CGM.getFrameFieldOffset(T, CGM.getFrame(T).Fields.lookup(&Dcl)),
          ArgNo, EntryPoint);
      return;
    }
}
