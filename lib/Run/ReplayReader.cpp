//===- ReplayReader.cpp - a recording read as its cycles come -------------===//
//
// A line is checked to be JSON without building values (bsc::isJSON), then
// its top-level object is scanned for where each member's value starts and
// ends; `input` and `output` are parsed with bsc::parseJSON, `cycle` and
// `tasks` skipped. A line that is not JSON is parsed whole, so that its
// error is the JSON parser's, at its byte.
//
//===----------------------------------------------------------------------===//
#include "ReplayReader.h"
#include "bsc/Basic/JSON.h"

using namespace bsc;

namespace {
/// A scan over a line already known to be JSON: where each member of the
/// top-level object starts and ends.
struct Scanner {
  llvm::StringRef Text;
  size_t At = 0;

  void skipSpace() {
    while (At < Text.size() && llvm::StringRef(" \t\r").contains(Text[At]))
      ++At;
  }
  bool eat(char C) {
    skipSpace();
    if (At < Text.size() && Text[At] == C)
      return ++At, true;
    return false;
  }
  void string() {
    for (++At; At < Text.size(); ++At) {
      if (Text[At] == '\\')
        ++At;
      else if (Text[At] == '"')
        return void(++At);
    }
  }
  /// The value at At: a string, a bracketed value, or a scalar.
  llvm::StringRef value() {
    skipSpace();
    size_t Start = At;
    if (Text[At] == '"') {
      string();
    } else if (Text[At] == '{' || Text[At] == '[') {
      size_t Depth = 0;
      do {
        if (Text[At] == '"') {
          string();
          continue;
        }
        Depth += Text[At] == '{' || Text[At] == '[';
        Depth -= Text[At] == '}' || Text[At] == ']';
        ++At;
      } while (Depth);
    } else {
      while (At < Text.size() && !llvm::StringRef(",}] \t\r").contains(Text[At]))
        ++At;
    }
    return Text.slice(Start, At);
  }
};
} // namespace

bool ReplayReader::open(llvm::StringRef Path) {
  unsigned ID = addSourceFile(C, Path, MaxRecordingMiB);
  if (!ID)
    return false;
  Rest = C.SM.getMemoryBuffer(ID)->getBuffer();
  if (Rest.trim().empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_replay_empty) << Path;
    return false;
  }
  return true;
}

bool ReplayReader::next(ReplayLine &Line) {
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
  if (!isJSON(Raw) || !Raw.ltrim().starts_with("{"))
    return reportDamaged(Raw);
  Scanner S{Raw};
  S.eat('{');
  bool OK = true;
  for (bool First = true; !S.eat('}'); First = false) {
    if (!First)
      S.eat(',');
    S.skipSpace();
    size_t KeyStart = S.At;
    S.string();
    llvm::StringRef Key = Raw.slice(KeyStart + 1, S.At - 1);
    S.eat(':');
    llvm::StringRef Value = S.value();
    if (Key == "input" || Key == "output") {
      if (!(Key == "input" ? L.InputClass : L.OutputClass)) {
        C.Diags.report(Line.Loc, diag::err_replay_no_world) << Key;
        OK = false;
        continue;
      }
      std::optional<llvm::json::Value> V = parseJSONLine(C.Diags, Value);
      if (!V)
        return false;
      (Key == "input" ? Line.Input : Line.Output) = std::move(*V);
    } else if (Key != "cycle" && Key != "tasks") {
      C.Diags.report(Line.Loc, diag::err_replay_unknown_key) << Key;
      OK = false;
    }
  }
  return OK;
}
