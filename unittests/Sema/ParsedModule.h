//===- ParsedModule.h - a module parsed and checked from text, for tests -===//
#ifndef BSC_UNITTESTS_SEMA_PARSEDMODULE_H
#define BSC_UNITTESTS_SEMA_PARSEDMODULE_H

#include "bsc/Parse/Parser.h"
#include "bsc/Sema/Sema.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/SourceMgr.h"

namespace bsc {

/// Module `P`, parsed from source text and checked as a behavior.
struct ParsedModule {
  llvm::SourceMgr SM;
  ASTContext Ctx;
  DiagnosticEngine Diags;
  Behavior Out;
  ModuleAST *M = nullptr;
  bool OK = false;

  explicit ParsedModule(llvm::StringRef Source) {
    unsigned ID = SM.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(Source, "P.bs"), llvm::SMLoc());
    M = parseModule(SM, ID, "P", Ctx, Diags);
    OK = !Diags.hasErrors() && checkBehavior({M}, Ctx, Diags, Out);
  }

  /// A func or task by qualified name (`P::t`, `P::t.f` for a nested
  /// func), or null.
  const CallableDecl *find(llvm::StringRef QualifiedName) const {
    for (const ModuleAST *Mod : Out.Modules)
      for (const CallableDecl *C : Mod->Decls) {
        if (C->getQualifiedName() == QualifiedName)
          return C;
        if (const auto *T = llvm::dyn_cast<TaskDecl>(C))
          for (const FuncDecl *F : T->NestedFuncs)
            if (F->getQualifiedName() == QualifiedName)
              return F;
      }
    return nullptr;
  }
};

} // namespace bsc

#endif
