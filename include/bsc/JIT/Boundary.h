//===- Boundary.h - what a behavior observed of its calls into C++ -*- C++ -*-===//
//
// A behavior's cycle is a function of its state and its input, except for
// its calls into registered C++, which may return random numbers, read a
// clock, print, or write the behavior's memory through pointers they kept
// (a simulation stepped by the behavior writes the next `input`). To
// re-run a cycle exactly (the REPL's time travel, an exact replay of a
// recording), the JIT's code keeps what each such call did as the behavior
// could see it, and a re-run takes the call from that record instead of
// calling the C++ again.
//
// In the JIT every call of registered C++ that is not registered `pure`
// goes through a wrapper (CodeGenOptions::Boundary) that calls
// bs_boundary_enter and bs_boundary_leave around the thunk with a
// BoundarySite that says what the call can write: its result and its
// mutable pointer arguments (the object of a non-const method, `T&`
// arguments, a class result's storage). Besides those, a call may write
// anything of the behavior's view: its state, `input` and `output`; the
// difference of the view before and after the call is kept too.
//
// A CycleRecord holds one cycle's calls, encoded compactly (Boundary.cpp):
// per call its site's name, its result, its pointer arguments' bytes after
// the call and the runs of view bytes the call changed. Recording happens
// while a session's cycle runs with a record to fill; replaying when it
// runs from one. Outside cycles (a REPL line, a probe) calls go to the C++
// unrecorded.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_JIT_BOUNDARY_H
#define BSC_JIT_BOUNDARY_H

#include "bsc/CodeGen/CodeGen.h"
#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/JSON.h"
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

extern "C" {
/// What generated code tells the recorder about one wrapper (one thunk).
/// Laid out as CodeGen emits it (CGNative.cpp, getBoundaryWrapper).
struct bs_boundary_site {
  const char *name;          ///< `Module::function`, `Class.method`, ...
  uint32_t flags;            ///< BoundarySiteFlags.
  uint32_t result_size;      ///< Bytes of the result slot; 0: void.
  uint32_t num_ptrs;         ///< Mutable pointer arguments.
  const uint32_t *ptr_sizes; ///< Their sizes in bytes.
  uint32_t index;            ///< In the module's order (flight tables).
};
/// Before the thunk: nonzero if the call is to be taken from the record
/// (the thunk is then not called).
int32_t bs_boundary_enter(const bs_boundary_site *Site);
/// After the thunk (or instead of it): records or applies the call's
/// effects. `Result` is the result slot; `Ptrs` the mutable pointers.
void bs_boundary_leave(const bs_boundary_site *Site, void *Result,
                       void *const *Ptrs);
/// Around the evaluation of an assertion's condition: 1 before, 0 after.
void bs_boundary_assertion(int32_t Inside);
}

namespace bsc {

// The site's flags: BoundarySiteFlags (bsc/CodeGen/CodeGen.h).

/// The calls of one cycle, as kept by the recorder.
struct CycleRecord {
  /// The input when the entry was called (after the world's begin hook):
  /// what the cycle's first statement saw.
  std::vector<unsigned char> EntryInput;
  /// The output when the entry was called: what the cycle before left, as
  /// the robot's software (or the world's begin hook) left it.
  std::vector<unsigned char> EntryOutput;
  /// The encoded calls (Boundary.cpp) and their number.
  std::vector<unsigned char> Calls;
  unsigned NumCalls = 0;
  void clear() {
    EntryInput.clear();
    EntryOutput.clear();
    Calls.clear();
    NumCalls = 0;
  }
};

/// One call of a record, decoded (for recordings and messages).
struct RecordedCall {
  std::string Name;
  std::vector<unsigned char> Result; ///< A string's characters, no NUL.
  bool ResultIsString = false;
  std::vector<std::vector<unsigned char>> Ptrs;
  /// Changed runs of the view: (block, offset, bytes); block 0 is the
  /// state, 1 `input`, 2 `output`.
  struct Write {
    unsigned Block;
    uint64_t Offset;
    std::vector<unsigned char> Bytes;
  };
  std::vector<Write> Writes;
};

/// The names of the view's blocks, as recordings spell them.
extern const char *const BoundaryBlockNames[3];

/// Decodes every call of `R` (given the sizes of the view's blocks, for
/// the block of each write).
std::vector<RecordedCall> decodeCalls(const CycleRecord &R,
                                      const size_t BlockSizes[3]);
/// Encodes `Calls` into `R` (replacing its calls); false with `Error` set
/// if a write falls outside the view.
bool encodeCalls(llvm::ArrayRef<RecordedCall> Calls,
                 const size_t BlockSizes[3], CycleRecord &R,
                 std::string &Error);

/// Re-encodes the calls `In` (the encoding of CycleRecord::Calls) from one
/// numbering of call sites and one view to another, for logs that number
/// their sites themselves (bsc/Run/BinaryLog.h): each call's site through
/// `MapId` (nullopt: a site the log does not name), each write from the
/// view of blocks `From` to that of `To` (it must lie in its block in
/// both), telling `OnWrite` (if given) of each. Appends to `Out` and
/// counts the calls into `NumCalls`; false
/// with `Error` set on bytes that are not calls or do not fit.
bool translateCalls(llvm::ArrayRef<unsigned char> In,
                    llvm::function_ref<std::optional<uint32_t>(uint32_t)> MapId,
                    const size_t From[3], const size_t To[3],
                    std::vector<unsigned char> &Out, unsigned &NumCalls,
                    std::string &Error,
                    llvm::function_ref<void(unsigned Block, uint64_t Offset,
                                            llvm::ArrayRef<unsigned char>)>
                        OnWrite);

/// `R`'s calls as a recording's `calls` (docs/repl.md "Recordings"): per
/// call `fn`, its result as hex (`result`) or a string's `text`, the
/// bytes of the arguments it may write (`args`) and the runs of the view
/// it changed (`writes`: [block, offset, hex]).
llvm::json::Value callsToJSON(const CycleRecord &R, const size_t BlockSizes[3]);
/// The inverse, into `Into`'s calls; false with `Error` set for a value
/// that is not of that form or writes outside the view.
bool callsFromJSON(const llvm::json::Value &Calls, const size_t BlockSizes[3],
                   CycleRecord &Into, std::string &Error);

/// The recorder of one session: its view (state, input, output) and what
/// the cycle running now does with calls.
class Boundary {
public:
  Boundary(void *State, size_t StateSize, void *Input, size_t InputSize,
           void *Output, size_t OutputSize);

  /// The calls of the cycle about to run go into `R` (cleared first).
  void startRecording(CycleRecord &R);
  /// The cycle about to run takes its calls from `R`, in order.
  void startReplay(const CycleRecord &R);
  /// What the running cycle's print-capture redirects C++'s standard
  /// output to (-1: nothing).
  void setCaptureFd(int Fd) { CaptureFd = Fd; }
  /// Whether a replay makes the calls of assertions' conditions for real
  /// instead of taking them from the record: a robot's object that leaves
  /// its assertions out (the default) never made them.
  void setReplayMakesAssertionCalls(bool On) { ReplayMakesAssertionCalls = On; }
  /// bs_boundary_assertion: whether an assertion's condition runs now.
  void setInAssertion(bool On) { InAssertion = On; }
  /// Whether a replay calls the standard `io` module for real: a replay of
  /// a recording prints what the behavior prints, the REPL's re-runs print
  /// nothing again.
  void setReplayCallsStandard(bool On) { ReplayCallsStandard = On; }
  /// Ends the cycle's recording or replay. In a replay, returns why the
  /// cycle parted from its record (a call it did not make, or made
  /// differently), or empty if it followed it.
  std::string finish();
  /// Whether a cycle is being recorded or replayed now.
  bool isActive() const { return M != Mode::Off; }
  bool isReplaying() const { return M == Mode::Replay; }

  /// A call made outside generated code, by the session itself (the
  /// world's end hook): as a wrapper would report it, without a result or
  /// pointers. Returns true if the call is to be taken from the record.
  bool enterPseudo(const bs_boundary_site &Site) { return enter(&Site); }
  void leavePseudo(const bs_boundary_site &Site) {
    leave(&Site, nullptr, nullptr);
  }

  /// In a replay, whether the record's next call is the site named `Name`
  /// (a world's end hook recorded where this session has no world).
  bool nextCallIs(llvm::StringRef Name) const;

  /// The recorder of the session whose cycle runs now (null outside).
  static Boundary *Current;

  /// What bs_boundary_enter and bs_boundary_leave do with this recorder:
  /// enter says whether the call is taken from the record (the thunk is
  /// then not called); leave records the call or applies its recorded
  /// effects to `Result`, `Ptrs` and the view.
  bool enter(const bs_boundary_site *Site);
  void leave(const bs_boundary_site *Site, void *Result, void *const *Ptrs);

private:
  enum class Mode { Off, Record, Replay };
  uint32_t internSite(const bs_boundary_site *Site);
  void snapshotView();
  /// Appends the view's changed runs to the record; false if none.
  bool recordViewWrites();
  /// In a replay, reports the first way the run parts from the record.
  void diverge(std::string Why);
  void redirectOutput(bool To);

  struct Block {
    unsigned char *Ptr;
    size_t Size;
  };
  Block Blocks[3];
  size_t ViewSize = 0;
  Mode M = Mode::Off;
  CycleRecord *Recording = nullptr;
  const CycleRecord *Replaying = nullptr;
  size_t ReadAt = 0;   ///< Replay: the next call's byte in Replaying->Calls.
  unsigned CallIndex = 0; ///< Calls so far in this cycle.
  std::string Divergence;
  /// The view before the running call (Record).
  std::vector<unsigned char> Before;
  llvm::DenseMap<const bs_boundary_site *, uint32_t> SiteIds;
  /// Replayed strings, kept until the record is done with.
  std::deque<std::string> Strings;
  int CaptureFd = -1, SavedStdout = -1;
  bool ReplayCallsStandard = false;
  bool ReplayMakesAssertionCalls = false, InAssertion = false;
  /// In a replay, a call made for real (an assertion's) is running.
  bool callsForReal() const {
    return M == Mode::Replay && InAssertion && ReplayMakesAssertionCalls;
  }
};

/// The name of call-site id `Id` (ids are the same in the whole process).
llvm::StringRef getBoundaryName(uint32_t Id);
/// The id of `Name`, added if new.
uint32_t internBoundaryName(llvm::StringRef Name);

} // namespace bsc

#endif
