//===- Encoder.cpp - one cycle's LLVM IR as Z3 terms ----------------------===//
//
// Blocks are encoded in reverse post-order: a block is reached when one of
// the edges into it is taken, its phis are the value of the edge taken,
// and its memory is its predecessors' merged by the same conditions. The
// head of a loop (what is left of it after Verify.cpp peeled passes off
// it) is not encoded: reaching it is an escape, which the verifier asks
// the solver about.
// Floats are Z3's IEEE floats with rounding to nearest even, as the host
// computes them; comparisons follow LLVM's ordered and unordered forms.
//
//===----------------------------------------------------------------------===//
#include "Encoder.h"
#include "llvm/ADT/PostOrderIterator.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Analysis/PostDominators.h"
#include "llvm/IR/Dominators.h"
#include "llvm/IR/GetElementPtrTypeIterator.h"
#include "llvm/IR/Instructions.h"
#include "llvm/IR/IntrinsicInst.h"
#include "llvm/IR/Operator.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;
using namespace bsc::verify;

/// " at Loop.bs:6" from the block's first line, or " in FUNCTION".
static std::string placeOf(const llvm::BasicBlock &BB) {
  for (const llvm::Instruction &I : BB)
    if (const llvm::DebugLoc &Loc = I.getDebugLoc())
      if (Loc.getLine())
        return " at " + Loc->getFilename().str() + ":" +
               std::to_string(Loc.getLine());
  return " in " + BB.getParent()->getName().str();
}

bool Encoder::unsupported(const std::string &What) {
  if (Unsupported.empty())
    Unsupported = What;
  return false;
}

/// "the instruction 'fdiv <2 x float> ...'" for a message.
static std::string describe(const llvm::Value &V) {
  std::string Text;
  llvm::raw_string_ostream OS(Text);
  V.print(OS);
  llvm::StringRef T = llvm::StringRef(Text).trim();
  return "'" + T.take_front(80).str() + (T.size() > 80 ? "...'" : "'");
}

z3::sort Encoder::floatSort(llvm::Type *T) {
  return T->isDoubleTy() ? Z.fpa_sort<64>() : Z.fpa_sort<32>();
}

//===----------------------------------------------------------------------===//
// Values
//===----------------------------------------------------------------------===//

std::optional<Encoder::Value> Encoder::valueOf(llvm::Value *V) {
  auto It = Values.find(V);
  if (It != Values.end())
    return It->second;
  if (auto *CI = llvm::dyn_cast<llvm::ConstantInt>(V)) {
    const llvm::APInt &A = CI->getValue();
    unsigned W = A.getBitWidth();
    z3::expr E = W <= 64 ? Z.bv_val(uint64_t(A.getZExtValue()), W)
                         : Z.bv_val(llvm::toString(A, 10, false).c_str(), W);
    return Value::bits(E);
  }
  if (auto *CF = llvm::dyn_cast<llvm::ConstantFP>(V)) {
    llvm::APInt Bits = CF->getValueAPF().bitcastToAPInt();
    z3::expr B = Z.bv_val(uint64_t(Bits.getZExtValue()), Bits.getBitWidth());
    z3::expr F(Z, Z3_mk_fpa_to_fp_bv(Z, B, floatSort(CF->getType())));
    return Value::flt(F);
  }
  if (llvm::isa<llvm::UndefValue>(V) || llvm::isa<llvm::PoisonValue>(V))
    return fresh(V->getType(), "undef");
  if (llvm::isa<llvm::ConstantPointerNull>(V))
    return unsupported("a null pointer"), std::nullopt;
  unsupported("the value " + describe(*V));
  return std::nullopt;
}

std::optional<z3::expr> Encoder::bits(llvm::Value *V) {
  std::optional<Value> X = valueOf(V);
  if (!X)
    return std::nullopt;
  if (X->K == Value::Bits)
    return X->E;
  if (X->K == Value::Float)
    return z3::expr(Z, Z3_mk_fpa_to_ieee_bv(Z, X->E));
  unsupported("a pointer used as a number: " + describe(*V));
  return std::nullopt;
}

std::optional<z3::expr> Encoder::floating(llvm::Value *V) {
  std::optional<Value> X = valueOf(V);
  if (!X)
    return std::nullopt;
  if (X->K == Value::Float)
    return X->E;
  if (X->K == Value::Bits)
    return z3::expr(Z, Z3_mk_fpa_to_fp_bv(Z, X->E, floatSort(V->getType())));
  unsupported("a pointer used as a float: " + describe(*V));
  return std::nullopt;
}

std::optional<Pointer> Encoder::pointer(llvm::Value *V) {
  std::optional<Value> X = valueOf(V);
  if (!X)
    return std::nullopt;
  if (X->K != Value::Ptr) {
    unsupported("a number used as a pointer: " + describe(*V));
    return std::nullopt;
  }
  return *X->P;
}

std::optional<Encoder::Value> Encoder::fresh(llvm::Type *T,
                                             const std::string &Name) {
  std::string Full = TagPrefix + Name + "." + std::to_string(Fresh++);
  if (T->isIntegerTy())
    return Value::bits(Z.bv_const(Full.c_str(), T->getIntegerBitWidth()));
  if (T->isFloatTy() || T->isDoubleTy())
    return Value::flt(Z.constant(Full.c_str(), floatSort(T)));
  unsupported("a value of type " + describe(*llvm::UndefValue::get(T)));
  return std::nullopt;
}

//===----------------------------------------------------------------------===//
// Memory
//===----------------------------------------------------------------------===//

Pointer Pointer::choose(const z3::expr &C, const Pointer &A, const Pointer &B) {
  z3::expr Offset =
      z3::eq(A.Offset, B.Offset) ? A.Offset : z3::ite(C, A.Offset, B.Offset);
  if (A.isKnown() && B.isKnown() && A.Objects[0] == B.Objects[0])
    return A.at(Offset);
  std::vector<unsigned> Objects = A.Objects;
  for (unsigned O : B.Objects)
    if (!llvm::is_contained(Objects, O))
      Objects.push_back(O);
  return Pointer{std::move(Objects), z3::ite(C, A.Which, B.Which), Offset};
}

std::optional<z3::expr> Encoder::loadFrom(const std::vector<z3::expr> &Bytes,
                                          const z3::expr &At, unsigned Size) {
  if (Size == 0 || Size > Bytes.size())
    return std::nullopt;
  auto Read = [&](uint64_t Offset) {
    z3::expr V = Bytes[Offset];
    for (unsigned I = 1; I < Size; ++I) // Little-endian.
      V = z3::concat(Bytes[Offset + I], V);
    return V;
  };
  z3::expr Offset = At.simplify();
  uint64_t Known;
  if (Offset.is_numeral_u64(Known)) {
    if (Known + Size > Bytes.size())
      return std::nullopt;
    return Read(Known);
  }
  // An index the behavior computed: any place the read fits (bsc clamps
  // indices, so there is one).
  z3::expr V = Read(Bytes.size() - Size);
  for (uint64_t O = Bytes.size() - Size; O-- > 0;)
    V = z3::ite(Offset == Z.bv_val(O, 64), Read(O), V);
  return V;
}

std::optional<z3::expr> Encoder::load(const Memory &M, const Pointer &P,
                                      unsigned Size) {
  // Of several objects, those the read fits (the code reads no other).
  std::optional<z3::expr> V;
  for (unsigned O : P.Objects)
    if (std::optional<z3::expr> X = loadFrom(M.Bytes[O], P.Offset, Size))
      V = V ? z3::ite(P.isIn(O), *X, *V) : *X;
  if (!V)
    unsupported("a read of " + std::to_string(Size) +
                " bytes past the end of " + M.Names[P.Objects.front()]);
  return V;
}

bool Encoder::storeInto(std::vector<z3::expr> &Bytes, const z3::expr &At,
                        const z3::expr &Bits) {
  unsigned Size = Bits.get_sort().bv_size() / 8;
  if (Size == 0 || Size > Bytes.size())
    return false;
  z3::expr Offset = At.simplify();
  uint64_t Known;
  if (Offset.is_numeral_u64(Known)) {
    if (Known + Size > Bytes.size())
      return false;
    for (unsigned I = 0; I < Size; ++I)
      Bytes[Known + I] = Bits.extract(8 * I + 7, 8 * I).simplify();
    return true;
  }
  for (uint64_t O = 0; O + Size <= Bytes.size(); ++O)
    for (unsigned I = 0; I < Size; ++I)
      Bytes[O + I] = z3::ite(Offset == Z.bv_val(O, 64),
                             Bits.extract(8 * I + 7, 8 * I), Bytes[O + I]);
  return true;
}

bool Encoder::store(Memory &M, const Pointer &P, const z3::expr &Bits) {
  if (P.isKnown()) {
    if (storeInto(M.Bytes[P.Objects[0]], P.Offset, Bits))
      return true;
  } else {
    // Each object the write fits changes where the pointer is into it.
    bool Any = false;
    for (unsigned O : P.Objects) {
      std::vector<z3::expr> New = M.Bytes[O];
      if (!storeInto(New, P.Offset, Bits))
        continue;
      Any = true;
      z3::expr In = P.isIn(O);
      for (size_t B = 0; B < New.size(); ++B)
        if (!z3::eq(New[B], M.Bytes[O][B]))
          M.Bytes[O][B] = z3::ite(In, New[B], M.Bytes[O][B]);
    }
    if (Any)
      return true;
  }
  return unsupported("a write of " +
                     std::to_string(Bits.get_sort().bv_size() / 8) +
                     " bytes past the end of " + M.Names[P.Objects.front()]);
}

std::optional<Pointer> Encoder::loadPointer(const Memory &M, const Pointer &P) {
  uint64_t Known;
  std::optional<Pointer> V;
  if (P.Offset.simplify().is_numeral_u64(Known))
    for (unsigned O : P.Objects) {
      // Every object it may be into must hold a pointer there.
      auto It = M.Cells.find({O, Known});
      if (It == M.Cells.end())
        return std::nullopt;
      V = V ? Pointer::choose(P.isIn(O), It->second, *V) : It->second;
    }
  return V;
}

bool Encoder::storePointer(Memory &M, const Pointer &P, const Pointer &Stored) {
  uint64_t Known;
  if (!P.Offset.simplify().is_numeral_u64(Known))
    return false;
  for (unsigned O : P.Objects) {
    auto It = M.Cells.find({O, Known});
    if (P.isKnown() || It == M.Cells.end())
      M.Cells.insert_or_assign({O, Known}, Stored);
    else
      It->second = Pointer::choose(P.isIn(O), Stored, It->second);
  }
  return true;
}

/// The memory where the paths `Conds` select meet: each byte (and pointer
/// kept whole) is the one of the path taken (the last is the rest).
static Memory merge(const std::vector<const Memory *> &Ins,
                    const std::vector<z3::expr> &Conds) {
  Memory M = *Ins.back();
  for (size_t K = Ins.size() - 1; K-- > 0;) {
    const Memory &In = *Ins[K];
    // An object only one path made (a local of a branch) is that path's.
    for (size_t O = M.Bytes.size(); O < In.Bytes.size(); ++O)
      M.add(In.Names[O], In.Bytes[O]);
    for (size_t O = 0; O < In.Bytes.size() && O < M.Bytes.size(); ++O)
      for (size_t B = 0; B < In.Bytes[O].size(); ++B)
        if (!z3::eq(In.Bytes[O][B], M.Bytes[O][B]))
          M.Bytes[O][B] = z3::ite(Conds[K], In.Bytes[O][B], M.Bytes[O][B]);
    for (const auto &[Key, P] : In.Cells) {
      auto It = M.Cells.find(Key);
      if (It == M.Cells.end())
        M.Cells.insert({Key, P});
      else
        It->second = Pointer::choose(Conds[K], P, It->second);
    }
  }
  return M;
}

//===----------------------------------------------------------------------===//
// Instructions
//===----------------------------------------------------------------------===//

bool Encoder::encodeCall(llvm::CallInst &C, Memory &M, z3::expr Reached) {
  llvm::Function *Callee = C.getCalledFunction();
  if (!Callee)
    return unsupported("a call through a pointer: " + describe(C));
  if (Callee->getName() == VerifyCheckSymbol) {
    std::optional<z3::expr> Cond = bits(C.getArgOperand(0));
    auto *Index = llvm::dyn_cast<llvm::ConstantInt>(C.getArgOperand(1));
    auto *Assume = llvm::dyn_cast<llvm::ConstantInt>(C.getArgOperand(2));
    if (!Cond || !Index || !Assume)
      return unsupported("a check the verifier cannot read: " + describe(C));
    if (Assume->isOne())
      Assumed = Assumed && z3::implies(Reached, asBool(*Cond));
    else
      Checks.push_back(
          {unsigned(Index->getZExtValue()), Reached && !asBool(*Cond)});
    return true;
  }
  if (auto *II = llvm::dyn_cast<llvm::IntrinsicInst>(&C)) {
    auto Arg = [&](unsigned I) { return bits(C.getArgOperand(I)); };
    auto Set = [&](z3::expr E) {
      set(&C, Value::bits(E));
      return true;
    };
    switch (II->getIntrinsicID()) {
    case llvm::Intrinsic::lifetime_start:
    case llvm::Intrinsic::lifetime_end:
    case llvm::Intrinsic::dbg_declare:
    case llvm::Intrinsic::dbg_value:
    case llvm::Intrinsic::dbg_label:
    case llvm::Intrinsic::experimental_noalias_scope_decl:
      return true;
    case llvm::Intrinsic::assume: {
      std::optional<z3::expr> Cond = Arg(0);
      if (!Cond)
        return false;
      // What the code generator knows (a task's gap of cycles): true on
      // every path that reaches it.
      Known = Known && z3::implies(Reached, asBool(*Cond));
      return true;
    }
    case llvm::Intrinsic::expect: {
      std::optional<z3::expr> A = Arg(0);
      return A && Set(*A);
    }
    case llvm::Intrinsic::smax:
    case llvm::Intrinsic::smin:
    case llvm::Intrinsic::umax:
    case llvm::Intrinsic::umin: {
      std::optional<z3::expr> A = Arg(0), B = Arg(1);
      if (!A || !B)
        return false;
      auto ID = II->getIntrinsicID();
      z3::expr Less = ID == llvm::Intrinsic::smax || ID == llvm::Intrinsic::smin
                          ? *A < *B
                          : z3::ult(*A, *B);
      bool Max = ID == llvm::Intrinsic::smax || ID == llvm::Intrinsic::umax;
      return Set(z3::ite(Less, Max ? *B : *A, Max ? *A : *B));
    }
    case llvm::Intrinsic::abs: {
      std::optional<z3::expr> A = Arg(0);
      return A && Set(z3::ite(*A < 0, -*A, *A));
    }
    case llvm::Intrinsic::fptosi_sat:
    case llvm::Intrinsic::fptoui_sat: {
      // Saturating: NaN is 0, out of range the nearest end.
      std::optional<z3::expr> A = floating(C.getArgOperand(0));
      if (!A)
        return false;
      unsigned W = C.getType()->getIntegerBitWidth();
      bool Signed = II->getIntrinsicID() == llvm::Intrinsic::fptosi_sat;
      z3::expr RTZ(Z, Z3_mk_fpa_rtz(Z));
      z3::expr Converted(Z, Signed ? Z3_mk_fpa_to_sbv(Z, RTZ, *A, W)
                                   : Z3_mk_fpa_to_ubv(Z, RTZ, *A, W));
      llvm::APInt MaxI = Signed ? llvm::APInt::getSignedMaxValue(W)
                                : llvm::APInt::getMaxValue(W);
      llvm::APInt MinI = Signed ? llvm::APInt::getSignedMinValue(W)
                                : llvm::APInt::getMinValue(W);
      z3::sort S = A->get_sort();
      z3::expr Hi(Z, Signed ? Z3_mk_fpa_to_fp_signed(
                                  Z, RTZ, Z.bv_val(MaxI.getSExtValue(), W), S)
                            : Z3_mk_fpa_to_fp_unsigned(
                                  Z, RTZ, Z.bv_val(MaxI.getZExtValue(), W), S));
      z3::expr Lo(Z, Signed ? Z3_mk_fpa_to_fp_signed(
                                  Z, RTZ, Z.bv_val(MinI.getSExtValue(), W), S)
                            : Z3_mk_fpa_to_fp_unsigned(
                                  Z, RTZ, Z.bv_val(MinI.getZExtValue(), W), S));
      // Hi is the largest float at most the maximum (rounded towards
      // zero): above it is out of range; Lo is exact.
      z3::expr R = z3::ite(
          z3::expr(Z, Z3_mk_fpa_is_nan(Z, *A)), Z.bv_val(0, W),
          z3::ite(z3::expr(Z, Z3_mk_fpa_gt(Z, *A, Hi)),
                  Z.bv_val(MaxI.getZExtValue(), W),
                  z3::ite(z3::expr(Z, Z3_mk_fpa_lt(Z, *A, Lo)),
                          Z.bv_val(MinI.getZExtValue(), W), Converted)));
      return Set(R);
    }
    case llvm::Intrinsic::fabs: {
      std::optional<z3::expr> A = floating(C.getArgOperand(0));
      if (!A)
        return false;
      set(&C, Value::flt(z3::abs(*A)));
      return true;
    }
    case llvm::Intrinsic::memset:
    case llvm::Intrinsic::memcpy:
    case llvm::Intrinsic::memmove: {
      auto *Len = llvm::dyn_cast<llvm::ConstantInt>(C.getArgOperand(2));
      std::optional<Pointer> Dst = pointer(C.getArgOperand(0));
      if (!Len || !Dst)
        return unsupported("a copy of a length the verifier cannot see: " +
                           describe(C));
      for (uint64_t I = 0; I < Len->getZExtValue(); ++I) {
        Pointer D = Dst->at(Dst->Offset + Z.bv_val(I, 64));
        std::optional<z3::expr> Byte;
        if (II->getIntrinsicID() == llvm::Intrinsic::memset) {
          Byte = Arg(1);
        } else {
          std::optional<Pointer> Src = pointer(C.getArgOperand(1));
          if (!Src)
            return false;
          Byte = load(M, Src->at(Src->Offset + Z.bv_val(I, 64)), 1);
        }
        if (!Byte || !store(M, D, *Byte))
          return false;
      }
      return true;
    }
    default:
      return unsupported("the intrinsic " + Callee->getName().str());
    }
  }
  if (!Callee->isDeclaration())
    return unsupported("a call of " + Callee->getName().str() +
                       " that was not inlined (a recursive func?)");
  // Registered C++ (NativeCall says what it is): a fresh result, fresh
  // bytes where it may write, the same result for the same arguments (and
  // the same bytes of the objects it reads) where it is pure or a getter.
  const BehaviorLayout::NativeCall *Known = nullptr;
  if (Natives) {
    auto It = Natives->find(Callee->getName().str());
    Known = It != Natives->end() ? &It->second : nullptr;
  }
  // The same result for the same arguments: registered pure, or a getter
  // (whose argument is its object).
  bool SameForSame = Known && (Known->Pure || Known->Getter);
  NativeResult Result{Callee->getName().str(), Reached, std::nullopt, {}};
  Result.Recorded = Known && !Known->Pure && !(Known->Flags & SiteStandard);
  std::vector<z3::expr> Args;
  for (unsigned I = 0; I < C.arg_size(); ++I) {
    llvm::Value *A = C.getArgOperand(I);
    if (!A->getType()->isPointerTy()) {
      std::optional<z3::expr> E = bits(A);
      if (!E)
        return false;
      Args.push_back(*E);
      continue;
    }
    // A pure function's objects are part of its arguments.
    if (!SameForSame)
      continue;
    for (auto [Arg, Size] : Known->Reads)
      if (Arg == I && Size) {
        std::optional<Pointer> P = pointer(A);
        std::optional<z3::expr> Bytes = P ? load(M, *P, Size) : std::nullopt;
        if (!Bytes)
          return false;
        Args.push_back(*Bytes);
      }
  }
  if (Known)
    for (auto [Arg, Size] : Known->Writes) {
      std::optional<Pointer> P = pointer(C.getArgOperand(Arg));
      if (!P)
        return false;
      std::vector<z3::expr> Written;
      for (uint64_t B = 0; B < Size; ++B) {
        Written.push_back(
            freshByte(TagPrefix + "wrote." + std::to_string(Fresh++)));
        if (!store(M, P->at(P->Offset + Z.bv_val(B, 64)), Written.back()))
          return false;
      }
      Result.Ptrs.push_back(std::move(Written));
    }
  llvm::Type *T = C.getType();
  if (T->isPointerTy())
    return unsupported("a string returned by registered C++ ('" +
                       (Known ? Known->Name : Callee->getName().str()) +
                       "')");
  if (!T->isVoidTy()) {
    std::optional<Value> V = fresh(T, "native");
    if (!V)
      return false;
    if (SameForSame) {
      for (const auto &[Seen, Old] : PureCalls[Callee->getName().str()]) {
        z3::expr Same = Z.bool_val(Seen.size() == Args.size());
        for (size_t I = 0; I < Args.size() && I < Seen.size(); ++I)
          Same = Same &&
                 (Seen[I].get_sort().bv_size() == Args[I].get_sort().bv_size()
                      ? Seen[I] == Args[I]
                      : Z.bool_val(false));
        Assumed = Assumed && z3::implies(Same, V->E == Old.E);
      }
      PureCalls[Callee->getName().str()].push_back({Args, *V});
    }
    Result.Value = V->E;
    set(&C, *V);
  }
  NativeCalls.push_back(std::move(Result));
  return true;
}

bool Encoder::encodeInstruction(llvm::Instruction &I, Memory &M,
                                z3::expr Reached) {
  using llvm::Instruction;
  auto SetBits = [&](z3::expr E) {
    set(&I, Value::bits(E));
    return true;
  };
  auto SetFloat = [&](z3::expr E) {
    set(&I, Value::flt(E));
    return true;
  };
  z3::expr RNE(Z, Z3_mk_fpa_rne(Z));
  if (auto *B = llvm::dyn_cast<llvm::BinaryOperator>(&I)) {
    if (B->getType()->isFloatingPointTy()) {
      std::optional<z3::expr> A = floating(B->getOperand(0)),
                              C = floating(B->getOperand(1));
      if (!A || !C)
        return false;
      switch (B->getOpcode()) {
      case Instruction::FAdd:
        return SetFloat(z3::expr(Z, Z3_mk_fpa_add(Z, RNE, *A, *C)));
      case Instruction::FSub:
        return SetFloat(z3::expr(Z, Z3_mk_fpa_sub(Z, RNE, *A, *C)));
      case Instruction::FMul:
        return SetFloat(z3::expr(Z, Z3_mk_fpa_mul(Z, RNE, *A, *C)));
      case Instruction::FDiv:
        return SetFloat(z3::expr(Z, Z3_mk_fpa_div(Z, RNE, *A, *C)));
      case Instruction::FRem:
        return SetFloat(z3::expr(Z, Z3_mk_fpa_rem(Z, *A, *C)));
      default:
        return unsupported("the instruction " + describe(I));
      }
    }
    if (!B->getType()->isIntegerTy())
      return unsupported("the instruction " + describe(I));
    std::optional<z3::expr> A = bits(B->getOperand(0)),
                            C = bits(B->getOperand(1));
    if (!A || !C)
      return false;
    switch (B->getOpcode()) {
    case Instruction::Add:
      return SetBits(*A + *C);
    case Instruction::Sub:
      return SetBits(*A - *C);
    case Instruction::Mul:
      return SetBits(*A * *C);
    case Instruction::UDiv:
      return SetBits(z3::udiv(*A, *C));
    case Instruction::SDiv:
      return SetBits(*A / *C);
    case Instruction::URem:
      return SetBits(z3::urem(*A, *C));
    case Instruction::SRem:
      return SetBits(z3::srem(*A, *C));
    case Instruction::Shl:
      return SetBits(z3::shl(*A, *C));
    case Instruction::LShr:
      return SetBits(z3::lshr(*A, *C));
    case Instruction::AShr:
      return SetBits(z3::ashr(*A, *C));
    case Instruction::And:
      return SetBits(*A & *C);
    case Instruction::Or:
      return SetBits(*A | *C);
    case Instruction::Xor:
      return SetBits(*A ^ *C);
    default:
      return unsupported("the instruction " + describe(I));
    }
  }
  if (auto *N = llvm::dyn_cast<llvm::UnaryOperator>(&I)) {
    std::optional<z3::expr> A = floating(N->getOperand(0));
    if (!A || N->getOpcode() != Instruction::FNeg)
      return A ? unsupported("the instruction " + describe(I)) : false;
    return SetFloat(-*A);
  }
  if (auto *Cmp = llvm::dyn_cast<llvm::ICmpInst>(&I)) {
    if (Cmp->getOperand(0)->getType()->isPointerTy()) {
      std::optional<Pointer> A = pointer(Cmp->getOperand(0)),
                             C = pointer(Cmp->getOperand(1));
      if (!A || !C)
        return false;
      if (!Cmp->isEquality())
        return unsupported("an ordering of pointers: " + describe(I));
      // Distinct objects are at distinct addresses (the optimiser merged
      // equal constants before): a string compared by its address first.
      z3::expr Eq =
          A->isKnown() && C->isKnown()
              ? (A->Objects[0] == C->Objects[0] ? A->Offset == C->Offset
                                                : Z.bool_val(false))
              : A->Which == C->Which && A->Offset == C->Offset;
      return SetBits(
          fromBool(Cmp->getPredicate() == llvm::CmpInst::ICMP_EQ ? Eq : !Eq));
    }
    std::optional<z3::expr> A = bits(Cmp->getOperand(0)),
                            C = bits(Cmp->getOperand(1));
    if (!A || !C)
      return false;
    z3::expr R = Z.bool_val(false);
    switch (Cmp->getPredicate()) {
    case llvm::CmpInst::ICMP_EQ:
      R = *A == *C;
      break;
    case llvm::CmpInst::ICMP_NE:
      R = *A != *C;
      break;
    case llvm::CmpInst::ICMP_UGT:
      R = z3::ugt(*A, *C);
      break;
    case llvm::CmpInst::ICMP_UGE:
      R = z3::uge(*A, *C);
      break;
    case llvm::CmpInst::ICMP_ULT:
      R = z3::ult(*A, *C);
      break;
    case llvm::CmpInst::ICMP_ULE:
      R = z3::ule(*A, *C);
      break;
    case llvm::CmpInst::ICMP_SGT:
      R = *A > *C;
      break;
    case llvm::CmpInst::ICMP_SGE:
      R = *A >= *C;
      break;
    case llvm::CmpInst::ICMP_SLT:
      R = *A < *C;
      break;
    case llvm::CmpInst::ICMP_SLE:
      R = *A <= *C;
      break;
    default:
      return unsupported("the instruction " + describe(I));
    }
    return SetBits(fromBool(R));
  }
  if (auto *Cmp = llvm::dyn_cast<llvm::FCmpInst>(&I)) {
    std::optional<z3::expr> A = floating(Cmp->getOperand(0)),
                            C = floating(Cmp->getOperand(1));
    if (!A || !C)
      return false;
    z3::expr Unordered = z3::expr(Z, Z3_mk_fpa_is_nan(Z, *A)) ||
                         z3::expr(Z, Z3_mk_fpa_is_nan(Z, *C));
    z3::expr Eq(Z, Z3_mk_fpa_eq(Z, *A, *C)), Lt(Z, Z3_mk_fpa_lt(Z, *A, *C)),
        Gt(Z, Z3_mk_fpa_gt(Z, *A, *C));
    z3::expr R = Z.bool_val(false);
    using P = llvm::CmpInst::Predicate;
    switch (Cmp->getPredicate()) {
    case P::FCMP_FALSE:
      R = Z.bool_val(false);
      break;
    case P::FCMP_TRUE:
      R = Z.bool_val(true);
      break;
    case P::FCMP_OEQ:
      R = Eq;
      break;
    case P::FCMP_OGT:
      R = Gt;
      break;
    case P::FCMP_OGE:
      R = Gt || Eq;
      break;
    case P::FCMP_OLT:
      R = Lt;
      break;
    case P::FCMP_OLE:
      R = Lt || Eq;
      break;
    case P::FCMP_ONE:
      R = Lt || Gt;
      break;
    case P::FCMP_ORD:
      R = !Unordered;
      break;
    case P::FCMP_UNO:
      R = Unordered;
      break;
    case P::FCMP_UEQ:
      R = Unordered || Eq;
      break;
    case P::FCMP_UGT:
      R = Unordered || Gt;
      break;
    case P::FCMP_UGE:
      R = Unordered || Gt || Eq;
      break;
    case P::FCMP_ULT:
      R = Unordered || Lt;
      break;
    case P::FCMP_ULE:
      R = Unordered || Lt || Eq;
      break;
    case P::FCMP_UNE:
      R = !Eq;
      break;
    default:
      return unsupported("the instruction " + describe(I));
    }
    return SetBits(fromBool(R));
  }
  if (auto *Sel = llvm::dyn_cast<llvm::SelectInst>(&I)) {
    std::optional<z3::expr> Cond = bits(Sel->getCondition());
    std::optional<Value> A = valueOf(Sel->getTrueValue()),
                         C = valueOf(Sel->getFalseValue());
    if (!Cond || !A || !C || A->K != C->K)
      return Cond && A && C ? unsupported("the instruction " + describe(I))
                            : false;
    if (A->K == Value::Ptr)
      set(&I, Value::ptr(Pointer::choose(asBool(*Cond), *A->P, *C->P)));
    else
      set(&I, Value{A->K, z3::ite(asBool(*Cond), A->E, C->E), {}});
    return true;
  }
  if (auto *Cast = llvm::dyn_cast<llvm::CastInst>(&I)) {
    llvm::Type *To = Cast->getType();
    switch (Cast->getOpcode()) {
    case Instruction::ZExt:
    case Instruction::SExt:
    case Instruction::Trunc: {
      std::optional<z3::expr> A = bits(Cast->getOperand(0));
      if (!A)
        return false;
      unsigned From = A->get_sort().bv_size(), W = To->getIntegerBitWidth();
      if (Cast->getOpcode() == Instruction::Trunc)
        return SetBits(A->extract(W - 1, 0));
      return SetBits(Cast->getOpcode() == Instruction::ZExt
                         ? z3::zext(*A, W - From)
                         : z3::sext(*A, W - From));
    }
    case Instruction::BitCast:
      if (To->isFloatingPointTy()) {
        std::optional<z3::expr> A = bits(Cast->getOperand(0));
        return A &&
               SetFloat(z3::expr(Z, Z3_mk_fpa_to_fp_bv(Z, *A, floatSort(To))));
      }
      if (To->isIntegerTy()) {
        std::optional<z3::expr> A = bits(Cast->getOperand(0));
        return A && SetBits(*A);
      }
      break;
    case Instruction::SIToFP:
    case Instruction::UIToFP: {
      std::optional<z3::expr> A = bits(Cast->getOperand(0));
      if (!A)
        return false;
      return SetFloat(z3::expr(
          Z, Cast->getOpcode() == Instruction::SIToFP
                 ? Z3_mk_fpa_to_fp_signed(Z, RNE, *A, floatSort(To))
                 : Z3_mk_fpa_to_fp_unsigned(Z, RNE, *A, floatSort(To))));
    }
    case Instruction::FPToSI:
    case Instruction::FPToUI: {
      std::optional<z3::expr> A = floating(Cast->getOperand(0));
      if (!A)
        return false;
      z3::expr RTZ(Z, Z3_mk_fpa_rtz(Z));
      unsigned W = To->getIntegerBitWidth();
      return SetBits(z3::expr(Z, Cast->getOpcode() == Instruction::FPToSI
                                     ? Z3_mk_fpa_to_sbv(Z, RTZ, *A, W)
                                     : Z3_mk_fpa_to_ubv(Z, RTZ, *A, W)));
    }
    case Instruction::FPExt:
    case Instruction::FPTrunc: {
      std::optional<z3::expr> A = floating(Cast->getOperand(0));
      return A && SetFloat(z3::expr(
                      Z, Z3_mk_fpa_to_fp_float(Z, RNE, *A, floatSort(To))));
    }
    default:
      break;
    }
    return unsupported("the instruction " + describe(I));
  }
  if (auto *GEP = llvm::dyn_cast<llvm::GetElementPtrInst>(&I)) {
    std::optional<Pointer> Base = pointer(GEP->getPointerOperand());
    if (!Base)
      return false;
    z3::expr Offset = Base->Offset;
    for (llvm::gep_type_iterator It = llvm::gep_type_begin(GEP),
                                 End = llvm::gep_type_end(GEP);
         It != End; ++It) {
      if (llvm::StructType *ST = It.getStructTypeOrNull()) {
        unsigned Field =
            llvm::cast<llvm::ConstantInt>(It.getOperand())->getZExtValue();
        Offset =
            Offset +
            Z.bv_val(uint64_t(DL.getStructLayout(ST)->getElementOffset(Field)),
                     64);
        continue;
      }
      std::optional<z3::expr> Index = bits(It.getOperand());
      if (!Index)
        return false;
      unsigned W = Index->get_sort().bv_size();
      z3::expr I64 = W < 64 ? z3::sext(*Index, 64 - W) : *Index;
      Offset = Offset +
               I64 * Z.bv_val(uint64_t(It.getSequentialElementStride(DL)), 64);
    }
    set(&I, Value::ptr(Base->at(Offset.simplify())));
    return true;
  }
  if (auto *Ld = llvm::dyn_cast<llvm::LoadInst>(&I)) {
    std::optional<Pointer> P = pointer(Ld->getPointerOperand());
    if (!P)
      return false;
    llvm::Type *T = Ld->getType();
    if (T->isPointerTy()) {
      std::optional<Pointer> Loaded = loadPointer(M, *P);
      if (!Loaded)
        return unsupported("a pointer read from memory the verifier does "
                           "not follow: " +
                           describe(I));
      set(&I, Value::ptr(*Loaded));
      return true;
    }
    std::optional<z3::expr> B = load(M, *P, DL.getTypeStoreSize(T));
    if (!B)
      return false;
    if (T->isIntegerTy()) {
      unsigned W = T->getIntegerBitWidth();
      return SetBits(W == B->get_sort().bv_size() ? *B : B->extract(W - 1, 0));
    }
    if (T->isFloatTy() || T->isDoubleTy())
      return SetFloat(z3::expr(Z, Z3_mk_fpa_to_fp_bv(Z, *B, floatSort(T))));
    return unsupported("a read of " + describe(I));
  }
  if (auto *St = llvm::dyn_cast<llvm::StoreInst>(&I)) {
    std::optional<Pointer> P = pointer(St->getPointerOperand());
    if (!P)
      return false;
    llvm::Value *V = St->getValueOperand();
    if (V->getType()->isPointerTy()) {
      std::optional<Pointer> Stored = pointer(V);
      if (!Stored)
        return false;
      if (!storePointer(M, *P, *Stored))
        return unsupported("a pointer written where the verifier does not "
                           "follow it: " +
                           describe(I));
      return true;
    }
    std::optional<z3::expr> B = bits(V);
    if (!B)
      return false;
    unsigned Bytes = DL.getTypeStoreSize(V->getType());
    unsigned W = B->get_sort().bv_size();
    z3::expr Wide = W == 8 * Bytes ? *B : z3::zext(*B, 8 * Bytes - W);
    return store(M, *P, Wide);
  }
  if (auto *A = llvm::dyn_cast<llvm::AllocaInst>(&I)) {
    std::optional<llvm::TypeSize> Size = A->getAllocationSize(DL);
    if (!Size || Size->isScalable() || !A->isStaticAlloca())
      return unsupported("the instruction " + describe(I));
    std::vector<z3::expr> Content;
    for (uint64_t B = 0; B < Size->getFixedValue(); ++B)
      Content.push_back(
          freshByte(TagPrefix + "stack." + std::to_string(Fresh++)));
    unsigned Object = M.add("a local", std::move(Content));
    set(&I, Value::ptr(Pointer::into(Object, Z.bv_val(0, 64))));
    return true;
  }
  if (auto *C = llvm::dyn_cast<llvm::CallInst>(&I))
    return encodeCall(*C, M, Reached);
  if (auto *Fr = llvm::dyn_cast<llvm::FreezeInst>(&I)) {
    std::optional<Value> V = valueOf(Fr->getOperand(0));
    if (!V)
      return false;
    set(&I, *V);
    return true;
  }
  return unsupported("the instruction " + describe(I));
}

//===----------------------------------------------------------------------===//
// Blocks
//===----------------------------------------------------------------------===//

bool Encoder::encode(llvm::Function &F, llvm::ArrayRef<Pointer> Args,
                     Memory &Mem, llvm::StringRef Tag) {
  Values.clear();
  Out.clear();
  Edges.clear();
  Checks.clear();
  NativeCalls.clear();
  Escapes.clear();
  PureCalls.clear();
  Unsupported.clear();
  Assumed = Z.bool_val(true);
  Known = Z.bool_val(true);
  TagPrefix = Tag.str() + ".";
  for (unsigned I = 0; I < Args.size() && I < F.arg_size(); ++I)
    set(F.getArg(I), Value::ptr(Args[I]));

  // Constant globals the code reads (strings, tables) are objects of their
  // bytes; a global the code could write is not known.
  for (llvm::BasicBlock &BB : F)
    for (llvm::Instruction &I : BB)
      for (llvm::Value *Op : I.operands()) {
        auto *GV = llvm::dyn_cast<llvm::GlobalVariable>(Op);
        if (!GV || Values.count(GV))
          continue;
        if (!GV->isConstant() || !GV->hasDefinitiveInitializer())
          return unsupported("the global " + GV->getName().str() +
                             ", which the code may change");
        std::vector<z3::expr> Bytes;
        const llvm::Constant *Init = GV->getInitializer();
        uint64_t Size = DL.getTypeAllocSize(Init->getType());
        if (auto *Data = llvm::dyn_cast<llvm::ConstantDataSequential>(Init)) {
          llvm::StringRef Raw = Data->getRawDataValues();
          for (uint64_t B = 0; B < Size; ++B)
            Bytes.push_back(Z.bv_val(
                B < Raw.size() ? unsigned((unsigned char)Raw[B]) : 0u, 8));
        } else if (Init->isNullValue()) {
          for (uint64_t B = 0; B < Size; ++B)
            Bytes.push_back(Z.bv_val(0, 8));
        } else {
          return unsupported("the constant " + describe(*GV));
        }
        unsigned Object = Mem.add(GV->getName(), std::move(Bytes));
        set(GV, Value::ptr(Pointer::into(Object, Z.bv_val(0, 64))));
      }
  llvm::ReversePostOrderTraversal<llvm::Function *> RPO(&F);
  llvm::DenseMap<llvm::BasicBlock *, unsigned> Order;
  for (llvm::BasicBlock *BB : RPO)
    Order[BB] = Order.size();
  std::vector<const Memory *> Returns;
  std::vector<z3::expr> ReturnConds;
  // A block that every path from its dominator passes (the join after an
  // `if`) is reached when the dominator is: its condition is the
  // dominator's, not the disjunction of its edges', which would drag the
  // branches' conditions (a float division) into every later question.
  llvm::DominatorTree DT(F);
  llvm::PostDominatorTree PDT(F);
  std::map<llvm::BasicBlock *, z3::expr> ReachedAt;
  for (llvm::BasicBlock *BB : RPO) {
    // Where control comes from: the entry, or the edges encoded so far.
    Memory M;
    z3::expr Reached = Z.bool_val(BB->isEntryBlock());
    if (BB->isEntryBlock()) {
      M = Mem;
    } else {
      std::vector<const Memory *> Ins;
      std::vector<z3::expr> Conds;
      std::vector<llvm::BasicBlock *> Preds;
      bool LoopHead = false;
      for (llvm::BasicBlock *P : llvm::predecessors(BB)) {
        if (!Order.count(P) || llvm::is_contained(Preds, P))
          continue; // Unreachable from the entry, or seen (a switch).
        LoopHead |= Order[P] >= Order[BB];
        auto E = Edges.find({P, BB});
        if (E == Edges.end())
          continue;
        Preds.push_back(P);
        Ins.push_back(&Out.at(P));
        Conds.push_back(E->second);
        Reached = Reached || E->second;
      }
      if (Ins.empty())
        continue;
      // A loop that runs more passes than were peeled off it: what follows
      // is not encoded, and a run that gets here is not explored.
      if (LoopHead) {
        Escapes.push_back({Reached.simplify(), BB, placeOf(*BB)});
        continue;
      }
      M = merge(Ins, Conds);
      for (llvm::PHINode &Phi : BB->phis()) {
        std::optional<Value> V;
        for (size_t K = Ins.size(); K-- > 0;) {
          std::optional<Value> In =
              valueOf(Phi.getIncomingValueForBlock(Preds[K]));
          if (!In)
            return false;
          if (!V) {
            V = In;
          } else if (V->K != In->K) {
            return unsupported("the phi " + describe(Phi));
          } else if (V->K == Value::Ptr) {
            V = Value::ptr(Pointer::choose(Conds[K], *In->P, *V->P));
          } else {
            V->E = z3::ite(Conds[K], In->E, V->E);
          }
        }
        set(&Phi, *V);
      }
    }
    z3::expr ReachBB = Reached.simplify();
    if (llvm::DomTreeNode *Node = DT.getNode(BB); Node && Node->getIDom()) {
      llvm::BasicBlock *Dom = Node->getIDom()->getBlock();
      auto It = ReachedAt.find(Dom);
      if (It != ReachedAt.end() && PDT.dominates(BB, Dom))
        ReachBB = It->second;
    }
    ReachedAt.insert_or_assign(BB, ReachBB);
    for (llvm::Instruction &I : *BB) {
      if (llvm::isa<llvm::PHINode>(I))
        continue;
      if (I.isTerminator())
        break;
      if (!encodeInstruction(I, M, ReachBB))
        return false;
    }
    llvm::Instruction *Term = BB->getTerminator();
    if (auto *Br = llvm::dyn_cast<llvm::BranchInst>(Term)) {
      if (Br->isUnconditional()) {
        Edges.emplace(std::pair(BB, Br->getSuccessor(0)), ReachBB);
      } else {
        std::optional<z3::expr> C = bits(Br->getCondition());
        if (!C)
          return false;
        z3::expr T = asBool(*C);
        if (Br->getSuccessor(0) == Br->getSuccessor(1)) {
          Edges.emplace(std::pair(BB, Br->getSuccessor(0)), ReachBB);
        } else {
          Edges.emplace(std::pair(BB, Br->getSuccessor(0)), ReachBB && T);
          Edges.emplace(std::pair(BB, Br->getSuccessor(1)), ReachBB && !T);
        }
      }
    } else if (auto *Sw = llvm::dyn_cast<llvm::SwitchInst>(Term)) {
      std::optional<z3::expr> C = bits(Sw->getCondition());
      if (!C)
        return false;
      z3::expr Other = ReachBB;
      std::map<llvm::BasicBlock *, z3::expr> To;
      for (auto &Case : Sw->cases()) {
        std::optional<z3::expr> V = bits(Case.getCaseValue());
        z3::expr Taken = *C == *V;
        auto It = To.find(Case.getCaseSuccessor());
        if (It == To.end())
          To.insert({Case.getCaseSuccessor(), Taken});
        else
          It->second = It->second || Taken;
        Other = Other && !Taken;
      }
      for (auto &[Succ, Taken] : To)
        Edges.emplace(std::pair(BB, Succ), ReachBB && Taken);
      auto It = Edges.find({BB, Sw->getDefaultDest()});
      if (It == Edges.end())
        Edges.emplace(std::pair(BB, Sw->getDefaultDest()), Other);
      else
        It->second = It->second || Other;
    } else if (llvm::isa<llvm::ReturnInst>(Term)) {
      Out.insert_or_assign(BB, std::move(M));
      Returns.push_back(&Out.at(BB));
      ReturnConds.push_back(ReachBB);
      continue;
    } else if (llvm::isa<llvm::UnreachableInst>(Term)) {
      Known = Known && !ReachBB;
    } else {
      return unsupported("the instruction " + describe(*Term));
    }
    Out.insert_or_assign(BB, std::move(M));
  }
  if (Returns.empty())
    return unsupported(F.getName().str() + " never returns");
  Mem = merge(Returns, ReturnConds);
  return true;
}
