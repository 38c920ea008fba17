//===- bsread.cpp - print what binding objects register -------------------===//
//
// A stand-alone reader for binding objects and archives: prints the model
// that bsc would compile against (the text of `bsc --dump-bindings --bind
// OBJ`, without the standard modules), or the reader's errors. Used by
// test/Bindings and for debugging a binding build without a b-script
// program at hand. The target is bsc's: `-target` as bsc takes it, the
// host by default, the process's own triple as for bsc, --version and the
// JIT (resolveTargetTriple: Basic/TargetName.h, the one spelling of targets).
//
//   bsread [-target i586|x86_64|TRIPLE] OBJ...
//
//===----------------------------------------------------------------------===//
#include "bsc/Bind/Bind.h"
#include "bsc/Basic/TargetName.h"
#include "llvm/Support/CommandLine.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/WithColor.h"
#include "llvm/Support/raw_ostream.h"
#include "llvm/TargetParser/Triple.h"

using namespace llvm;

static cl::list<std::string> Inputs(cl::Positional, cl::desc("<object|archive>..."),
                                    cl::OneOrMore);
static cl::opt<std::string>
    TargetName("target",
               cl::desc("i586, x86_64 or an LLVM triple, as bsc -target "
                        "(default: the host, as bsc)"),
               cl::value_desc("target"));

int main(int Argc, char **Argv) {
  InitLLVM X(Argc, Argv);
  cl::ParseCommandLineOptions(Argc, Argv, "print what binding objects register\n");
  Expected<bsc::bind::BindingModel> Model =
      bsc::bind::readBindings(Inputs, bsc::resolveTargetTriple(TargetName));
  if (!Model) {
    WithColor::error(errs(), "bsread") << toString(Model.takeError()) << "\n";
    return 1;
  }
  bsc::bind::dumpBindings(*Model, outs());
  return 0;
}
