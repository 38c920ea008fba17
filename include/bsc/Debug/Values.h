//===- Values.h - b-script values in memory as JSON ------------*- C++ -*-===//
//
// The debugger reads and writes the values a behavior keeps in memory: the
// `input` and `output` objects, the parameters and locals in task frames,
// the REPL's variables. Registered classes are shown through their
// registered fields and properties, named as b-script sees them, which is
// what a recording (`bsc run --record`) stores and what a replay writes
// back. A field is read at its offset; a property through its getter and
// setter thunks, which is why ValueIO needs the addresses of the thunks in
// the running JIT.
//
// Floats must survive a round trip bit for bit (a replay compares outputs
// bit-exactly), so numbers are written in the shortest form that reads back
// as the same float, and non-finite values as the strings "NaN",
// "Infinity" and "-Infinity" (JSON has no spelling for them).
//
//===----------------------------------------------------------------------===//
#ifndef BSC_DEBUG_VALUES_H
#define BSC_DEBUG_VALUES_H

#include "bsc/AST/Type.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/JSON.h"
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace bsc {
struct NativeClass;
struct NativeType;
struct NativeFunction;

namespace debug {

/// Called with a leaf's path and value.
using LeafCallback =
    llvm::function_ref<void(llvm::StringRef, const llvm::json::Value &)>;

/// Calls `Leaf` with the path and value of each number, string, bool or
/// null in `V`, after `Path`: `.member` for an object's members, `[i]` for
/// elements (`input.ball.position.x`, `output.wide[3]`).
void forEachJSONLeaf(std::string &Path, const llvm::json::Value &V,
                     LeafCallback Leaf);

/// Reads and writes values in this process's memory (the JIT's).
class ValueIO {
public:
  /// `Resolve` gives the address of a thunk by symbol, null if unknown.
  explicit ValueIO(std::function<void *(llvm::StringRef)> Resolve)
      : Resolve(std::move(Resolve)) {}

  /// A value of b-script type `T` stored as generated code stores it in a
  /// frame or variable (bool as one byte, string as a pointer, a class as
  /// its C++ object).
  llvm::json::Value read(const Type *T, const void *Addr);
  /// An object of a registered class: its fields and properties.
  llvm::json::Value readClass(const NativeClass &C, const void *Obj);

  /// Calls `Leaf` with each number, string, bool or null readClass would
  /// hold, named as forEachJSONLeaf names them after `Path` (`input` ->
  /// `input.ball.position.x`), without building the object (a timeline
  /// reads `input` every cycle, and the objects cost more than the cycle).
  void readLeaves(const NativeClass &C, const void *Obj, std::string &Path,
                  LeafCallback Leaf);

  /// The inverses. `Path` names the value in messages (`input.ball`);
  /// members a JSON object leaves out keep their values.
  llvm::Error write(const Type *T, void *Addr, const llvm::json::Value &V,
                    llvm::StringRef Path);
  llvm::Error writeClass(const NativeClass &C, void *Obj,
                         const llvm::json::Value &V, llvm::StringRef Path);

  /// A replay's fast paths, which build no tree of the object (a replay
  /// does this every cycle, and the trees cost more than the cycle). Both
  /// take checked JSON text of an object in the form recordings have (keys
  /// sorted, ASCII strings without escapes, plain numbers).
  /// writeClass of the text. False where the text is not of that form or
  /// a value does not fit, perhaps after writing some members: writeClass
  /// of the parsed text then does the rest and says what is wrong.
  bool writeClassText(const NativeClass &C, void *Obj, llvm::StringRef Text);
  /// Whether findDifferences(text, readClass(C, Obj)) is empty. False may
  /// also mean that the text is not of that form: ask findDifferences.
  bool matchesClassText(const NativeClass &C, const void *Obj,
                        llvm::StringRef Text);

private:
  /// A field's value; an array field's from dimension `Dim` on (nested
  /// JSON arrays).
  llvm::json::Value readNative(const NativeType &NT, const void *Addr,
                               size_t Dim = 0);
  void readNativeLeaves(const NativeType &NT, const void *Addr,
                        std::string &Path, LeafCallback Leaf, size_t Dim);
  llvm::Error writeNative(const NativeType &NT, void *Addr,
                          const llvm::json::Value &V, llvm::StringRef Path,
                          size_t Dim = 0);
  llvm::json::Value readMember(const NativeClass &C, const NativeFunction &M,
                               const void *Obj);
  llvm::Error writeMember(const NativeClass &C, const NativeFunction &M,
                          void *Obj, const llvm::json::Value &V,
                          llvm::StringRef Path);
  /// The address of a thunk named by a member of the registry (whose
  /// strings live as long as this).
  void *thunk(const std::string &Symbol);
  class TextWalker;
  bool writeObjectText(TextWalker &W, const NativeClass &C, void *Obj);
  bool matchObjectText(TextWalker &W, const NativeClass &C, const void *Obj);

  std::function<void *(llvm::StringRef)> Resolve;
  /// The thunks found so far, by the registry's string of the symbol: a
  /// JIT lookup costs microseconds (hashing the name, a tenth of that), and
  /// a replay calls each getter and setter every cycle.
  llvm::DenseMap<const std::string *, void *> Thunks;
  /// Strings written into values: they must outlive the values.
  std::set<std::string> Strings;
};

/// A float as a JSON value: a number, or "NaN"/"Infinity"/"-Infinity".
llvm::json::Value floatToJSON(double F);
/// The inverse; std::nullopt if `V` is neither.
std::optional<double> floatFromJSON(const llvm::json::Value &V);

/// Writes `V` on one line with keys sorted and numbers that are exact
/// floats in their shortest round-trip form.
void printJSON(llvm::raw_ostream &OS, const llvm::json::Value &V);
std::string toJSONString(const llvm::json::Value &V);
/// A value as the REPL and the driver show it: an enum's value by name,
/// unquoted, as the script writes it; anything else as JSON.
std::string formatValue(const Type *T, const llvm::json::Value &V);

/// The first place where `Got` differs from `Recorded`, with both values as
/// text; numbers compare exactly (as the floats they were written from).
struct Difference {
  std::string Path, Recorded, Got;
};
std::optional<Difference> findDifference(const llvm::json::Value &Recorded,
                                         const llvm::json::Value &Got,
                                         llvm::StringRef Path);
/// Every place where `Got` differs from `Recorded`, in the order of
/// findDifference (keys sorted, array elements by index): a replay names
/// them all, so one run shows everything an edit changed in a cycle.
std::vector<Difference> findDifferences(const llvm::json::Value &Recorded,
                                        const llvm::json::Value &Got,
                                        llvm::StringRef Path);

} // namespace debug
} // namespace bsc

#endif
