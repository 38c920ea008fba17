//===- Coverage.cpp - what the runs exercised: lcov and a summary ---------===//
//
// The JIT's counters (CodeGenOptions::Coverage, lib/CodeGen/CGCoverage.cpp)
// read after a run, summed over the logs of a replay, and written as an
// lcov tracefile (the format of `geninfo`, which `lcov` merges and
// `genhtml` renders):
//
//   SF:<absolute path of a module's file>
//   FN:<line>,<Module::task>   FNDA:<calls>,<Module::task>   FNF/FNH
//   BRDA:<line>,<k>,<0 true|1 false>,<count or - if never evaluated>
//   DA:<line>,<runs of its statements (the most of any)>   LF/LH
//   end_of_record
//
// and as a summary of what a corpus never did: tasks never active, yields
// never reached, named task states never taken.
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/Run.h"
#include "bsc/Basic/Output.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Format.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/ToolOutputFile.h"
#include <map>

using namespace bsc;

std::vector<uint64_t> bsc::readCoverage(const LoadedBehavior &L) {
  const auto *Counters =
      static_cast<const uint64_t *>(L.JIT->lookup(CoverageCountersSymbol));
  if (!Counters)
    return {};
  return std::vector<uint64_t>(Counters,
                               Counters + L.Layout.CoverageSites.size());
}

void bsc::clearCoverage(const LoadedBehavior &L) {
  if (auto *Counters =
          static_cast<uint64_t *>(L.JIT->lookup(CoverageCountersSymbol)))
    std::fill(Counters, Counters + L.Layout.CoverageSites.size(), 0);
}

namespace {
/// One source file's records.
struct FileRecords {
  struct Function {
    unsigned Line;
    std::string Name;
    uint64_t Calls;
  };
  std::vector<Function> Functions;
  std::map<unsigned, uint64_t> Lines; ///< Line -> the most runs of a statement.
  /// Line -> each condition's (true, false) counts, in the order emitted.
  std::map<unsigned, std::vector<std::pair<uint64_t, uint64_t>>> Branches;
};

/// The counters sorted by file and line.
class CoverageMap {
public:
  CoverageMap(const llvm::SourceMgr &SM, const BehaviorLayout &Layout,
              llvm::ArrayRef<uint64_t> Counts);
  std::map<std::string, FileRecords> Files;

private:
  /// Where `Loc` is: the absolute file and the line; empty if unknown.
  std::pair<std::string, unsigned> place(llvm::SMLoc Loc);
  const llvm::SourceMgr &SM;
};
} // namespace

std::pair<std::string, unsigned> CoverageMap::place(llvm::SMLoc Loc) {
  unsigned Buffer = SM.FindBufferContainingLoc(Loc);
  if (!Buffer)
    return {"", 0};
  llvm::SmallString<256> Path(
      SM.getMemoryBuffer(Buffer)->getBufferIdentifier());
  llvm::sys::fs::make_absolute(Path);
  llvm::sys::path::remove_dots(Path, /*remove_dot_dot=*/true);
  return {Path.str().str(), SM.FindLineNumber(Loc, Buffer)};
}

CoverageMap::CoverageMap(const llvm::SourceMgr &SM,
                         const BehaviorLayout &Layout,
                         llvm::ArrayRef<uint64_t> Counts)
    : SM(SM) {
  const std::vector<CoverageSite> &Sites = Layout.CoverageSites;
  for (size_t I = 0; I < Sites.size() && I < Counts.size(); ++I) {
    const CoverageSite &S = Sites[I];
    auto [File, Line] = place(S.N->getLoc());
    if (File.empty())
      continue;
    FileRecords &R = Files[File];
    switch (S.Kind) {
    case CoverageSite::Call:
      R.Functions.push_back({Line, S.Owner->getQualifiedName(), Counts[I]});
      R.Lines[Line] = std::max(R.Lines[Line], Counts[I]);
      break;
    case CoverageSite::Stmt:
      R.Lines[Line] = std::max(R.Lines[Line], Counts[I]);
      break;
    case CoverageSite::True:
      // The false counter follows its true one.
      if (I + 1 < Counts.size())
        R.Branches[Line].push_back({Counts[I], Counts[I + 1]});
      ++I;
      break;
    case CoverageSite::False:
      break;
    }
  }
}

bool bsc::writeLcov(Compilation &C, const LoadedBehavior &L,
                    llvm::ArrayRef<uint64_t> Counts, llvm::StringRef Path,
                    llvm::StringRef TestName) {
  std::unique_ptr<llvm::ToolOutputFile> Out =
      openOutput(C.Diags, Path, /*Text=*/true);
  if (!Out)
    return false;
  llvm::raw_ostream &OS = Out->os();
  // A test name is a C identifier to lcov (`C::main` becomes `C__main`).
  std::string Test = TestName.str();
  for (char &Ch : Test)
    if (!llvm::isAlnum(Ch))
      Ch = '_';
  CoverageMap Map(C.SM, L.Layout, Counts);
  for (const auto &[File, R] : Map.Files) {
    OS << "TN:" << Test << "\nSF:" << File << "\n";
    unsigned Hit = 0;
    for (const FileRecords::Function &F : R.Functions)
      OS << "FN:" << F.Line << "," << F.Name << "\n";
    for (const FileRecords::Function &F : R.Functions) {
      OS << "FNDA:" << F.Calls << "," << F.Name << "\n";
      Hit += F.Calls != 0;
    }
    OS << "FNF:" << R.Functions.size() << "\nFNH:" << Hit << "\n";
    unsigned Branches = 0;
    Hit = 0;
    for (const auto &[Line, Conditions] : R.Branches)
      for (size_t K = 0; K < Conditions.size(); ++K) {
        auto [True, False] = Conditions[K];
        bool Ran = True + False != 0;
        for (unsigned Way : {0, 1}) {
          uint64_t Taken = Way == 0 ? True : False;
          OS << "BRDA:" << Line << "," << K << "," << Way << ",";
          if (Ran)
            OS << Taken;
          else
            OS << "-";
          OS << "\n";
          ++Branches;
          Hit += Taken != 0;
        }
      }
    OS << "BRF:" << Branches << "\nBRH:" << Hit << "\n";
    Hit = 0;
    for (const auto &[Line, Runs] : R.Lines) {
      OS << "DA:" << Line << "," << Runs << "\n";
      Hit += Runs != 0;
    }
    OS << "LF:" << R.Lines.size() << "\nLH:" << Hit << "\nend_of_record\n";
  }
  Out->keep();
  return true;
}

CoverageSummary bsc::summarizeCoverage(Compilation &C, const LoadedBehavior &L,
                                       llvm::ArrayRef<uint64_t> Counts) {
  CoverageSummary S;
  CoverageMap Map(C.SM, L.Layout, Counts);
  for (const auto &[File, R] : Map.Files) {
    S.Lines += R.Lines.size();
    S.LinesHit += llvm::count_if(
        R.Lines, [](const auto &Line) { return Line.second != 0; });
    for (const auto &[Line, Conditions] : R.Branches)
      for (auto [True, False] : Conditions) {
        S.Branches += 2;
        S.BranchesHit += (True != 0) + (False != 0);
      }
  }
  const std::vector<CoverageSite> &Sites = L.Layout.CoverageSites;
  auto Where = [&](const Node *N) {
    std::string Text;
    if (unsigned Buffer = C.SM.FindBufferContainingLoc(N->getLoc()))
      Text = llvm::sys::path::filename(
                 C.SM.getMemoryBuffer(Buffer)->getBufferIdentifier())
                 .str() +
             ":" + std::to_string(C.SM.FindLineNumber(N->getLoc(), Buffer));
    return Text;
  };
  for (size_t I = 0; I < Sites.size() && I < Counts.size(); ++I) {
    const CoverageSite &Site = Sites[I];
    if (Counts[I])
      continue;
    if (Site.Kind == CoverageSite::Call && llvm::isa<TaskDecl>(Site.Owner))
      S.NeverActive.push_back(Site.Owner->getQualifiedName());
    const auto *Y = llvm::dyn_cast<YieldStmt>(Site.N);
    if (Site.Kind != CoverageSite::Stmt || !Y)
      continue;
    std::string Place =
        Where(Y) + " (" + Site.Owner->getQualifiedName() + ")";
    // A named state: `yield Done::kicked`.
    const auto *Name = llvm::dyn_cast_or_null<NameExpr>(Y->Value);
    if (Name && Name->Kind == NameKind::EnumValue && !Name->BuiltinState)
      S.StatesNeverTaken.push_back(Name->Name.str() + " at " + Place);
    else
      S.YieldsNeverReached.push_back(Place);
  }
  return S;
}

void bsc::printCoverageSummary(llvm::raw_ostream &OS,
                               const CoverageSummary &S) {
  OS << "coverage: " << llvm::format("%.1f", S.linePercent()) << "% of lines ("
     << S.LinesHit << " of " << S.Lines << "), " << S.BranchesHit << " of "
     << S.Branches << " branches\n";
  auto List = [&](llvm::StringRef What, const std::vector<std::string> &Items) {
    OS << What << ": ";
    if (Items.empty())
      OS << "none";
    for (size_t I = 0; I < Items.size(); ++I)
      OS << (I ? ", " : "") << Items[I];
    OS << "\n";
  };
  List("tasks never active", S.NeverActive);
  List("yields never reached", S.YieldsNeverReached);
  List("named task states never taken", S.StatesNeverTaken);
}

static std::string printNumber(const char *Format, double V) {
  char Text[32];
  snprintf(Text, sizeof Text, Format, V);
  return Text;
}

bool bsc::checkCoverageFloor(Compilation &C, const CoverageSummary &S,
                             double Floor) {
  if (S.linePercent() >= Floor)
    return true;
  C.Diags.report(llvm::SMLoc(), diag::err_coverage_below)
      << printNumber("%.1f", S.linePercent()) << printNumber("%g", Floor);
  return false;
}
