//===- ValueWrite.cpp - JSON written into values in memory ----------------===//
//
// The inverse of ValueRead.cpp, member by member as generated code stores
// them: a replay writes a recording's `input`, the REPL a line's
// assignment. A value that does not fit its member is an error that names
// it (`input.s[1] must be ...`).
//
//===----------------------------------------------------------------------===//
#include "ValuesImpl.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/ErrorHandling.h"
#include "llvm/Support/MemAlloc.h"
#include <cmath>
#include <string>

using namespace bsc;
using namespace bsc::debug;
using llvm::json::Value;

static llvm::Error makeError(const llvm::Twine &Msg) {
  return llvm::createStringError(llvm::inconvertibleErrorCode(), Msg);
}

//===----------------------------------------------------------------------===//
// Writing
//===----------------------------------------------------------------------===//

/// What a JSON value must be to fit a native type, for messages.
static const char *describe(const NativeType &NT) {
  switch (NT.TheCode) {
  case NativeType::Void:
    return "nothing";
  case NativeType::Bool:
    return "true or false";
  case NativeType::Int:
    return "an integer";
  case NativeType::Enum:
    return "an enum value's name or number";
  case NativeType::Float:
    return "a number";
  case NativeType::String:
    return "a string";
  case NativeType::Class:
    return "an object";
  }
  return "a value";
}

/// The ints a member of `Size` bytes gives back as b-script reads it: the
/// storage's own range below 4 bytes, int32 from 4 up (readNative reads an
/// int32). A value outside would be stored as another number, so a replay
/// would feed the behavior what the file does not say.
static std::pair<int64_t, int64_t> getIntRange(unsigned Size, bool Unsigned) {
  if (Size >= 4)
    return {INT32_MIN, INT32_MAX};
  unsigned Bits = 8 * Size;
  if (Unsigned)
    return {0, (int64_t(1) << Bits) - 1};
  return {-(int64_t(1) << (Bits - 1)), (int64_t(1) << (Bits - 1)) - 1};
}

/// A JSON number a float cannot hold (1e39 would become infinity: a
/// recording says "Infinity" for that).
static bool isBeyondFloat(const Value &V) {
  std::optional<double> D = V.getAsNumber();
  return D && !std::isfinite(float(*D));
}

llvm::Error ValueIO::writeNative(const NativeType &NT, void *Addr,
                                 const Value &V, llvm::StringRef Path,
                                 size_t Dim) {
  if (Dim < NT.Extents.size()) {
    // An array field: every element, so a replay leaves nothing stale.
    const llvm::json::Array *A = V.getAsArray();
    uint32_t Extent = NT.Extents[Dim];
    if (!A || A->size() != Extent)
      return makeError(Path + " must be an array of " + llvm::Twine(Extent) +
                       " elements, not " + toJSONString(V));
    uint64_t Stride = getStride(NT, Dim);
    for (uint32_t I = 0; I < Extent; ++I)
      if (llvm::Error E = writeNative(
              NT, static_cast<char *>(Addr) + I * Stride, (*A)[I],
              (Path + "[" + llvm::Twine(I) + "]").str(), Dim + 1))
        return E;
    return llvm::Error::success();
  }
  auto Mismatch = [&] {
    return makeError(Path + " must be " + describe(NT) + ", not " +
                     toJSONString(V));
  };
  unsigned Size = NT.StorageSize;
  switch (NT.TheCode) {
  case NativeType::Void:
    return Mismatch();
  case NativeType::Bool:
    if (std::optional<bool> B = V.getAsBoolean()) {
      storeInt(Addr, Size ? Size : 1, *B);
      return llvm::Error::success();
    }
    return Mismatch();
  case NativeType::Int:
  case NativeType::Enum: {
    std::optional<int64_t> I = NT.TheCode == NativeType::Int
                                   ? V.getAsInteger()
                                   : enumFromJSON(NT.TheEnum, V);
    if (!I)
      return Mismatch();
    auto [Min, Max] = getIntRange(Size ? Size : 4, NT.Unsigned);
    if (*I < Min || *I > Max)
      return makeError(Path + " must be from " + llvm::Twine(Min) + " to " +
                       llvm::Twine(Max) + ", not " + toJSONString(V));
    storeInt(Addr, Size ? Size : 4, *I);
    return llvm::Error::success();
  }
  case NativeType::Float:
    if (isBeyondFloat(V))
      return makeError(Path + " must be a number within a float's range " +
                       "(or \"Infinity\"), not " + toJSONString(V));
    if (std::optional<double> D = floatFromJSON(V)) {
      if (Size == 8) {
        double X = float(*D);
        std::memcpy(Addr, &X, 8);
      } else {
        float F = float(*D);
        std::memcpy(Addr, &F, 4);
      }
      return llvm::Error::success();
    }
    return Mismatch();
  case NativeType::String:
    if (std::optional<llvm::StringRef> S = V.getAsString()) {
      const char *P = Strings.insert(S->str()).first->c_str();
      std::memcpy(Addr, &P, sizeof P);
      return llvm::Error::success();
    }
    if (V.kind() == Value::Null) {
      // A null pointer reads as null (readNative): it replays as one.
      const char *P = nullptr;
      std::memcpy(Addr, &P, sizeof P);
      return llvm::Error::success();
    }
    return Mismatch();
  case NativeType::Class:
    if (!NT.TheClass)
      return Mismatch();
    return writeClass(*NT.TheClass, Addr, V, Path);
  }
  return Mismatch();
}

/// A scalar property's value as writeNative stored it in its wire type
/// (int32 for int, enum and bool), handed to its setter thunk.
static void callScalarSetter(const NativeType &NT, void *Setter, void *Obj,
                             const unsigned char *Wire) {
  switch (NT.TheCode) {
  case NativeType::Float: {
    float F;
    std::memcpy(&F, Wire, 4);
    reinterpret_cast<void (*)(void *, float)>(Setter)(Obj, F);
    return;
  }
  case NativeType::String: {
    const char *S;
    std::memcpy(&S, Wire, sizeof S);
    reinterpret_cast<void (*)(void *, const char *)>(Setter)(Obj, S);
    return;
  }
  case NativeType::Int:
  case NativeType::Enum:
  case NativeType::Bool: {
    int32_t I;
    std::memcpy(&I, Wire, 4);
    reinterpret_cast<void (*)(void *, int32_t)>(Setter)(Obj, I);
    return;
  }
  case NativeType::Void:  // writeNative refused the value.
  case NativeType::Class: // writeMember writes it through its getter.
    break;
  }
  llvm_unreachable("not a scalar property");
}

llvm::Error ValueIO::writeMember(const NativeClass &C, const NativeFunction &M,
                                 void *Obj, const Value &V,
                                 llvm::StringRef Path) {
  if (M.FieldOffset && !M.ReadOnly)
    return writeNative(M.Result, static_cast<char *>(Obj) + *M.FieldOffset, V,
                       Path);
  void *Setter = thunk(M.Setter);
  if (M.ReadOnly || !Setter) {
    // Writing what it already holds is harmless (a replayed recording
    // lists read-only members too).
    if (!findDifference(V, readMember(C, M, Obj), Path))
      return llvm::Error::success();
    return makeError(Path + " is read-only");
  }
  const NativeType &NT = M.Result;
  if (NT.TheCode == NativeType::Class) {
    // Read the property, change what the JSON names, write it back.
    const NativeClass *RC = NT.TheClass;
    void *Getter = thunk(M.Symbol);
    if (!RC || !Getter || !M.ResultViaOut)
      return makeError(Path + " cannot be written by the debugger");
    size_t Align = RC->Align ? RC->Align : 1, Size = RC->Size ? RC->Size : 1;
    void *Tmp = llvm::allocate_buffer(Size, Align);
    std::memset(Tmp, 0, Size);
    reinterpret_cast<void (*)(void *, const void *)>(Getter)(Tmp, Obj);
    llvm::Error E = writeClass(*RC, Tmp, V, Path);
    if (!E)
      reinterpret_cast<void (*)(void *, const void *)>(Setter)(Obj, Tmp);
    if (!RC->TriviallyDestructible)
      if (void *Destroy = thunk(RC->Destroy))
        reinterpret_cast<void (*)(void *)>(Destroy)(Tmp);
    llvm::deallocate_buffer(Tmp, Size, Align);
    return E;
  }
  // A scalar travels in its wire type: int32 for int, enum and bool.
  alignas(8) unsigned char Wire[8] = {};
  NativeType WireType = NT;
  WireType.StorageSize = NT.TheCode == NativeType::String ? sizeof(void *) : 4;
  if (llvm::Error E = writeNative(WireType, Wire, V, Path))
    return E;
  callScalarSetter(NT, Setter, Obj, Wire);
  return llvm::Error::success();
}

llvm::Error ValueIO::writeClass(const NativeClass &C, void *Obj,
                                const Value &V, llvm::StringRef Path) {
  const llvm::json::Object *O = V.getAsObject();
  if (!O)
    return makeError(Path + " must be an object (a " + C.QualifiedName +
                     "), not " + toJSONString(V));
  std::vector<llvm::StringRef> Keys;
  for (const auto &KV : *O)
    Keys.push_back(KV.first);
  llvm::sort(Keys);
  for (llvm::StringRef K : Keys) {
    const NativeFunction *M = C.findMember(K);
    std::string Sub = (Path + "." + K).str();
    if (!M || !M->isData()) {
      std::string Known;
      llvm::ListSeparator Sep(", ");
      for (const NativeFunction &F : C.Members)
        if (F.isData())
          Known += (llvm::Twine(Sep) + F.Name).str();
      return makeError(Sub + ": " + C.QualifiedName + " has no field '" + K +
                       "'" + (Known.empty() ? "" : " (it has " + Known + ")"));
    }
    if (llvm::Error E = writeMember(C, *M, Obj, *O->get(K), Sub))
      return E;
  }
  return llvm::Error::success();
}

llvm::Error ValueIO::write(const Type *T, void *Addr, const Value &V,
                           llvm::StringRef Path) {
  auto Mismatch = [&](const char *What) {
    return makeError(Path + " must be " + What + ", not " + toJSONString(V));
  };
  switch (T->getKind()) {
  case TypeKind::Error:
  case TypeKind::Void:
  case TypeKind::Array: // Only fields are arrays: writeNative.
    return Mismatch("a value");
  case TypeKind::Int:
  case TypeKind::TaskState:
    if (std::optional<int64_t> I = V.getAsInteger()) {
      storeInt(Addr, 4, *I);
      return llvm::Error::success();
    }
    return Mismatch("an integer");
  case TypeKind::Enum:
    if (std::optional<int64_t> I = enumFromJSON(T->getEnum(), V)) {
      storeInt(Addr, 4, *I);
      return llvm::Error::success();
    }
    return Mismatch("an enum value's name or number");
  case TypeKind::Float:
    if (std::optional<double> D = floatFromJSON(V)) {
      float F = float(*D);
      std::memcpy(Addr, &F, 4);
      return llvm::Error::success();
    }
    return Mismatch("a number");
  case TypeKind::Bool:
    if (std::optional<bool> B = V.getAsBoolean()) {
      *static_cast<uint8_t *>(Addr) = *B;
      return llvm::Error::success();
    }
    return Mismatch("true or false");
  case TypeKind::String:
    if (std::optional<llvm::StringRef> S = V.getAsString()) {
      const char *P = Strings.insert(S->str()).first->c_str();
      std::memcpy(Addr, &P, sizeof P);
      return llvm::Error::success();
    }
    return Mismatch("a string");
  case TypeKind::Class:
    return writeClass(*T->getClass(), Addr, V, Path);
  }
  return Mismatch("a value");
}
