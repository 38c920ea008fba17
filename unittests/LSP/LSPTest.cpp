//===- LSPTest.cpp - the wire, URIs, bscript.json, the index --------------===//
#include "bsc/Basic/Transport.h"
#include "Workspace.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"
#include "gtest/gtest.h"
#include <unistd.h>

using namespace bsc;
using namespace bsc::lsp;

namespace {

/// A pipe whose write end the test fills.
struct Pipe {
  int Fds[2];
  Pipe() { EXPECT_EQ(pipe(Fds), 0); }
  ~Pipe() {
    close(Fds[0]);
    if (Fds[1] >= 0)
      close(Fds[1]);
  }
  void write(llvm::StringRef S) {
    ASSERT_EQ(::write(Fds[1], S.data(), S.size()), ssize_t(S.size()));
  }
  void closeWriter() {
    close(Fds[1]);
    Fds[1] = -1;
  }
};

TEST(TransportTest, ReadsFramedMessagesAndSkipsDamagedOnes) {
  Pipe In, Out;
  Transport T(In.Fds[0], Out.Fds[1]);
  In.write("Content-Length: 7\r\n\r\n{\"a\":1}"
           "X-Other: y\r\n\r\n"                     // no length
           "Content-Length: 5\r\n\r\n{nope"           // not JSON
           "content-length:  2\r\nX: z\r\n\r\n[]");   // any case, other headers
  In.closeWriter();
  llvm::json::Value V = nullptr;
  std::string Error;
  ASSERT_EQ(T.read(V, Error, 1000), Transport::Read::Message);
  EXPECT_EQ(*V.getAsObject()->getInteger("a"), 1);
  EXPECT_EQ(T.read(V, Error, 1000), Transport::Read::Malformed);
  EXPECT_EQ(Error, "message header without a Content-Length");
  EXPECT_EQ(T.read(V, Error, 1000), Transport::Read::Malformed);
  ASSERT_EQ(T.read(V, Error, 1000), Transport::Read::Message);
  EXPECT_TRUE(V.getAsArray());
  EXPECT_EQ(T.read(V, Error, 1000), Transport::Read::End);
}

TEST(TransportTest, TimesOutAndRefusesHugeLengths) {
  Pipe In, Out;
  Transport T(In.Fds[0], Out.Fds[1]);
  llvm::json::Value V = nullptr;
  std::string Error;
  EXPECT_EQ(T.read(V, Error, 10), Transport::Read::Timeout);
  In.write("Content-Length: 99999999999\r\n\r\n");
  EXPECT_EQ(T.read(V, Error, 1000), Transport::Read::Malformed);
  EXPECT_EQ(Error, "message longer than 64 MiB");
}

TEST(TransportTest, WritesAFramedMessage) {
  Pipe In, Out;
  Transport T(In.Fds[0], Out.Fds[1]);
  T.write(llvm::json::Object{{"id", 1}});
  char Buf[64] = {};
  ssize_t N = read(Out.Fds[0], Buf, sizeof Buf - 1);
  EXPECT_EQ(std::string(Buf, N), "Content-Length: 8\r\n\r\n{\"id\":1}");
}

TEST(URITest, FilePathsBothWays) {
  EXPECT_EQ(uriToPath("file:///a/b%20c/d.bs"), "/a/b c/d.bs");
  EXPECT_EQ(uriToPath("file:///a/./b/../c.bs"), "/a/c.bs");
  EXPECT_EQ(uriToPath("http://x/y.bs"), "");
  EXPECT_EQ(uriToPath("file:///a%2"), "/a%2");
  EXPECT_EQ(pathToURI("/a/b c/d.bs"), "file:///a/b%20c/d.bs");
  EXPECT_EQ(uriToPath(pathToURI("/x/%y#z.bs")), "/x/%y#z.bs");
}

/// A folder with files, removed at the end.
class TempTree {
public:
  TempTree() { llvm::sys::fs::createUniqueDirectory("bsc-lsp", Root); }
  ~TempTree() { llvm::sys::fs::remove_directories(Root); }
  std::string write(llvm::StringRef Rel, llvm::StringRef Text) {
    llvm::SmallString<128> P(Root);
    llvm::sys::path::append(P, Rel);
    llvm::sys::fs::create_directories(llvm::sys::path::parent_path(P));
    std::error_code EC;
    llvm::raw_fd_ostream OS(P, EC);
    OS << Text;
    return std::string(P);
  }
  llvm::SmallString<128> Root;
};

TEST(ConfigTest, NearestFileWithPathsRelativeToIt) {
  TempTree T;
  T.write("bscript.json",
          R"({"bind": ["objs/w.o"], "include": ["lib"], "target": "i586"})");
  std::string Script = T.write("src/deep/A.bs", "");
  BehaviorConfig C = findConfig(Script);
  EXPECT_EQ(C.Error, "");
  ASSERT_EQ(C.Bind.size(), 1u);
  EXPECT_EQ(C.Bind[0], (T.Root + "/objs/w.o").str());
  EXPECT_EQ(C.Include[0], (T.Root + "/lib").str());
  EXPECT_EQ(C.Target, "i586");
  // A nearer one wins.
  T.write("src/bscript.json", "{}");
  EXPECT_TRUE(findConfig(Script).Bind.empty());
}

TEST(ConfigTest, ABuildFolderListsBehaviors) {
  TempTree T;
  std::string A = T.write("behaviors/a.bs", "");
  std::string Lib = T.write("behaviors/lib/skills.bs", "");
  std::string Other = T.write("elsewhere/o.bs", "");
  T.write("build/bscript.json",
          R"({"behaviors": [{"sources": [")" + A +
              R"("], "include": [")" + (T.Root + "/behaviors/lib").str() +
              R"("], "bind": ["/b.o"], "target": ""}]})");
  EXPECT_EQ(findConfig(A).Bind, std::vector<std::string>{"/b.o"});
  EXPECT_EQ(findConfig(Lib).Bind, std::vector<std::string>{"/b.o"});
  BehaviorConfig None = findConfig(Other);
  EXPECT_TRUE(None.Bind.empty());
  EXPECT_EQ(None.Error, "");
}

TEST(ConfigTest, MistakesAreSaid) {
  TempTree T;
  std::string S = T.write("a.bs", "");
  T.write("bscript.json", "[1]");
  EXPECT_NE(findConfig(S).Error.find("is not a JSON object"), std::string::npos);
  T.write("bscript.json", R"({"bind": "x.o"})");
  EXPECT_NE(findConfig(S).Error.find("\"bind\" must be a list of paths"),
            std::string::npos);
  T.write("bscript.json", R"({"target": 3})");
  EXPECT_NE(findConfig(S).Error.find("\"target\" must be a string"),
            std::string::npos);
  T.write("bscript.json", "{");
  EXPECT_NE(findConfig(S).Error.find("is not JSON"), std::string::npos);
}

TEST(AnalysisTest, IndexesDeclarationsAndUsesAndConvertsPositions) {
  TempTree T;
  std::string Path = T.write("M.bs", "func f(int a) : int\n"
                                     "    return a + 1\n"
                                     "task t()\n"
                                     "    int x = f(2)\n");
  ServerOptions Opts;
  Opts.BaseOptions = [](llvm::StringRef) {
    FrontendOptions F;
    F.StandardModules = {BSC_HOST_RUNTIME};
    return F;
  };
  Workspace W(Opts);
  std::unique_ptr<Analysis> A = W.analyze(Path);
  unsigned Buf = A->getBuffer(Path);
  ASSERT_NE(Buf, 0u);
  // `f` in `int x = f(2)`: a use of the func declared on line 0.
  llvm::json::Value Pos = llvm::json::Object{{"line", 3}, {"character", 12}};
  llvm::SMLoc Loc = A->getLoc(Buf, &Pos);
  const Occurrence *O = A->Idx.findAt(Loc);
  ASSERT_TRUE(O);
  EXPECT_FALSE(O->IsDefinition);
  ASSERT_EQ(O->Sym.K, Symbol::Decl);
  EXPECT_EQ(static_cast<const Decl *>(O->Sym.Ptr)->getName().Name, "f");
  llvm::json::Object Back = A->getPosition(O->Range.Start);
  EXPECT_EQ(*Back.getInteger("line"), 3);
  EXPECT_EQ(*Back.getInteger("character"), 12);
  // The unsaved text wins over the file.
  W.open(Path, "task t()\n    yield\n", 1);
  A = W.analyze(Path);
  EXPECT_FALSE(A->C->Diags.hasErrors());
  EXPECT_EQ(A->C->Modules[0]->Decls.size(), 1u);
}

} // namespace
