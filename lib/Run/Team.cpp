//===- Team.cpp - `--robots N`: sessions of one behavior and their world --===//
//
// A team is N sessions of one loaded behavior in one process, as a
// simulator of a whole team runs them: each robot has its own state, input,
// output and user pointer. A world library feeds them: a robot world
// (bs_world_*) once per robot, each robot in a world of its own, or a team
// world (bs_team_*, bscript/world.h) that simulates them all and gets the
// robot's index in its hooks.
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/Run.h"
#include "llvm/Support/DynamicLibrary.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/WithColor.h"

using namespace bsc;

void bsc::noteRobot(Compilation &C, unsigned Robot, unsigned Robots) {
  if (Robots > 1)
    C.Diags.report(llvm::SMLoc(), diag::note_team_robot) << Robot << Robots;
}

llvm::Expected<std::unique_ptr<Team>>
Team::start(Compilation &C, LoadedBehavior &L, unsigned Robots) {
  std::unique_ptr<Team> T(new Team());
  for (unsigned K = 0; K < Robots; ++K) {
    auto S = startSession(C, L);
    if (!S)
      return S.takeError();
    if (!*S)
      return nullptr;
    T->Robots.push_back(std::move(*S));
  }
  return T;
}

Team::~Team() {
  // The team's world ends first, while every robot's state still lives.
  if (TeamHooks.TeamExit && !Robots.empty())
    Robots.front()->runWorldHook(
        "bs_team_exit", [&] { TeamHooks.TeamExit(TeamUser); }, 0);
  // In index order, as they started.
  for (std::unique_ptr<BehaviorSession> &S : Robots)
    S.reset();
}

std::vector<BehaviorSession *> Team::getSessions() const {
  std::vector<BehaviorSession *> Sessions;
  for (const std::unique_ptr<BehaviorSession> &S : Robots)
    Sessions.push_back(S.get());
  return Sessions;
}

bool Team::grow(Compilation &C, LoadedBehavior &L, unsigned N) {
  while (Robots.size() < N) {
    auto S = startSession(C, L);
    if (!S) {
      // Not the user's: the first session started from the same code.
      reportInternalError(S.takeError());
      return false;
    }
    if (!*S)
      return false;
    Robots.push_back(std::move(*S));
    // A robot that joins gets the team's world (its user pointer) and its
    // output, as the first ones did.
    BehaviorSession &New = *Robots.back();
    New.setWorldOutput(WorldOutputFd);
    if (!World.Init && !World.isTeam())
      continue;
    unsigned K = Robots.size() - 1;
    BehaviorSession::Outcome O =
        World.isTeam() ? New.attachTeamWorld(World, TeamUser, K, LimitMs)
                       : New.attachWorld(World, LimitMs, K, N);
    if (!reportOutcome(C, L, O, 0, LimitMs)) {
      noteRobot(C, K, N);
      return false;
    }
  }
  return true;
}

void Team::setWorldOutput(int Fd) {
  WorldOutputFd = Fd;
  for (std::unique_ptr<BehaviorSession> &S : Robots)
    S->setWorldOutput(Fd);
}

/// Loads world library `Path` and finds its hooks: a team world's if it
/// exports bs_team_init, else a robot world's. False after reporting.
static bool loadWorldHooks(Compilation &C, llvm::StringRef Path,
                           WorldHooks &H) {
  // By absolute path, as --bind loads a library: dlopen looks for a bare
  // name in the library path, not in the current folder.
  llvm::SmallString<256> Abs(Path);
  llvm::sys::fs::make_absolute(Abs);
  std::string Err;
  llvm::sys::DynamicLibrary Lib =
      llvm::sys::DynamicLibrary::getPermanentLibrary(Abs.c_str(), &Err);
  if (!Lib.isValid()) {
    C.Diags.report(llvm::SMLoc(), diag::err_world_load) << Path << Err;
    return false;
  }
  bool Team = Lib.getAddressOfSymbol("bs_team_init");
  auto Find = [&](const char *Name, auto &Slot, bool Required) {
    Slot = reinterpret_cast<std::remove_reference_t<decltype(Slot)>>(
        Lib.getAddressOfSymbol(Name));
    if (!Slot && Required)
      C.Diags.report(llvm::SMLoc(), Team ? diag::err_team_world_missing_hook
                                         : diag::err_world_missing_hook)
          << Path << Name;
    return Slot || !Required;
  };
  if (Team) {
    Find("bs_team_init", H.TeamInit, true);
    Find("bs_team_robot", H.TeamRobot, false);
    Find("bs_team_end", H.TeamEnd, false);
    Find("bs_team_exit", H.TeamExit, false);
    return Find("bs_team_begin", H.TeamBegin, true);
  }
  bool OK = Find("bs_world_init", H.Init, true);
  OK &= Find("bs_world_begin", H.Begin, true);
  Find("bs_world_end", H.End, false);
  Find("bs_world_exit", H.Exit, false);
  Find("bs_world_robot", H.Robot, false);
  return OK;
}

bool Team::attachWorld(Compilation &C, const LoadedBehavior &L,
                       llvm::StringRef Path, unsigned Limit) {
  WorldHooks H;
  if (!loadWorldHooks(C, Path, H))
    return false;
  LimitMs = Limit;
  World = H;
  unsigned N = size();
  if (H.isTeam()) {
    BehaviorSession &First = *Robots.front();
    BehaviorSession::Outcome O = First.runWorldHook(
        "bs_team_init", [&] { TeamUser = H.TeamInit(N); }, Limit);
    if (!reportOutcome(C, L, O, 0, Limit))
      return false;
    // From here on the team's exit runs when the team ends.
    TeamHooks = H;
  }
  for (unsigned K = 0; K < N; ++K) {
    BehaviorSession::Outcome O =
        H.isTeam() ? Robots[K]->attachTeamWorld(H, TeamUser, K, Limit)
                   : Robots[K]->attachWorld(H, Limit, K, N);
    if (!reportOutcome(C, L, O, 0, Limit)) {
      noteRobot(C, K, N);
      return false;
    }
  }
  return true;
}
