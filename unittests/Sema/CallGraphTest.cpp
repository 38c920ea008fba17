//===- CallGraphTest.cpp - Behavior::Calls and its DOT writer -------------===//
//
// The call sites Sema exports and the text writeCallGraphDOT makes of them,
// on a parsed module so that lines are real; the `Active` highlighting is
// only reachable from here until a REPL uses it. test/Driver/emit-graph.test
// covers the same end to end, with modules and bindings.
//
//===----------------------------------------------------------------------===//
#include "bsc/Sema/CallGraph.h"
#include "ParsedModule.h"
#include "bsc/Parse/Parser.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/Support/raw_ostream.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {

/// Module `P` with its call graph as DOT.
struct Parsed : ParsedModule {
  using ParsedModule::ParsedModule;

  std::string
  dot(const llvm::DenseSet<const CallableDecl *> *Active = nullptr) const {
    std::string S;
    llvm::raw_string_ostream OS(S);
    writeCallGraphDOT(Out, SM, OS, Active);
    return S;
  }
};

/// Tasks, a func, a nested func; a task called from three places in two
/// callers, one of them a `for` step; two calls of one func on one line.
const char *const Source = "task leaf()\n"
                           "    yield\n"
                           "func add(int a, int b) : int\n"
                           "    return a + b\n"
                           "task top()\n"
                           "    func twice() : int\n"
                           "        return add(1, 2) + add(3, 4)\n"
                           "    for(; twice() < 10; leaf())\n"
                           "        leaf()\n"
                           "func main()\n"
                           "    top()\n"
                           "    leaf()\n";

TEST(CallGraphTest, ExportsEveryCallByCallerInSourceOrder) {
  Parsed P(Source);
  ASSERT_TRUE(P.OK);
  std::vector<std::string> Calls;
  for (const CallSite &S : P.Out.Calls)
    Calls.push_back(S.Caller->getQualifiedName() + " -> " +
                    S.Callee->getQualifiedName() + " @" +
                    std::to_string(P.SM.getLineAndColumn(S.Loc).first));
  // The `for` step (line 8) comes before the body (line 9); the task's own
  // calls before its nested func's, as the nodes are ordered.
  EXPECT_EQ(Calls, (std::vector<std::string>{
                       "P::top -> P::top.twice @8",
                       "P::top -> P::leaf @8",
                       "P::top -> P::leaf @9",
                       "P::top.twice -> P::add @7",
                       "P::top.twice -> P::add @7",
                       "P::main -> P::top @11",
                       "P::main -> P::leaf @12",
                   }));
}

TEST(CallGraphTest, WritesNodesAndMergedEdges) {
  Parsed P(Source);
  ASSERT_TRUE(P.OK);
  EXPECT_EQ(P.dot(), "digraph calls {\n"
                     "  subgraph \"cluster_P\" {\n"
                     "    label=\"P\";\n"
                     "    \"P::leaf\" [shape=box];\n"
                     "    \"P::add\" [shape=ellipse];\n"
                     "    \"P::top\" [shape=box];\n"
                     "    \"P::top.twice\" [shape=ellipse];\n"
                     "    \"P::main\" [shape=ellipse];\n"
                     "  }\n"
                     "  \"P::top\" -> \"P::top.twice\" [label=\"8\"];\n"
                     "  \"P::top\" -> \"P::leaf\" [label=\"8, 9\"];\n"
                     "  \"P::top.twice\" -> \"P::add\" [label=\"7\"];\n"
                     "  \"P::main\" -> \"P::top\" [label=\"11\"];\n"
                     "  \"P::main\" -> \"P::leaf\" [label=\"12\"];\n"
                     "}\n");
}

TEST(CallGraphTest, HighlightsActiveCallables) {
  Parsed P(Source);
  ASSERT_TRUE(P.OK);
  const CallableDecl *Top = P.find("P::top");
  const CallableDecl *Twice = P.find("P::top.twice");
  ASSERT_TRUE(Top && Twice);
  llvm::DenseSet<const CallableDecl *> Active{Top, Twice};
  std::string Text = P.dot(&Active);
  EXPECT_NE(Text.find("    \"P::top\" [shape=box, style=filled, "
                      "fillcolor=gold];\n"),
            std::string::npos)
      << Text;
  EXPECT_NE(Text.find("    \"P::top.twice\" [shape=ellipse, style=filled, "
                      "fillcolor=gold];\n"),
            std::string::npos)
      << Text;
  // Only the active ones; the edges do not change.
  EXPECT_EQ(llvm::StringRef(Text).count("filled"), 2u) << Text;
  EXPECT_NE(Text.find("    \"P::leaf\" [shape=box];\n"), std::string::npos);
  EXPECT_NE(Text.find("  \"P::top\" -> \"P::leaf\" [label=\"8, 9\"];\n"),
            std::string::npos);

  // An empty set highlights nothing: the same text as no set.
  llvm::DenseSet<const CallableDecl *> None;
  EXPECT_EQ(P.dot(&None), P.dot());
}

TEST(CallGraphTest, EmptyBehaviorIsAnEmptyGraph) {
  Behavior B;
  llvm::SourceMgr SM;
  std::string S;
  llvm::raw_string_ostream OS(S);
  writeCallGraphDOT(B, SM, OS);
  EXPECT_EQ(S, "digraph calls {\n}\n");
}

} // namespace
