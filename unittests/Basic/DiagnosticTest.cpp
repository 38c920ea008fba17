//===- DiagnosticTest.cpp - the diagnostics table, engine and printing ----===//
#include "bsc/Basic/Diagnostic.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/raw_ostream.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {

TEST(DiagnosticTest, FormatsArgumentsInOrder) {
  EXPECT_EQ(DiagnosticEngine::format("'%0' takes %1, not %2", {"f", "1", "2"}),
            "'f' takes 1, not 2");
  // A missing argument formats as nothing rather than reading past the end.
  EXPECT_EQ(DiagnosticEngine::format("a %0 b %1", {"x"}), "a x b ");
  EXPECT_EQ(DiagnosticEngine::format("100%", {}), "100%");
}

TEST(DiagnosticTest, TableGivesSeverityAndId) {
  EXPECT_EQ(getSeverity(diag::err_unexpected_indent), Severity::Error);
  EXPECT_EQ(getSeverity(diag::note_previous_definition), Severity::Note);
  EXPECT_EQ(getSeverity(diag::warn_unreachable_code), Severity::Warning);
  EXPECT_EQ(getIdName(diag::err_unexpected_indent), "err_unexpected_indent");
}

TEST(DiagnosticTest, EveryFormatIsLowerCaseWithoutPeriod) {
  for (unsigned K = 0; K != diag::NumKinds; ++K) {
    llvm::StringRef F = getFormat(diag::Kind(K));
    ASSERT_FALSE(F.empty()) << getIdName(diag::Kind(K)).str();
    EXPECT_FALSE(llvm::isUpper(F[0]) && !F.starts_with("TaskState"))
        << getIdName(diag::Kind(K)).str();
    EXPECT_FALSE(F.ends_with(".")) << getIdName(diag::Kind(K)).str();
  }
}

TEST(DiagnosticTest, CountsAndStopsAfterTooManyErrors) {
  DiagnosticEngine D;
  D.report(llvm::SMLoc(), diag::warn_unreachable_code) << "return";
  EXPECT_EQ(D.getNumWarnings(), 1u);
  EXPECT_FALSE(D.hasErrors());
  for (unsigned I = 0; I != DiagnosticEngine::MaxErrors + 10; ++I) {
    D.report(llvm::SMLoc(), diag::err_undeclared_name) << "x";
    D.report(llvm::SMLoc(), diag::note_previous_definition);
  }
  EXPECT_TRUE(D.tooManyErrors());
  EXPECT_EQ(D.getNumErrors(), DiagnosticEngine::MaxErrors);
  // The warning, then each kept error with its note; dropped errors drop
  // their notes too.
  EXPECT_EQ(D.getDiagnostics().size(), 1 + 2 * DiagnosticEngine::MaxErrors);
}

TEST(DiagnosticTest, PrintsFileLineColumnSourceLineAndCaret) {
  llvm::SourceMgr SM;
  unsigned ID = SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy("task t()\n    yield 1.5\n", "m.bs"),
      llvm::SMLoc());
  const char *Start = SM.getMemoryBuffer(ID)->getBufferStart();
  DiagnosticEngine D;
  D.report(llvm::SMLoc::getFromPointer(Start + 19), diag::err_yield_value_type)
      << "float";
  D.report(llvm::SMLoc(), diag::err_no_input_files);
  std::string Out;
  llvm::raw_string_ostream OS(Out);
  printDiagnostics(SM, D.getDiagnostics(), OS);
  EXPECT_EQ(OS.str(),
            "m.bs:2:11: error: the value of 'yield' must be 'int' or "
            "'TaskState', not 'float'\n"
            "    yield 1.5\n"
            "          ^\n"
            "bsc: error: no input files\n");
}

/// A diagnostic at a line of data names the place only: the line is not
/// echoed, nor a caret, for it or its notes.
TEST(DiagnosticTest, NoSourceLineNamesThePlaceOnly) {
  llvm::SourceMgr SM;
  unsigned ID = SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy("{}\n{\"output\":{\"a\":1}}\n",
                                           "run.jsonl"),
      llvm::SMLoc());
  llvm::SMLoc Line2 = llvm::SMLoc::getFromPointer(
      SM.getMemoryBuffer(ID)->getBufferStart() + 3);
  DiagnosticEngine D;
  D.report(Line2, diag::err_replay_mismatch) << 2 << NoSourceLine();
  D.report(Line2, diag::note_replay_difference)
      << "output.a" << "2" << "1" << NoSourceLine();
  // Otherwise the same location echoes the line.
  D.report(Line2, diag::err_replay_not_object);
  std::string Out;
  llvm::raw_string_ostream OS(Out);
  printDiagnostics(SM, D.getDiagnostics(), OS);
  EXPECT_EQ(OS.str(),
            "run.jsonl:2:1: error: cycle 2: the output differs from the "
            "recording\n"
            "run.jsonl:2:1: note: output.a: recorded 2, got 1\n"
            "run.jsonl:2:1: error: a replay line must be a JSON object like "
            "{\"input\":{...},\"output\":{...}}\n"
            "{\"output\":{\"a\":1}}\n"
            "^\n");
}

TEST(DiagnosticTest, SortsBySourceKeepingNotesWithTheirDiagnostic) {
  llvm::SourceMgr SM;
  unsigned A = SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy("a1\na2\n", "a.bs"), llvm::SMLoc());
  unsigned B = SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy("b1\n", "b.bs"), llvm::SMLoc());
  auto At = [&](unsigned ID, unsigned Offset) {
    return llvm::SMLoc::getFromPointer(
        SM.getMemoryBuffer(ID)->getBufferStart() + Offset);
  };
  DiagnosticEngine D;
  D.report(At(B, 0), diag::err_undeclared_name) << "b1";
  D.report(At(A, 3), diag::err_undeclared_name) << "a2";
  D.report(At(A, 3), diag::note_did_you_mean) << "a1";
  D.report(llvm::SMLoc(), diag::err_no_input_files);
  D.report(At(A, 0), diag::err_undeclared_name) << "a1";
  D.sortBySource(SM);
  std::vector<std::string> Order;
  for (const Diagnostic &Diag : D.getDiagnostics())
    Order.push_back(Diag.Message);
  EXPECT_EQ(Order, (std::vector<std::string>{
                       "no input files", "use of undeclared name 'a1'",
                       "use of undeclared name 'a2'", "did you mean 'a1'?",
                       "use of undeclared name 'b1'"}));
}

TEST(DiagnosticTest, WarningGroupsSilenceTheirWarningsAndNotes) {
  DiagnosticEngine D;
  EXPECT_FALSE(D.ignoreWarningGroup("no-such-group"));
  EXPECT_TRUE(D.ignoreWarningGroup("yield-loop"));
  D.report(llvm::SMLoc(), diag::warn_yield_loop);
  D.report(llvm::SMLoc(), diag::note_previous_definition);
  D.report(llvm::SMLoc(), diag::warn_unreachable_code) << "return";
  ASSERT_EQ(D.getDiagnostics().size(), 1u);
  EXPECT_EQ(D.getDiagnostics()[0].Kind, diag::warn_unreachable_code);
  EXPECT_EQ(D.getNumWarnings(), 1u);
  EXPECT_EQ(DiagnosticEngine::getWarningGroupList(),
            "'yield-loop', 'unreachable-code', 'double-yield', "
            "'skipped-yield', 'duplicate-require'");
}

/// -Werror makes every warning an error (and says so); -Werror=<group>
/// one group's; a silenced group stays silent.
TEST(DiagnosticTest, WerrorPromotesWarnings) {
  DiagnosticEngine D;
  EXPECT_FALSE(D.promoteWarningGroup("no-such-group"));
  EXPECT_TRUE(D.promoteWarningGroup("skipped-yield"));
  D.report(llvm::SMLoc(), diag::warn_loop_skips_yield);
  D.report(llvm::SMLoc(), diag::warn_unreachable_code) << "return";
  ASSERT_EQ(D.getDiagnostics().size(), 2u);
  EXPECT_EQ(D.getDiagnostics()[0].Sev, Severity::Error);
  EXPECT_TRUE(llvm::StringRef(D.getDiagnostics()[0].Message)
                  .ends_with(" [-Werror]"));
  EXPECT_EQ(D.getDiagnostics()[1].Sev, Severity::Warning);
  EXPECT_EQ(D.getNumErrors(), 1u);

  DiagnosticEngine All;
  All.promoteAllWarnings();
  EXPECT_TRUE(All.ignoreWarningGroup("unreachable-code"));
  All.report(llvm::SMLoc(), diag::warn_unreachable_code) << "return";
  All.report(llvm::SMLoc(), diag::warn_double_yield);
  ASSERT_EQ(All.getDiagnostics().size(), 1u);
  EXPECT_EQ(All.getDiagnostics()[0].Kind, diag::warn_double_yield);
  EXPECT_TRUE(All.hasErrors());
}

} // namespace
