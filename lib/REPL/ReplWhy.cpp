//===- ReplWhy.cpp - `:why`: the conditions a task evaluated --------------===//
//===----------------------------------------------------------------------===//
#include "ReplImpl.h"

using namespace bsc;
using namespace bsc::repl;

void Repl::cmdWhy(llvm::StringRef Args, llvm::SMLoc Loc) {
  OS << ":why is not implemented yet\n";
}
