//===- Target.cpp - which machine a behavior is compiled for --------------===//
//
// Maps the driver's `-target`/`-mcpu` to an llvm::TargetMachine. The short
// names exist because the robot target is what users type most: `-target
// i586` must give exactly the paper's robot (Geode: no CMOV, no SSE) and PIC,
// so the object links into a robot's shared library without text
// relocations. Every machine is PIC: host programs are PIE on Debian, and
// one relocation model keeps host and robot objects alike.
//
//===----------------------------------------------------------------------===//
#include "bsc/CodeGen/Target.h"
#include "llvm/IR/Module.h"
#include "llvm/IR/Verifier.h"
#include "llvm/MC/MCSubtargetInfo.h"
#include "llvm/MC/TargetRegistry.h"
#include "llvm/Support/TargetSelect.h"
#include "llvm/Support/raw_ostream.h"
#include "llvm/Target/TargetOptions.h"
#include "llvm/TargetParser/Host.h"

using namespace bsc;

extern "C" {
void LLVMInitializeX86TargetInfo();
void LLVMInitializeX86Target();
void LLVMInitializeX86TargetMC();
void LLVMInitializeX86AsmPrinter();
void LLVMInitializeX86AsmParser();
}

void bsc::initializeTargets() {
  static bool Done = [] {
    LLVMInitializeX86TargetInfo();
    LLVMInitializeX86Target();
    LLVMInitializeX86TargetMC();
    LLVMInitializeX86AsmPrinter();
    LLVMInitializeX86AsmParser();
    return true;
  }();
  (void)Done;
}

llvm::Triple bsc::resolveTargetTriple(llvm::StringRef Name) {
  if (Name.empty())
    return llvm::Triple(llvm::sys::getDefaultTargetTriple());
  if (Name == "i586")
    return llvm::Triple("i586-unknown-linux-gnu");
  if (Name == "x86_64")
    return llvm::Triple("x86_64-unknown-linux-gnu");
  return llvm::Triple(llvm::Triple::normalize(Name));
}

std::string bsc::getDefaultCPU(const llvm::Triple &T) {
  if (T.getArchName() == "i586")
    return "geode";
  if (T.getArch() == llvm::Triple::x86_64)
    return "x86-64";
  return "generic";
}

std::optional<unsigned> bsc::parseOptLevel(llvm::StringRef Value) {
  unsigned Level;
  if (Value.size() != 1 || Value.getAsInteger(10, Level) ||
      Level > MaxOptLevel)
    return std::nullopt;
  return Level;
}

static llvm::CodeGenOptLevel getCodeGenOptLevel(unsigned OptLevel) {
  switch (OptLevel) {
  case 0:
    return llvm::CodeGenOptLevel::None;
  case 1:
    return llvm::CodeGenOptLevel::Less;
  case 2:
    return llvm::CodeGenOptLevel::Default;
  }
  return llvm::CodeGenOptLevel::Aggressive;
}

std::unique_ptr<llvm::TargetMachine>
bsc::createTargetMachine(const TargetOptions &Opts, DiagnosticEngine &Diags) {
  initializeTargets();
  llvm::Triple T = resolveTargetTriple(Opts.Target);
  std::string Spelled = Opts.Target.empty() ? T.str() : Opts.Target;
  // An unknown architecture normalises to "unknown-..."; LLVM would look up
  // nothing for it anyway, but say so in the user's words.
  if (T.getArch() == llvm::Triple::UnknownArch) {
    Diags.report(llvm::SMLoc(), diag::err_unknown_target)
        << Spelled << "not an architecture LLVM knows (try 'i586' or 'x86_64')";
    return nullptr;
  }
  std::string Error;
  const llvm::Target *Target =
      llvm::TargetRegistry::lookupTarget(T.str(), Error);
  if (!Target) {
    Diags.report(llvm::SMLoc(), diag::err_unknown_target)
        << Spelled << "bsc is built with the X86 back end only";
    return nullptr;
  }
  switch (T.getObjectFormat()) {
  case llvm::Triple::ELF:
  case llvm::Triple::COFF:
  case llvm::Triple::MachO:
    break;
  case llvm::Triple::UnknownObjectFormat:
  case llvm::Triple::DXContainer:
  case llvm::Triple::GOFF:
  case llvm::Triple::SPIRV:
  case llvm::Triple::Wasm:
  case llvm::Triple::XCOFF:
    Diags.report(llvm::SMLoc(), diag::err_unsupported_object_format)
        << Spelled
        << llvm::Triple::getObjectFormatTypeName(T.getObjectFormat());
    return nullptr;
  }
  // Operating systems whose object format the X86 MC layer writes
  // consistently (with ELF for UEFI, for one, LLVM 19 prints COFF
  // directives into an ELF file and crashes).
  bool KnownOS = T.isOSLinux() || T.getOS() == llvm::Triple::UnknownOS ||
                 T.isOSFreeBSD() || T.isOSNetBSD() || T.isOSOpenBSD();
  bool Consistent =
      (KnownOS && T.isOSBinFormatELF()) ||
      (T.isOSWindows() && T.isOSBinFormatCOFF()) ||
      (T.isOSDarwin() && T.isOSBinFormatMachO());
  if (!Consistent) {
    Diags.report(llvm::SMLoc(), diag::err_unknown_target)
        << Spelled
        << "bsc supports x86 Linux, BSD and bare-metal (ELF), Windows (COFF) "
           "and Darwin (Mach-O) triples";
    return nullptr;
  }
  std::string CPU = Opts.CPU.empty() ? getDefaultCPU(T) : Opts.CPU;
  // LLVM only warns (on stderr) about an unknown CPU and then generates code
  // for a generic one; for a robot that is a silent miscompile, so check.
  std::unique_ptr<llvm::MCSubtargetInfo> STI(
      Target->createMCSubtargetInfo(T.str(), "", ""));
  if (!STI || !STI->isCPUStringValid(CPU)) {
    Diags.report(llvm::SMLoc(), diag::err_unknown_cpu) << CPU << Spelled;
    return nullptr;
  }
  llvm::TargetOptions TO;
  std::unique_ptr<llvm::TargetMachine> TM(Target->createTargetMachine(
      T.str(), CPU, /*Features=*/"", TO, llvm::Reloc::PIC_, std::nullopt,
      getCodeGenOptLevel(Opts.OptLevel)));
  if (!TM)
    Diags.report(llvm::SMLoc(), diag::err_unknown_target)
        << Spelled << "LLVM cannot create a machine for it";
  return TM;
}

llvm::Error bsc::verifyGeneratedModule(const llvm::Module &M) {
  std::string Message;
  llvm::raw_string_ostream OS(Message);
  if (!llvm::verifyModule(M, &OS))
    return llvm::Error::success();
  OS.flush();
  return llvm::createStringError(
      "the generated LLVM IR is invalid: " +
      llvm::StringRef(Message).split('\n').first);
}
