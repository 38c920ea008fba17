//===- ValuesImpl.h - what reading and writing values share -----*- C++ -*-===//
#ifndef BSC_LIB_DEBUG_VALUESIMPL_H
#define BSC_LIB_DEBUG_VALUESIMPL_H

#include "bsc/AST/Native.h"
#include "bsc/Debug/Values.h"
#include <cstdint>
#include <cstring>
#include <optional>

namespace bsc::debug {

/// An integer of `Size` bytes at `Addr`, sign- or zero-extended.
inline int64_t loadInt(const void *Addr, unsigned Size, bool Unsigned) {
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

inline void storeInt(void *Addr, unsigned Size, int64_t V) {
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
inline llvm::json::Value enumToJSON(const NativeEnum *E, int64_t N) {
  if (E)
    for (const NativeEnum::Value &V : E->Values)
      if (V.Number == N)
        return V.Name;
  return N;
}

inline std::optional<int64_t> enumFromJSON(const NativeEnum *E,
                                           const llvm::json::Value &V) {
  if (std::optional<int64_t> N = V.getAsInteger())
    return N;
  if (std::optional<llvm::StringRef> S = V.getAsString(); S && E)
    for (const NativeEnum::Value &EV : E->Values)
      if (EV.Name == *S)
        return EV.Number;
  return std::nullopt;
}

/// The bytes between two elements of dimension `Dim` of an array field.
inline uint64_t getStride(const NativeType &NT, size_t Dim) {
  uint64_t Stride = NT.StorageSize;
  for (size_t D = Dim + 1; D < NT.Extents.size(); ++D)
    Stride *= NT.Extents[D];
  return Stride;
}

} // namespace bsc::debug

#endif
