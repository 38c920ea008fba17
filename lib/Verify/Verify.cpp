//===- Verify.cpp - `bsc verify`: bounded model checking with Z3 ----------===//
//
// The behavior is loaded into the JIT as `bsc run` loads it, for the state
// its first cycle starts from (bs_state_init's, the constructors of its
// C++ values included) and the layout of `input` and `output`. Its cycle
// is then compiled again with AssertionMode::Verify and the `--model`s,
// optimised as `-O2` (tasks and funcs inlined into the entry, counted
// loops unrolled, the other loops peeled `--loop-limit` passes), and
// encoded once per cycle: the state, `input` and `output` are bytes that
// carry from one cycle to the next, the header's cycle number is the
// cycle's, `input` is free in every cycle. Z3 is then asked whether an
// assertion can fail (or a loop run further) in cycles 1 to k while every
// assumption so far held, and whether k-induction shows it for every
// cycle, for k = 1, 2, 4, ... up to the cycles asked for; the first bad
// cycle is the counterexample, its inputs and C++ results the model's.
//
//===----------------------------------------------------------------------===//
#include "bsc/Verify/Verify.h"
#include "Encoder.h"
#include "Models.h"
#include "bsc/Basic/Output.h"
#include "bsc/CodeGen/Target.h"
#include "bsc/JIT/Boundary.h"
#include "bscript/bscript.h"
#include "llvm/Analysis/AssumptionCache.h"
#include "llvm/Analysis/LoopInfo.h"
#include "llvm/Analysis/ScalarEvolution.h"
#include "llvm/Analysis/TargetLibraryInfo.h"
#include "llvm/IR/DebugInfoMetadata.h"
#include "llvm/IR/Dominators.h"
#include "llvm/IR/LLVMContext.h"
#include "llvm/Support/Format.h"
#include "llvm/Support/MathExtras.h"
#include "llvm/Support/Timer.h"
#include "llvm/Support/ToolOutputFile.h"
#include "llvm/Transforms/Utils/LoopPeel.h"
#include "llvm/Transforms/Utils/LoopSimplify.h"
#include "llvm/Transforms/Utils/LoopUtils.h"
#include <chrono>
#include <cstddef>
#include <cstring>
#include <map>

using namespace bsc;
using namespace bsc::verify;

namespace {
/// The objects of the behavior's memory.
struct Objects {
  unsigned State, Input, Output, User;
};

/// Concrete bytes as terms.
std::vector<z3::expr> bytesOf(z3::context &Z, const void *Data, size_t Size) {
  std::vector<z3::expr> Bytes;
  const auto *P = static_cast<const unsigned char *>(Data);
  for (size_t I = 0; I < Size; ++I)
    Bytes.push_back(Z.bv_val(unsigned(P[I]), 8));
  return Bytes;
}

/// A native's result as the model has it: an int (signed) or a float.
std::string describeValue(z3::context &Z, const z3::model &Model,
                          const z3::expr &V) {
  if (V.get_sort().is_bv()) {
    // Z3 gives a bit-vector's value unsigned: signed as the behavior reads
    // it, here.
    unsigned W = V.get_sort().bv_size();
    uint64_t U = 0;
    Model.eval(V, true).is_numeral_u64(U);
    if (W == 1)
      return U ? "true" : "false";
    return std::to_string(llvm::SignExtend64(U, std::min(W, 64u)));
  }
  uint64_t Bits = 0;
  Model.eval(z3::expr(Z, Z3_mk_fpa_to_ieee_bv(Z, V)), true)
      .is_numeral_u64(Bits);
  std::string Text;
  llvm::raw_string_ostream OS(Text);
  if (V.get_sort().fpa_sbits() > 24) {
    double D;
    std::memcpy(&D, &Bits, sizeof D);
    OS << D;
  } else {
    float F;
    uint32_t B = uint32_t(Bits);
    std::memcpy(&F, &B, sizeof F);
    OS << F;
  }
  return Text;
}

/// Peels `Limit` passes off each loop the optimiser left in `F` (a loop
/// whose passes depend on what the cycle computes), nested loops too, so
/// that the encoder follows up to `Limit` passes of each; what remains of
/// a loop is reached only by a run of more passes (Encoder::getEscapes).
/// `Places` gets each remaining loop's head and its line (` at F.bs:6`,
/// its `for`'s); false with `Where` set for a loop that cannot be peeled.
bool peelLoops(llvm::Function &F, unsigned Limit, std::string &Where,
               std::map<const llvm::BasicBlock *, std::string> &Places) {
  // Peeling a loop copies the loops inside it: each round peels one loop
  // not peeled before (a copy has a header of its own), until none is left.
  constexpr unsigned MaxLoops = 64;
  llvm::SmallPtrSet<const llvm::BasicBlock *, 8> Peeled;
  llvm::TargetLibraryInfoImpl TLII(
      llvm::Triple(F.getParent()->getTargetTriple()));
  llvm::TargetLibraryInfo TLI(TLII);
  for (;;) {
    llvm::DominatorTree DT(F);
    llvm::LoopInfo LI(DT);
    llvm::AssumptionCache AC(F);
    llvm::ScalarEvolution SE(F, TLI, AC, DT, LI);
    auto Loops = LI.getLoopsInPreorder();
    auto Next = llvm::find_if(
        Loops, [&](llvm::Loop *L) { return !Peeled.count(L->getHeader()); });
    if (Next == Loops.end())
      return true;
    llvm::DebugLoc Loc = (*Next)->getStartLoc();
    Where = Loc ? Loc->getFilename().str() + ":" + std::to_string(Loc.getLine())
                : F.getName().str();
    if (Peeled.size() == MaxLoops)
      return false;
    // The optimiser's last passes may leave a loop without a preheader;
    // values used after it go through phis of its exits (LCSSA), which
    // peeling extends by the values of each pass peeled.
    llvm::simplifyLoop(*Next, &DT, &LI, &SE, &AC, nullptr,
                       /*PreserveLCSSA=*/false);
    llvm::formLCSSARecursively(**Next, DT, &LI, &SE);
    if (!llvm::canPeel(*Next))
      return false;
    Peeled.insert((*Next)->getHeader());
    Places[(*Next)->getHeader()] = " at " + Where;
    llvm::ValueToValueMapTy VMap;
    llvm::peelLoop(*Next, Limit, &LI, &SE, DT, &AC, /*PreserveLCSSA=*/true,
                   VMap);
  }
}

/// The value the model gives a byte term.
unsigned char byteIn(const z3::model &Model, const z3::expr &Byte) {
  uint64_t V = 0;
  Model.eval(Byte, /*model_completion=*/true).is_numeral_u64(V);
  return static_cast<unsigned char>(V);
}
/// The bytes of `V` (a bit-vector or a float) in the model, little-endian.
std::vector<unsigned char> bytesIn(z3::context &Z, const z3::model &Model,
                                   const z3::expr &V) {
  z3::expr Bits =
      V.get_sort().is_bv() ? V : z3::expr(Z, Z3_mk_fpa_to_ieee_bv(Z, V));
  unsigned W = Bits.get_sort().bv_size();
  if (W % 8)
    Bits = z3::zext(Bits, 8 - W % 8);
  std::vector<unsigned char> Bytes;
  for (unsigned I = 0; I < (W + 7) / 8; ++I)
    Bytes.push_back(byteIn(Model, Bits.extract(8 * I + 7, 8 * I)));
  return Bytes;
}

/// The calls of one cycle that the JIT's recorder keeps, as the model has
/// them (bsc/JIT/Boundary.h): what the counterexample's cycle takes from
/// its record, and what its recording says, so that an exact replay takes
/// the values the counterexample needs.
CycleRecord recordCalls(z3::context &Z, const z3::model &Model,
                        const std::vector<NativeResult> &Natives,
                        const BehaviorLayout &Layout,
                        const size_t ViewSizes[3]) {
  std::vector<RecordedCall> Calls;
  for (const NativeResult &N : Natives) {
    if (!N.Recorded || !Model.eval(N.Reached, true).is_true())
      continue;
    RecordedCall Call;
    Call.Name = Layout.NativeCalls.at(N.Callee).Name;
    if (N.Value)
      Call.Result = bytesIn(Z, Model, *N.Value);
    for (const std::vector<z3::expr> &Ptr : N.Ptrs) {
      Call.Ptrs.emplace_back();
      for (const z3::expr &Byte : Ptr)
        Call.Ptrs.back().push_back(byteIn(Model, Byte));
    }
    Calls.push_back(std::move(Call));
  }
  CycleRecord Record;
  std::string Error; // The calls write nothing of the view: no error.
  encodeCalls(Calls, ViewSizes, Record, Error);
  return Record;
}
/// One cycle, encoded: its input's bytes, the assumptions of it and every
/// cycle before, its checks, its loops that may run further than followed
/// and its calls of registered C++.
struct CycleTerms {
  std::vector<z3::expr> Input;
  z3::expr Assumed;
  std::vector<Check> Checks;
  std::vector<Escape> Escapes;
  std::vector<NativeResult> Natives;
  /// An assertion fails or a loop runs further, the assumptions so far
  /// holding.
  z3::expr bad() const {
    z3::expr Any = Assumed.ctx().bool_val(false);
    for (const Check &Ch : Checks)
      Any = Any || Ch.Fails;
    for (const Escape &Esc : Escapes)
      Any = Any || Esc.Reached;
    return Assumed && Any;
  }
};

/// The solver: Z3's tactic for bit-vectors and floats after its
/// simplifications (equalities solved, unconstrained terms eliminated),
/// which bit-blasts the whole formula for each question: far faster here
/// than the incremental core, for a few questions of one large formula
/// each (bench/README.md, "bsc verify").
z3::solver makeSolver(z3::context &Z, unsigned TimeoutSeconds) {
  z3::tactic Tactic(Z, "simplify");
  for (const char *Next :
       {"propagate-values", "solve-eqs", "elim-uncnstr", "qffpbv"})
    Tactic = Tactic & z3::tactic(Z, Next);
  // A question that takes longer fails: "unknown", never a proof.
  return z3::try_for(Tactic, TimeoutSeconds * 1000).mk_solver();
}

double elapsedSince(std::chrono::steady_clock::time_point Start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - Start)
      .count();
}

/// Asks `Solver` whether `Query` can hold, adding the time to `Seconds`.
z3::check_result ask(z3::solver &Solver, const z3::expr &Query,
                     double &Seconds) {
  auto Start = std::chrono::steady_clock::now();
  Solver.push();
  Solver.add(Query);
  z3::check_result R = Solver.check();
  Seconds += elapsedSince(Start);
  return R;
}

/// The first cycle in which something can go wrong (CycleTerms::bad), with
/// a model; none; or why the solver gave up.
struct FirstBad {
  std::optional<unsigned> Cycle;
  std::optional<z3::model> Model;
  std::optional<std::string> Unknown;
};

/// One question for cycles From + 1 to Upto (the earlier ones had nothing
/// bad); a model's first bad cycle, then earlier cycles asked again until
/// none is: the shortest counterexample.
FirstBad findFirstBad(z3::solver &Solver, const std::vector<CycleTerms> &Cycles,
                      size_t From, size_t Upto, double &Seconds) {
  FirstBad Found;
  while (Upto > From) {
    z3::expr Any = Solver.ctx().bool_val(false);
    for (size_t K = From; K < Upto; ++K)
      Any = Any || Cycles[K].bad();
    z3::check_result R = ask(Solver, Any, Seconds);
    if (R == z3::unknown) {
      Found.Unknown = Solver.reason_unknown();
      Solver.pop();
      return Found;
    }
    if (R == z3::unsat) {
      Solver.pop();
      break;
    }
    z3::model Model = Solver.get_model();
    Solver.pop();
    size_t K = From;
    while (K + 1 < Upto && !Model.eval(Cycles[K].bad(), true).is_true())
      ++K;
    Found.Cycle = K + 1;
    Found.Model = Model;
    Upto = K;
  }
  return Found;
}

/// The first cycle whose assumptions no input meets (with those of the
/// cycles before), if the last cycle's exclude every input.
std::optional<unsigned> firstVacuousCycle(z3::solver &Solver,
                                          const std::vector<CycleTerms> &Cycles,
                                          double &Seconds) {
  auto Meets = [&](size_t K) {
    z3::check_result R = ask(Solver, Cycles[K].Assumed, Seconds);
    Solver.pop();
    return R != z3::unsat;
  };
  if (Meets(Cycles.size() - 1))
    return std::nullopt;
  // Each cycle's assumptions include the earlier ones': bisect.
  size_t Lo = 0, Hi = Cycles.size() - 1; // Hi fails.
  while (Lo < Hi) {
    size_t Mid = (Lo + Hi) / 2;
    if (Meets(Mid))
      Lo = Mid + 1;
    else
      Hi = Mid;
  }
  return Hi + 1;
}
/// The step of k-induction: from any state (the header's cycle number
/// any too), `Depth` cycles in which every assumption and assertion held,
/// then one in which the assumptions hold: can an assertion fail there?
/// True if it cannot (the base case, the first `Depth` cycles from the
/// initial state, was checked before). `Proto` gives the objects' sizes
/// and the header's pointers. False too where the cycle cannot be encoded
/// from any state (the bounded check could from the initial one).
bool provesByInduction(z3::context &Z, Encoder &E, llvm::Function &Cycle,
                       const Memory &Proto, const Objects &O, size_t StateSize,
                       size_t InputSize, unsigned Depth,
                       unsigned TimeoutSeconds, double &Seconds) {
  Memory Mem = Proto;
  auto Fresh = [&](const std::string &Prefix, size_t N) {
    std::vector<z3::expr> Bytes;
    for (size_t I = 0; I < N; ++I)
      Bytes.push_back(E.freshByte(Prefix + std::to_string(I)));
    return Bytes;
  };
  Mem.Bytes[O.State] = Fresh("any.state.", StateSize);
  Mem.Bytes[O.Output] = Fresh("any.output.", Proto.Bytes[O.Output].size());
  z3::expr Base = Z.bv_const("any.cycle", 32);
  z3::solver Solver = makeSolver(Z, TimeoutSeconds);
  for (unsigned K = 0; K <= Depth; ++K) {
    std::string Tag = "k" + std::to_string(K);
    Mem.Bytes[O.Input] = Fresh(Tag + ".input.", InputSize);
    z3::expr Number = Base + Z.bv_val(K + 1, 32);
    for (unsigned I = 0; I < 4; ++I)
      Mem.Bytes[O.State][offsetof(bs_state_header, cycle) + I] =
          Number.extract(8 * I + 7, 8 * I);
    if (!E.encode(Cycle, {Pointer::into(O.State, Z.bv_val(0, 64))}, Mem, Tag))
      return false;
    Solver.add(E.getAssumed() && E.getKnown());
    // A loop that runs further than followed counts as a failure: the
    // step shows that it cannot, as that no assertion fails.
    z3::expr AnyFails = Z.bool_val(false);
    for (const Check &Ch : E.getChecks())
      AnyFails = AnyFails || Ch.Fails;
    for (const Escape &Esc : E.getEscapes())
      AnyFails = AnyFails || Esc.Reached;
    if (K < Depth)
      Solver.add(!AnyFails);
    else
      return ask(Solver, AnyFails, Seconds) == z3::unsat;
  }
  return false;
}
/// Writes the counterexample as a recording: its cycles run in the JIT
/// from `S`'s initial state on the model's `Inputs`, each taking its calls
/// of registered C++ from `Calls` (the model's), so that each line holds
/// what `bsc run --record` writes, the output and tasks the JIT computed
/// (what `bsc timeline` draws) with the calls; the last is the cycle whose
/// assertion fails, as the cycle left them. False after reporting.
bool writeCounterexample(Compilation &C, const LoadedBehavior &L,
                         BehaviorSession &S,
                         const std::vector<std::vector<unsigned char>> &Inputs,
                         const std::vector<CycleRecord> &Calls,
                         const size_t ViewSizes[3], llvm::StringRef Path) {
  std::unique_ptr<llvm::ToolOutputFile> Out =
      openOutput(C.Diags, Path, /*Text=*/true);
  if (!Out)
    return false;
  debug::ValueIO Values(
      [&L](llvm::StringRef Sym) { return L.JIT->lookup(Sym); });
  debug::printJSON(Out->os(), recordHeader(L));
  Out->os() << "\n";
  for (size_t J = 0; J < Inputs.size(); ++J) {
    std::memcpy(S.getInput(), Inputs[J].data(), Inputs[J].size());
    // The failing assertion ends the last cycle; the run says so, not this.
    S.replayCycle(DefaultCycleLimitMs, Calls[J]);
    llvm::json::Value Line = recordCycle(Values, L, S);
    llvm::json::Object &Fields = *Line.getAsObject();
    if (L.InputClass) // As the cycle began.
      Fields["input"] = Values.readClass(*L.InputClass, Inputs[J].data());
    // A cycle that called no C++ (or only pure C++) has no `calls`.
    if (Calls[J].NumCalls)
      Fields["calls"] = callsToJSON(Calls[J], ViewSizes);
    debug::printJSON(Out->os(), Line);
    Out->os() << "\n";
  }
  Out->keep();
  return true;
}
/// The behavior's cycle as the verifier reads it: compiled with
/// AssertionMode::Verify and `Models`, every task and func inlined into
/// the entry (L.EntrySymbol) and optimised as `-O2`, in a module of `Ctx`
/// laid out as the JIT's `L` is (`Layout`). Null after an internal error.
std::unique_ptr<llvm::Module>
emitCycle(Compilation &C, const CallableDecl &Entry, const LoadedBehavior &L,
          const ModelMap &Models, llvm::LLVMContext &Ctx,
          BehaviorLayout &Layout) {
  CodeGenOptions CGOpts;
  CGOpts.BehaviorName = C.Modules.front()->Name;
  CGOpts.Assertions = AssertionMode::Verify;
  CGOpts.Models = &Models;
  CGOpts.OptLevel = 2;
  // Lines, for what the verifier cannot explore.
  CGOpts.DebugInfo = true;
  CGOpts.Sources = &C.SM;
  CGOpts.Exports.emplace();
  if (isCallableFromC(Entry))
    CGOpts.Exports->push_back(&Entry);
  std::unique_ptr<llvm::Module> M =
      emitLLVM(C.Checked, Ctx, L.JIT->getTriple(), L.JIT->getDataLayout(),
               CGOpts, Layout);
  // Both without probes: one layout. Else a bug of bsc's.
  if (Layout.StateSize != L.Layout.StateSize) {
    reportInternalError(llvm::createStringError(
        llvm::inconvertibleErrorCode(),
        "bsc verify: the verifier's state is not the JIT's"));
    return nullptr;
  }
  // One function: every task and func inlined into the entry, whatever
  // the inliner's thresholds say (a behavior's call graph has no cycle).
  for (llvm::Function &F : *M)
    if (!F.isDeclaration() && F.getName() != L.EntrySymbol) {
      F.removeFnAttr(llvm::Attribute::NoInline);
      F.removeFnAttr(llvm::Attribute::OptimizeNone);
      F.addFnAttr(llvm::Attribute::AlwaysInline);
    }
  optimizeModule(*M, nullptr, 2);
  llvm::Function *Cycle = M->getFunction(L.EntrySymbol);
  if (!Cycle || Cycle->isDeclaration()) {
    reportInternalError(llvm::createStringError(
        llvm::inconvertibleErrorCode(),
        "bsc verify: no entry function " + L.EntrySymbol));
    return nullptr;
  }
  return M;
}

/// What the report of a result needs of the check.
struct CheckRun {
  Compilation &C;
  const LoadedBehavior &L;
  BehaviorSession &S;
  BehaviorLayout &Layout;
  const VerifyOptions &Opts;
  z3::context &Z;
  const std::vector<CycleTerms> &Cycles;
  std::map<const llvm::BasicBlock *, std::string> &LoopPlaces;
  const size_t *ViewSizes;
  std::chrono::steady_clock::time_point Start;
  double SolverSeconds;
  unsigned Assertions;
};

/// Reports the first bad cycle `K` of `Model`: the assertion that fails,
/// each cycle's input and calls, and with -o the recording; or the loop
/// that ran further than followed.
VerifyResult reportCounterexample(const CheckRun &R, unsigned K,
                                  const z3::model &Model,
                                  llvm::raw_ostream &OS) {
  auto &[C, L, S, Layout, Opts, Z, Cycles, LoopPlaces, ViewSizes, Start,
         SolverSeconds, Assertions] = R;
  const CycleTerms &At = Cycles[K - 1];
  size_t InputSize = ViewSizes[1];
  // A loop that ran further than followed makes what the model says of
  // the rest of the cycle unknown; else the first check the model fails
  // names the assertion.
  for (const Escape &Esc : At.Escapes)
    if (Model.eval(Esc.Reached, true).is_true()) {
      C.Diags.report(llvm::SMLoc(), diag::err_verify_not_explored)
          << "a loop" +
                 (LoopPlaces.count(Esc.Head) ? LoopPlaces[Esc.Head]
                                             : Esc.Place) +
                 " can run more than " + std::to_string(Opts.LoopLimit) +
                 " passes in cycle " + std::to_string(K) + " (--loop-limit)";
      return VerifyResult::NotExplored;
    }
  const Check *Failed = nullptr;
  for (const Check &Ch : At.Checks)
    if (!Failed && Model.eval(Ch.Fails, true).is_true())
      Failed = &Ch;
  if (!Failed) { // CycleTerms::bad held: a check or an escape did.
    reportInternalError(llvm::createStringError(
        llvm::inconvertibleErrorCode(),
        "bsc verify: the model fails no check of cycle " + std::to_string(K)));
    return VerifyResult::Error;
  }
  const AssertStmt *A = C.Checked.Assertions[Failed->Index].S;
  std::string Message = A->Message ? ": " + A->Message->Value : "";
  // The condition as the JIT's failed assertion spells it.
  std::vector<ExpressionPart> Parts = listExpressionParts(*A->Cond);
  llvm::SMRange Cond = A->Cond->getRange();
  std::string Text =
      !Parts.empty()
          ? Parts.front().Text
          : std::string(Cond.Start.getPointer(),
                        Cond.End.getPointer() - Cond.Start.getPointer());
  C.Diags.report(A->getLoc(), diag::err_verify_counterexample)
      << K << Text << Message;
  // Each cycle's input and the results of registered C++, as the model
  // has them; written into the session's input to read it as the REPL
  // prints values.
  debug::ValueIO Values(
      [&L](llvm::StringRef Sym) { return L.JIT->lookup(Sym); });
  std::vector<std::vector<unsigned char>> InputBytes;
  for (unsigned J = 0; J < K; ++J) {
    InputBytes.emplace_back();
    for (size_t I = 0; I < InputSize; ++I)
      InputBytes.back().push_back(byteIn(Model, Cycles[J].Input[I]));
    if (L.InputClass) {
      std::string Line;
      llvm::raw_string_ostream LS(Line);
      debug::printJSON(
          LS, Values.readClass(*L.InputClass, InputBytes.back().data()));
      C.Diags.report(llvm::SMLoc(), diag::note_verify_input) << J + 1 << Line;
    }
    for (const NativeResult &N : Cycles[J].Natives)
      if (N.Value && Model.eval(N.Reached, true).is_true())
        C.Diags.report(llvm::SMLoc(), diag::note_verify_native)
            << J + 1 << Layout.NativeCalls[N.Callee].Name
            << describeValue(Z, Model, *N.Value);
  }
  if (!Opts.CounterexamplePath.empty()) {
    std::vector<CycleRecord> Calls;
    for (unsigned J = 0; J < K; ++J)
      Calls.push_back(
          recordCalls(Z, Model, Cycles[J].Natives, Layout, ViewSizes));
    if (writeCounterexample(C, L, S, InputBytes, Calls, ViewSizes,
                            Opts.CounterexamplePath))
      OS << "wrote the counterexample to " << Opts.CounterexamplePath << "\n";
  }
  OS << "counterexample: an assertion of " << Assertions
     << " can fail in cycle " << K << " of " << Opts.Cycles << " ("
     << llvm::format("%.2f s; the solver %.2f s", elapsedSince(Start),
                     SolverSeconds)
     << ")\n";
  return VerifyResult::Counterexample;
}

} // namespace

VerifyResult bsc::verifyBehavior(Compilation &C, const VerifyOptions &Opts,
                                 llvm::raw_ostream &OS) {
  auto Start = std::chrono::steady_clock::now();
  const CallableDecl *Entry = findProgramEntry(C, Opts.EntryName);
  if (!Entry)
    return VerifyResult::Error;
  ModelMap Models;
  if (!findModels(C, Models))
    return VerifyResult::Error;
  // The JIT's load: the initial state, the layout, the world's classes;
  // without probes, which keep every local in the state.
  LoadOptions Load = Opts.Load;
  Load.Probes = false;
  auto Loaded = loadBehavior(C, *Entry, Load);
  if (!Loaded) {
    reportInternalError(Loaded.takeError());
    return VerifyResult::Error;
  }
  if (!*Loaded)
    return VerifyResult::Error;
  LoadedBehavior &L = **Loaded;
  auto Session = startSession(C, L);
  if (!Session) {
    reportInternalError(Session.takeError());
    return VerifyResult::Error;
  }
  if (!*Session)
    return VerifyResult::Error;
  BehaviorSession &S = **Session;

  // The cycle as the verifier reads it.
  llvm::LLVMContext Ctx;
  BehaviorLayout Layout;
  std::unique_ptr<llvm::Module> M =
      emitCycle(C, *Entry, L, Models, Ctx, Layout);
  if (!M)
    return VerifyResult::Error;
  llvm::Function *Cycle = M->getFunction(L.EntrySymbol);
  std::string LoopPlace;
  std::map<const llvm::BasicBlock *, std::string> LoopPlaces;
  if (!peelLoops(*Cycle, Opts.LoopLimit, LoopPlace, LoopPlaces)) {
    C.Diags.report(llvm::SMLoc(), diag::err_verify_not_explored)
        << "a loop at " + LoopPlace + " that the verifier cannot unroll";
    return VerifyResult::NotExplored;
  }
  // Deleting a context whose formulas were large takes Z3 minutes (its
  // tables, not the terms); the command ends right after the check, so
  // the context is left to the process's end.
  z3::context &Z = *new z3::context;
  Memory Mem;
  Objects O;
  O.State = Mem.add("the state", bytesOf(Z, S.getState(), L.Layout.StateSize));
  O.Input = Mem.add("input", {});
  O.Output = Mem.add(
      "output", L.OutputClass ? bytesOf(Z, S.getOutput(), L.OutputClass->Size)
                              : std::vector<z3::expr>());
  O.User = Mem.add("the user pointer's object", {});
  Mem.Cells.insert({{O.State, offsetof(bs_state_header, input)},
                    Pointer::into(O.Input, Z.bv_val(0, 64))});
  Mem.Cells.insert({{O.State, offsetof(bs_state_header, output)},
                    Pointer::into(O.Output, Z.bv_val(0, 64))});
  Mem.Cells.insert({{O.State, offsetof(bs_state_header, user)},
                    Pointer::into(O.User, Z.bv_val(0, 64))});
  // The recorder's view (state, input, output), as recordings count it.
  size_t ViewSizes[3];
  S.getViewSizes(ViewSizes);
  size_t InputSize = ViewSizes[1];

  Encoder E(Z, M->getDataLayout(), &Layout.NativeCalls);
  unsigned Assertions = 0;
  for (const Behavior::Assertion &A : C.Checked.Assertions)
    Assertions += !A.S->IsAssume;
  // Every cycle encoded first; then the solver looks for the first in
  // which an assertion can fail or a loop run further than followed.
  std::vector<CycleTerms> Cycles;
  for (unsigned K = 1; K <= Opts.Cycles; ++K) {
    // bs_begin_cycle: the cycle number; a fresh input.
    std::string Tag = "c" + std::to_string(K);
    std::vector<z3::expr> Input;
    for (size_t I = 0; I < InputSize; ++I)
      Input.push_back(E.freshByte(Tag + ".input." + std::to_string(I)));
    Mem.Bytes[O.Input] = Input;
    for (unsigned I = 0; I < 4; ++I)
      Mem.Bytes[O.State][offsetof(bs_state_header, cycle) + I] =
          Z.bv_val((K >> (8 * I)) & 0xff, 8);
    if (!E.encode(*Cycle, {Pointer::into(O.State, Z.bv_val(0, 64))}, Mem,
                  Tag)) {
      C.Diags.report(llvm::SMLoc(), diag::err_verify_not_explored)
          << E.getUnsupported();
      return VerifyResult::NotExplored;
    }
    z3::expr Prefix =
        K == 1 ? E.getAssumed() : (Cycles.back().Assumed && E.getAssumed());
    Cycles.push_back({Input, Prefix.simplify(), E.getChecks(), E.getEscapes(),
                      E.getNativeResults()});
  }
  // Checks from the start and inductions interleaved: cycle 1, then up to
  // 2, 4, ... cycles checked, each followed by the induction over as many
  // (whose base case they are); the first induction that succeeds shows
  // every cycle, and a property that is not inductive is checked for all
  // the cycles asked for.
  z3::solver Solver = makeSolver(Z, Opts.SolverTimeout);
  double SolverSeconds = 0, InductionSeconds = 0;
  std::optional<unsigned> Depth;
  FirstBad Bad;
  for (unsigned Checked = 0, Next = 1; Checked < Opts.Cycles; Next *= 2) {
    unsigned Upto = std::min(Next, Opts.Cycles);
    Bad = findFirstBad(Solver, Cycles, Checked, Upto, SolverSeconds);
    Checked = Upto;
    if (Bad.Cycle || Bad.Unknown)
      break;
    if (Assertions > 0 &&
        provesByInduction(Z, E, *Cycle, Mem, O, L.Layout.StateSize, InputSize,
                          Upto, Opts.SolverTimeout, InductionSeconds)) {
      Depth = Upto;
      break;
    }
  }
  if (Bad.Unknown) {
    C.Diags.report(llvm::SMLoc(), diag::err_verify_not_explored)
        << "the solver gave up: " + *Bad.Unknown;
    return VerifyResult::NotExplored;
  }
  if (Bad.Cycle)
    return reportCounterexample({C, L, S, Layout, Opts, Z, Cycles, LoopPlaces,
                                 ViewSizes, Start, SolverSeconds, Assertions},
                                *Bad.Cycle, *Bad.Model, OS);
  // Assumptions that no input meets prove anything: say so, with the first
  // cycle they exclude every input from.
  if (std::optional<unsigned> K =
          firstVacuousCycle(Solver, Cycles, SolverSeconds)) {
    C.Diags.report(llvm::SMLoc(), diag::err_verify_vacuous) << *K;
    return VerifyResult::NotExplored;
  }
  double Seconds = elapsedSince(Start);
  OS << "verified: " << Assertions
     << (Assertions == 1 ? " assertion holds" : " assertions hold");
  if (Depth)
    OS << " in every cycle (by induction over " << *Depth << ")";
  else
    OS << " for " << Opts.Cycles << (Opts.Cycles == 1 ? " cycle" : " cycles");
  OS << ", every input the assumptions allow ("
     << llvm::format("%.2f s; the solver %.2f s, of which the induction %.2f s",
                     Seconds, SolverSeconds + InductionSeconds,
                     InductionSeconds)
     << ")\n";
  return VerifyResult::Verified;
}
