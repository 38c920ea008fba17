//===- Boundary.cpp - recording and replaying calls into registered C++ ---===//
//
// The encoding of one call in CycleRecord::Calls (all numbers LEB128):
//   id << 1 | string-result    the site's name (internBoundaryName)
//   length, bytes              the result (a string's characters)
//   count, (length, bytes)...  the mutable pointer arguments after the call
//   count, (gap, length, bytes)...
//                              the runs of the view the call changed; the
//                              view is state, input and output end to end,
//                              and a run starts `gap` bytes after the end
//                              of the one before (the first: after 0)
// A call that changed nothing but its result costs 4 to 8 bytes.
//
//===----------------------------------------------------------------------===//
#include "bsc/JIT/Boundary.h"
#include "bsc/Basic/ByteCoding.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringMap.h"
#include <cstdio>
#include <cstring>
#include <unistd.h>

using namespace bsc;

Boundary *Boundary::Current = nullptr;

const char *const bsc::BoundaryBlockNames[3] = {"state", "input", "output"};

namespace {
/// Call-site names by id, for the whole process: a record made by one
/// session (the REPL's history) is read by the same process only.
struct NameTable {
  std::vector<std::string> Names;
  llvm::StringMap<uint32_t> Ids;
};
NameTable &getNames() {
  static NameTable T;
  return T;
}

void putBytes(std::vector<unsigned char> &Out, const void *P, size_t N) {
  appendULEB(Out, N);
  auto *B = static_cast<const unsigned char *>(P);
  if (N)
    Out.insert(Out.end(), B, B + N);
}

/// One call of a record as it lies in the bytes (nothing copied).
struct CallView {
  uint32_t Id = 0;
  bool IsString = false;
  llvm::ArrayRef<unsigned char> Result;
  llvm::SmallVector<llvm::ArrayRef<unsigned char>, 2> Ptrs;
  /// Runs of the view: the offset in the view (blocks end to end).
  struct Run {
    uint64_t At;
    llvm::ArrayRef<unsigned char> Bytes;
  };
  llvm::SmallVector<Run, 4> Writes;
};

/// Reads the call at `R` (the encoding above); false if the bytes end or
/// are not of that form.
bool readCall(ByteReader &R, CallView &C) {
  C = CallView();
  uint64_t Head = R.uleb();
  C.Id = uint32_t(Head >> 1);
  C.IsString = Head & 1;
  C.Result = R.bytes(R.uleb());
  uint64_t NumPtrs = R.uleb();
  for (uint64_t I = 0; I < NumPtrs && !R.Bad; ++I) {
    llvm::ArrayRef<unsigned char> B = R.bytes(R.uleb());
    if (!R.Bad)
      C.Ptrs.push_back(B);
  }
  uint64_t NumRuns = R.uleb();
  uint64_t At = 0;
  for (uint64_t I = 0; I < NumRuns && !R.Bad; ++I) {
    At += R.uleb();
    uint64_t N = R.uleb();
    llvm::ArrayRef<unsigned char> B = R.bytes(N);
    if (R.Bad || At + N < At) // Past the bytes, or a wrapping offset.
      R.Bad = true;
    else
      C.Writes.push_back({At, B});
    At += N;
  }
  return !R.Bad;
}
} // namespace

llvm::StringRef bsc::getBoundaryName(uint32_t Id) {
  NameTable &T = getNames();
  return Id < T.Names.size() ? llvm::StringRef(T.Names[Id]) : "?";
}

uint32_t bsc::internBoundaryName(llvm::StringRef Name) {
  NameTable &T = getNames();
  auto [It, New] = T.Ids.try_emplace(Name, uint32_t(T.Names.size()));
  if (New)
    T.Names.push_back(Name.str());
  return It->second;
}

Boundary::Boundary(void *State, size_t StateSize, void *Input,
                   size_t InputSize, void *Output, size_t OutputSize) {
  Blocks[0] = {static_cast<unsigned char *>(State), StateSize};
  Blocks[1] = {static_cast<unsigned char *>(Input), InputSize};
  Blocks[2] = {static_cast<unsigned char *>(Output), OutputSize};
  ViewSize = StateSize + InputSize + OutputSize;
}

uint32_t Boundary::internSite(const bs_boundary_site *Site) {
  auto [It, New] = SiteIds.try_emplace(Site, 0);
  if (New)
    It->second = internBoundaryName(Site->name);
  return It->second;
}

void Boundary::startRecording(CycleRecord &R) {
  R.clear();
  if (Blocks[1].Size)
    R.EntryInput.assign(Blocks[1].Ptr, Blocks[1].Ptr + Blocks[1].Size);
  if (Blocks[2].Size)
    R.EntryOutput.assign(Blocks[2].Ptr, Blocks[2].Ptr + Blocks[2].Size);
  M = Mode::Record;
  Recording = &R;
  CallIndex = 0;
}

void Boundary::startReplay(const CycleRecord &R) {
  M = Mode::Replay;
  Replaying = &R;
  ReadAt = 0;
  CallIndex = 0;
  Divergence.clear();
  Strings.clear();
}

std::string Boundary::finish() {
  redirectOutput(false); // A crash in a call left it redirected.
  InAssertion = false;   // A failed assertion stopped the cycle inside.
  if (M == Mode::Replay && Divergence.empty() &&
      ReadAt < Replaying->Calls.size()) {
    ByteReader R{Replaying->Calls.data() + ReadAt,
             Replaying->Calls.data() + Replaying->Calls.size()};
    diverge("the cycle ended after " + std::to_string(CallIndex) +
            " calls into C++; the recorded run went on to call '" +
            getBoundaryName(uint32_t(R.uleb() >> 1)).str() + "'");
  }
  M = Mode::Off;
  Recording = nullptr;
  Replaying = nullptr;
  return std::move(Divergence);
}

bool Boundary::nextCallIs(llvm::StringRef Name) const {
  if (M != Mode::Replay || !Divergence.empty() ||
      ReadAt >= Replaying->Calls.size())
    return false;
  ByteReader R{Replaying->Calls.data() + ReadAt,
           Replaying->Calls.data() + Replaying->Calls.size()};
  return getBoundaryName(uint32_t(R.uleb() >> 1)) == Name;
}

void Boundary::diverge(std::string Why) {
  if (Divergence.empty())
    Divergence = std::move(Why);
}

void Boundary::redirectOutput(bool To) {
  if (To && CaptureFd >= 0 && SavedStdout < 0) {
    std::fflush(stdout);
    SavedStdout = dup(STDOUT_FILENO);
    dup2(CaptureFd, STDOUT_FILENO);
  } else if (!To && SavedStdout >= 0) {
    std::fflush(stdout);
    dup2(SavedStdout, STDOUT_FILENO);
    close(SavedStdout);
    SavedStdout = -1;
  }
}

void Boundary::snapshotView() {
  Before.resize(ViewSize);
  unsigned char *To = Before.data();
  for (const Block &B : Blocks) {
    if (B.Size)
      std::memcpy(To, B.Ptr, B.Size);
    To += B.Size;
  }
}

bool Boundary::recordViewWrites() {
  // Runs of changed bytes, joined across gaps of fewer than 4 unchanged
  // bytes (a gap's own length costs about as much).
  struct Run {
    size_t Start, End;
  };
  llvm::SmallVector<Run, 4> Runs;
  size_t Base = 0;
  for (const Block &B : Blocks) {
    const unsigned char *Old = Before.data() + Base;
    for (size_t I = 0; I < B.Size;) {
      // Eight equal bytes at a time: a call changes few.
      if (I + 8 <= B.Size) {
        uint64_t X, Y;
        std::memcpy(&X, B.Ptr + I, 8);
        std::memcpy(&Y, Old + I, 8);
        if (X == Y) {
          I += 8;
          continue;
        }
      }
      if (B.Ptr[I] == Old[I]) {
        ++I;
        continue;
      }
      size_t At = Base + I;
      if (!Runs.empty() && At - Runs.back().End < 4 &&
          Runs.back().End > Base) // Runs do not cross blocks.
        Runs.back().End = At + 1;
      else
        Runs.push_back({At, At + 1});
      ++I;
    }
    Base += B.Size;
  }
  std::vector<unsigned char> &Out = Recording->Calls;
  appendULEB(Out, Runs.size());
  size_t Prev = 0;
  for (const Run &R : Runs) {
    appendULEB(Out, R.Start - Prev);
    appendULEB(Out, R.End - R.Start);
    // The bytes now, from the blocks.
    size_t Off = R.Start;
    for (const Block &B : Blocks) {
      if (Off < B.Size) {
        Out.insert(Out.end(), B.Ptr + Off, B.Ptr + Off + (R.End - R.Start));
        break;
      }
      Off -= B.Size;
    }
    Prev = R.End;
  }
  return !Runs.empty();
}

bool Boundary::enter(const bs_boundary_site *Site) {
  if (Site->flags & SiteStandard) // Prints only: never kept.
    return M == Mode::Replay && !ReplayCallsStandard;
  if (callsForReal()) { // As outside cycles.
    redirectOutput(true);
    return false;
  }
  switch (M) {
  case Mode::Off:
    redirectOutput(true);
    return false;
  case Mode::Record:
    snapshotView();
    redirectOutput(true);
    return false;
  case Mode::Replay:
    break;
  }
  uint32_t Id = internSite(Site);
  ++CallIndex;
  if (!Divergence.empty())
    return true;
  const std::vector<unsigned char> &Calls = Replaying->Calls;
  if (ReadAt >= Calls.size()) {
    diverge("call " + std::to_string(CallIndex) + " into C++ is '" +
            Site->name + "'; the recorded run made " +
            std::to_string(Replaying->NumCalls) + " in this cycle");
    return true;
  }
  ByteReader R{Calls.data() + ReadAt, Calls.data() + Calls.size()};
  uint32_t Recorded = uint32_t(R.uleb() >> 1);
  if (Recorded != Id)
    diverge("call " + std::to_string(CallIndex) + " into C++ is '" +
            Site->name + "'; the recorded run called '" +
            getBoundaryName(Recorded).str() + "'");
  return true;
}

void Boundary::leave(const bs_boundary_site *Site, void *Result,
                     void *const *Ptrs) {
  bool IsString = Site->flags & SiteResultIsString;
  if (Site->flags & SiteStandard)
    return;
  if (M == Mode::Off || callsForReal()) {
    redirectOutput(false);
    return;
  }
  if (M == Mode::Record) {
    redirectOutput(false);
    std::vector<unsigned char> &Out = Recording->Calls;
    size_t Start = Out.size();
    appendULEB(Out, uint64_t(internSite(Site)) << 1 | (IsString ? 1 : 0));
    if (IsString) {
      const char *S = Result ? *static_cast<const char *const *>(Result)
                             : nullptr;
      putBytes(Out, S, S ? std::strlen(S) : 0);
    } else {
      putBytes(Out, Result, Result ? Site->result_size : 0);
    }
    appendULEB(Out, Ptrs ? Site->num_ptrs : 0);
    for (uint32_t I = 0; Ptrs && I < Site->num_ptrs; ++I)
      putBytes(Out, Ptrs[I], Site->ptr_sizes[I]);
    if (!recordViewWrites() && (Site->flags & SitePseudo)) {
      Out.resize(Start); // A hook that wrote nothing: nothing to replay.
      return;
    }
    ++Recording->NumCalls;
    return;
  }
  // Replay: the effects as recorded.
  if (!Divergence.empty()) {
    if (Result)
      std::memset(Result, 0, Site->result_size);
    return;
  }
  const std::vector<unsigned char> &Calls = Replaying->Calls;
  ByteReader R{Calls.data() + ReadAt, Calls.data() + Calls.size()};
  CallView C; // Its id was checked by enter.
  bool Fits = readCall(R, C) &&
              (IsString || C.Result.size() == (Result ? Site->result_size
                                                      : C.Result.size())) &&
              C.Ptrs.size() == (Ptrs ? Site->num_ptrs : 0);
  for (size_t I = 0; Fits && I < C.Ptrs.size(); ++I)
    Fits = C.Ptrs[I].size() == Site->ptr_sizes[I];
  // Each run lies in one block.
  llvm::SmallVector<unsigned char *, 4> Into;
  for (const CallView::Run &W : C.Writes) {
    uint64_t Off = W.At;
    unsigned char *To = nullptr;
    for (const Block &B : Blocks) {
      if (Off < B.Size) {
        To = Off + W.Bytes.size() <= B.Size ? B.Ptr + Off : nullptr;
        break;
      }
      Off -= B.Size;
    }
    Fits &= To != nullptr;
    Into.push_back(To);
  }
  R.Bad = !Fits;
  if (Fits) {
    if (Result && IsString) {
      Strings.emplace_back(reinterpret_cast<const char *>(C.Result.data()),
                           C.Result.size());
      const char *S = Strings.back().c_str();
      std::memcpy(Result, &S, sizeof S);
    } else if (Result && !C.Result.empty()) {
      std::memcpy(Result, C.Result.data(), C.Result.size());
    }
    for (size_t I = 0; I < C.Ptrs.size(); ++I)
      std::memcpy(Ptrs[I], C.Ptrs[I].data(), C.Ptrs[I].size());
    for (size_t I = 0; I < C.Writes.size(); ++I)
      if (!C.Writes[I].Bytes.empty())
        std::memcpy(Into[I], C.Writes[I].Bytes.data(),
                    C.Writes[I].Bytes.size());
  }
  if (R.Bad) {
    diverge("call " + std::to_string(CallIndex) + " into C++ ('" +
            Site->name + "') does not fit its record (a result or argument "
            "of another size: the record is of another behavior)");
    if (Result)
      std::memset(Result, 0, Site->result_size);
    return;
  }
  ReadAt = R.P - Calls.data();
}

//===----------------------------------------------------------------------===//
// Decoding and encoding whole records (recordings)
//===----------------------------------------------------------------------===//

std::vector<RecordedCall> bsc::decodeCalls(const CycleRecord &Rec,
                                           const size_t BlockSizes[3]) {
  std::vector<RecordedCall> Calls;
  ByteReader R{Rec.Calls.data(), Rec.Calls.data() + Rec.Calls.size()};
  CallView V;
  while (R.P < R.End && readCall(R, V)) {
    RecordedCall C;
    C.Name = getBoundaryName(V.Id).str();
    C.ResultIsString = V.IsString;
    C.Result.assign(V.Result.begin(), V.Result.end());
    for (llvm::ArrayRef<unsigned char> P : V.Ptrs)
      C.Ptrs.emplace_back(P.begin(), P.end());
    for (const CallView::Run &W : V.Writes) {
      uint64_t Off = W.At;
      unsigned Block = 0;
      while (Block < 2 && Off >= BlockSizes[Block])
        Off -= BlockSizes[Block++];
      C.Writes.push_back({Block, Off, {W.Bytes.begin(), W.Bytes.end()}});
    }
    Calls.push_back(std::move(C));
  }
  return Calls;
}

bool bsc::encodeCalls(llvm::ArrayRef<RecordedCall> Calls,
                      const size_t BlockSizes[3], CycleRecord &Rec,
                      std::string &Error) {
  Rec.Calls.clear();
  Rec.NumCalls = 0;
  std::vector<unsigned char> &Out = Rec.Calls;
  for (const RecordedCall &C : Calls) {
    appendULEB(Out, uint64_t(internBoundaryName(C.Name)) << 1 |
                     (C.ResultIsString ? 1 : 0));
    putBytes(Out, C.Result.data(), C.Result.size());
    appendULEB(Out, C.Ptrs.size());
    for (const std::vector<unsigned char> &P : C.Ptrs)
      putBytes(Out, P.data(), P.size());
    appendULEB(Out, C.Writes.size());
    uint64_t Prev = 0;
    for (const RecordedCall::Write &W : C.Writes) {
      if (W.Block > 2 || W.Offset + W.Bytes.size() > BlockSizes[W.Block]) {
        Error = "a write of " + std::to_string(W.Bytes.size()) +
                " bytes at " + BoundaryBlockNames[std::min(W.Block, 2u)] +
                "+" + std::to_string(W.Offset) + " is outside the " +
                (W.Block > 2 ? "view" : BoundaryBlockNames[W.Block]);
        return false;
      }
      uint64_t At = W.Offset;
      for (unsigned B = 0; B < W.Block; ++B)
        At += BlockSizes[B];
      if (At < Prev) {
        Error = "the writes of a call are not in the order of the view";
        return false;
      }
      appendULEB(Out, At - Prev);
      putBytes(Out, W.Bytes.data(), W.Bytes.size());
      Prev = At + W.Bytes.size();
    }
    ++Rec.NumCalls;
  }
  return true;
}

bool bsc::translateCalls(
    llvm::ArrayRef<unsigned char> In,
    llvm::function_ref<std::optional<uint32_t>(uint32_t)> MapId,
    const size_t From[3], const size_t To[3], std::vector<unsigned char> &Out,
    unsigned &NumCalls, std::string &Error,
    llvm::function_ref<void(unsigned, uint64_t, llvm::ArrayRef<unsigned char>)>
        OnWrite) {
  ByteReader R{In.data(), In.data() + In.size()};
  CallView V;
  while (R.P < R.End) {
    if (!readCall(R, V)) {
      Error = "call " + std::to_string(NumCalls + 1) + " is damaged";
      return false;
    }
    std::optional<uint32_t> Id = MapId(V.Id);
    if (!Id) {
      Error = "call " + std::to_string(NumCalls + 1) + " is of site " +
              std::to_string(V.Id) + ", which the log does not name";
      return false;
    }
    appendULEB(Out, uint64_t(*Id) << 1 | (V.IsString ? 1 : 0));
    putBytes(Out, V.Result.data(), V.Result.size());
    appendULEB(Out, V.Ptrs.size());
    for (llvm::ArrayRef<unsigned char> P : V.Ptrs)
      putBytes(Out, P.data(), P.size());
    appendULEB(Out, V.Writes.size());
    uint64_t Prev = 0;
    for (const CallView::Run &W : V.Writes) {
      uint64_t Off = W.At;
      unsigned Block = 0;
      while (Block < 2 && Off >= From[Block])
        Off -= From[Block++];
      if (Off + W.Bytes.size() > From[Block] ||
          Off + W.Bytes.size() > To[Block]) {
        Error = "call " + std::to_string(NumCalls + 1) + " writes " +
                std::to_string(W.Bytes.size()) + " bytes at " +
                BoundaryBlockNames[Block] + "+" + std::to_string(Off) +
                ", outside the " + BoundaryBlockNames[Block];
        return false;
      }
      if (OnWrite)
        OnWrite(Block, Off, W.Bytes);
      uint64_t At = Off;
      for (unsigned B = 0; B < Block; ++B)
        At += To[B];
      appendULEB(Out, At - Prev);
      putBytes(Out, W.Bytes.data(), W.Bytes.size());
      Prev = At + W.Bytes.size();
    }
    ++NumCalls;
  }
  return true;
}

//===----------------------------------------------------------------------===//
// Records as recordings spell them (docs/repl.md "Recordings")
//===----------------------------------------------------------------------===//

static std::string toHex(llvm::ArrayRef<unsigned char> Bytes) {
  return llvm::toHex(Bytes, /*LowerCase=*/true);
}

llvm::json::Value bsc::callsToJSON(const CycleRecord &Record,
                                   const size_t Sizes[3]) {
  llvm::json::Array Calls;
  for (const RecordedCall &C : decodeCalls(Record, Sizes)) {
    llvm::json::Object Call{{"fn", C.Name}};
    llvm::StringRef Text(reinterpret_cast<const char *>(C.Result.data()),
                         C.Result.size());
    if (C.ResultIsString && llvm::json::isUTF8(Text)) {
      Call["text"] = Text.str();
    } else if (C.ResultIsString) {
      Call["string"] = toHex(C.Result);
    } else if (!C.Result.empty()) {
      Call["result"] = toHex(C.Result);
    }
    if (!C.Ptrs.empty()) {
      llvm::json::Array Args;
      for (const std::vector<unsigned char> &P : C.Ptrs)
        Args.push_back(toHex(P));
      Call["args"] = std::move(Args);
    }
    if (!C.Writes.empty()) {
      llvm::json::Array Writes;
      for (const RecordedCall::Write &W : C.Writes)
        Writes.push_back(llvm::json::Array{BoundaryBlockNames[W.Block],
                                           int64_t(W.Offset),
                                           toHex(W.Bytes)});
      Call["writes"] = std::move(Writes);
    }
    Calls.push_back(std::move(Call));
  }
  return Calls;
}

/// Bytes from hex text; false if it is not.
static bool fromHex(llvm::StringRef Hex, std::vector<unsigned char> &Into) {
  std::string Bytes;
  if (Hex.size() % 2 || !llvm::tryGetFromHex(Hex, Bytes))
    return false;
  Into.assign(Bytes.begin(), Bytes.end());
  return true;
}

bool bsc::callsFromJSON(const llvm::json::Value &Value,
                        const size_t Sizes[3], CycleRecord &Into,
                        std::string &Error) {
  const llvm::json::Array *Array = Value.getAsArray();
  if (!Array) {
    Error = "'calls' must be an array of calls";
    return false;
  }
  std::vector<RecordedCall> Calls;
  for (const llvm::json::Value &V : *Array) {
    std::string Where = "call " + std::to_string(Calls.size() + 1);
    const llvm::json::Object *O = V.getAsObject();
    std::optional<llvm::StringRef> Fn = O ? O->getString("fn") : std::nullopt;
    if (!Fn) {
      Error = Where + " must be an object with the function's name in 'fn'";
      return false;
    }
    RecordedCall C;
    C.Name = Fn->str();
    Where += " ('" + C.Name + "')";
    for (const auto &[Key, Member] : *O) {
      std::optional<llvm::StringRef> Hex = Member.getAsString();
      if (Key == "fn") {
        continue;
      } else if (Key == "text" && Hex) {
        C.ResultIsString = true;
        C.Result.assign(Hex->begin(), Hex->end());
      } else if ((Key == "result" || Key == "string") && Hex &&
                 fromHex(*Hex, C.Result)) {
        C.ResultIsString = Key == "string";
      } else if (Key == "args" && Member.getAsArray()) {
        for (const llvm::json::Value &A : *Member.getAsArray()) {
          C.Ptrs.emplace_back();
          std::optional<llvm::StringRef> H = A.getAsString();
          if (!H || !fromHex(*H, C.Ptrs.back())) {
            Error = Where + ": 'args' must hold hex strings";
            return false;
          }
        }
      } else if (Key == "writes" && Member.getAsArray()) {
        for (const llvm::json::Value &W : *Member.getAsArray()) {
          const llvm::json::Array *Triple = W.getAsArray();
          std::optional<llvm::StringRef> Block =
              Triple && Triple->size() == 3 ? (*Triple)[0].getAsString()
                                            : std::nullopt;
          std::optional<int64_t> Offset =
              Block ? (*Triple)[1].getAsInteger() : std::nullopt;
          std::optional<llvm::StringRef> Bytes =
              Offset ? (*Triple)[2].getAsString() : std::nullopt;
          RecordedCall::Write Write{3, 0, {}};
          for (unsigned B = 0; Block && B < 3; ++B)
            if (*Block == BoundaryBlockNames[B])
              Write.Block = B;
          if (!Bytes || Write.Block > 2 || *Offset < 0 ||
              !fromHex(*Bytes, Write.Bytes)) {
            Error = Where + ": each of 'writes' must be [\"state\", \"input\" "
                            "or \"output\", an offset, hex bytes]";
            return false;
          }
          Write.Offset = uint64_t(*Offset);
          C.Writes.push_back(std::move(Write));
        }
      } else {
        Error = Where + ": unknown or malformed member '" + Key.str() +
                "'; a call has 'fn', 'result' or 'text', 'args' and "
                "'writes'";
        return false;
      }
    }
    Calls.push_back(std::move(C));
  }
  if (!encodeCalls(Calls, Sizes, Into, Error))
    return false;
  return true;
}

//===----------------------------------------------------------------------===//
// What generated code calls
//===----------------------------------------------------------------------===//

int32_t bs_boundary_enter(const bs_boundary_site *Site) {
  Boundary *B = Boundary::Current;
  return B && B->enter(Site) ? 1 : 0;
}

void bs_boundary_leave(const bs_boundary_site *Site, void *Result,
                       void *const *Ptrs) {
  if (Boundary *B = Boundary::Current)
    B->leave(Site, Result, Ptrs);
}

void bs_boundary_assertion(int32_t Inside) {
  if (Boundary *B = Boundary::Current)
    B->setInAssertion(Inside != 0);
}
