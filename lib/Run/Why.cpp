//===- Why.cpp - `:why`: the conditions a task evaluated ------------------===//
//
// The REPL's `:why [TASK]` and `bsc replay`'s report of a failure show the
// way each task went in the last cycle: every `if` and `for` condition it
// evaluated (or a func it called did), with the values of the condition's
// sub-expressions as the cycle computed them, and the yield its call
// stopped at or how it ended.
//
// The values come from the log the JIT's code writes while the cycle runs
// (CodeGenOptions::Explain, lib/CodeGen/CGExplain.cpp), read here with the
// table of sites in the layout; nothing is evaluated again. The log is
// the cycle's records in the order the conditions began, with a record at
// the start and at the end of every task call: a condition belongs to the
// task call open around it. A condition evaluated many times (a loop's)
// is shown once, with its count and the values of its last evaluation.
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/Run.h"
#include "llvm/ADT/StringExtras.h"
#include <cstring>
#include <functional>
#include <map>

using namespace bsc;

namespace {

/// What the log says of one task (or of the entry func) in the cycle.
struct TaskLog {
  unsigned Calls = 0;
  /// Its conditions: site number and record, in the order they began.
  std::vector<std::pair<unsigned, const uint8_t *>> Conditions;
  /// How its last call ended (from its end record).
  std::optional<debug::Activation> End;
  /// Its last call has no end record: the cycle stopped in it, or the
  /// log was full first.
  bool Open = false;
};

/// The log of one cycle, sorted by task: the layout's task index, -1 for
/// conditions outside every task (a func entry's).
struct CycleLog {
  std::map<int, TaskLog> Tasks;
  uint32_t Overflow = 0;
};

template <typename T> T readWord(const uint8_t *P) {
  T V;
  std::memcpy(&V, P, sizeof(T));
  return V;
}

CycleLog decodeLog(const BehaviorLayout &Layout, const ExplainLogHeader &H,
                   const uint8_t *Records) {
  CycleLog Log;
  Log.Overflow = H.Overflow;
  const std::vector<ExplainSite> &Sites = Layout.ExplainSites;
  auto TaskIndex = [&](const CallableDecl *D) {
    for (size_t I = 0; I < Layout.Tasks.size(); ++I)
      if (Layout.Tasks[I].Decl == D)
        return int(I);
    return -1;
  };
  std::vector<int> Open; // The task calls open here, innermost last.
  uint32_t Used = std::min(H.Used, ExplainLogCapacity);
  for (uint32_t Off = 0; Off + ExplainRecordHeaderSize <= Used;) {
    const uint8_t *R = Records + Off;
    uint32_t Number = readWord<uint32_t>(R);
    if (Number == 0 || Number > Sites.size())
      break; // Not a record: nothing follows that can be read.
    const ExplainSite &Site = Sites[Number - 1];
    if (Off + Site.RecordSize > Used)
      break;
    Off += Site.RecordSize;
    switch (Site.Kind) {
    case ExplainSite::TaskStart: {
      int T = TaskIndex(Site.In);
      Open.push_back(T);
      TaskLog &TL = Log.Tasks[T];
      ++TL.Calls;
      TL.Open = true;
      break;
    }
    case ExplainSite::TaskEnd: {
      int T = TaskIndex(Site.In);
      while (!Open.empty() && Open.back() != T)
        Open.pop_back();
      if (!Open.empty())
        Open.pop_back();
      TaskLog &TL = Log.Tasks[T];
      TL.Open = false;
      TL.End = debug::Activation{unsigned(T),
                                 readWord<uint32_t>(R + ExplainTaskEndResume),
                                 readWord<int32_t>(R + ExplainTaskEndState)};
      break;
    }
    case ExplainSite::Assert: // Never in the log.
      break;
    case ExplainSite::If:
    case ExplainSite::For:
      Log.Tasks[Open.empty() ? -1 : Open.back()].Conditions.push_back(
          {Number, R});
      break;
    }
  }
  return Log;
}

/// The name the script gives a TaskState value, if it has one.
std::optional<std::string> getStateName(int32_t V) {
  switch (V) {
  case 1:
    return "running";
  case 0:
    return "done";
  case -1:
    return "failure";
  default:
    return std::nullopt;
  }
}

/// A TaskState value as the script names it, or its number.
std::string describeTaskState(int32_t V) {
  return getStateName(V).value_or(std::to_string(V));
}

/// `running`, `failure`, `Done::kicked`, `state 3`: the state a call left
/// at the yield it stopped at (named when the yield names it).
std::string describeState(const debug::DebugTables::Task &T,
                          const debug::Activation &A) {
  if (A.Resume > 0 && A.Resume <= T.YieldStates.size() &&
      !T.YieldStates[A.Resume - 1].empty())
    return T.YieldStates[A.Resume - 1];
  return getStateName(A.State).value_or("state " + std::to_string(A.State));
}

/// Prints what `:why` shows of one cycle's log: per task its conditions,
/// each with its operands, and where the call ended.
class WhyPrinter {
public:
  WhyPrinter(const LoadedBehavior &L, debug::ValueIO &Values, CycleLog &Log,
             llvm::raw_ostream &OS)
      : L(L), Values(Values), Log(Log), OS(OS) {}

  /// The entry func is -1; tasks by their index.
  std::string taskName(int T) const {
    return T < 0 ? L.Entry->getName().Name.str() : L.Tables.Tasks[T].ShortName;
  }

  void printTask(int T, const TaskLog &TL) {
    OS << "  " << taskName(T);
    if (TL.Calls > 1)
      OS << " (called " << TL.Calls << " times; the conditions of all calls)";
    OS << ":\n";
    // Each condition once, in the order of first evaluation.
    std::vector<unsigned> Order;
    std::map<unsigned, std::vector<const uint8_t *>> BySite;
    for (auto [Number, Record] : TL.Conditions) {
      std::vector<const uint8_t *> &Rs = BySite[Number];
      if (Rs.empty())
        Order.push_back(Number);
      Rs.push_back(Record);
    }
    if (Order.empty())
      OS << "    no condition evaluated\n";
    const CallableDecl *Owner = T < 0 ? L.Entry : L.Layout.Tasks[T].Decl;
    for (unsigned Number : Order)
      printCondition(Owner, Number, BySite[Number]);
    if (T >= 0)
      printCallEnd(L.Tables.Tasks[T], TL);
  }

private:
  static bool isTrue(const ExplainSite &Site, const uint8_t *Record) {
    return Record[Site.Operands[0].Offset] != 0;
  }

  std::string formatOperand(const ExplainSite::Operand &O,
                            const uint8_t *Record) {
    const uint8_t *V = Record + O.Offset;
    if (O.Ty->isTaskState())
      return describeTaskState(readWord<int32_t>(V));
    return debug::formatValue(O.Ty, Values.read(O.Ty, V));
  }

  /// One condition: its line (and the func it is in, if not `Owner`), its
  /// last value and each operand that ran, under the operand that encloses
  /// it.
  void printCondition(const CallableDecl *Owner, unsigned Number,
                      llvm::ArrayRef<const uint8_t *> Records) {
    const ExplainSite &Site = L.Layout.ExplainSites[Number - 1];
    const uint8_t *Last = Records.back();
    OS << "    " << Site.File << ":" << Site.Line;
    if (Site.In != Owner)
      OS << " (" << Site.In->getName().Name << ")";
    OS << ": " << (Site.Kind == ExplainSite::For ? "for" : "if") << " ("
       << Site.Operands[0].Text << ") is "
       << (isTrue(Site, Last) ? "true" : "false");
    if (Records.size() > 1)
      printEvaluations(Site, Records);
    OS << "\n";
    printOperands(Site, Last);
  }

  /// `, the last of 3 evaluations (1 true, 2 false)`.
  void printEvaluations(const ExplainSite &Site,
                        llvm::ArrayRef<const uint8_t *> Records) {
    unsigned True = llvm::count_if(
        Records, [&](const uint8_t *R) { return isTrue(Site, R); });
    OS << ", the last of " << Records.size()
       << (Log.Overflow ? " recorded" : "") << " evaluations (";
    if (True == 0 || True == Records.size())
      OS << (True ? "all true" : "all false");
    else
      OS << True << " true, " << Records.size() - True << " false";
    OS << ")";
  }

  void printOperands(const ExplainSite &Site, const uint8_t *Last) {
    uint64_t Mask = readWord<uint64_t>(Last + 8);
    std::vector<unsigned> Depth(Site.Operands.size(), 0);
    for (size_t I = 1; I < Site.Operands.size(); ++I) {
      const ExplainSite::Operand &O = Site.Operands[I];
      // Under an operand that did not run, nothing ran.
      if (O.Parent > 0 && !(Mask & (uint64_t(1) << O.Parent)))
        continue;
      Depth[I] = O.Parent > 0 ? Depth[O.Parent] + 1 : 0;
      OS << std::string(6 + 2 * Depth[I], ' ') << O.Text;
      if (Mask & (uint64_t(1) << I))
        OS << " = " << formatOperand(O, Last) << "\n";
      else
        OS << ": not evaluated\n";
    }
  }

  /// Where the task's call ended: the yield it stopped at, or its end.
  void printCallEnd(const debug::DebugTables::Task &Info, const TaskLog &TL) {
    if (TL.Open || !TL.End) {
      OS << "    "
         << (Log.Overflow ? "the log was full before the call ended"
                          : "the cycle was stopped during the call")
         << "\n";
      return;
    }
    const debug::Activation &A = *TL.End;
    std::string Yield;
    if (A.Resume > 0 && A.Resume <= Info.YieldLines.size())
      Yield = Info.File + ":" + std::to_string(Info.YieldLines[A.Resume - 1]);
    if (A.State > 0)
      OS << "    stopped at the yield on " << Yield << ": "
         << describeState(Info, A) << "\n";
    else if (!Yield.empty())
      OS << "    ended at the yield on " << Yield << ": "
         << describeState(Info, A) << "\n";
    else
      OS << "    ended: " << describeState(Info, A) << "\n";
  }

  const LoadedBehavior &L;
  debug::ValueIO &Values;
  CycleLog &Log;
  llvm::raw_ostream &OS;
};

/// The order `:why` prints the tasks of a cycle in: the entry func's own
/// conditions, then the tasks as `:tasks` orders them (the hierarchy,
/// depth first), then any the hierarchy lacks.
std::vector<int> whyOrder(const CycleLog &Log, const debug::ActiveTree &Tree) {
  std::vector<int> Order;
  if (Log.Tasks.count(-1))
    Order.push_back(-1);
  std::function<void(unsigned)> Visit = [&](unsigned N) {
    int T = int(Tree.Nodes[N].Record.Task);
    if (Log.Tasks.count(T) && !llvm::is_contained(Order, T))
      Order.push_back(T);
    for (unsigned Child : Tree.Nodes[N].Children)
      Visit(Child);
  };
  for (unsigned R : Tree.Roots)
    Visit(R);
  for (const auto &[T, TL] : Log.Tasks)
    if (!llvm::is_contained(Order, T))
      Order.push_back(T);
  return Order;
}

} // namespace

WhyOutcome bsc::explainLastCycle(const LoadedBehavior &L,
                                 debug::ValueIO &Values,
                                 const BehaviorSession &S,
                                 std::optional<int> Task,
                                 llvm::raw_ostream &OS,
                                 const ExplainLogHeader *Copy) {
  uint32_t Cycle = S.getCycle();
  if (Cycle == 0)
    return WhyOutcome::NoCycle;
  const ExplainLogHeader *Header = Copy ? Copy : L.ExplainLog;
  if (!Header || Header->Cycle != Cycle)
    return WhyOutcome::NotRecorded;
  CycleLog Log = decodeLog(L.Layout, *Header,
                           reinterpret_cast<const uint8_t *>(Header + 1));
  WhyPrinter Why(L, Values, Log, OS);
  if (Task) {
    auto It = Log.Tasks.find(*Task);
    if (It == Log.Tasks.end() || (*Task >= 0 && !It->second.Calls))
      return WhyOutcome::DidNotRun;
    Why.printTask(*Task, It->second);
  } else {
    std::vector<int> Order = whyOrder(
        Log, debug::buildActiveTree(L.Tables, debug::takeSnapshot(
                                                  S.getState(), &S.getInfo())));
    if (Order.empty())
      OS << "  no task ran and no condition was evaluated\n";
    for (int T : Order)
      Why.printTask(T, Log.Tasks[T]);
  }
  if (Log.Overflow)
    OS << "the log of cycle " << Cycle << " was full: " << Log.Overflow
       << " later conditions and task calls were not recorded\n";
  return WhyOutcome::Printed;
}

void bsc::startExplainLog(const LoadedBehavior &L) {
  // A state's cycle is 1 or more while its entry runs: 0 is no cycle's.
  if (L.ExplainLog)
    L.ExplainLog->Cycle = 0;
}
