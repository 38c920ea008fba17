//===- SemaTask.cpp - yields, taskState and the call graph ----------------===//
//
// A task has one context, so it must never be re-entered while it runs; a
// func gets a statically bounded stack only if it cannot recurse. Both come
// down to one rule: the call graph of funcs and tasks has no cycle. The graph
// is collected while bodies are checked (an edge per call site, from the
// callable whose body holds the call, nested funcs included) and checked
// once at the end with Tarjan's algorithm, run iteratively so that a long
// call chain cannot exhaust the compiler's stack. Each strongly connected
// component with a cycle is reported once, as the shortest cycle through
// its first callable in module and source order, so the output is
// deterministic. The edges are also exported as Behavior::Calls, for the
// DOT writer of CallGraph.h.
//
//===----------------------------------------------------------------------===//
#include "SemaImpl.h"
#include "llvm/ADT/SmallPtrSet.h"
#include <algorithm>
#include <deque>

using namespace bsc;
using namespace bsc::sema;

void Sema::checkYield(YieldStmt *S) {
  auto *Task = llvm::dyn_cast<TaskDecl>(CurCallable);
  if (!Task)
    diag(S->getLoc(), diag::err_yield_outside_task);
  if (S->Value) {
    const Type *T = checkExpr(S->Value);
    if (T->isEnum())
      diag(S->Value->getLoc(), diag::err_yield_plain_enum)
          << T->getName() << S->Value->getRange();
    else if (!T->isError() && !T->isInt() && !T->isTaskState())
      diag(S->Value->getLoc(), diag::err_yield_value_type)
          << T->getName() << S->Value->getRange();
  }
  if (!Task)
    return;
  Task->Yields.push_back(S);
  S->ResumePoint = Task->Yields.size();
  // Every local in scope here may have to keep its value to the next call.
  for (const Scope &Sc : Scopes)
    for (auto &[Name, D] : Sc)
      if (auto *V = llvm::dyn_cast<VarDecl>(D))
        V->LivesAcrossYield = true;
}

const Type *Sema::checkTaskState(TaskStateExpr *E) {
  // The type is TaskState even after a mistake in the operand: the
  // expression around it is still well typed, so nothing cascades.
  LookupResult L = lookup(E->TaskName, LookupMode::Value);
  if (L.Kind == LookupKind::Callable)
    if (auto *T = llvm::dyn_cast<TaskDecl>(L.Callable)) {
      E->Task = T;
      return Types.getTaskState();
    }
  if (L.Kind != LookupKind::Error)
    diag(E->TaskName.getLoc(), diag::err_task_state_not_task)
        << E->TaskName.str() << E->TaskName.getRange();
  return Types.getTaskState();
}

void Sema::recordCall(CallableDecl *Callee, llvm::SMLoc Loc) {
  if (CurCallable)
    Calls[CurCallable].push_back({Callee, Loc, ScopeClock});
}

/// A nested func may be called before the task's locals it uses are
/// declared (docs/language.md: it then reads them as the reset left them,
/// zero). Those locals are zeroed at the reset and keep a frame field of
/// their own (no earlier local's leftover value), in every configuration;
/// all other scalars get their values where they are declared.
void Sema::markLocalsUsedBeforeDeclared() {
  // The locals each nested func may reach, through the nested funcs it
  // calls too (funcs do not recurse, so this settles in a few rounds).
  llvm::DenseMap<const CallableDecl *, llvm::SmallPtrSet<VarDecl *, 4>> Reach;
  for (FuncDecl *F : CurTask->NestedFuncs)
    Reach[F].insert(TaskLocalsUsed[F].begin(), TaskLocalsUsed[F].end());
  for (bool Changed = true; Changed;) {
    Changed = false;
    for (FuncDecl *F : CurTask->NestedFuncs)
      for (const CallEdge &Edge : Calls[F]) {
        auto It = Reach.find(Edge.Callee);
        if (It == Reach.end() || Edge.Callee == F)
          continue;
        llvm::SmallVector<VarDecl *, 8> More(It->second.begin(),
                                             It->second.end());
        for (VarDecl *V : More)
          Changed |= Reach[F].insert(V).second;
      }
  }
  for (const CallEdge &Edge : Calls[CurTask]) {
    auto It = Reach.find(Edge.Callee);
    if (It == Reach.end())
      continue;
    for (VarDecl *V : It->second)
      if (Edge.Clock < V->ScopeBegin)
        V->ReadBeforeDeclared = true;
  }
}

void Sema::exportCalls() {
  auto Export = [&](const CallableDecl *Caller) {
    auto It = Calls.find(Caller);
    if (It == Calls.end())
      return;
    size_t First = Out.Calls.size();
    for (const CallEdge &Edge : It->second)
      Out.Calls.push_back({Caller, Edge.Callee, Edge.Loc});
    // Sorted, so that source order does not rest on the order in which the
    // checker visits expressions; a caller's calls all lie in its own
    // buffer, so their pointers order them.
    std::stable_sort(Out.Calls.begin() + First, Out.Calls.end(),
                     [](const CallSite &A, const CallSite &B) {
                       return A.Loc.getPointer() < B.Loc.getPointer();
                     });
  };
  for (ModuleAST *M : Out.Modules)
    for (CallableDecl *C : M->Decls) {
      Export(C);
      if (auto *T = llvm::dyn_cast<TaskDecl>(C))
        for (FuncDecl *F : T->NestedFuncs)
          Export(F);
    }
}

namespace {
/// The call graph over dense node numbers, in module and source order.
struct CallGraph {
  std::vector<CallableDecl *> Nodes;
  llvm::DenseMap<const CallableDecl *, unsigned> Index;
  /// Out-edges of each node: (callee index, edge in Sema::Calls).
  std::vector<std::vector<std::pair<unsigned, const CallEdge *>>> Succ;
};

/// Tarjan's strongly connected components, without recursion. Returns the
/// component number of each node.
std::vector<unsigned> findComponents(const CallGraph &G) {
  const unsigned None = ~0u;
  size_t N = G.Nodes.size();
  std::vector<unsigned> Num(N, None), Low(N, 0), Comp(N, None);
  std::vector<bool> OnStack(N, false);
  std::vector<unsigned> Stack;
  unsigned Counter = 0, NumComps = 0;
  struct Frame {
    unsigned Node;
    size_t NextEdge;
  };
  std::vector<Frame> Work;
  for (unsigned Root = 0; Root != N; ++Root) {
    if (Num[Root] != None)
      continue;
    Work.push_back({Root, 0});
    Num[Root] = Low[Root] = Counter++;
    Stack.push_back(Root);
    OnStack[Root] = true;
    while (!Work.empty()) {
      Frame &F = Work.back();
      unsigned V = F.Node;
      if (F.NextEdge < G.Succ[V].size()) {
        unsigned W = G.Succ[V][F.NextEdge++].first;
        if (Num[W] == None) {
          Num[W] = Low[W] = Counter++;
          Stack.push_back(W);
          OnStack[W] = true;
          Work.push_back({W, 0});
        } else if (OnStack[W]) {
          Low[V] = std::min(Low[V], Num[W]);
        }
        continue;
      }
      if (Low[V] == Num[V]) {
        unsigned W;
        do {
          W = Stack.back();
          Stack.pop_back();
          OnStack[W] = false;
          Comp[W] = NumComps;
        } while (W != V);
        ++NumComps;
      }
      Work.pop_back();
      if (!Work.empty())
        Low[Work.back().Node] = std::min(Low[Work.back().Node], Low[V]);
    }
  }
  return Comp;
}
} // namespace

void Sema::checkCallGraph() {
  CallGraph G;
  for (ModuleAST *M : Out.Modules)
    for (CallableDecl *C : M->Decls) {
      G.Index[C] = G.Nodes.size();
      G.Nodes.push_back(C);
      if (auto *T = llvm::dyn_cast<TaskDecl>(C))
        for (FuncDecl *F : T->NestedFuncs) {
          G.Index[F] = G.Nodes.size();
          G.Nodes.push_back(F);
        }
    }
  G.Succ.resize(G.Nodes.size());
  for (unsigned I = 0, E = G.Nodes.size(); I != E; ++I) {
    auto It = Calls.find(G.Nodes[I]);
    if (It == Calls.end())
      continue;
    for (const CallEdge &Edge : It->second) {
      auto Target = G.Index.find(Edge.Callee);
      if (Target != G.Index.end())
        G.Succ[I].push_back({Target->second, &Edge});
    }
  }

  std::vector<unsigned> Comp = findComponents(G);
  llvm::DenseSet<unsigned> Reported;
  for (unsigned Start = 0, E = G.Nodes.size(); Start != E; ++Start) {
    if (Reported.count(Comp[Start]))
      continue;
    // The shortest cycle through Start inside its component, by BFS.
    std::vector<int> Parent(G.Nodes.size(), -1);
    std::vector<const CallEdge *> Via(G.Nodes.size(), nullptr);
    const CallEdge *Closing = nullptr;
    int Last = -1;
    std::deque<unsigned> Queue{Start};
    std::vector<bool> Seen(G.Nodes.size(), false);
    Seen[Start] = true;
    while (!Queue.empty() && !Closing) {
      unsigned V = Queue.front();
      Queue.pop_front();
      for (auto [W, Edge] : G.Succ[V]) {
        if (Comp[W] != Comp[Start])
          continue;
        if (W == Start) {
          Closing = Edge;
          Last = V;
          break;
        }
        if (Seen[W])
          continue;
        Seen[W] = true;
        Parent[W] = V;
        Via[W] = Edge;
        Queue.push_back(W);
      }
    }
    if (!Closing)
      continue; // Not on a cycle.
    Reported.insert(Comp[Start]);

    // Walk back from the last node to Start to list the cycle in order.
    std::vector<unsigned> Path;
    for (int V = Last; V != -1; V = Parent[V])
      Path.push_back(V);
    std::reverse(Path.begin(), Path.end()); // Path[0] == Start.
    std::string Text;
    for (unsigned V : Path)
      Text += G.Nodes[V]->getQualifiedName() + " -> ";
    Text += G.Nodes[Start]->getQualifiedName();

    CallableDecl *First = G.Nodes[Start];
    diag(First->getName().Loc, diag::err_call_cycle)
        << (llvm::isa<TaskDecl>(First) ? "task" : "function")
        << First->getQualifiedName() << Text << First->getName().getRange();
    for (size_t I = 0; I != Path.size(); ++I) {
      unsigned From = Path[I];
      unsigned To = I + 1 == Path.size() ? Start : Path[I + 1];
      const CallEdge *Edge = I + 1 == Path.size() ? Closing : Via[To];
      diag(Edge->Loc, diag::note_call_cycle_edge)
          << G.Nodes[From]->getQualifiedName()
          << G.Nodes[To]->getQualifiedName();
    }
  }
}
