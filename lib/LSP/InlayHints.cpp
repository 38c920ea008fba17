//===- InlayHints.cpp - parameter names at calls of literals ---------------===//
//
// `SetHeadPanTilt(0.0, 0.0, 1.0)` says nothing of which number is which:
// at a call with two literal arguments or more, each literal gets its
// parameter's name before it (`pan: 0.0`). Off unless the client asks for
// them (initializationOptions `{"parameterNameHints": true}`,
// docs/editors.md): they change how every line of such calls reads.
//
//===----------------------------------------------------------------------===//
#include "Features.h"

using namespace bsc;
using namespace bsc::lsp;

/// A literal as written: a number, a bool, a string, or a negated number.
static bool isLiteral(const Expr *E) {
  if (const auto *U = llvm::dyn_cast<UnaryExpr>(E))
    E = U->Operand;
  return llvm::isa<IntLiteralExpr>(E) || llvm::isa<FloatLiteralExpr>(E) ||
         llvm::isa<BoolLiteralExpr>(E) || llvm::isa<StringLiteralExpr>(E);
}

/// The name of the call's parameter `I`, or empty.
static std::string parameterName(const CallExpr &C, size_t I) {
  if (C.Target && I < C.Target->Params.size())
    return C.Target->Params[I]->getName().Name.str();
  if (C.NativeFn && I < C.NativeFn->ParamNames.size())
    return C.NativeFn->ParamNames[I];
  return "";
}

llvm::json::Value lsp::inlayHints(const Analysis &A, unsigned Buffer,
                                  llvm::SMRange Range) {
  llvm::json::Array Hints;
  const char *Begin = Range.Start.getPointer(), *End = Range.End.getPointer();
  std::function<void(const Node &)> Visit = [&](const Node &N) {
    if (const auto *C = llvm::dyn_cast<CallExpr>(&N)) {
      // The arguments the source wrote, not the defaults Sema appended.
      size_t Written = C->Args.size() - C->NumDefaultArgs;
      size_t Literals = 0;
      for (size_t I = 0; I < Written; ++I)
        Literals += isLiteral(C->Args[I]);
      for (size_t I = 0; I < Written && Literals >= 2; ++I) {
        const Expr *Arg = C->Args[I];
        const char *At = Arg->getRange().Start.getPointer();
        std::string Name = parameterName(*C, I);
        if (!isLiteral(Arg) || Name.empty() || At < Begin || At > End)
          continue;
        Hints.push_back(llvm::json::Object{
            {"position", A.getPosition(Arg->getRange().Start)},
            {"label", Name + ":"},
            {"kind", 2}, // Parameter
            {"paddingRight", true}});
      }
    }
    forEachChild(N, Visit);
  };
  for (const ModuleAST *M : A.C->Modules)
    if (M->BufferID == Buffer)
      for (const CallableDecl *D : M->Decls)
        Visit(*D);
  return Hints;
}
