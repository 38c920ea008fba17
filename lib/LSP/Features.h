//===- Features.h - what the server answers, one function each -*- C++ -*-===//
//
// Each takes an Analysis of the behavior and the request's position (an
// SMLoc in the document's buffer) and returns the result's JSON, null when
// there is nothing to say.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_LSP_FEATURES_H
#define BSC_LIB_LSP_FEATURES_H

#include "Workspace.h"

namespace bsc {
namespace lsp {

llvm::json::Value hover(const Analysis &A, llvm::SMLoc Loc);
llvm::json::Value definition(const Analysis &A, llvm::SMLoc Loc);

/// A script symbol's identity across analyses: the file and offset of its
/// declaration (a module's name for a module); empty for registered C++.
std::string definitionKey(const Analysis &A, const Symbol &S);
/// One occurrence of a name, found in some analysis.
struct Location {
  std::string Path;
  unsigned Begin, End; ///< Byte offsets.
  llvm::json::Object Range;
};
/// Every occurrence of the symbol at `Loc` of `A` in the analyses `All`
/// (which check the behavior from each of its files), each place once.
std::vector<Location> findOccurrences(llvm::ArrayRef<const Analysis *> All,
                                      const Analysis &A, llvm::SMLoc Loc,
                                      bool IncludeDeclaration);
/// The occurrences in the document (`Buffer`) of the name at `Loc`, its
/// declaration among them.
llvm::json::Value documentHighlights(const Analysis &A, unsigned Buffer,
                                     llvm::SMLoc Loc);
/// `textDocument/prepareCallHierarchy`: the task or func named at `Loc`.
llvm::json::Value prepareCallHierarchy(const Analysis &A, llvm::SMLoc Loc);
/// `callHierarchy/incomingCalls` (`Incoming`) or `outgoingCalls` of the
/// item whose name is at `Loc` of `A`, over the analyses `All`.
llvm::json::Value hierarchyCalls(llvm::ArrayRef<const Analysis *> All,
                                 const Analysis &A, llvm::SMLoc Loc,
                                 bool Incoming);
/// `textDocument/inlayHint`: the parameter names at the literal arguments
/// of calls with two or more, in `Range` of the document (InlayHints.cpp).
llvm::json::Value inlayHints(const Analysis &A, unsigned Buffer,
                             llvm::SMRange Range);
/// `workspace/willRenameFiles` of one module file: the edits that make
/// every `requires "Old"` and `Old::name` of the analyses `All` name the
/// new file's module; null if there are none (or the new name is no
/// module's).
llvm::json::Value renameModuleFile(llvm::ArrayRef<const Analysis *> All,
                                   llvm::StringRef OldPath,
                                   llvm::StringRef NewPath);
llvm::json::Value references(llvm::ArrayRef<const Analysis *> All,
                             const Analysis &A, llvm::SMLoc Loc,
                             bool IncludeDeclaration);
llvm::json::Value documentSymbols(const Analysis &A, unsigned BufferID);
llvm::json::Value workspaceSymbols(llvm::ArrayRef<const Analysis *> All,
                                   llvm::StringRef Query);
llvm::json::Value completion(const Analysis &A, unsigned BufferID,
                             llvm::SMLoc Loc);
llvm::json::Value signatureHelp(const Analysis &A, unsigned BufferID,
                                llvm::SMLoc Loc);
/// The legend of semanticTokens: its token types and modifiers.
extern const char *const TokenTypes[14];
extern const char *const TokenModifiers[4];
llvm::json::Value semanticTokens(const Analysis &A, unsigned BufferID);
llvm::json::Value foldingRanges(const Analysis &A, unsigned BufferID);
/// The edits of a rename, or an error message (a name that is not the
/// script's, a new name that is not an identifier).
llvm::Expected<llvm::json::Value> rename(llvm::ArrayRef<const Analysis *> All,
                                         const Analysis &A, llvm::SMLoc Loc,
                                         llvm::StringRef NewName);
llvm::json::Value prepareRename(const Analysis &A, llvm::SMLoc Loc);
/// The diagnostics of every file the analysis read, by URI (every module's
/// file, also those without any).
std::map<std::string, llvm::json::Array> diagnostics(const Analysis &A);
/// Quick fixes: the fix-its of the diagnostics in `R`.
llvm::json::Value codeActions(const Analysis &A, unsigned BufferID,
                              llvm::SMRange R);

} // namespace lsp
} // namespace bsc

#endif
