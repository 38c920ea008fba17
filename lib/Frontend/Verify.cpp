//===- Verify.cpp - checking diagnostics against expected-* comments -----===//
//
// Tests put the expected diagnostic next to the offending line, as clang's
// -verify does, in a b-script comment:
//     x = 1.5   # expected-error {{cannot assign}}
//     # expected-error@+1 {{unexpected indent}}
// The comparison is by line and message substring, so a test keeps passing
// when a message gains detail, and fails when a diagnostic moves or appears.
//
//===----------------------------------------------------------------------===//
#include "bsc/Frontend/Frontend.h"
#include "llvm/Support/raw_ostream.h"
#include <optional>

using namespace bsc;

namespace {
struct Expectation {
  Severity Sev;
  unsigned BufferID;
  unsigned Line;
  std::string Text;
  bool Seen = false;
};

llvm::StringRef severityName(Severity S) {
  switch (S) {
  case Severity::Error:
    return "error";
  case Severity::Warning:
    return "warning";
  case Severity::Note:
    return "note";
  }
  llvm_unreachable("unknown severity");
}

/// Parses `expected-<severity>[@[+-]N] {{text}}` at the start of `S`.
std::optional<Expectation> parseExpectation(llvm::StringRef &S,
                                            unsigned BufferID, unsigned Line,
                                            std::string &Problem) {
  Expectation E{Severity::Error, BufferID, Line, ""};
  if (S.consume_front("error"))
    E.Sev = Severity::Error;
  else if (S.consume_front("warning"))
    E.Sev = Severity::Warning;
  else if (S.consume_front("note"))
    E.Sev = Severity::Note;
  else {
    Problem = "unknown kind after 'expected-'";
    return std::nullopt;
  }
  if (S.consume_front("@")) {
    bool Plus = S.consume_front("+");
    bool Minus = !Plus && S.consume_front("-");
    unsigned N = 0;
    if (S.consumeInteger(10, N) || (!Plus && !Minus)) {
      Problem = "expected '@+N' or '@-N'";
      return std::nullopt;
    }
    if (Minus && N >= Line) {
      Problem = "'@-N' points before the first line";
      return std::nullopt;
    }
    E.Line = Plus ? Line + N : Line - N;
  }
  S = S.ltrim(" \t");
  if (!S.consume_front("{{")) {
    Problem = "expected '{{' after the expectation";
    return std::nullopt;
  }
  size_t End = S.find("}}");
  if (End == llvm::StringRef::npos) {
    Problem = "expected '}}' to close the expected text";
    return std::nullopt;
  }
  E.Text = S.take_front(End).str();
  S = S.drop_front(End + 2);
  return E;
}
} // namespace

bool bsc::verifyDiagnostics(const llvm::SourceMgr &SM,
                            llvm::ArrayRef<Diagnostic> Diags,
                            llvm::raw_ostream &OS) {
  std::vector<Expectation> Expected;
  bool OK = true;
  for (unsigned ID = 1, E = SM.getNumBuffers(); ID <= E; ++ID) {
    const llvm::MemoryBuffer *Buf = SM.getMemoryBuffer(ID);
    llvm::StringRef Text = Buf->getBuffer();
    unsigned Line = 0;
    while (!Text.empty()) {
      ++Line;
      auto [LineText, Rest] = Text.split('\n');
      Text = Rest;
      for (size_t Pos; (Pos = LineText.find("expected-")) !=
                       llvm::StringRef::npos;) {
        LineText = LineText.drop_front(Pos + strlen("expected-"));
        std::string Problem;
        if (auto Exp = parseExpectation(LineText, ID, Line, Problem)) {
          Expected.push_back(std::move(*Exp));
          continue;
        }
        OS << "error: " << Buf->getBufferIdentifier() << ":" << Line
           << ": malformed expectation: " << Problem << "\n";
        OK = false;
      }
    }
  }

  std::vector<const Diagnostic *> Unexpected;
  for (const Diagnostic &D : Diags) {
    unsigned ID = D.Loc.isValid() ? SM.FindBufferContainingLoc(D.Loc) : 0;
    unsigned Line = ID ? SM.getLineAndColumn(D.Loc, ID).first : 0;
    auto Match = llvm::find_if(Expected, [&](const Expectation &E) {
      return !E.Seen && E.Sev == D.Sev && E.BufferID == ID && E.Line == Line &&
             llvm::StringRef(D.Message).contains(E.Text);
    });
    if (Match == Expected.end())
      Unexpected.push_back(&D);
    else
      Match->Seen = true;
  }

  for (Severity S : {Severity::Error, Severity::Warning, Severity::Note}) {
    std::string Missing, Extra;
    llvm::raw_string_ostream MissingOS(Missing), ExtraOS(Extra);
    for (const Expectation &E : Expected)
      if (!E.Seen && E.Sev == S)
        MissingOS << "  File "
                  << SM.getMemoryBuffer(E.BufferID)->getBufferIdentifier()
                  << " Line " << E.Line << ": " << E.Text << "\n";
    for (const Diagnostic *D : Unexpected) {
      if (D->Sev != S)
        continue;
      if (D->Loc.isValid()) {
        unsigned ID = SM.FindBufferContainingLoc(D->Loc);
        ExtraOS << "  File " << SM.getMemoryBuffer(ID)->getBufferIdentifier()
                << " Line " << SM.getLineAndColumn(D->Loc, ID).first;
      } else {
        ExtraOS << "  (no location)";
      }
      ExtraOS << ": " << D->Message << "\n";
    }
    if (!Missing.empty())
      OS << "error: '" << severityName(S)
         << "' diagnostics expected but not seen:\n"
         << Missing;
    if (!Extra.empty())
      OS << "error: '" << severityName(S)
         << "' diagnostics seen but not expected:\n"
         << Extra;
    OK &= Missing.empty() && Extra.empty();
  }
  return OK;
}
