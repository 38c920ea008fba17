//===- Repl.cpp - `bsc repl`: stepping a behavior and asking it questions -===//
//
// The REPL holds one compilation, the behavior loaded from it into a JIT,
// and a session (the state and the input and output objects). A line is a
// command (`:step`, `:tasks`, ...) or b-script: ReplChecker checks it as
// the body of a new func in the entry's module, emitReplLine compiles it
// into the same JIT, and it runs under the session's guard between cycles.
// Its variables live here, at fixed addresses the generated code is given,
// so they outlive the line.
//
// The commands are in ReplCommands.cpp, the breakpoints in
// ReplBreakpoints.cpp (ReplImpl.h).
//
// `:reload` compiles the edited files into a new JIT and a new state, then
// carries over what still fits: each task frame whose fields are the same
// (names and types, in order), the input and output values, the cycle
// number. Other tasks start afresh, as after a missed cycle.
//
// Everything printed is deterministic, so that lit tests drive the REPL
// with `--batch` (or a standard input that is not a terminal).
//
//===----------------------------------------------------------------------===//
#include "ReplImpl.h"
#include "bsc/CodeGen/Target.h"
#include "bsc/Parse/Parser.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/MemAlloc.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/Process.h"
#include "llvm/Support/WithColor.h"
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

using namespace bsc;
using namespace bsc::repl;

//===----------------------------------------------------------------------===//
// Loading
//===----------------------------------------------------------------------===//

Repl::~Repl() {
  for (Slot &V : Variables)
    destroySlot(V);
  destroyBreakpoints();
  // The sessions go before the descriptors they write the world's output to.
  S = nullptr;
  Robots.reset();
  for (int Fd : {WorldOutputFd, QuietFd})
    if (Fd >= 0)
      close(Fd);
}

bool Repl::colors() const {
  return &Err == &llvm::errs() && llvm::WithColor(llvm::errs()).colorsEnabled();
}

void Repl::flushDiagnostics() {
  OS.flush();
  if (!C)
    return;
  printDiagnostics(C->SM, C->Diags.getDiagnostics(), Err, colors());
  Err.flush();
  C->Diags.clear();
}

std::unique_ptr<Compilation> Repl::compileFiles() {
  auto NewC = std::make_unique<Compilation>();
  if (!runFrontend(*NewC, Frontend) ||
      !findProgramEntry(*NewC, Opts.EntryName)) {
    printDiagnostics(NewC->SM, NewC->Diags.getDiagnostics(), Err, colors());
    return nullptr;
  }
  return NewC;
}

/// Whether a task's frame has the same fields, in order, in both layouts,
/// the task as many yields and its resume point and state the same widths:
/// then its bytes mean the same in the new state.
static bool sameFrame(const BehaviorLayout::Task &A,
                      const BehaviorLayout::Task &B) {
  // The resume point numbers the yields: a task with more or fewer yields
  // would resume somewhere else.
  if (A.FrameSize != B.FrameSize || A.Fields.size() != B.Fields.size() ||
      A.Decl->Yields.size() != B.Decl->Yields.size() ||
      A.OnlyRunningStates != B.OnlyRunningStates ||
      A.Resume.Bytes != B.Resume.Bytes || A.State.Bytes != B.State.Bytes)
    return false;
  for (size_t I = 0; I < A.Fields.size(); ++I) {
    const BehaviorLayout::FrameField &FA = A.Fields[I], &FB = B.Fields[I];
    if (FA.D->getName().Name != FB.D->getName().Name ||
        FA.Ty->getName() != FB.Ty->getName() ||
        FA.Offset - A.FrameOffset != FB.Offset - B.FrameOffset)
      return false;
  }
  return true;
}

bool Repl::load(std::unique_ptr<Compilation> NewC) {
  const CallableDecl *Entry = findProgramEntry(*NewC, Opts.EntryName);
  LoadOptions LOpts = Opts.Load;
  LOpts.ExternalFunctions = true;
  LOpts.Explain = true;  // :why
  LOpts.Coverage = true; // :coverage
  auto Loaded = loadBehavior(*NewC, *Entry, LOpts);
  if (!Loaded) {
    reportInternalError(Loaded.takeError());
    return false;
  }
  if (!*Loaded) {
    printDiagnostics(NewC->SM, NewC->Diags.getDiagnostics(), Err, colors());
    return false;
  }
  auto NewTeam = Team::start(*NewC, **Loaded, Opts.Robots);
  if (!NewTeam || !*NewTeam) {
    if (!NewTeam)
      reportInternalError(NewTeam.takeError());
    printDiagnostics(NewC->SM, NewC->Diags.getDiagnostics(), Err, colors());
    return false;
  }
  std::unique_ptr<LoadedBehavior> NewL = std::move(*Loaded);
  std::unique_ptr<Team> NewRobots = std::move(*NewTeam);
  auto NewValues = std::make_unique<debug::ValueIO>(
      [J = NewL->JIT.get()](llvm::StringRef Sym) { return J->lookup(Sym); });
  bool FirstLoad = !S;
  if (S) // One robot: :reload is refused for a team (oneRobot).
    carryOver(*NewL, (*NewRobots)[0], *NewValues);
  // `:frame` stays on a task of the same name.
  std::string FrameTask = Checker && Checker->getFrame()
                              ? Checker->getFrame()->getQualifiedName()
                              : "";
  // The old session ends before its JIT, the JIT before its compilation.
  S = nullptr;
  Robots = std::move(NewRobots);
  S = &(*Robots)[Selected];
  Checker.reset();
  Values = std::move(NewValues);
  L = std::move(NewL);
  C = std::move(NewC);
  makeChecker(FrameTask);
  startHistory();
  if (Recording && !FirstLoad) {
    // A recording names one behavior (its header): cycles of the reloaded
    // one would not replay as recorded.
    stopRecording();
    OS << "recording stopped: it names the behavior as it was; ':record "
          "FILE' records the reloaded one\n";
  }
  EntryIndex.reset();
  for (unsigned T = 0; T < L->Layout.Tasks.size(); ++T)
    if (L->Layout.Tasks[T].Decl == L->Entry)
      EntryIndex = T;
  return !FirstLoad || attachWorld();
}

void Repl::carryOver(const LoadedBehavior &NewL, BehaviorSession &NewS,
                     debug::ValueIO &NewValues) {
  NewS.takeWorldFrom(*S);
  OS.flush();
  auto *OldBytes = static_cast<unsigned char *>(S->getState());
  auto *NewBytes = static_cast<unsigned char *>(NewS.getState());
  std::vector<std::string> Reset;
  for (const BehaviorLayout::Task &NT : NewL.Layout.Tasks) {
    std::string Name = NT.Decl->getQualifiedName();
    bool Kept = false;
    for (const BehaviorLayout::Task &OT : L->Layout.Tasks) {
      if (OT.Decl->getQualifiedName() != Name || !sameFrame(OT, NT))
        continue;
      std::memcpy(NewBytes + NT.FrameOffset, OldBytes + OT.FrameOffset,
                  OT.FrameSize);
      // Narrow resume points and states sit outside the frame.
      std::memcpy(NewBytes + NT.Resume.Offset, OldBytes + OT.Resume.Offset,
                  NT.Resume.Bytes);
      std::memcpy(NewBytes + NT.State.Offset, OldBytes + OT.State.Offset,
                  NT.State.Bytes);
      // The values moved: the old state must not destroy them.
      std::memset(OldBytes + OT.FrameOffset, 0, OT.FrameSize);
      Kept = true;
    }
    if (!Kept)
      Reset.push_back(Name);
  }
  auto *OldHeader = static_cast<bs_state_header *>(S->getState());
  static_cast<bs_state_header *>(NewS.getState())->cycle = OldHeader->cycle;
  if (L->InputClass && NewL.InputClass)
    llvm::consumeError(NewValues.writeClass(
        *NewL.InputClass, NewS.getInput(),
        Values->readClass(*L->InputClass, S->getInput()), "input"));
  if (L->OutputClass && NewL.OutputClass)
    llvm::consumeError(NewValues.writeClass(
        *NewL.OutputClass, NewS.getOutput(),
        Values->readClass(*L->OutputClass, S->getOutput()), "output"));
  OS << "reloaded; "
     << (Reset.empty() ? std::string("every task keeps its state")
                       : "reset: " + llvm::join(Reset, ", "))
     << "\n";
  if (!Variables.empty() || !Breakpoints.empty())
    OS << "REPL variables and breakpoints were cleared\n";
  for (Slot &V : Variables)
    destroySlot(V);
  Variables.clear();
  destroyBreakpoints();
}

void Repl::makeChecker(llvm::StringRef FrameTask) {
  Checker = makeLineChecker(*C, *L, FrameTask);
}

bool Repl::attachWorld() {
  if (!Opts.WorldOutput.empty()) {
    WorldOutputFd = openWorldOutput(*C, Opts.WorldOutput);
    if (WorldOutputFd < 0) {
      printDiagnostics(C->SM, C->Diags.getDiagnostics(), Err, colors());
      return false;
    }
    Robots->setWorldOutput(WorldOutputFd);
  }
  if (!Opts.WorldLibrary.empty() &&
      !Robots->attachWorld(*C, *L, Opts.WorldLibrary, Opts.CycleLimitMs)) {
    printDiagnostics(C->SM, C->Diags.getDiagnostics(), Err, colors());
    return false;
  }
  return true;
}

bool Repl::start() {
  std::unique_ptr<Compilation> NewC = compileFiles();
  return NewC && load(std::move(NewC));
}

void Repl::cmdReload(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (!noArgs("reload", Args, Loc) || !oneRobot(":reload", Loc))
    return;
  std::unique_ptr<Compilation> NewC = compileFiles();
  if (!NewC || !load(std::move(NewC))) {
    C->Diags.report(llvm::SMLoc(), diag::err_repl_reload_failed);
    flushDiagnostics();
  }
}

//===----------------------------------------------------------------------===//
// Lines of b-script
//===----------------------------------------------------------------------===//

void Repl::requireModule(llvm::StringRef Line, llvm::SMLoc Loc) {
  llvm::StringRef Name = Line.drop_front(8).trim();
  llvm::SMLoc NameLoc = Loc.getFromPointer(Loc.getPointer() +
                                           (Line.size() - Name.size()));
  if (!Name.consume_front("\"") || !Name.consume_back("\"") ||
      Name.empty() || Name.contains('"')) {
    C->Diags.report(NameLoc, diag::err_expected_after)
        << "a module name in quotes" << "'requires'";
    flushDiagnostics();
    return;
  }
  bool Loaded = C->Natives.find(Name);
  for (const ModuleAST *M : C->Checked.Modules)
    Loaded |= M->Name == Name;
  if (Loaded) {
    OS << "module " << Name << " is loaded: its names are reachable as "
       << Name << "::name\n";
    return;
  }
  if (!oneRobot("requires", Loc)) { // Loading a module is a :reload.
    flushDiagnostics();
    return;
  }
  std::string Searched;
  std::string Path = findScriptModule(*L->Entry->Module, Name,
                                      Frontend.IncludeDirs, Searched);
  if (Path.empty()) {
    C->Diags.report(NameLoc, diag::err_unknown_module) << Name << Searched;
    flushDiagnostics();
    return;
  }
  Frontend.Inputs.push_back(Path);
  std::unique_ptr<Compilation> NewC = compileFiles();
  if (!NewC || !load(std::move(NewC))) {
    Frontend.Inputs.pop_back();
    C->Diags.report(llvm::SMLoc(), diag::err_repl_reload_failed);
    flushDiagnostics();
    return;
  }
  OS << "loaded module " << Name << " from " << Path << "\n";
}

llvm::SMLoc Repl::addBuffer(llvm::StringRef Text) {
  unsigned ID = C->SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(Text, "<repl>"), llvm::SMLoc());
  return llvm::SMLoc::getFromPointer(
      C->SM.getMemoryBuffer(ID)->getBufferStart());
}

void Repl::destroySlot(Slot &Sl) { bsc::destroySlot(L.get(), Sl); }

std::optional<CompiledLine> Repl::compileLine(llvm::StringRef Text) {
  return bsc::compileLine(*C, *L, *Checker, Text, "<repl>", ++LineNo,
                          Variables);
}

std::optional<LineValue> Repl::runLine(llvm::StringRef Line) {
  std::optional<CompiledLine> R = compileLine(Line);
  if (!R)
    return std::nullopt;
  std::vector<unsigned char> Before = copyBlocks();
  BehaviorSession::Outcome O = S->runGuarded(R->Fn, Opts.CycleLimitMs);
  noteEdits(Before);
  if (!reportOutcome(*C, *L, O, S->getCycle(), Opts.CycleLimitMs)) {
    flushDiagnostics();
    OS << "the line was stopped; the state is as it left it\n";
    destroySlot(R->Result);
    return std::nullopt;
  }
  LineValue V;
  if (R->Result.Ptr) {
    V.Ty = R->Result.Ty;
    V.Value = Values->read(R->Result.Ty, R->Result.Ptr);
  }
  destroySlot(R->Result);
  return V;
}

void Repl::evaluate(llvm::StringRef Line) {
  std::optional<LineValue> V = runLine(Line);
  flushDiagnostics();
  if (V && V->Ty)
    OS << "(" << V->Ty->getName() << ") " << formatValue(V->Ty, V->Value)
       << "\n";
}

bool Repl::handleLine(llvm::StringRef Line) {
  llvm::StringRef Text = Line.trim();
  if (Text.empty() || Text.starts_with("#"))
    return true;
  if (Text.starts_with("requires") &&
      (Text.size() == 8 || !(llvm::isAlnum(Text[8]) || Text[8] == '_'))) {
    requireModule(Text, addBuffer(Text));
    OS.flush();
    return true;
  }
  if (!Text.consume_front(":")) {
    evaluate(Text);
    OS.flush();
    return true;
  }
  llvm::SMLoc Loc = addBuffer(":" + Text.str());
  auto [Name, Args] = Text.split(' ');
  if (Name == "quit" || Name == "q")
    return false;
  command(Name, Args.trim(), Loc);
  OS.flush();
  return true;
}

std::vector<llvm::LineEditor::Completion>
Repl::complete(llvm::StringRef Buffer, size_t Pos) const {
  std::vector<llvm::LineEditor::Completion> Result;
  llvm::StringRef Before = Buffer.substr(0, Pos);
  size_t WordStart = Before.find_last_of(" (,=+-*/<>!&|");
  llvm::StringRef Word =
      WordStart == llvm::StringRef::npos ? Before : Before.substr(WordStart + 1);
  std::vector<std::string> Candidates;
  if (Word.starts_with(":")) {
    for (const CommandInfo &Cmd : getCommands())
      Candidates.push_back(":" + std::string(Cmd.Name));
  } else if (Word.contains('.')) {
    // Members of `input.` / `output.` chains, by the world's classes.
    auto [Base, Partial] = Word.rsplit('.');
    const NativeClass *Class = nullptr;
    llvm::SmallVector<llvm::StringRef, 4> Parts;
    Base.split(Parts, '.');
    if (Parts[0] == "input")
      Class = L->InputClass;
    else if (Parts[0] == "output")
      Class = L->OutputClass;
    for (size_t I = 1; Class && I < Parts.size(); ++I) {
      const NativeFunction *M = Class->findMember(Parts[I]);
      Class = M ? M->Result.TheClass : nullptr;
    }
    if (Class)
      for (const NativeFunction &M : Class->Members)
        Candidates.push_back((Base + "." + M.Name).str());
    // `Striker.`: the task's parameters and locals.
    if (Parts.size() == 1 && Parts[0] != "input" && Parts[0] != "output")
      if (std::optional<unsigned> T = findTask(Parts[0]))
        for (const BehaviorLayout::FrameField &F : L->Layout.Tasks[*T].Fields)
          Candidates.push_back((Base + "." + F.D->getName().Name).str());
  } else {
    for (const debug::DebugTables::Task &T : L->Tables.Tasks)
      Candidates.push_back(T.ShortName);
    for (const ModuleAST *M : C->Checked.Modules)
      Candidates.push_back(M->Name + "::");
    for (const NativeModule *M : C->Checked.NativeModules)
      Candidates.push_back(M->Name + "::");
    Candidates.insert(Candidates.end(), {"input", "output"});
  }
  for (const std::string &Cand : Candidates)
    if (llvm::StringRef(Cand).starts_with(Word))
      Result.emplace_back(Cand.substr(Word.size()), Cand);
  return Result;
}

//===----------------------------------------------------------------------===//
// Entry
//===----------------------------------------------------------------------===//

int bsc::runRepl(const ReplOptions &Opts, llvm::raw_ostream &OS) {
  Repl R(Opts, OS);
  if (!R.start())
    return 1;
  // A terminal gets a prompt with history and completion; anything else
  // (a pipe, a file, --batch) runs as a batch with no prompt.
  std::unique_ptr<llvm::MemoryBuffer> Batch;
  if (!Opts.BatchFile.empty()) {
    auto Buf = llvm::MemoryBuffer::getFile(Opts.BatchFile);
    if (!Buf) {
      llvm::WithColor::error(llvm::errs(), "bsc")
          << "cannot open '" << Opts.BatchFile
          << "': " << Buf.getError().message() << "\n";
      return 1;
    }
    Batch = std::move(*Buf);
  } else if (!llvm::sys::Process::StandardInIsUserInput()) {
    // Line by line, answering each before reading the next, so that a
    // program can hold a conversation through a pipe.
    std::string Line;
    char Buf[4096];
    while (std::fgets(Buf, sizeof Buf, stdin)) {
      Line += Buf;
      if (Line.back() != '\n' && !std::feof(stdin))
        continue;
      if (!R.handleLine(llvm::StringRef(Line).rtrim("\r\n")))
        break;
      Line.clear();
    }
    return 0;
  }
  if (Batch) {
    llvm::SmallVector<llvm::StringRef, 0> Lines;
    Batch->getBuffer().split(Lines, '\n');
    for (llvm::StringRef Line : Lines)
      if (!R.handleLine(Line.rtrim('\r')))
        break;
    return 0;
  }
  llvm::SmallString<256> History;
  if (llvm::sys::path::home_directory(History))
    llvm::sys::path::append(History, ".bsc_history");
  llvm::LineEditor LE("bsc", History);
  LE.setPrompt("bsc> ");
  LE.setListCompleter([&R](llvm::StringRef Buffer, size_t Pos) {
    return R.complete(Buffer, Pos);
  });
  OS << "bsc repl: ':help' lists the commands, ':quit' leaves\n";
  while (std::optional<std::string> Line = LE.readLine())
    if (!R.handleLine(*Line))
      break;
  return 0;
}

