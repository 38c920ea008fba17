//===- ValueRead.cpp - values in memory read as JSON ----------------------===//
//
// Registered members come in two forms (Native.h): a field with an offset,
// read and written in place by its C++ storage size, and a property (or a
// field bsc may not touch directly) behind getter and setter thunks with
// the plain C ABI of docs/bindings.md. Both are handled here the way
// generated code handles them, so what the debugger shows is what the
// behavior reads.
//
//===----------------------------------------------------------------------===//
#include "ValuesImpl.h"
#include "llvm/Support/MemAlloc.h"
#include <string>

using namespace bsc;
using namespace bsc::debug;
using llvm::json::Value;

//===----------------------------------------------------------------------===//
// Reading
//===----------------------------------------------------------------------===//

void *ValueIO::thunk(const std::string &Symbol) {
  if (Symbol.empty())
    return nullptr;
  auto [It, New] = Thunks.try_emplace(&Symbol, nullptr);
  if (New)
    It->second = Resolve(Symbol);
  return It->second;
}


Value ValueIO::readNative(const NativeType &NT, const void *Addr,
                          size_t Dim) {
  if (Dim < NT.Extents.size()) {
    // An array field: a JSON array per dimension.
    llvm::json::Array A;
    uint64_t Stride = getStride(NT, Dim);
    for (uint32_t I = 0; I < NT.Extents[Dim]; ++I)
      A.push_back(
          readNative(NT, static_cast<const char *>(Addr) + I * Stride, Dim + 1));
    return A;
  }
  unsigned Size = NT.StorageSize;
  switch (NT.TheCode) {
  case NativeType::Void:
    return nullptr;
  case NativeType::Bool:
    return loadInt(Addr, Size ? Size : 1, true) != 0;
  case NativeType::Int:
    // The b-script value is the int32 the behavior reads.
    return int64_t(int32_t(loadInt(Addr, Size ? Size : 4, NT.Unsigned)));
  case NativeType::Enum:
    return enumToJSON(NT.TheEnum, loadInt(Addr, Size ? Size : 4, NT.Unsigned));
  case NativeType::Float:
    if (Size == 8) {
      double D;
      std::memcpy(&D, Addr, 8);
      return floatToJSON(float(D));
    } else {
      float F;
      std::memcpy(&F, Addr, 4);
      return floatToJSON(F);
    }
  case NativeType::String: {
    const char *S;
    std::memcpy(&S, Addr, sizeof S);
    return S ? Value(std::string(S)) : Value(nullptr);
  }
  case NativeType::Class:
    return NT.TheClass ? readClass(*NT.TheClass, Addr) : Value(nullptr);
  }
  return nullptr;
}

Value ValueIO::read(const Type *T, const void *Addr) {
  switch (T->getKind()) {
  case TypeKind::Error:
  case TypeKind::Void:
  case TypeKind::Array: // Only fields are arrays: readNative.
    return nullptr;
  case TypeKind::Int:
  case TypeKind::TaskState:
    return loadInt(Addr, 4, false);
  case TypeKind::Enum:
    return enumToJSON(T->getEnum(), loadInt(Addr, 4, false));
  case TypeKind::Float: {
    float F;
    std::memcpy(&F, Addr, 4);
    return floatToJSON(F);
  }
  case TypeKind::Bool:
    return *static_cast<const uint8_t *>(Addr) != 0;
  case TypeKind::String: {
    const char *S;
    std::memcpy(&S, Addr, sizeof S);
    return std::string(S ? S : "");
  }
  case TypeKind::Class:
    return readClass(*T->getClass(), Addr);
  }
  return nullptr;
}

Value ValueIO::readMember(const NativeClass &C, const NativeFunction &M,
                          const void *Obj) {
  if (M.FieldOffset)
    return readNative(M.Result, static_cast<const char *>(Obj) + *M.FieldOffset);
  void *Getter = thunk(M.Symbol);
  if (!Getter)
    return nullptr;
  switch (M.Result.TheCode) {
  case NativeType::Void:
    return nullptr;
  case NativeType::Bool:
    return reinterpret_cast<int32_t (*)(const void *)>(Getter)(Obj) != 0;
  case NativeType::Int:
    return reinterpret_cast<int32_t (*)(const void *)>(Getter)(Obj);
  case NativeType::Enum:
    return enumToJSON(M.Result.TheEnum,
                      reinterpret_cast<int32_t (*)(const void *)>(Getter)(Obj));
  case NativeType::Float:
    return floatToJSON(reinterpret_cast<float (*)(const void *)>(Getter)(Obj));
  case NativeType::String: {
    const char *S =
        reinterpret_cast<const char *(*)(const void *)>(Getter)(Obj);
    return S ? Value(std::string(S)) : Value(nullptr);
  }
  case NativeType::Class: {
    const NativeClass *RC = M.Result.TheClass;
    if (!RC || !M.ResultViaOut)
      return nullptr;
    // The getter copy-constructs into raw storage, as for generated code.
    size_t Align = RC->Align ? RC->Align : 1, Size = RC->Size ? RC->Size : 1;
    void *Tmp = llvm::allocate_buffer(Size, Align);
    std::memset(Tmp, 0, Size);
    reinterpret_cast<void (*)(void *, const void *)>(Getter)(Tmp, Obj);
    Value Result = readClass(*RC, Tmp);
    if (!RC->TriviallyDestructible)
      if (void *Destroy = thunk(RC->Destroy))
        reinterpret_cast<void (*)(void *)>(Destroy)(Tmp);
    llvm::deallocate_buffer(Tmp, Size, Align);
    return Result;
  }
  }
  return nullptr;
}

Value ValueIO::readClass(const NativeClass &C, const void *Obj) {
  llvm::json::Object O;
  for (const NativeFunction &M : C.Members)
    if (M.isData())
      O[M.Name] = readMember(C, M, Obj);
  return O;
}

void debug::forEachJSONLeaf(std::string &Path, const Value &V,
                            LeafCallback Leaf) {
  size_t Length = Path.size();
  if (const llvm::json::Object *O = V.getAsObject()) {
    for (const auto &KV : *O) {
      (Path += ".") += llvm::StringRef(KV.first);
      forEachJSONLeaf(Path, KV.second, Leaf);
      Path.resize(Length);
    }
    return;
  }
  if (const llvm::json::Array *A = V.getAsArray()) {
    for (size_t I = 0; I < A->size(); ++I) {
      ((Path += "[") += std::to_string(I)) += "]";
      forEachJSONLeaf(Path, (*A)[I], Leaf);
      Path.resize(Length);
    }
    return;
  }
  Leaf(Path, V);
}

void ValueIO::readNativeLeaves(const NativeType &NT, const void *Addr,
                               std::string &Path, LeafCallback Leaf,
                               size_t Dim) {
  size_t Length = Path.size();
  if (Dim < NT.Extents.size()) {
    uint64_t Stride = getStride(NT, Dim);
    for (uint32_t I = 0; I < NT.Extents[Dim]; ++I) {
      ((Path += "[") += std::to_string(I)) += "]";
      readNativeLeaves(NT, static_cast<const char *>(Addr) + I * Stride, Path,
                       Leaf, Dim + 1);
      Path.resize(Length);
    }
    return;
  }
  if (NT.TheCode == NativeType::Class && NT.TheClass)
    return readLeaves(*NT.TheClass, Addr, Path, Leaf);
  Leaf(Path, readNative(NT, Addr, Dim));
}

void ValueIO::readLeaves(const NativeClass &C, const void *Obj,
                         std::string &Path, LeafCallback Leaf) {
  size_t Length = Path.size();
  for (const NativeFunction &M : C.Members) {
    if (!M.isData())
      continue;
    (Path += ".") += M.Name;
    if (M.FieldOffset)
      readNativeLeaves(M.Result, static_cast<const char *>(Obj) + *M.FieldOffset,
                       Path, Leaf, 0);
    else // A property: a class it returns is read whole.
      forEachJSONLeaf(Path, readMember(C, M, Obj), Leaf);
    Path.resize(Length);
  }
}
