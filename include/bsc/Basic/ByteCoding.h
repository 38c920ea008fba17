//===- ByteCoding.h - LEB128 numbers and runs of bytes ---------*- C++ -*-===//
//
// The encoding of the JIT's records of calls into C++ (bsc/JIT/Boundary.h)
// and of binary logs (bsc/Run/BinaryLog.h): unsigned LEB128 numbers and
// runs of bytes, written into a vector and read back with bounds checks.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_BASIC_BYTECODING_H
#define BSC_BASIC_BYTECODING_H

#include "llvm/ADT/ArrayRef.h"
#include "llvm/Support/LEB128.h"
#include "llvm/Support/MemoryBuffer.h"
#include <cstdint>
#include <vector>

namespace bsc {

/// The first bytes of every binary log (bsc/Run/BinaryLog.h), then its
/// version.
inline constexpr char BinaryLogMagic[6] = {'B', 'S', 'L', 'O', 'G', 0x1a};

/// Whether the file at `Path` starts as a binary log does (a robot's
/// flight log, a `.bslog` recording), whatever its name: for the readers
/// that take either a binary log or their own format.
inline bool isBinaryLogFile(llvm::StringRef Path) {
  auto Head = llvm::MemoryBuffer::getFileSlice(Path, sizeof BinaryLogMagic, 0);
  return Head && (*Head)->getBuffer() ==
                     llvm::StringRef(BinaryLogMagic, sizeof BinaryLogMagic);
}

/// Appends `V` as unsigned LEB128.
inline void appendULEB(std::vector<unsigned char> &Out, uint64_t V) {
  unsigned char Buf[16];
  unsigned N = llvm::encodeULEB128(V, Buf);
  Out.insert(Out.end(), Buf, Buf + N);
}

/// Reads LEB128 numbers and runs of bytes from P up to End, moving P on. A
/// read past the end (or a malformed number) sets Bad and gives 0 or no
/// bytes.
struct ByteReader {
  const unsigned char *P = nullptr, *End = nullptr;
  bool Bad = false;

  uint64_t uleb() {
    const char *Error = nullptr;
    unsigned N = 0;
    uint64_t V = llvm::decodeULEB128(P, &N, End, &Error);
    if (Error) {
      Bad = true;
      return 0;
    }
    P += N;
    return V;
  }
  /// The next `N` bytes (and moves past them); none if there are fewer.
  llvm::ArrayRef<unsigned char> bytes(uint64_t N) {
    if (Bad || uint64_t(End - P) < N) {
      Bad = true;
      return {};
    }
    llvm::ArrayRef<unsigned char> B(P, size_t(N));
    P += N;
    return B;
  }
};

} // namespace bsc

#endif
