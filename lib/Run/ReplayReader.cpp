//===- ReplayReader.cpp - a recording read as its cycles come -------------===//
//
// A line is checked to be JSON without building values (bsc::isJSON),
// which also hands over its top-level members as text: `input` and
// `output` are kept as text for the runner, `cycle` and `tasks` skipped. A
// line that is not JSON is parsed whole, so that its error is the JSON
// parser's, at its byte.
//
//===----------------------------------------------------------------------===//
#include "ReplayReader.h"
#include "bsc/Basic/JSON.h"
#include "llvm/TargetParser/Host.h"
#include "llvm/TargetParser/Triple.h"

using namespace bsc;


bool ReplayReader::open(llvm::StringRef Path) {
  unsigned ID = addSourceFile(C, Path, MaxRecordingMiB);
  if (!ID)
    return false;
  Rest = C.SM.getMemoryBuffer(ID)->getBuffer();
  this->Path = Path.str();
  if (isBinaryLog(Rest))
    return openLog(Rest);
  // A file whose first line is not text, and does not start as JSON
  // within its first bytes, is neither: not worth a line of garbage under
  // a JSON error. (A recording damaged anywhere, even with bytes before its
  // first `{`, is reported at its line, after the cycles before it.)
  llvm::StringRef First = Rest.ltrim().split('\n').first;
  if ((First.contains('\0') || !llvm::json::isUTF8(First)) &&
      !First.take_front(16).contains('{')) {
    C.Diags.report(llvm::SMLoc(), diag::err_replay_not_log) << Path;
    return false;
  }
  // The header, on the first line that is not blank.
  for (llvm::StringRef Scan = Rest; !Scan.empty();) {
    auto [Raw, After] = Scan.split('\n');
    if (Raw.trim().empty()) {
      Scan = After;
      continue;
    }
    bool IsHeader = false;
    if (!readHeader(Raw, IsHeader))
      return false;
    if (IsHeader)
      Rest = After;
    break;
  }
  if (Rest.trim().empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_replay_empty) << Path;
    return false;
  }
  return true;
}

bool ReplayReader::openLog(llvm::StringRef Bytes) {
  Log.emplace();
  if (!Log->open(Bytes)) {
    C.Diags.report(llvm::SMLoc(), diag::err_log_damaged)
        << Path << Log->getError();
    return false;
  }
  const BinaryLogHeader &H = Log->getHeader();
  Header.Format = RecordingFormat; // With its calls.
  Header.Behavior = H.Behavior;
  Header.Entry = H.Entry;
  Header.Binary = true;
  Header.Assertions = H.Assertions;
  // The log's bytes are written into this workstation's objects as they
  // are: the two must be laid out alike.
  auto SizeOf = [](const NativeClass *C) { return C ? C->Size : 0; };
  if (H.Layout != getIOLayoutHash(C.Checked) ||
      H.InputSize != SizeOf(L.InputClass) ||
      H.OutputSize != SizeOf(L.OutputClass)) {
    // On this very target the classes themselves differ.
    llvm::Triple Host(llvm::sys::getProcessTriple());
    if (H.Target == Host.getArchName())
      C.Diags.report(llvm::SMLoc(), diag::err_log_other_world) << Path;
    else
      C.Diags.report(llvm::SMLoc(), diag::err_log_layout)
          << Path << H.Target << llvm::sys::getProcessTriple();
    return false;
  }
  if (!checkWorldAsBytes(C.Diags, llvm::SMLoc(), L, Path))
    return false;
  Log->setView(L.Layout.StateSize);
  return true;
}

bool ReplayReader::readHeader(llvm::StringRef Raw, bool &IsHeader) {
  std::optional<llvm::StringRef> Text;
  unsigned Members = 0;
  if (!isJSON(Raw, [&](llvm::StringRef Key, llvm::StringRef Value) {
        ++Members;
        if (Key == "recording")
          Text = Value;
      }) ||
      !Text)
    return true; // A cycle's line, or damage that next() reports.
  IsHeader = true;
  llvm::SMLoc Loc = llvm::SMLoc::getFromPointer(Raw.data());
  std::optional<llvm::json::Value> V = parseJSONLine(C.Diags, *Text);
  if (!V)
    return false;
  const llvm::json::Object *O = V->getAsObject();
  std::optional<int64_t> Format = O ? O->getInteger("format") : std::nullopt;
  if (Format && (*Format < 2 || *Format > RecordingFormat)) {
    C.Diags.report(Loc, diag::err_recording_format)
        << std::to_string(*Format) << RecordingFormat;
    return false;
  }
  std::optional<llvm::StringRef> Behavior, Entry;
  if (O) {
    Behavior = O->getString("behavior");
    Entry = O->getString("entry");
  }
  if (Members != 1 || !Format || !Behavior || !Entry || O->size() != 3) {
    C.Diags.report(Loc, diag::err_replay_value)
        << "a recording's header is {\"recording\":{\"format\":N,"
           "\"behavior\":\"HASH\",\"entry\":\"NAME\"}} and nothing else";
    return false;
  }
  Header.Format = unsigned(*Format);
  Header.Behavior = Behavior->str();
  Header.Entry = Entry->str();
  return true;
}

bool ReplayReader::next(ReplayLine &Line) {
  if (Log) {
    Line = ReplayLine();
    if (!Log->next(Logged)) {
      if (Log->failed()) {
        C.Diags.report(llvm::SMLoc(), diag::err_log_damaged)
            << Path << Log->getError();
        Failed = true;
      }
      return false;
    }
    if (Log->countRobots() > 1)
      Line.Robot = Logged.Robot;
    Line.Logged = &Logged;
    return true;
  }
  while (!Rest.empty()) {
    auto [Raw, After] = Rest.split('\n');
    Rest = After;
    if (Raw.trim().empty())
      continue;
    if (!read(Raw, Line)) {
      Failed = true;
      return false;
    }
    return true;
  }
  return false;
}

bool ReplayReader::reportDamaged(llvm::StringRef Raw) {
  std::optional<llvm::json::Value> V = parseJSONLine(C.Diags, Raw);
  if (V) // Valid JSON the scan refused: not an object of members.
    C.Diags.report(llvm::SMLoc::getFromPointer(Raw.data()),
                   diag::err_replay_not_object);
  return false;
}

bool ReplayReader::read(llvm::StringRef Raw, ReplayLine &Line) {
  Line = ReplayLine();
  Line.Loc = llvm::SMLoc::getFromPointer(Raw.data());
  llvm::SmallVector<std::pair<llvm::StringRef, llvm::StringRef>, 4> Members;
  if (!isJSON(Raw, [&](llvm::StringRef Key, llvm::StringRef Value) {
        Members.push_back({Key, Value});
      }) ||
      !Raw.ltrim().starts_with("{"))
    return reportDamaged(Raw);
  bool OK = true;
  for (auto [Key, Value] : Members) {
    if (Key == "input" || Key == "output") {
      if (!(Key == "input" ? L.InputClass : L.OutputClass)) {
        C.Diags.report(Line.Loc, diag::err_replay_no_world) << Key;
        OK = false;
        continue;
      }
      (Key == "input" ? Line.Input : Line.Output) = Value;
    } else if (Key == "robot") {
      unsigned Robot = 0;
      if (Value.trim().getAsInteger(10, Robot)) {
        C.Diags.report(Line.Loc, diag::err_replay_value)
            << "'robot' must be a robot's number, 0 or more";
        OK = false;
      }
      Line.Robot = Robot;
    } else if (Key == "calls") {
      Line.Calls = Value;
    } else if (Key == "tasks") {
      Line.Tasks = Value;
    } else if (Key == "recording") {
      C.Diags.report(Line.Loc, diag::err_replay_value)
          << "a recording's header ('recording') belongs on its first line "
             "(were two recordings written to one file?)";
      OK = false;
    } else if (Key != "cycle") {
      C.Diags.report(Line.Loc, diag::err_replay_unknown_key) << Key;
      OK = false;
    }
  }
  return OK;
}

/// The `robot` member of a line, if it has one that is a number.
static std::optional<unsigned> findRobot(llvm::StringRef Raw) {
  std::optional<unsigned> Robot;
  isJSON(Raw, [&](llvm::StringRef Key, llvm::StringRef Value) {
    unsigned N;
    if (Key == "robot" && !Value.trim().getAsInteger(10, N))
      Robot = N;
  });
  return Robot;
}

unsigned ReplayReader::countRobots() const {
  if (Log)
    return Log->countRobots();
  unsigned Robots = 0;
  for (llvm::StringRef Rest = this->Rest; !Rest.empty();) {
    auto [Raw, After] = Rest.split('\n');
    Rest = After;
    if (Raw.trim().empty())
      continue;
    std::optional<unsigned> Robot = findRobot(Raw);
    if (!Robot || *Robot != Robots)
      break;
    ++Robots;
  }
  return std::max(Robots, 1u);
}
