//===- Assertion.cpp - a failed `assert` in the JIT, as a diagnostic ------===//
//
// The JIT compiles assertions with AssertionMode::Report: a failure copies
// its condition's record (the values of the sub-expressions as the cycle
// computed them, as `:why` shows them) to bs.assert.record and traps. The
// guard reports a SIGILL; this file finds the record behind it and turns
// it into an error at the `assert`, with a note per value.
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/Run.h"
#include <cstring>

using namespace bsc;

/// An operand's value as the record holds it.
static std::string formatOperand(debug::ValueIO &Values,
                                 const ExplainSite::Operand &O,
                                 const uint8_t *Record) {
  const uint8_t *V = Record + O.Offset;
  if (O.Ty->isTaskState()) {
    int32_t State;
    std::memcpy(&State, V, sizeof State);
    return State == 1    ? "running"
           : State == 0  ? "done"
           : State == -1 ? "failure"
                         : std::to_string(State);
  }
  return debug::formatValue(O.Ty, Values.read(O.Ty, V));
}

bool bsc::reportFailedAssertion(Compilation &C, const LoadedBehavior &L,
                                uint32_t Cycle) {
  auto *Record = static_cast<uint8_t *>(L.JIT->lookup(AssertRecordSymbol));
  if (!Record)
    return false;
  uint32_t Number;
  std::memcpy(&Number, Record, sizeof Number);
  const std::vector<ExplainSite> &Sites = L.Layout.ExplainSites;
  if (Number == 0 || Number > Sites.size() ||
      Sites[Number - 1].Kind != ExplainSite::Assert)
    return false;
  // Taken: the next failure writes its own.
  std::memset(Record, 0, sizeof Number);
  const ExplainSite &Site = Sites[Number - 1];
  const AssertStmt *Assert = nullptr;
  for (const Behavior::Assertion &A : C.Checked.Assertions)
    if (A.S->getLoc() == Site.Loc)
      Assert = A.S;
  std::string Message =
      Assert && Assert->Message ? ": " + Assert->Message->Value : "";
  C.Diags.report(Site.Loc, Assert && Assert->IsAssume
                               ? diag::err_assumption_failed
                               : diag::err_assertion_failed)
      << Cycle << Site.Operands[0].Text << Message;

  // Each operand that ran, under the one that encloses it (as `:why`).
  uint64_t Mask;
  std::memcpy(&Mask, Record + 8, sizeof Mask);
  debug::ValueIO Values([&L](llvm::StringRef Sym) { return L.JIT->lookup(Sym); });
  std::vector<unsigned> Depth(Site.Operands.size(), 0);
  for (size_t I = 1; I < Site.Operands.size(); ++I) {
    const ExplainSite::Operand &O = Site.Operands[I];
    if (O.Parent > 0 && !(Mask & (uint64_t(1) << O.Parent)))
      continue; // Under an operand that did not run, nothing ran.
    Depth[I] = O.Parent > 0 ? Depth[O.Parent] + 1 : 0;
    std::string Indent(2 * Depth[I], ' ');
    if (Mask & (uint64_t(1) << I))
      C.Diags.report(Site.Loc, diag::note_assertion_value)
          << Indent + O.Text << formatOperand(Values, O, Record)
          << NoSourceLine();
    else
      C.Diags.report(Site.Loc, diag::note_assertion_not_evaluated)
          << Indent + O.Text << NoSourceLine();
  }
  return true;
}
