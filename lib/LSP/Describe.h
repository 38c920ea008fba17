//===- Describe.h - names and signatures as the editor shows them -*- C++ -*-===//
#ifndef BSC_LIB_LSP_DESCRIBE_H
#define BSC_LIB_LSP_DESCRIBE_H

#include "bsc/LSP/Index.h"
#include "bsc/Frontend/Frontend.h"
#include <string>

namespace bsc {
namespace lsp {

/// `int`, `Math::Vector2f`, `float[3]`.
std::string typeName(const NativeType &T);
/// A registered member's b-script signature: `func io::printi(int v)`,
/// `float Math::Vector2f.x`, `func Math::Vector2f.norm() : float`.
std::string signatureOf(const NativeFunction &F, llvm::StringRef Module);
/// A script task's or func's header as written, defaults included, on one
/// line: `task walkTo(Math::Vector2f target, float speed = 1.0)`.
std::string headerOf(const llvm::SourceMgr &SM, const CallableDecl &D);
/// The comment lines directly above a declaration, without their `#`.
std::string docCommentOf(const llvm::SourceMgr &SM, const Decl &D);
/// The module a registered member belongs to, by its owner or by search.
std::string moduleOf(const Compilation &C, const NativeFunction &F);
/// The parameter labels of a signature, for signature help.
std::vector<std::string> parameterLabels(const CallableDecl &D);
std::vector<std::string> parameterLabels(const NativeFunction &F);

} // namespace lsp
} // namespace bsc

#endif
