//===- Parser.h - b-script source to AST -----------------------*- C++ -*-===//
//
// The second phase: a module's text becomes its syntax tree (bsc/AST).
// The lexer (Lexer.h) turns indentation into INDENT/DEDENT tokens, so the
// parser is an ordinary recursive descent over tokens, one function per
// construct (lib/Parse: ParseStmt.cpp, ParseExpr.cpp; ParseHabits.cpp
// recognises habits from other languages and says what b-script writes
// instead). It never fails: an error is reported and its part of the tree
// becomes an ErrorStmt or ErrorExpr, so Sema and the language tools see
// every module whole. Names are not resolved here (that is Sema).
//
//===----------------------------------------------------------------------===//
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
