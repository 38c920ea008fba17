//===- BindingFuzzer.cpp - bytes into the binding reader ------------------===//
//
// libFuzzer target (`./dev.sh fuzz binding`), and the same function run on
// a corpus by the replay driver in the test suite (fuzz/README.md). The
// input is a binding object or shared library, as `--bind` reads it, for
// the host and for i586: any bytes must give a model or an error, never a
// crash, an "LLVM ERROR" or a hang. A model is also turned into native
// modules and printed, as --dump-bindings does.
//
//===----------------------------------------------------------------------===//
#include "bsc/AST/Native.h"
#include "bsc/Bind/Bind.h"
#include "llvm/Support/raw_ostream.h"
#include "llvm/TargetParser/Triple.h"
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *Data, size_t Size) {
  using namespace bsc;
  llvm::MemoryBufferRef Buffer(
      llvm::StringRef(reinterpret_cast<const char *>(Data), Size), "fuzz.o");
  for (const char *Triple : {"x86_64-unknown-linux-gnu", "i586-unknown-linux-gnu"}) {
    llvm::Expected<bind::BindingModel> Model =
        bind::readBindingBuffers({Buffer}, llvm::Triple(Triple));
    if (!Model) {
      llvm::consumeError(Model.takeError());
      continue;
    }
    NativeRegistry Registry;
    bind::addToNativeRegistry(*Model, Registry);
    std::string Text;
    llvm::raw_string_ostream OS(Text);
    bind::dumpBindings(*Model, OS);
  }
  return 0;
}
