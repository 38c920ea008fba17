//===- Encoder.h - one cycle's LLVM IR as Z3 terms --------------*- C++ -*-===//
//
// `bsc verify` checks the code the JIT runs: the LLVM IR of the behavior's
// cycle, optimised and inlined into one function without loops. The
// encoder turns one call of that function into terms over the memory it
// reads (Z3's bit-vectors, IEEE floats bit-precise): every value is a term
// of the values before it, each block is reached under a condition, and
// memory is bytes, merged where paths meet.
//
// Memory is a few objects (the state, `input`, `output`, each alloca, what
// registered C++ returns), each a vector of byte terms; a pointer is an
// object and an offset term, so that an index the behavior computes is a
// term too. Pointers stored in memory (the state header's `input` and
// `output`) are kept whole, in cells beside the bytes.
//
// Registered C++ is unknown: each call returns a fresh value (the same for
// the same arguments where the function is pure) and writes nothing. A
// construct the encoder does not know makes the result "not fully
// explored", with the reason, never a proof.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_VERIFY_ENCODER_H
#define BSC_LIB_VERIFY_ENCODER_H

#include "bsc/AST/Layout.h"
#include "bsc/CodeGen/CodeGen.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/IR/DataLayout.h"
#include "llvm/IR/Function.h"
#include <map>
#include <optional>
#include <string>
#include <vector>
#include <z3++.h>

namespace bsc::verify {

/// A place in memory: an object and a byte offset (a 64-bit term). Most
/// pointers know their object; one chosen by a branch (the string of one
/// branch or the other) may be in any of `Objects`, the one whose index
/// the 32-bit term `Which` is.
struct Pointer {
  std::vector<unsigned> Objects;
  z3::expr Which;
  z3::expr Offset;
  /// A pointer into `Object`.
  static Pointer into(unsigned Object, const z3::expr &Offset) {
    z3::context &Z = Offset.ctx();
    return Pointer{{Object}, Z.bv_val(Object, 32), Offset};
  }
  /// `C` ? A : B.
  static Pointer choose(const z3::expr &C, const Pointer &A, const Pointer &B);
  /// The same objects, at another offset.
  Pointer at(const z3::expr &NewOffset) const {
    return Pointer{Objects, Which, NewOffset};
  }
  bool isKnown() const { return Objects.size() == 1; }
  /// True where the pointer is into `Object`.
  z3::expr isIn(unsigned Object) const {
    return isKnown() ? Which.ctx().bool_val(Objects[0] == Object)
                     : Which == Which.ctx().bv_val(Object, 32);
  }
};

/// What the cycle sees of memory.
struct Memory {
  /// Per object, its bytes (8-bit terms).
  std::vector<std::vector<z3::expr>> Bytes;
  /// Pointers stored whole: (object, constant offset) -> the pointer.
  std::map<std::pair<unsigned, uint64_t>, Pointer> Cells;
  /// Objects' names, for messages and counterexamples.
  std::vector<std::string> Names;
  unsigned add(llvm::StringRef Name, std::vector<z3::expr> Content) {
    Bytes.push_back(std::move(Content));
    Names.push_back(Name.str());
    return Bytes.size() - 1;
  }
};

/// An assertion's check in one cycle: it fails when `Fails` is true.
struct Check {
  unsigned Index; ///< Behavior::Assertions index (bs.verify.check's).
  z3::expr Fails;
};

/// A loop that runs more passes than the verifier follows: where it is
/// (" at Loop.bs:7") and when the cycle gets there.
struct Escape {
  z3::expr Reached;
  const llvm::BasicBlock *Head;
  std::string Place;
};

/// A call of registered C++ in a cycle, for the counterexample: whether
/// it ran, its result and the bytes it wrote through its pointer arguments
/// (BehaviorLayout::NativeCall::Writes).
struct NativeResult {
  std::string Callee; ///< The thunk's symbol.
  z3::expr Reached;
  std::optional<z3::expr> Value;
  std::vector<std::vector<z3::expr>> Ptrs;
  /// Kept by the JIT's recorder (not pure, not the standard `io`): a
  /// recording of the counterexample holds it.
  bool Recorded = false;
};

class Encoder {
public:
  /// `Natives`: the thunks the code calls (BehaviorLayout::NativeCalls);
  /// without it every declaration is an unknown function that writes
  /// nothing.
  Encoder(z3::context &Z, const llvm::DataLayout &DL,
          const std::map<std::string, BehaviorLayout::NativeCall> *Natives =
              nullptr)
      : Z(Z), DL(DL), Natives(Natives) {}

  /// Encodes one call of `F` with `Args` (pointers), reading and updating
  /// `Mem`. `Tag` makes its fresh names unique (`c3`). False if F holds a
  /// construct the encoder does not know (getUnsupported says which).
  bool encode(llvm::Function &F, llvm::ArrayRef<Pointer> Args, Memory &Mem,
              llvm::StringRef Tag);

  /// This call's checks; the conjunction of its assumptions (those of the
  /// paths taken); the results of its calls into registered C++.
  const std::vector<Check> &getChecks() const { return Checks; }
  z3::expr getAssumed() const { return Assumed; }
  /// What the code generator knows to hold on every run (llvm.assume, an
  /// `unreachable`): implied from the initial state, so the bounded check
  /// leaves it out (it would only add terms), and the induction's step,
  /// which starts from any state, adds it.
  z3::expr getKnown() const { return Known; }
  const std::vector<NativeResult> &getNativeResults() const {
    return NativeCalls;
  }
  /// The loops this call may run further than the code encoded follows.
  const std::vector<Escape> &getEscapes() const { return Escapes; }
  /// "a call through a pointer: ...", "the instruction 'fdiv ...'".
  const std::string &getUnsupported() const { return Unsupported; }

  /// A fresh byte.
  z3::expr freshByte(const std::string &Name) {
    return Z.bv_const(Name.c_str(), 8);
  }

private:
  /// A value: a bit-vector (integers, i1 as bv1), a float, or a pointer
  /// (P; E is then its offset).
  struct Value {
    enum Kind { Bits, Float, Ptr } K;
    z3::expr E;
    std::optional<Pointer> P;
    static Value bits(const z3::expr &E) { return Value{Bits, E, {}}; }
    static Value flt(const z3::expr &E) { return Value{Float, E, {}}; }
    static Value ptr(const Pointer &P) { return Value{Ptr, P.Offset, P}; }
  };
  void set(llvm::Value *V, Value X) { Values.insert_or_assign(V, X); }

  bool encodeBlock(llvm::BasicBlock &BB);
  bool encodeInstruction(llvm::Instruction &I, Memory &M, z3::expr Reached);
  bool encodeCall(llvm::CallInst &C, Memory &M, z3::expr Reached);
  std::optional<Value> valueOf(llvm::Value *V);
  /// The term of an integer or i1 value as a bit-vector.
  std::optional<z3::expr> bits(llvm::Value *V);
  std::optional<z3::expr> floating(llvm::Value *V);
  std::optional<Pointer> pointer(llvm::Value *V);
  z3::sort floatSort(llvm::Type *T);
  /// Reads `Size` bytes at P as a bit-vector; writes one.
  std::optional<z3::expr> load(const Memory &M, const Pointer &P,
                               unsigned Size);
  bool store(Memory &M, const Pointer &P, const z3::expr &Bits);
  /// The same in one object; nullopt or false (nothing reported) where the
  /// access does not fit it.
  std::optional<z3::expr> loadFrom(const std::vector<z3::expr> &Bytes,
                                   const z3::expr &Offset, unsigned Size);
  bool storeInto(std::vector<z3::expr> &Bytes, const z3::expr &Offset,
                 const z3::expr &Bits);
  /// A pointer stored in memory at P; a pointer stored there.
  std::optional<Pointer> loadPointer(const Memory &M, const Pointer &P);
  bool storePointer(Memory &M, const Pointer &P, const Pointer &Stored);
  /// The fresh value of type T named Name.
  std::optional<Value> fresh(llvm::Type *T, const std::string &Name);
  z3::expr asBool(const z3::expr &Bit) { return Bit == Z.bv_val(1, 1); }
  z3::expr fromBool(const z3::expr &B) {
    return z3::ite(B, Z.bv_val(1, 1), Z.bv_val(0, 1));
  }
  bool unsupported(const std::string &What);

  z3::context &Z;
  const llvm::DataLayout &DL;
  const std::map<std::string, BehaviorLayout::NativeCall> *Natives;
  std::string TagPrefix;
  unsigned Fresh = 0;
  std::map<llvm::Value *, Value> Values;
  /// Each block's memory at its end, and the condition of each edge.
  std::map<llvm::BasicBlock *, Memory> Out;
  std::map<std::pair<llvm::BasicBlock *, llvm::BasicBlock *>, z3::expr> Edges;
  std::vector<Check> Checks;
  std::vector<NativeResult> NativeCalls;
  std::vector<Escape> Escapes;
  /// Pure natives called with the same arguments give the same result.
  std::map<std::string, std::vector<std::pair<std::vector<z3::expr>, Value>>>
      PureCalls;
  z3::expr Assumed{Z};
  z3::expr Known{Z};
  std::string Unsupported;
};

} // namespace bsc::verify

#endif
