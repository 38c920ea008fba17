//===- TargetName.cpp - the triple a `-target` spelling stands for --------===//
#include "bsc/Basic/TargetName.h"
#include "llvm/TargetParser/Host.h"

using namespace bsc;

llvm::Triple bsc::getHostTriple() {
  return llvm::Triple(llvm::sys::getProcessTriple());
}

llvm::Triple bsc::resolveTargetTriple(llvm::StringRef Name) {
  if (Name.empty())
    return getHostTriple();
  if (Name == "i586")
    return llvm::Triple("i586-unknown-linux-gnu");
  if (Name == "x86_64")
    return llvm::Triple("x86_64-unknown-linux-gnu");
  return llvm::Triple(llvm::Triple::normalize(Name));
}
