//===- Parser.h - b-script source to AST -----------------------*- C++ -*-===//
#ifndef BSC_PARSE_PARSER_H
#define BSC_PARSE_PARSER_H

#include "bsc/AST/AST.h"
#include "bsc/Basic/Diagnostic.h"
#include "llvm/Support/SourceMgr.h"

namespace bsc {

/// Limits that keep the recursive-descent parser (and every later phase that
/// recurses over the tree) within a bounded stack on any input.
constexpr unsigned MaxNestingDepth = 1000;

/// Parses buffer `BufferID` of `SM` into a new module of `Ctx` called
/// `ModuleName`. Always returns a module: syntax errors are reported to
/// `Diags` and the bad parts become ErrorStmt/ErrorExpr nodes.
ModuleAST *parseModule(const llvm::SourceMgr &SM, unsigned BufferID,
                       llvm::StringRef ModuleName, ASTContext &Ctx,
                       DiagnosticEngine &Diags);

/// Parses a line typed at `bsc repl` (the whole buffer `BufferID`): the
/// statements of a func body, one per line, at column 1. Diagnostics as for
/// a module; the result is never null.
BlockStmt *parseReplLine(const llvm::SourceMgr &SM, unsigned BufferID,
                         ASTContext &Ctx, DiagnosticEngine &Diags);

} // namespace bsc

#endif
