//===- Diagnostics.cpp - bsc's diagnostics as the editor shows them -------===//
//
// The same diagnostics `bsc` prints, in the file each is in: an error in a
// required module appears in that module's file. A note becomes related
// information of the error or warning before it; a fix-it becomes a quick
// fix (codeActions). A diagnostic without a place (a binding object that
// cannot be read) is shown at the top of the file that was checked.
//
//===----------------------------------------------------------------------===//
#include "Features.h"
#include "llvm/ADT/StringExtras.h"

using namespace bsc;
using namespace bsc::lsp;

/// The range to underline: the diagnostic's first range if it has one,
/// else the word (or character) at its place.
static llvm::SMRange underline(const Analysis &A, const Diagnostic &D) {
  if (!D.Ranges.empty() && D.Ranges[0].isValid() &&
      A.C->SM.FindBufferContainingLoc(D.Ranges[0].End) ==
          A.C->SM.FindBufferContainingLoc(D.Loc))
    return D.Ranges[0];
  unsigned ID = A.C->SM.FindBufferContainingLoc(D.Loc);
  const char *End = A.C->SM.getMemoryBuffer(ID)->getBufferEnd();
  const char *P = D.Loc.getPointer();
  const char *Q = P;
  while (Q != End && (llvm::isAlnum(*Q) || *Q == '_'))
    ++Q;
  if (Q == P && Q != End && *Q != '\n')
    ++Q;
  return {D.Loc, llvm::SMLoc::getFromPointer(Q)};
}

/// The editor's way to give what a message asks of the command line: a
/// missing binding object is `"bind"` in the behavior's bscript.json, not
/// `--bind`.
static std::string inEditor(const Analysis &A, const Diagnostic &D) {
  bool AsksForBind = llvm::is_contained(
      {diag::err_needs_binding, diag::err_no_input_type,
       diag::err_no_output_type, diag::err_unknown_module,
       diag::note_maybe_unbound},
      D.Kind);
  if (!AsksForBind || !A.Config.Bind.empty())
    return D.Message;
  return D.Message + "; in the editor, list the binding objects under " +
         "\"bind\" in " +
         (A.Config.File.empty()
              ? std::string("a bscript.json in the behavior's folder or "
                            "above (docs/editors.md)")
              : "'" + A.Config.File + "'");
}

std::map<std::string, llvm::json::Array> lsp::diagnostics(const Analysis &A) {
  std::map<std::string, llvm::json::Array> ByURI;
  for (const ModuleAST *M : A.C->Modules)
    ByURI[pathToURI(A.getPath(M->BufferID))];
  std::string Checked = pathToURI(A.Path);
  ByURI[Checked];
  auto Top = [] {
    return llvm::json::Object{
        {"start", llvm::json::Object{{"line", 0}, {"character", 0}}},
        {"end", llvm::json::Object{{"line", 0}, {"character", 0}}}};
  };
  std::vector<std::string> Setup = A.SetupErrors;
  if (!A.Config.Error.empty())
    Setup.insert(Setup.begin(), A.Config.Error);
  for (const std::string &Message : Setup)
    ByURI[Checked].push_back(llvm::json::Object{{"range", Top()},
                                                {"severity", 1},
                                                {"source", "bsc"},
                                                {"message", Message}});
  llvm::json::Object *Last = nullptr;
  for (const Diagnostic &D : A.C->Diags.getDiagnostics()) {
    bool Placed = D.Loc.isValid() && A.C->SM.FindBufferContainingLoc(D.Loc);
    if (D.Sev == Severity::Note && Last) {
      if (!Placed) {
        (*Last)["message"] =
            (*Last->getString("message") + "\n" + inEditor(A, D)).str();
        continue;
      }
      llvm::json::Array *Related = Last->getArray("relatedInformation");
      if (!Related) {
        (*Last)["relatedInformation"] = llvm::json::Array();
        Related = Last->getArray("relatedInformation");
      }
      Related->push_back(llvm::json::Object{
          {"location", A.getLocation(underline(A, D))},
          {"message", inEditor(A, D)}});
      continue;
    }
    int Severity = D.Sev == Severity::Error     ? 1
                   : D.Sev == Severity::Warning ? 2
                                                : 3;
    llvm::json::Object Entry{{"severity", Severity},
                             {"source", "bsc"},
                             {"code", getIdName(D.Kind)},
                             {"message", inEditor(A, D)}};
    std::string URI = Checked;
    if (Placed) {
      URI = pathToURI(A.getPath(A.C->SM.FindBufferContainingLoc(D.Loc)));
      Entry["range"] = A.getRange(underline(A, D));
    } else {
      Entry["range"] = Top();
    }
    llvm::json::Array &List = ByURI[URI];
    List.push_back(std::move(Entry));
    Last = List.back().getAsObject();
  }
  return ByURI;
}

llvm::json::Value lsp::codeActions(const Analysis &A, unsigned BufferID,
                                   llvm::SMRange R) {
  llvm::json::Array Actions;
  const char *From = R.Start.getPointer(), *To = R.End.getPointer();
  for (const Diagnostic &D : A.C->Diags.getDiagnostics()) {
    if (D.FixIts.empty() || !D.Loc.isValid() ||
        A.C->SM.FindBufferContainingLoc(D.Loc) != BufferID)
      continue;
    llvm::SMRange U = underline(A, D);
    if (U.End.getPointer() < From || U.Start.getPointer() > To)
      continue;
    llvm::json::Array Edits;
    for (const llvm::SMFixIt &F : D.FixIts)
      Edits.push_back(llvm::json::Object{{"range", A.getRange(F.getRange())},
                                         {"newText", F.getText().str()}});
    std::string Title = D.FixIts.size() == 1 && !D.FixIts[0].getText().empty()
                            ? "Write '" + D.FixIts[0].getText().str() + "'"
                            : "Apply the fix of: " + D.Message;
    Actions.push_back(llvm::json::Object{
        {"title", Title},
        {"kind", "quickfix"},
        {"diagnostics",
         llvm::json::Array{llvm::json::Object{
             {"range", A.getRange(U)}, {"message", D.Message}}}},
        {"edit",
         llvm::json::Object{
             {"changes",
              llvm::json::Object{{pathToURI(A.getPath(BufferID)),
                                  std::move(Edits)}}}}}});
  }
  return Actions;
}
