//===- DepFile.cpp - -MD: the dependency file for make and Ninja ----------===//
//
// One rule, `OUTPUT: INPUT...`, as `gcc -MD` writes it: a build system that
// reads it rebuilds the output when a required module file or a binding
// object changes, without knowing b-script's `requires`.
//
//===----------------------------------------------------------------------===//
#include "bsc/Driver/Driver.h"
#include "llvm/ADT/SmallString.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;

/// `S` as make reads a file name: space and `#` escaped, `$` doubled.
static std::string escapeForMake(llvm::StringRef S) {
  std::string E;
  for (char Ch : S) {
    if (Ch == ' ' || Ch == '#')
      E += '\\';
    else if (Ch == '$')
      E += '$';
    E += Ch;
  }
  return E;
}

std::optional<std::string> bsc::getDepFilePath(const DepFileOptions &Opts,
                                               llvm::StringRef Output) {
  if (!Opts.Path.empty())
    return Opts.Path;
  if (Output == "-")
    return std::nullopt;
  llvm::SmallString<256> D(Output);
  llvm::sys::path::replace_extension(D, ".d");
  return std::string(D);
}

void bsc::writeDependencies(llvm::raw_ostream &OS, llvm::StringRef Output,
                            llvm::ArrayRef<std::string> Inputs) {
  OS << escapeForMake(Output) << ":";
  for (const std::string &Input : Inputs)
    OS << " \\\n  " << escapeForMake(Input);
  OS << "\n";
}

bool bsc::writeDepFile(Compilation &C, const DepFileOptions &Opts,
                       llvm::StringRef Output,
                       llvm::ArrayRef<std::string> BindObjects) {
  if (!Opts.Enabled)
    return true;
  std::optional<std::string> Path = getDepFilePath(Opts, Output);
  if (!Path) {
    C.Diags.report(llvm::SMLoc(), diag::err_depfile_needs_path);
    return false;
  }
  auto Out = openOutput(C.Diags, *Path, /*Text=*/true);
  if (!Out)
    return false;
  std::vector<std::string> Inputs;
  for (const ModuleAST *M : C.Modules)
    Inputs.push_back(M->Path);
  Inputs.insert(Inputs.end(), BindObjects.begin(), BindObjects.end());
  writeDependencies(Out->os(), Output, Inputs);
  Out->keep();
  return true;
}
