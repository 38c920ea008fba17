//===- Trace.cpp - which tasks ran in a cycle, and where they stopped -----===//
//
// See Trace.h for why the hierarchy comes from the static call graph and
// not from the records.
//
//===----------------------------------------------------------------------===//
#include "bsc/Debug/Trace.h"
#include "bsc/Basic/JSON.h"
#include "bsc/AST/Layout.h"
#include "bsc/AST/Behavior.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/Sequence.h"
#include "llvm/ADT/SetVector.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/Support/Endian.h"
#include "llvm/Support/ErrorHandling.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/SourceMgr.h"
#include <functional>
#include <set>

using namespace bsc;
using namespace bsc::debug;

DebugTables debug::buildDebugTables(const Behavior &B,
                                    const BehaviorLayout &Layout,
                                    const llvm::SourceMgr &SM) {
  DebugTables T;
  llvm::DenseMap<const CallableDecl *, unsigned> TaskIndex;
  llvm::StringMap<unsigned> NameCount;
  for (const BehaviorLayout::Task &LT : Layout.Tasks) {
    TaskIndex[LT.Decl] = TaskIndex.size();
    ++NameCount[LT.Decl->getName().Name];
  }
  // Task-level callers: the tasks from which a task is reached through
  // funcs only (a call of a task inside a func belongs to the tasks that
  // call the func).
  llvm::DenseMap<const CallableDecl *, llvm::SetVector<const CallableDecl *>>
      Callees;
  for (const CallSite &Call : B.Calls)
    Callees[Call.Caller].insert(Call.Callee);
  std::vector<std::set<unsigned>> Callers(Layout.Tasks.size());
  for (const BehaviorLayout::Task &LT : Layout.Tasks) {
    unsigned From = TaskIndex.lookup(LT.Decl);
    llvm::SmallVector<const CallableDecl *, 8> Work = {LT.Decl};
    llvm::DenseSet<const CallableDecl *> Seen = {LT.Decl};
    while (!Work.empty()) {
      const CallableDecl *D = Work.pop_back_val();
      for (const CallableDecl *Callee : Callees.lookup(D)) {
        if (auto It = TaskIndex.find(Callee); It != TaskIndex.end()) {
          Callers[It->second].insert(From);
          continue;
        }
        if (Seen.insert(Callee).second)
          Work.push_back(Callee);
      }
    }
  }

  auto FileOf = [&](llvm::SMLoc Loc) {
    unsigned Buf = SM.FindBufferContainingLoc(Loc);
    if (!Buf)
      return std::string();
    return llvm::sys::path::filename(
               SM.getMemoryBuffer(Buf)->getBufferIdentifier())
        .str();
  };
  auto LineOf = [&](llvm::SMLoc Loc) {
    return SM.FindBufferContainingLoc(Loc) ? SM.getLineAndColumn(Loc).first
                                           : 0u;
  };
  T.RecordSize = Layout.Trace.RecordSize;
  T.SlotBytes = Layout.Trace.SlotBytes;
  T.Budget = Layout.Budget.Budget;
  T.BudgetWord = Layout.Trace.BudgetWord;
  for (const BehaviorLayout::BudgetLayout::Loop &L : Layout.Budget.Loops)
    T.Loops.push_back(
        {L.Owner->getQualifiedName(), FileOf(L.Loc), LineOf(L.Loc)});
  for (const BehaviorLayout::Task &LT : Layout.Tasks) {
    const TaskDecl *D = LT.Decl;
    DebugTables::Task Task;
    Task.YieldValues = LT.YieldValues;
    if (T.RecordSize)
      Task.StateWord = Layout.Trace.StateWords[T.Tasks.size()];
    Task.Name = D->getQualifiedName();
    Task.ShortName = NameCount[D->getName().Name] == 1
                         ? D->getName().Name.str()
                         : Task.Name;
    Task.File = FileOf(D->getLoc());
    Task.Line = LineOf(D->getName().Loc);
    for (const YieldStmt *Y : D->Yields) {
      Task.YieldLines.push_back(LineOf(Y->getLoc()));
      // `yield Done::kicked`: a value of an `enum Done : TaskState`.
      std::string State;
      if (const auto *N = llvm::dyn_cast_or_null<NameExpr>(Y->Value))
        if (N->Kind == NameKind::EnumValue && N->Ty && N->Ty->isTaskState() &&
            N->Name.Parts.size() >= 2 && N->Name.Parts[0].Name != "TaskState")
          State = (N->Name.Parts[N->Name.Parts.size() - 2].Name + "::" +
                   N->Name.Parts.back().Name)
                      .str();
      Task.YieldStates.push_back(std::move(State));
    }
    unsigned Index = TaskIndex.lookup(D);
    Task.Callers.assign(Callers[Index].begin(), Callers[Index].end());
    for (const BehaviorLayout::FrameField &F : LT.Fields)
      Task.Fields.push_back({F.D->getName().Name.str(),
                             F.Ty->getName().str(),
                             llvm::isa<ParamDecl>(F.D)});
    T.Tasks.push_back(std::move(Task));
  }
  return T;
}

//===----------------------------------------------------------------------===//
// JSON
//===----------------------------------------------------------------------===//

/// Bumped when the JSON form of the tables changes.
static constexpr int64_t TablesVersion = 3;

llvm::json::Value debug::toJSON(const DebugTables &T) {
  llvm::json::Array Tasks;
  for (const DebugTables::Task &Task : T.Tasks) {
    llvm::json::Array Fields;
    for (const DebugTables::Field &F : Task.Fields)
      Fields.push_back(llvm::json::Object{
          {"name", F.Name}, {"type", F.Type}, {"param", F.IsParam}});
    llvm::json::Object O{{"name", Task.Name},
                         {"short", Task.ShortName},
                         {"file", Task.File},
                         {"line", Task.Line},
                         {"yields", llvm::json::Array(Task.YieldLines)},
                         {"callers", llvm::json::Array(Task.Callers)},
                         {"fields", std::move(Fields)}};
    if (Task.YieldStates.size() == Task.YieldLines.size())
      O["yieldStates"] = llvm::json::Array(Task.YieldStates);
    llvm::json::Array Values;
    for (std::optional<int32_t> V : Task.YieldValues)
      Values.push_back(V ? llvm::json::Value(*V) : llvm::json::Value(nullptr));
    O["yieldValues"] = std::move(Values);
    if (Task.StateWord)
      O["stateWord"] = *Task.StateWord;
    Tasks.push_back(std::move(O));
  }
  llvm::json::Object Root{
      {"version", TablesVersion},
      {"record", llvm::json::Object{{"size", T.RecordSize},
                                    {"slotBytes", T.SlotBytes}}},
      {"tasks", std::move(Tasks)}};
  if (T.Budget) {
    llvm::json::Array Loops;
    for (const DebugTables::Loop &L : T.Loops)
      Loops.push_back(llvm::json::Object{
          {"owner", L.Owner}, {"file", L.File}, {"line", L.Line}});
    llvm::json::Object Budget{{"passes", T.Budget},
                              {"loops", std::move(Loops)}};
    if (T.BudgetWord)
      Budget["word"] = *T.BudgetWord;
    Root["budget"] = std::move(Budget);
  }
  return Root;
}

static llvm::Error badTables(const llvm::Twine &Why) {
  return llvm::createStringError(llvm::inconvertibleErrorCode(),
                                 "damaged debug tables: " + Why);
}

/// A task's yields: lines, named states (optional: tables of older objects
/// have none), constant states or null, and the state word when a yield
/// computes its state.
static llvm::Error parseYields(const llvm::json::Object &O,
                               const llvm::json::Array &Yields,
                               const DebugTables &T, size_t NumTasks,
                               DebugTables::Task &Task) {
  for (const llvm::json::Value &Y : Yields) {
    std::optional<int64_t> L = Y.getAsInteger();
    if (!L)
      return badTables("a yield line is not a number");
    Task.YieldLines.push_back(*L);
  }
  if (const llvm::json::Array *States = O.getArray("yieldStates")) {
    if (States->size() != Yields.size())
      return badTables("the yield states do not match the yields");
    for (const llvm::json::Value &S : *States) {
      std::optional<llvm::StringRef> Str = S.getAsString();
      if (!Str)
        return badTables("a yield state is not a string");
      Task.YieldStates.push_back(Str->str());
    }
  }
  const llvm::json::Array *Values = O.getArray("yieldValues");
  if (!Values || Values->size() != Yields.size())
    return badTables("the yield values do not match the yields");
  bool Computed = false;
  for (const llvm::json::Value &V : *Values) {
    std::optional<int64_t> I = V.getAsInteger();
    if (I ? *I != int32_t(*I) : V.kind() != llvm::json::Value::Null)
      return badTables("a yield value is neither a task state nor null");
    Computed |= !I;
    Task.YieldValues.push_back(I ? std::optional<int32_t>(*I) : std::nullopt);
  }
  if (std::optional<int64_t> Word = O.getInteger("stateWord")) {
    if (*Word < int64_t(NumTasks * T.SlotBytes) || *Word % 4 != 0 ||
        *Word + 4 > int64_t(T.RecordSize))
      return badTables("a state word is outside the record");
    Task.StateWord = *Word;
  }
  if (Computed && !Task.StateWord)
    return badTables("a task yields computed states but has no state word");
  return llvm::Error::success();
}

/// One entry of the task list; `T` has the record's layout already.
static llvm::Expected<DebugTables::Task>
parseTask(const llvm::json::Value &V, const DebugTables &T, size_t NumTasks) {
  const llvm::json::Object *O = V.getAsObject();
  if (!O)
    return badTables("a task is not an object");
  DebugTables::Task Task;
  auto Name = O->getString("name"), Short = O->getString("short"),
       File = O->getString("file");
  auto Line = O->getInteger("line");
  const llvm::json::Array *Yields = O->getArray("yields"),
                          *Callers = O->getArray("callers"),
                          *Fields = O->getArray("fields");
  if (!Name || !Short || !File || !Line || !Yields || !Callers || !Fields)
    return badTables("a task lacks a member");
  Task.Name = Name->str();
  Task.ShortName = Short->str();
  Task.File = File->str();
  Task.Line = *Line;
  if (llvm::Error E = parseYields(*O, *Yields, T, NumTasks, Task))
    return llvm::Expected<DebugTables::Task>(std::move(E));
  for (const llvm::json::Value &C : *Callers) {
    std::optional<int64_t> I = C.getAsInteger();
    if (!I || *I < 0 || size_t(*I) >= NumTasks)
      return badTables("a caller is not a task");
    Task.Callers.push_back(*I);
  }
  for (const llvm::json::Value &F : *Fields) {
    const llvm::json::Object *FO = F.getAsObject();
    auto FName = FO ? FO->getString("name") : std::nullopt;
    auto FType = FO ? FO->getString("type") : std::nullopt;
    if (!FName || !FType)
      return badTables("a field lacks a name or type");
    Task.Fields.push_back({FName->str(), FType->str(),
                           FO->getBoolean("param").value_or(false)});
  }
  return Task;
}

/// `--cycle-budget`: the passes, the loops, the word naming the loop that
/// ran out.
static llvm::Error parseBudget(const llvm::json::Object &Budget,
                               DebugTables &T) {
  std::optional<int64_t> Passes = Budget.getInteger("passes");
  const llvm::json::Array *Loops = Budget.getArray("loops");
  if (!Passes || *Passes <= 0 || *Passes > int64_t(UINT32_MAX) || !Loops)
    return badTables("no valid budget");
  T.Budget = *Passes;
  for (const llvm::json::Value &V : *Loops) {
    const llvm::json::Object *O = V.getAsObject();
    auto Owner = O ? O->getString("owner") : std::nullopt;
    auto File = O ? O->getString("file") : std::nullopt;
    auto Line = O ? O->getInteger("line") : std::nullopt;
    if (!Owner || !File || !Line)
      return badTables("a loop lacks its owner, file or line");
    T.Loops.push_back({Owner->str(), File->str(), unsigned(*Line)});
  }
  if (std::optional<int64_t> Word = Budget.getInteger("word")) {
    if (*Word < int64_t(T.Tasks.size() * T.SlotBytes) || *Word % 4 != 0 ||
        *Word + 4 > int64_t(T.RecordSize))
      return badTables("the budget word is outside the record");
    T.BudgetWord = *Word;
  }
  return llvm::Error::success();
}

llvm::Expected<DebugTables> debug::parseDebugTables(llvm::StringRef Text) {
  llvm::Expected<llvm::json::Value> Parsed = parseJSON(Text);
  if (!Parsed)
    return badTables(llvm::toString(Parsed.takeError()));
  const llvm::json::Object *Root = Parsed->getAsObject();
  if (!Root)
    return badTables("not an object");
  if (Root->getInteger("version") != TablesVersion)
    return badTables("unknown version (compiled by another bsc?)");
  const llvm::json::Array *Tasks = Root->getArray("tasks");
  if (!Tasks)
    return badTables("no task list");
  DebugTables T;
  const llvm::json::Object *Record = Root->getObject("record");
  std::optional<int64_t> Size, SlotBytes;
  if (Record) {
    Size = Record->getInteger("size");
    SlotBytes = Record->getInteger("slotBytes");
  }
  if (!Size || !SlotBytes ||
      (*SlotBytes != 1 && *SlotBytes != 2 && *SlotBytes != 4) ||
      *Size < int64_t(Tasks->size() * *SlotBytes) || *Size % 4 != 0)
    return badTables("no valid trace record layout");
  T.RecordSize = *Size;
  T.SlotBytes = *SlotBytes;
  for (const llvm::json::Value &V : *Tasks) {
    llvm::Expected<DebugTables::Task> Task = parseTask(V, T, Tasks->size());
    if (!Task)
      return Task.takeError();
    T.Tasks.push_back(std::move(*Task));
  }
  if (const llvm::json::Object *Budget = Root->getObject("budget"))
    if (llvm::Error E = parseBudget(*Budget, T))
      return llvm::Expected<DebugTables>(std::move(E));
  return T;
}

//===----------------------------------------------------------------------===//
// Activations
//===----------------------------------------------------------------------===//

ActiveTree debug::buildActiveTree(const DebugTables &T,
                                  llvm::ArrayRef<Activation> Records) {
  ActiveTree Tree;
  llvm::DenseMap<unsigned, unsigned> NodeOfTask;
  for (const Activation &A : Records) {
    if (A.Task >= T.Tasks.size() || NodeOfTask.count(A.Task))
      continue;
    NodeOfTask[A.Task] = Tree.Nodes.size();
    Tree.Nodes.push_back({A, {}});
  }
  // Each node's parent is its deepest active caller (the first in table
  // order among equals); depths come from the callers' own choices, which
  // terminates because tasks cannot call themselves, even indirectly.
  std::vector<int> Depth(Tree.Nodes.size(), -1);
  std::vector<std::optional<unsigned>> Parent(Tree.Nodes.size());
  std::function<int(unsigned)> Place = [&](unsigned N) {
    if (Depth[N] >= 0)
      return Depth[N];
    Depth[N] = 0;
    const DebugTables::Task &Task = T.Tasks[Tree.Nodes[N].Record.Task];
    for (unsigned Caller : Task.Callers) {
      auto It = NodeOfTask.find(Caller);
      if (It == NodeOfTask.end() || It->second == N)
        continue;
      int D = Place(It->second) + 1;
      if (!Parent[N] || D > Depth[N]) {
        Parent[N] = It->second;
        Depth[N] = D;
      }
    }
    return Depth[N];
  };
  for (unsigned I = 0; I < Tree.Nodes.size(); ++I) {
    Place(I);
    if (Parent[I])
      Tree.Nodes[*Parent[I]].Children.push_back(I);
    else
      Tree.Roots.push_back(I);
  }
  return Tree;
}

/// Whether the task waits at a yield (its resume point names one). A task
/// that ended (done) waits at none: optimised code does not clear its
/// resume point (lib/CodeGen/CGTask.cpp).
static bool waitsAtYield(const DebugTables &T, const Activation &A) {
  return A.State != BS_TASK_DONE && A.Resume != 0 && A.Task < T.Tasks.size() &&
         A.Resume <= T.Tasks[A.Task].YieldLines.size();
}

std::string debug::activationState(const DebugTables &T, const Activation &A) {
  std::string S;
  if (A.State == BS_TASK_RUNNING)
    S = "running";
  else if (A.State == BS_TASK_DONE)
    S = "done";
  else if (A.State == BS_TASK_FAILURE)
    S = "failure";
  else
    S = "state " + std::to_string(A.State);
  if (!waitsAtYield(T, A))
    return S;
  // Waiting at `yield Done::kicked`: the state has that name.
  const DebugTables::Task &Task = T.Tasks[A.Task];
  size_t Yield = A.Resume - 1;
  if (Yield < Task.YieldStates.size() && !Task.YieldStates[Yield].empty())
    return Task.YieldStates[Yield];
  return S;
}

std::string debug::activationPlace(const DebugTables &T, const Activation &A) {
  if (!waitsAtYield(T, A))
    return "";
  const DebugTables::Task &Task = T.Tasks[A.Task];
  return Task.File + ":" + std::to_string(Task.YieldLines[A.Resume - 1]);
}

std::string debug::describeActivation(const DebugTables &T,
                                      const Activation &A) {
  std::string State = activationState(T, A);
  std::string Place = activationPlace(T, A);
  return Place.empty() ? State : State + ", " + Place;
}

std::vector<RecordedTask>
debug::listActiveTasks(const DebugTables &T,
                       llvm::ArrayRef<Activation> Records) {
  ActiveTree Tree = buildActiveTree(T, Records);
  std::vector<RecordedTask> List;
  std::function<void(unsigned, int)> Walk = [&](unsigned N, int Parent) {
    const Activation &A = Tree.Nodes[N].Record;
    int Self = List.size();
    List.push_back({A, Parent, activationState(T, A), activationPlace(T, A)});
    for (unsigned C : Tree.Nodes[N].Children)
      Walk(C, Self);
  };
  for (unsigned R : Tree.Roots)
    Walk(R, -1);
  return List;
}

const std::vector<RecordedTask> &
ActiveTaskLister::list(llvm::ArrayRef<Activation> Records) {
  bool SameTasks =
      Records.size() == Tasks.size() &&
      llvm::all_of(llvm::seq(Records.size()),
                   [&](size_t I) { return Records[I].Task == Tasks[I]; });
  if (!SameTasks) {
    List = listActiveTasks(T, Records);
    Tasks.clear();
    llvm::DenseMap<unsigned, unsigned> RecordOfTask;
    for (size_t I = 0; I < Records.size(); ++I) {
      Tasks.push_back(Records[I].Task);
      RecordOfTask.try_emplace(Records[I].Task, I); // The first, as listed.
    }
    RecordOf.clear();
    for (const RecordedTask &R : List)
      RecordOf.push_back(RecordOfTask.lookup(R.Record.Task));
    return List;
  }
  for (size_t I = 0; I < List.size(); ++I) {
    const Activation &A = Records[RecordOf[I]];
    RecordedTask &R = List[I];
    if (A.Resume == R.Record.Resume && A.State == R.Record.State)
      continue;
    R.Record = A;
    R.State = activationState(T, A);
    R.Place = activationPlace(T, A);
  }
  return List;
}

std::string debug::formatTraceLine(const DebugTables &T,
                                   llvm::ArrayRef<Activation> Records,
                                   std::optional<unsigned> Subtree) {
  ActiveTree Tree = buildActiveTree(T, Records);
  std::vector<std::string> Paths;
  std::vector<unsigned> Stack;
  std::vector<unsigned> Previous; // The path before, for --trace=TASK.
  auto Part = [&](unsigned S) {
    const Activation &A = Tree.Nodes[S].Record;
    return T.Tasks[A.Task].ShortName + " [" + describeActivation(T, A) + "]";
  };
  // Depth first, children in task-table order: one path per leaf. Every
  // task on it shows its state and line, because a parent moving through
  // its yields under an unchanged leaf is what a reader looks for. Under a
  // subtree's root, a path shows the part it shares with the path before
  // as `...`, so that a line fits a terminal.
  std::function<void(unsigned, bool)> Walk = [&](unsigned N, bool In) {
    In = In || !Subtree || Tree.Nodes[N].Record.Task == *Subtree;
    if (In)
      Stack.push_back(N);
    const ActiveTask &Node = Tree.Nodes[N];
    if (Node.Children.empty() && In) {
      size_t Shared = 0;
      if (Subtree)
        while (Shared + 1 < Stack.size() && Shared < Previous.size() &&
               Previous[Shared] == Stack[Shared])
          ++Shared;
      std::string P = Shared ? "..." : "";
      for (size_t I = Shared; I < Stack.size(); ++I)
        P += (P.empty() ? "" : " > ") + Part(Stack[I]);
      Paths.push_back(std::move(P));
      Previous = Stack;
    }
    for (unsigned C : Node.Children)
      Walk(C, In);
    if (In)
      Stack.pop_back();
  };
  for (unsigned R : Tree.Roots)
    Walk(R, false);
  if (Paths.empty())
    return Subtree ? "not active" : "idle";
  return llvm::join(Paths, "; ");
}

bool TraceFilter::shouldPrint(llvm::StringRef Line) {
  switch (Mode) {
  case TraceMode::Off:
    return false;
  case TraceMode::EveryCycle:
    return true;
  case TraceMode::Changes:
    if (Last && *Last == Line)
      return false;
    Last = Line.str();
    return true;
  }
  llvm_unreachable("unknown trace mode");
}

std::vector<Activation> debug::takeSnapshot(const void *State,
                                            const bs_behavior_info *Info) {
  std::vector<Activation> Records;
  uint32_t Cycle = static_cast<const bs_state_header *>(State)->cycle;
  if (Cycle == 0)
    return Records;
  for (uint32_t I = 0; I < Info->num_tasks; ++I) {
    const bs_task_info &Task = Info->tasks[I];
    // Every call records the cycle (bit 31 flipped if the call ended the
    // task): the tasks called in this one.
    if (((bs_task_last_call_at(State, &Task) ^ Cycle) & ~BS_LAST_CALL_ENDED) ==
        0)
      Records.push_back({I, bs_task_resume_at(State, &Task),
                         bs_task_state_at(State, &Task)});
  }
  return Records;
}

llvm::Expected<std::vector<Activation>>
debug::decodeTraceRecord(const DebugTables &T,
                         llvm::ArrayRef<uint8_t> Record) {
  namespace endian = llvm::support::endian;
  assert(Record.size() == T.RecordSize && "one whole record");
  uint32_t Finished =
      BehaviorLayout::TraceLayout::getFinishedSlot(T.SlotBytes);
  std::vector<Activation> Records;
  for (unsigned I = 0; I < T.Tasks.size(); ++I) {
    const DebugTables::Task &Task = T.Tasks[I];
    const uint8_t *Slot = Record.data() + I * T.SlotBytes;
    uint32_t Value = T.SlotBytes == 1   ? *Slot
                     : T.SlotBytes == 2 ? endian::read16le(Slot)
                                        : endian::read32le(Slot);
    if (Value == 0)
      continue;
    if (Value == Finished) {
      Records.push_back({I, 0, BS_TASK_DONE});
      continue;
    }
    // Failed because the cycle ran out of budget (bscript.h).
    if (T.BudgetWord && Value == Finished - 1) {
      Records.push_back({I, 0, BS_TASK_FAILURE});
      continue;
    }
    if (Value > Task.YieldValues.size())
      return llvm::createStringError(
          llvm::inconvertibleErrorCode(),
          "task " + Task.Name + " stopped at yield " + llvm::Twine(Value) +
              ", but it has " + llvm::Twine(Task.YieldValues.size()));
    std::optional<int32_t> State = Task.YieldValues[Value - 1];
    if (!State)
      State = int32_t(endian::read32le(Record.data() + *Task.StateWord));
    Records.push_back({I, Value, *State});
  }
  return Records;
}

llvm::Expected<LoggedCycle>
debug::decodeLoggedCycle(const DebugTables &T, uint32_t Cycle,
                         llvm::ArrayRef<uint8_t> Record) {
  namespace endian = llvm::support::endian;
  if (Record.size() != T.RecordSize)
    return llvm::createStringError(
        llvm::inconvertibleErrorCode(),
        "cycle " + llvm::Twine(Cycle) + ": a trace record of " +
            llvm::Twine(Record.size()) + " bytes, but the object's are " +
            llvm::Twine(T.RecordSize));
  LoggedCycle C;
  C.Cycle = Cycle;
  auto Records = decodeTraceRecord(T, Record);
  if (!Records)
    return llvm::createStringError(llvm::inconvertibleErrorCode(),
                                   "cycle " + llvm::Twine(Cycle) + ": " +
                                       llvm::toString(Records.takeError()));
  C.Records = std::move(*Records);
  if (T.BudgetWord) {
    C.BudgetLoop = endian::read32le(Record.data() + *T.BudgetWord);
    if (C.BudgetLoop > T.Loops.size())
      return llvm::createStringError(
          llvm::inconvertibleErrorCode(),
          "cycle " + llvm::Twine(Cycle) + ": the budget ran out in loop " +
              llvm::Twine(C.BudgetLoop) + ", but there are " +
              llvm::Twine(T.Loops.size()));
  }
  return C;
}

llvm::Expected<std::vector<LoggedCycle>>
debug::parseTraceLog(llvm::StringRef Bytes, const DebugTables &T) {
  namespace endian = llvm::support::endian;
  std::vector<LoggedCycle> Cycles;
  size_t Pos = 0;
  auto Fail = [&](const llvm::Twine &Why) {
    return llvm::createStringError(llvm::inconvertibleErrorCode(),
                                   "byte " + llvm::Twine(Pos) + ": " + Why);
  };
  while (Pos < Bytes.size()) {
    if (Bytes.size() - Pos < 4 + T.RecordSize)
      return Fail("the log ends inside a cycle (a cycle is 4 + " +
                  llvm::Twine(T.RecordSize) + " bytes)");
    auto Record = llvm::ArrayRef(
        reinterpret_cast<const uint8_t *>(Bytes.data()) + Pos + 4,
        T.RecordSize);
    llvm::Expected<LoggedCycle> C =
        decodeLoggedCycle(T, endian::read32le(Bytes.data() + Pos), Record);
    if (!C)
      return Fail(llvm::toString(C.takeError()));
    Cycles.push_back(std::move(*C));
    Pos += 4 + T.RecordSize;
  }
  return Cycles;
}

std::string debug::formatBudgetLine(const DebugTables &T,
                                    const LoggedCycle &C) {
  if (!C.BudgetLoop || C.BudgetLoop > T.Loops.size())
    return "";
  const DebugTables::Loop &L = T.Loops[C.BudgetLoop - 1];
  return ("cycle " + llvm::Twine(C.Cycle) + " ran out of its budget of " +
          llvm::Twine(T.Budget) + " loop passes in the loop of '" + L.Owner +
          "' at " + L.File + ":" + llvm::Twine(L.Line))
      .str();
}
