//===- CallGraph.cpp - the static call graph as Graphviz DOT --------------===//
//
// The writer behind `bsc --emit=graph`. Everything it prints comes from
// Behavior in its order (modules, then each module's callables in source
// order with a task's nested funcs after it, then Behavior::Calls), so the
// same behavior always gives the same text and tests can match it line by
// line:
//
//   digraph calls {
//     subgraph "cluster_Kick" {
//       label="Kick";
//       "Kick::align" [shape=box];
//       "Kick::go" [shape=box];
//       "Kick::go.near" [shape=ellipse];
//     }
//     "Kick::go" -> "Kick::go.near" [label="8"];
//     "Kick::go" -> "Kick::align" [label="10, 14"];
//   }
//
// Every name is quoted: `::` and `.` cannot appear in a bare DOT identifier,
// and quotes (with `"` and `\` escaped) are safe for any name.
//
//===----------------------------------------------------------------------===//
#include "bsc/Sema/CallGraph.h"
#include "llvm/ADT/MapVector.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;

namespace {
/// Writes `S` as a DOT string literal.
void writeQuoted(llvm::raw_ostream &OS, llvm::StringRef S) {
  OS << '"';
  for (char Ch : S) {
    if (Ch == '"' || Ch == '\\')
      OS << '\\';
    OS << Ch;
  }
  OS << '"';
}

void writeNode(llvm::raw_ostream &OS, const CallableDecl *C,
               const llvm::DenseSet<const CallableDecl *> *Active) {
  OS << "    ";
  writeQuoted(OS, C->getQualifiedName());
  OS << " [shape=" << (llvm::isa<TaskDecl>(C) ? "box" : "ellipse");
  if (Active && Active->contains(C))
    OS << ", style=filled, fillcolor=gold";
  OS << "];\n";
}

/// Writes the edges of one caller: its calls `Sites`, merged per callee in
/// the order of the first call.
void writeEdges(llvm::raw_ostream &OS, const llvm::SourceMgr &SM,
                llvm::ArrayRef<CallSite> Sites) {
  llvm::MapVector<const CallableDecl *, llvm::SmallVector<unsigned, 2>> Lines;
  for (const CallSite &S : Sites) {
    unsigned Line = SM.getLineAndColumn(S.Loc).first;
    auto &L = Lines[S.Callee];
    // Two calls on one line name the line once.
    if (L.empty() || L.back() != Line)
      L.push_back(Line);
  }
  for (const auto &[Callee, L] : Lines) {
    OS << "  ";
    writeQuoted(OS, Sites.front().Caller->getQualifiedName());
    OS << " -> ";
    writeQuoted(OS, Callee->getQualifiedName());
    OS << " [label=\"";
    llvm::interleave(L, OS, ", ");
    OS << "\"];\n";
  }
}
} // namespace

void bsc::writeCallGraphDOT(
    const Behavior &B, const llvm::SourceMgr &SM, llvm::raw_ostream &OS,
    const llvm::DenseSet<const CallableDecl *> *Active) {
  OS << "digraph calls {\n";
  for (const ModuleAST *M : B.Modules) {
    if (M->Decls.empty())
      continue;
    OS << "  subgraph ";
    writeQuoted(OS, "cluster_" + M->Name);
    OS << " {\n    label=";
    writeQuoted(OS, M->Name);
    OS << ";\n";
    for (const CallableDecl *C : M->Decls) {
      writeNode(OS, C, Active);
      if (const auto *T = llvm::dyn_cast<TaskDecl>(C))
        for (const FuncDecl *F : T->NestedFuncs)
          writeNode(OS, F, Active);
    }
    OS << "  }\n";
  }
  // Behavior::Calls holds each caller's calls together.
  llvm::ArrayRef<CallSite> Rest = B.Calls;
  while (!Rest.empty()) {
    size_t N = 1;
    while (N != Rest.size() && Rest[N].Caller == Rest.front().Caller)
      ++N;
    writeEdges(OS, SM, Rest.take_front(N));
    Rest = Rest.drop_front(N);
  }
  OS << "}\n";
}
