//===- CycleQuestion.h - `bsc replay --find`: a question of every cycle -*- C++ -*-===//
//
// A retroactive logpoint: an expression of type bool, as the REPL takes it
// (task fields, `input`, `output`), compiled once into the loaded behavior
// and asked after every cycle of every log; or a task's name, which holds
// in the cycles the task ran. Each stretch of cycles in which it holds (of
// at least --lasting cycles) is noted with the values of its parts at the
// stretch's first cycle (the operands `:why` would show, each compiled and
// evaluated on its own after the cycle), or the task's state and yield.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_RUN_CYCLEQUESTION_H
#define BSC_LIB_RUN_CYCLEQUESTION_H

#include "bsc/Run/Line.h"
#include <memory>
#include <string>
#include <vector>

namespace bsc {

class CycleQuestion {
public:
  /// Compiles `Text` and its parts into `L`'s JIT; null after reporting
  /// (`Text` is not a line, or not of type bool).
  static std::unique_ptr<CycleQuestion>
  compile(Compilation &C, LoadedBehavior &L, llvm::StringRef Text,
          unsigned Lasting);
  ~CycleQuestion();

  /// Starts a log: no stretch is open.
  void startLog();
  /// Asks after robot `K`'s cycle in `S`; false after reporting a crash
  /// or a hang of the expression.
  bool ask(Compilation &C, unsigned K, BehaviorSession &S);
  /// Whether the last question asked made a stretch long enough to count.
  bool justFound() const { return Found; }
  /// The log's stretches, a line each (`  cycles 12 to 30 (19 cycles):
  /// x = 1, y = 2`), and how many there are.
  std::string finishLog(unsigned &Stretches);
  llvm::StringRef getText() const { return Text; }

private:
  CycleQuestion(LoadedBehavior &L, std::string Text, unsigned Lasting)
      : L(L), Text(std::move(Text)), Lasting(Lasting),
        Values([&L](llvm::StringRef Sym) { return L.JIT->lookup(Sym); }) {}
  /// Whether the question holds after the cycle `S` ran; std::nullopt
  /// after reporting.
  std::optional<bool> holds(Compilation &C, BehaviorSession &S);
  /// Each part and its value now, a line each.
  std::string describeParts(BehaviorSession &S, unsigned LimitMs);

  LoadedBehavior &L;
  std::string Text;
  unsigned Lasting;
  /// A task's name: its index in the tables.
  std::optional<unsigned> Task;
  debug::ValueIO Values;
  std::unique_ptr<ReplChecker> Checker;
  std::vector<Slot> Variables;
  CompiledLine Whole;
  struct Part {
    std::string Text;
    unsigned Depth;
    CompiledLine Line;
  };
  std::vector<Part> Parts;
  struct Stretch {
    unsigned Robot;
    uint32_t First, Last;
    std::string Parts;
  };
  std::vector<Stretch> Stretches;
  /// Per robot, the stretch it is in (an index into Stretches), if any.
  std::vector<int> Open;
  bool Found = false;
};

} // namespace bsc

#endif
