//===- bsread.cpp - print what binding objects register -------------------===//
//
// A stand-alone reader for binding objects and archives: prints the model
// that bsc would compile against (the text of `bsc --dump-bindings`), or
// the reader's errors. Used by test/Bindings and for debugging a binding
// build without a b-script program at hand.
//
//   bsread [-target i586|x86_64|TRIPLE] OBJ...
//
//===----------------------------------------------------------------------===//
#include "bsc/Bind/Bind.h"
#include "llvm/Support/CommandLine.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/WithColor.h"
#include "llvm/Support/raw_ostream.h"
#include "llvm/TargetParser/Triple.h"

using namespace llvm;

static cl::list<std::string> Inputs(cl::Positional, cl::desc("<object|archive>..."),
                                    cl::OneOrMore);
static cl::opt<std::string>
    TargetName("target", cl::desc("i586 (default), x86_64 or a triple"),
               cl::init("i586"));

int main(int Argc, char **Argv) {
  InitLLVM X(Argc, Argv);
  cl::ParseCommandLineOptions(Argc, Argv, "print what binding objects register\n");
  std::string T = TargetName;
  if (T == "i586" || T == "i386" || T == "i686")
    T += "-unknown-linux-gnu";
  else if (T == "x86_64" || T == "host")
    T = "x86_64-unknown-linux-gnu";
  Expected<bsc::bind::BindingModel> Model =
      bsc::bind::readBindings(Inputs, Triple(T));
  if (!Model) {
    WithColor::error(errs(), "bsread") << toString(Model.takeError()) << "\n";
    return 1;
  }
  bsc::bind::dumpBindings(*Model, outs());
  return 0;
}
