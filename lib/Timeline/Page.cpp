//===- Page.cpp - the timeline page: the page's template and the data -----===//
//
// The data is the page's format (docs/repl.md, "The timeline's data"):
// strings that repeat (states, places) once in a table, segments as flat
// integer arrays, values as changes. It is JSON inside a <script> element,
// so every `<` in it is written `\u003c`: no text in a recording can end
// the element.
//
//===----------------------------------------------------------------------===//
#include "TimelineImpl.h"
#include "bsc/Debug/Values.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/raw_ostream.h"
#include <functional>
#include <map>
#include <set>

#include "TimelinePage.inc"

using namespace bsc;
using namespace bsc::timeline;

namespace {
/// The version of the data the page's script reads.
constexpr int DataFormat = 1;

class DataWriter {
public:
  DataWriter(llvm::raw_ostream &OS) : J(OS) {}

  void write(llvm::ArrayRef<const Run *> Runs,
             const std::optional<Difference> &Diff) {
    chooseShortNames(Runs);
    J.object([&] {
      J.attribute("format", DataFormat);
      J.attributeArray("runs", [&] {
        for (const Run *R : Runs)
          writeRun(*R);
      });
      // After the runs, which fill it.
      J.attributeArray("strings", [&] {
        for (const std::string &S : Strings)
          J.value(S);
      });
      J.attributeBegin("difference");
      if (Diff)
        J.object([&] {
          J.attribute("cycle", int64_t(Diff->Cycle));
          J.attributeArray("notes", [&] {
            for (const std::string &N : Diff->Notes)
              J.value(N);
          });
        });
      else
        J.value(nullptr);
      J.attributeEnd();
    });
  }

private:
  /// A task's label: its name without the module, unless another task of
  /// the runs has that name too.
  void chooseShortNames(llvm::ArrayRef<const Run *> Runs) {
    std::map<std::string, std::set<std::string>> Qualified;
    for (const Run *R : Runs)
      for (const TaskLane &T : R->Tasks)
        Qualified[llvm::StringRef(T.Name).rsplit("::").second.str()].insert(
            T.Name);
    for (const auto &[Short, Names] : Qualified)
      for (const std::string &Name : Names)
        ShortName[Name] = Names.size() == 1 && !Short.empty() ? Short : Name;
  }

  int64_t intern(const std::string &S) {
    auto [It, New] = StringIndex.try_emplace(S, Strings.size());
    if (New)
      Strings.push_back(S);
    return It->second;
  }

  static const char *kindOf(const Series &S) {
    bool Numbers = false, Bools = false, Other = false;
    for (const llvm::json::Value &V : S.Values) {
      if (V.getAsNumber())
        Numbers = true;
      else if (V.getAsBoolean())
        Bools = true;
      else if (std::optional<llvm::StringRef> Str = V.getAsString();
               Str && (*Str == "NaN" || *Str == "Infinity" ||
                       *Str == "-Infinity"))
        continue; // A non-finite float, of a number's series.
      else if (V.kind() != llvm::json::Value::Null)
        Other = true;
    }
    if (Numbers && !Bools && !Other)
      return "number";
    if (Bools && !Numbers && !Other)
      return "bool";
    return "string";
  }

  /// `Path` names it on the page (a task field by its lane's label).
  void writeSeries(const Series &S, llvm::StringRef Path) {
    J.object([&] {
      J.attribute("path", Path);
      J.attribute("kind", kindOf(S));
      J.attributeArray("changes", [&] {
        for (size_t I = 0; I < S.Values.size(); ++I) {
          J.value(int64_t(S.ChangeCycles[I]));
          // Floats in their shortest round-trip form, as recorded.
          J.rawValue([&](llvm::raw_ostream &OS) {
            debug::printJSON(OS, S.Values[I]);
          });
        }
      });
    });
  }

  void writeTask(const TaskLane &T) {
    J.object([&] {
      J.attribute("name", T.Name);
      J.attribute("short", ShortName[T.Name]);
      J.attributeArray("segments", [&] {
        for (const Segment &S : T.Segments) {
          J.value(int64_t(S.Start));
          J.value(int64_t(S.End));
          J.value(intern(S.State));
          J.value(S.Place.empty() ? -1 : intern(S.Place));
          J.value(S.Parent);
        }
      });
      J.attributeArray("fields", [&] {
        for (const TaskLane::Field &F : T.Fields)
          J.object([&] {
            J.attribute("name", F.Name);
            J.attribute("param", F.IsParam);
            J.attributeBegin("series");
            writeSeries(F.Values, ShortName[T.Name] + "." + F.Name);
            J.attributeEnd();
          });
      });
    });
  }

  void writeRun(const Run &R) {
    J.object([&] {
      J.attribute("name", R.Name);
      J.attribute("kind", R.FromRobotLog ? "robot log" : "record");
      J.attribute("record", int64_t(R.Record));
      if (R.Robot >= 0)
        J.attribute("robot", int64_t(R.Robot));
      J.attributeArray("cycles", [&] {
        for (const auto &[First, Last] : R.Cycles)
          J.array([&] {
            J.value(int64_t(First));
            J.value(int64_t(Last));
          });
      });
      J.attributeArray("tasks", [&] {
        for (const TaskLane &T : R.Tasks)
          writeTask(T);
      });
      J.attributeArray("series", [&] {
        for (const Series &S : R.Leaves)
          writeSeries(S, S.Path);
      });
    });
  }

  llvm::json::OStream J;
  std::map<std::string, std::string> ShortName;
  std::vector<std::string> Strings;
  llvm::StringMap<int64_t> StringIndex;
};

/// Writes to `OS` with every `<` as `\u003c` (valid in JSON only inside
/// strings, where it means `<`): the data streams into the page, whose
/// tens of megabytes for a long run were built in a string and copied.
class ScriptEscaper : public llvm::raw_ostream {
public:
  explicit ScriptEscaper(llvm::raw_ostream &OS) : OS(OS) {}
  ~ScriptEscaper() override { flush(); }

private:
  void write_impl(const char *Ptr, size_t Size) override {
    llvm::StringRef Text(Ptr, Size);
    Written += Size;
    for (size_t At; (At = Text.find('<')) != llvm::StringRef::npos;) {
      OS << Text.take_front(At) << "\\u003c";
      Text = Text.drop_front(At + 1);
    }
    OS << Text;
  }
  uint64_t current_pos() const override { return Written; }

  llvm::raw_ostream &OS;
  uint64_t Written = 0;
};

std::string escapeHTML(llvm::StringRef Text) {
  std::string Out;
  for (char C : Text) {
    switch (C) {
    case '<': Out += "&lt;"; break;
    case '>': Out += "&gt;"; break;
    case '&': Out += "&amp;"; break;
    case '"': Out += "&quot;"; break;
    default: Out += C;
    }
  }
  return Out;
}
} // namespace

void timeline::writePage(llvm::raw_ostream &OS,
                         llvm::ArrayRef<const Run *> Runs,
                         const std::optional<Difference> &Diff) {
  std::vector<std::string> Names;
  for (const Run *R : Runs)
    Names.push_back(R->Name);
  std::string Title = escapeHTML(llvm::join(Names, " vs ") + " - bsc timeline");

  // One pass over the template: a marker's text inside the data or the
  // script is not a marker.
  using Filler = std::function<void()>;
  const std::pair<llvm::StringRef, Filler> Fills[] = {
      {"@BSC_TIMELINE_TITLE@", [&] { OS << Title; }},
      {"@BSC_TIMELINE_DATA@",
       [&] {
         ScriptEscaper Escaped(OS);
         DataWriter(Escaped).write(Runs, Diff);
       }},
      {"@BSC_TIMELINE_SCRIPT@", [&] { OS << PageScript; }}};
  llvm::StringRef Rest = PageHTML;
  while (!Rest.empty()) {
    size_t At = Rest.find("@BSC_TIMELINE_");
    const std::pair<llvm::StringRef, Filler> *Fill = nullptr;
    for (const auto &F : Fills)
      if (At != llvm::StringRef::npos && Rest.substr(At).starts_with(F.first))
        Fill = &F;
    if (!Fill) {
      OS << Rest.take_front(At == llvm::StringRef::npos ? Rest.size() : At + 1);
      Rest = Rest.drop_front(At == llvm::StringRef::npos ? Rest.size() : At + 1);
      continue;
    }
    OS << Rest.take_front(At);
    Fill->second();
    Rest = Rest.drop_front(At + Fill->first.size());
  }
}
