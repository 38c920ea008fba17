//===- Values.cpp - b-script values in memory as JSON ---------------------===//
//
// Registered members come in two forms (Native.h): a field with an offset,
// read and written in place by its C++ storage size, and a property (or a
// field bsc may not touch directly) behind getter and setter thunks with
// the plain C ABI of docs/bindings.md. Both are handled here the way
// generated code handles them, so what the debugger shows is what the
// behavior reads.
//
//===----------------------------------------------------------------------===//
#include "bsc/Debug/Values.h"
#include "bsc/AST/Native.h"
#include "bsc/Basic/JSON.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/Format.h"
#include "llvm/Support/MemAlloc.h"
#include "llvm/Support/raw_ostream.h"
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <utility>

using namespace bsc;
using namespace bsc::debug;
using llvm::json::Value;

static llvm::Error makeError(const llvm::Twine &Msg) {
  return llvm::createStringError(llvm::inconvertibleErrorCode(), Msg);
}

//===----------------------------------------------------------------------===//
// Numbers
//===----------------------------------------------------------------------===//

Value debug::floatToJSON(double F) {
  if (std::isnan(F))
    return "NaN";
  if (std::isinf(F))
    return F > 0 ? "Infinity" : "-Infinity";
  return F;
}

std::optional<double> debug::floatFromJSON(const Value &V) {
  if (std::optional<double> D = V.getAsNumber())
    return *D;
  if (std::optional<llvm::StringRef> S = V.getAsString()) {
    if (*S == "NaN")
      return std::nan("");
    if (*S == "Infinity")
      return HUGE_VAL;
    if (*S == "-Infinity")
      return -HUGE_VAL;
  }
  return std::nullopt;
}

/// The shortest decimal that reads back as `D` (as a float when `D` is
/// one, which every b-script float is): `%g` of the least precision that
/// does. No precision below the digits of std::to_chars's shortest form
/// can, so the search starts there (a page of a long run prints millions).
static std::string formatNumber(double D) {
  if (D == 0 && std::signbit(D))
    return "-0.0";
  if (D == std::trunc(D) && std::fabs(D) < 1e15)
    return llvm::formatv("{0}", (long long)D).str();
  bool IsFloat = double(float(D)) == D;
  char S[64];
  char *End = IsFloat ? std::to_chars(S, S + sizeof S, float(D),
                                      std::chars_format::scientific)
                            .ptr
                      : std::to_chars(S, S + sizeof S, D,
                                      std::chars_format::scientific)
                            .ptr;
  int Digits = llvm::count_if(llvm::StringRef(S, End - S).split('e').first,
                              llvm::isDigit);
  for (int Precision = std::max(Digits, 1); Precision <= 17; ++Precision) {
    End = std::to_chars(S, S + sizeof S, D, std::chars_format::general,
                        Precision)
              .ptr;
    double Back = 0;
    std::from_chars(S, End, Back);
    if (IsFloat ? float(Back) == float(D) : Back == D)
      return std::string(S, End);
  }
  std::snprintf(S, sizeof S, "%.17g", D);
  return S;
}

void debug::printJSON(llvm::raw_ostream &OS, const Value &V) {
  switch (V.kind()) {
  case Value::Null:
  case Value::Boolean:
  case Value::String:
    OS << V;
    return;
  case Value::Number:
    if (std::optional<int64_t> I = V.getAsInteger(); I && *I != 0)
      OS << *I;
    else
      OS << formatNumber(*V.getAsNumber());
    return;
  case Value::Array: {
    OS << '[';
    llvm::ListSeparator Sep(",");
    for (const Value &E : *V.getAsArray()) {
      OS << Sep;
      printJSON(OS, E);
    }
    OS << ']';
    return;
  }
  case Value::Object: {
    const llvm::json::Object &O = *V.getAsObject();
    std::vector<llvm::StringRef> Keys;
    for (const auto &KV : O)
      Keys.push_back(KV.first);
    llvm::sort(Keys);
    OS << '{';
    llvm::ListSeparator Sep(",");
    for (llvm::StringRef K : Keys) {
      OS << Sep << Value(K) << ':';
      printJSON(OS, *O.get(K));
    }
    OS << '}';
    return;
  }
  }
}

std::string debug::formatValue(const Type *T, const llvm::json::Value &V) {
  if (T->isEnum())
    if (std::optional<llvm::StringRef> Name = V.getAsString())
      return Name->str();
  return toJSONString(V);
}

std::string debug::toJSONString(const Value &V) {
  std::string S;
  llvm::raw_string_ostream OS(S);
  printJSON(OS, V);
  return S;
}

/// Appends the places where `Got` differs from `Recorded` to `Out`, objects
/// in key order and arrays in index order; with `FirstOnly`, stops after
/// the first. Returns whether it found one.
static bool collectDifferences(const Value &Recorded, const Value &Got,
                               llvm::StringRef Path, bool FirstOnly,
                               std::vector<Difference> &Out) {
  size_t Before = Out.size();
  auto Done = [&] { return FirstOnly && Out.size() > Before; };
  if (const llvm::json::Object *R = Recorded.getAsObject()) {
    if (const llvm::json::Object *G = Got.getAsObject()) {
      std::vector<llvm::StringRef> Keys;
      for (const auto &KV : *R)
        Keys.push_back(KV.first);
      llvm::sort(Keys);
      for (llvm::StringRef K : Keys) {
        const Value *GV = G->get(K);
        std::string Sub = (Path + "." + K).str();
        if (!GV)
          Out.push_back({Sub, toJSONString(*R->get(K)), "nothing"});
        else
          collectDifferences(*R->get(K), *GV, Sub, FirstOnly, Out);
        if (Done())
          break;
      }
      return Out.size() > Before;
    }
  }
  if (const llvm::json::Array *R = Recorded.getAsArray()) {
    // An array field: element by element, named `output.wide[3]`.
    const llvm::json::Array *G = Got.getAsArray();
    if (G && G->size() == R->size()) {
      for (size_t I = 0; I < R->size() && !Done(); ++I)
        collectDifferences((*R)[I], (*G)[I],
                           (Path + "[" + llvm::Twine(I) + "]").str(),
                           FirstOnly, Out);
      return Out.size() > Before;
    }
  }
  // Numbers compare as the floats (or ints) they are; a number written as
  // a float's shortest decimal reads back as that float.
  std::optional<double> RN = floatFromJSON(Recorded), GN = floatFromJSON(Got);
  std::optional<int64_t> RI = Recorded.getAsInteger(), GI = Got.getAsInteger();
  bool Same;
  if (RI && GI) // Zero's sign is the only thing an int cannot show.
    Same = *RI == *GI && (*RI != 0 || std::signbit(*RN) == std::signbit(*GN));
  else if (RN && GN) // Every non-integer number here is a b-script float.
    Same = (std::isnan(*RN) && std::isnan(*GN)) || float(*RN) == float(*GN);
  else
    Same = Recorded == Got;
  if (Same)
    return false;
  Out.push_back({Path.str(), toJSONString(Recorded), toJSONString(Got)});
  return true;
}

std::optional<Difference> debug::findDifference(const Value &Recorded,
                                                const Value &Got,
                                                llvm::StringRef Path) {
  std::vector<Difference> Found;
  if (!collectDifferences(Recorded, Got, Path, /*FirstOnly=*/true, Found))
    return std::nullopt;
  return std::move(Found.front());
}

std::vector<Difference> debug::findDifferences(const Value &Recorded,
                                               const Value &Got,
                                               llvm::StringRef Path) {
  std::vector<Difference> Found;
  collectDifferences(Recorded, Got, Path, /*FirstOnly=*/false, Found);
  return Found;
}

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

/// An integer of `Size` bytes at `Addr`, sign- or zero-extended.
static int64_t loadInt(const void *Addr, unsigned Size, bool Unsigned) {
  switch (Size) {
  case 1: {
    uint8_t V;
    std::memcpy(&V, Addr, 1);
    return Unsigned ? int64_t(V) : int64_t(int8_t(V));
  }
  case 2: {
    uint16_t V;
    std::memcpy(&V, Addr, 2);
    return Unsigned ? int64_t(V) : int64_t(int16_t(V));
  }
  case 8: {
    int64_t V;
    std::memcpy(&V, Addr, 8);
    return V;
  }
  default: {
    uint32_t V;
    std::memcpy(&V, Addr, 4);
    return Unsigned ? int64_t(V) : int64_t(int32_t(V));
  }
  }
}

static void storeInt(void *Addr, unsigned Size, int64_t V) {
  switch (Size) {
  case 1: {
    uint8_t B = uint8_t(V);
    std::memcpy(Addr, &B, 1);
    return;
  }
  case 2: {
    uint16_t H = uint16_t(V);
    std::memcpy(Addr, &H, 2);
    return;
  }
  case 8:
    std::memcpy(Addr, &V, 8);
    return;
  default: {
    uint32_t W = uint32_t(V);
    std::memcpy(Addr, &W, 4);
    return;
  }
  }
}

/// An enum value by name when it has one, else its number.
static Value enumToJSON(const NativeEnum *E, int64_t N) {
  if (E)
    for (const NativeEnum::Value &V : E->Values)
      if (V.Number == N)
        return V.Name;
  return N;
}

static std::optional<int64_t> enumFromJSON(const NativeEnum *E,
                                           const Value &V) {
  if (std::optional<int64_t> N = V.getAsInteger())
    return N;
  if (std::optional<llvm::StringRef> S = V.getAsString(); S && E)
    for (const NativeEnum::Value &EV : E->Values)
      if (EV.Name == *S)
        return EV.Number;
  return std::nullopt;
}

/// The bytes between two elements of dimension `Dim` of an array field.
static uint64_t getStride(const NativeType &NT, size_t Dim) {
  uint64_t Stride = NT.StorageSize;
  for (size_t D = Dim + 1; D < NT.Extents.size(); ++D)
    Stride *= NT.Extents[D];
  return Stride;
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
  default: {
    int32_t I;
    std::memcpy(&I, Wire, 4);
    reinterpret_cast<void (*)(void *, int32_t)>(Setter)(Obj, I);
    return;
  }
  }
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

//===----------------------------------------------------------------------===//
// A replay's fast paths
//===----------------------------------------------------------------------===//
//
// Both walk the text of an object in the form a recording has: keys sorted
// and distinct, strings of ASCII without escapes, plain numbers. A member
// that is a registered class held in place is walked into; any other
// value becomes a JSON value (a scalar read straight from its token, an
// array parsed) and goes through what writeClass and findDifferences
// do with it, so the results are theirs. Text of any other form makes them
// give up, and the caller takes the slow way.

/// The reading half: tokens of the plain form, by hand (StringRef's
/// searches build a table per call, which costs more than a token).
class ValueIO::TextWalker {
public:
  TextWalker(ValueIO &IO, llvm::StringRef Text) : IO(IO), Rest(Text) {}

  /// Calls `Member(C, M, Obj)` at each member of the object at the front,
  /// with its value next; false if the object is not of the plain form, a
  /// key is not a data member of `C`, or `Member` returns false.
  template <typename Fn>
  bool walkObject(const NativeClass &C, Fn Member) {
    if (!take('{'))
      return false;
    llvm::StringRef Previous;
    for (bool First = true; !take('}'); First = false) {
      llvm::StringRef Key;
      if ((!First && !take(',')) || !takeString(Key) || !take(':'))
        return false;
      // writeClass goes through the keys in order (and a key twice is
      // the last one's): the same when they are sorted and distinct.
      if (!First && Key <= Previous)
        return false;
      Previous = Key;
      const NativeFunction *M = C.findMember(Key);
      if (!M || !M->isData() || !Member(*M))
        return false;
    }
    return true;
  }
  /// Whether the value at the front is an object: a registered class held
  /// in place is walked into rather than read as a value.
  bool atObject() { return peek() == '{'; }
  /// The value at the front, as llvm::json would read it.
  std::optional<Value> takeValue();
  bool atEnd() {
    skipSpace();
    return Rest.empty();
  }

private:
  char peek() {
    skipSpace();
    return Rest.empty() ? 0 : Rest.front();
  }
  bool take(char Ch) {
    if (peek() != Ch)
      return false;
    Rest = Rest.drop_front();
    return true;
  }
  void skipSpace() {
    size_t I = 0;
    while (I < Rest.size() && (Rest[I] == ' ' || Rest[I] == '\t' ||
                               Rest[I] == '\r' || Rest[I] == '\n'))
      ++I;
    Rest = Rest.drop_front(I);
  }
  /// A string of ASCII without escapes: its text between the quotes.
  bool takeString(llvm::StringRef &S);
  std::optional<Value> takeNumber();

  ValueIO &IO;
  llvm::StringRef Rest;
};

bool ValueIO::TextWalker::takeString(llvm::StringRef &S) {
  if (!take('"'))
    return false;
  for (size_t I = 0; I < Rest.size(); ++I) {
    unsigned char Ch = Rest[I];
    if (Ch == '"') {
      S = Rest.take_front(I);
      Rest = Rest.drop_front(I + 1);
      return true;
    }
    if (Ch == '\\' || Ch < 0x20 || Ch >= 0x80)
      return false;
  }
  return false;
}

std::optional<Value> ValueIO::TextWalker::takeNumber() {
  size_t End = 0;
  bool Integer = true;
  for (; End < Rest.size(); ++End) {
    char Ch = Rest[End];
    if (Ch == '.' || Ch == 'e' || Ch == 'E' || Ch == '+')
      Integer = false;
    else if (!llvm::isDigit(Ch) && Ch != '-')
      break;
  }
  llvm::StringRef Token = Rest.take_front(End);
  Rest = Rest.drop_front(End);
  llvm::StringRef Digits = Token;
  bool Negative = Digits.consume_front("-");
  if (Integer) {
    // llvm::json reads an integer that fits into an int64; 18 digits do.
    if (Digits.empty() || Digits.size() > 18 ||
        !llvm::all_of(Digits, llvm::isDigit))
      return std::nullopt;
    int64_t N = 0;
    for (char D : Digits)
      N = N * 10 + (D - '0');
    return Value(Negative ? -N : N);
  }
  char Buf[64];
  if (Token.size() >= sizeof Buf)
    return std::nullopt;
  std::memcpy(Buf, Token.data(), Token.size());
  Buf[Token.size()] = 0;
  char *After;
  double D = std::strtod(Buf, &After);
  if (After != Buf + Token.size())
    return std::nullopt;
  return Value(D);
}

std::optional<Value> ValueIO::TextWalker::takeValue() {
  char Ch = peek();
  if (Ch == '"') {
    llvm::StringRef S;
    if (!takeString(S))
      return std::nullopt;
    return Value(S);
  }
  if (Ch == '-' || llvm::isDigit(Ch))
    return takeNumber();
  for (llvm::StringRef Word : {"true", "false", "null"})
    if (Rest.consume_front(Word))
      return Word == "null" ? Value(nullptr) : Value(Word == "true");
  if (Ch != '[')
    return std::nullopt;
  // An array field: parsed whole (its elements are what a member of its
  // type takes; this is rarer than scalars). The walker's text is checked
  // JSON, so the array ends at its bracket.
  unsigned Depth = 0;
  bool InString = false;
  for (size_t I = 0; I < Rest.size(); ++I) {
    char C = Rest[I];
    if (InString) {
      if (C == '\\')
        ++I;
      else if (C == '"')
        InString = false;
    } else if (C == '"') {
      InString = true;
    } else if (C == '[' || C == '{') {
      ++Depth;
    } else if ((C == ']' || C == '}') && --Depth == 0) {
      llvm::Expected<Value> V = parseJSON(Rest.take_front(I + 1));
      Rest = Rest.drop_front(I + 1);
      if (!V) {
        llvm::consumeError(V.takeError());
        return std::nullopt;
      }
      return std::move(*V);
    }
  }
  return std::nullopt;
}

/// A member that is a registered class held at an offset: walked into.
static const NativeClass *getClassInPlace(const NativeFunction &M) {
  const NativeType &NT = M.Result;
  if (M.FieldOffset && !M.ReadOnly && NT.TheCode == NativeType::Class &&
      NT.Extents.empty())
    return NT.TheClass;
  return nullptr;
}

bool ValueIO::writeObjectText(TextWalker &W, const NativeClass &C, void *Obj) {
  return W.walkObject(C, [&](const NativeFunction &M) {
    if (const NativeClass *Inner = getClassInPlace(M); Inner && W.atObject())
      return writeObjectText(W, *Inner,
                             static_cast<char *>(Obj) + *M.FieldOffset);
    std::optional<Value> V = W.takeValue();
    if (!V)
      return false;
    llvm::Error E = writeMember(C, M, Obj, *V, "");
    if (!E)
      return true;
    llvm::consumeError(std::move(E));
    return false;
  });
}

bool ValueIO::writeClassText(const NativeClass &C, void *Obj,
                             llvm::StringRef Text) {
  TextWalker W(*this, Text);
  return writeObjectText(W, C, Obj) && W.atEnd();
}

bool ValueIO::matchObjectText(TextWalker &W, const NativeClass &C,
                              const void *Obj) {
  return W.walkObject(C, [&](const NativeFunction &M) {
    if (const NativeClass *Inner = getClassInPlace(M); Inner && W.atObject())
      return matchObjectText(W, *Inner,
                             static_cast<const char *>(Obj) + *M.FieldOffset);
    std::optional<Value> Recorded = W.takeValue();
    return Recorded &&
           !findDifference(*Recorded, readMember(C, M, Obj), "").has_value();
  });
}

bool ValueIO::matchesClassText(const NativeClass &C, const void *Obj,
                               llvm::StringRef Text) {
  TextWalker W(*this, Text);
  return matchObjectText(W, C, Obj) && W.atEnd();
}
