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

using namespace bsc;

void bsc::initializeTargets() {
  static bool Done = [] {
    llvm::InitializeAllTargetInfos();
    llvm::InitializeAllTargets();
    llvm::InitializeAllTargetMCs();
    llvm::InitializeAllAsmPrinters();
    llvm::InitializeAllAsmParsers();
    llvm::InitializeAllDisassemblers();
    return true;
  }();
  (void)Done;
}

std::string bsc::getDefaultCPU(const llvm::Triple &T) {
  if (T.getArchName() == "i586")
    return "geode";
  if (T.getArch() == llvm::Triple::x86_64)
    return "x86-64";
  // Back ends without a "generic" CPU: the oldest supported one. (AMDGPU
  // has none either, but bsc refuses it: UnsupportedTargets.)
  switch (T.getArch()) {
  case llvm::Triple::nvptx:
  case llvm::Triple::nvptx64:
    return "sm_52";
  case llvm::Triple::avr:
    return "avr2";
  default:
    return "generic";
  }
}

bool bsc::supportsDebugInfo(const llvm::Triple &T) {
  // GOFF for other architectures is refused altogether (UnsupportedTargets).
  return !(T.isSystemZ() && T.isOSBinFormatGOFF());
}

bool bsc::usesX87Floats(const llvm::TargetMachine &TM) {
  return TM.getTargetTriple().getArch() == llvm::Triple::x86 &&
         !TM.getMCSubtargetInfo()->checkFeatures("+sse");
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

namespace {
/// What bsc refuses to write for a target.
enum class Refused { ObjectFiles, MachineCode, Everything };

/// A triple LLVM registers but crashes on (a segfault or abort, not an
/// error it reports) when it writes machine code for it, or that bsc's IR
/// generator does not support.
struct UnsupportedTarget {
  bool (*Matches)(const llvm::Triple &);
  Refused What;
  const char *Reason;
};

using llvm::Triple;

/// The architectures whose MC layer has a Mach-O and a COFF writer.
bool hasMachOAndCOFF(const Triple &T) {
  return T.isX86() || T.isARM() || T.isThumb() || T.isAArch64();
}
} // namespace

/// Every triple whose machine code bsc refuses, and why. Found by compiling
/// test/Target/Inputs/portable.bs for each architecture with each OS and
/// object format (utils/check-targets.py). Errors that LLVM reports (BPF
/// floats, Xtensa "Cannot select", XCOFF little-endian, ...) are not here: the
/// BackendErrorReporter turns them into diagnostics. IR and headers only
/// need the DataLayout, so they work for every triple.
static const UnsupportedTarget UnsupportedTargets[] = {
    {[](const Triple &T) { return T.getArch() == Triple::m68k; },
     Refused::MachineCode,
     "LLVM 19's experimental M68k back end crashes (instruction scheduling) "
     "on float arithmetic after a call returning a float"},
    {[](const Triple &T) { return T.isWasm() && !T.isOSBinFormatWasm(); },
     Refused::MachineCode,
     "WebAssembly is written only in the wasm object format"},
    {[](const Triple &T) { return !T.isWasm() && T.isOSBinFormatWasm(); },
     Refused::ObjectFiles,
     "only the WebAssembly architectures write wasm object files"},
    {[](const Triple &T) {
       return T.isOSBinFormatMachO() && !hasMachOAndCOFF(T);
     },
     Refused::ObjectFiles,
     "LLVM writes Mach-O objects only for x86, ARM and AArch64"},
    {[](const Triple &T) {
       return T.isOSBinFormatXCOFF() &&
              !(T.isPPC() && T.isOSAIX() && !T.isLittleEndian());
     },
     Refused::MachineCode,
     "XCOFF is written only for big-endian PowerPC AIX"},
    {[](const Triple &T) { return T.isOSBinFormatGOFF() && !T.isSystemZ(); },
     Refused::MachineCode, "GOFF is written only for SystemZ"},
    {[](const Triple &T) {
       return T.isUEFI() && T.getArch() != Triple::x86_64 && !T.isAArch64();
     },
     Refused::ObjectFiles,
     "LLVM writes UEFI objects only for x86_64 and AArch64"},
    {[](const Triple &T) {
       return T.isOSBinFormatCOFF() && !T.isOSWindows() && !T.isUEFI();
     },
     Refused::MachineCode,
     "COFF is written only for Windows and UEFI"},
    // IRBuilder puts allocas in the DataLayout's address space (5 on
    // AMDGPU), and the IR generator passes their addresses where it expects
    // address space 0: invalid IR.
    {[](const Triple &T) { return T.isAMDGPU(); }, Refused::Everything,
     "bsc's IR generator keeps locals in address space 0, AMDGPU's stack is "
     "address space 5"},
};

bool bsc::checkMachineCodeSupport(const llvm::Triple &T,
                                  llvm::CodeGenFileType Kind,
                                  DiagnosticEngine &Diags) {
  bool Object = Kind == llvm::CodeGenFileType::ObjectFile;
  for (const UnsupportedTarget &U : UnsupportedTargets) {
    if (!U.Matches(T) || U.What == Refused::Everything ||
        (U.What == Refused::ObjectFiles && !Object))
      continue;
    bool OnlyObjects = U.What == Refused::ObjectFiles;
    Diags.report(llvm::SMLoc(), diag::err_unsupported_target)
        << (OnlyObjects ? "object files" : "machine code") << T.str()
        << U.Reason
        << (OnlyObjects ? "; use -S or --emit=llvm" : "; use --emit=llvm");
    return false;
  }
  return true;
}

std::unique_ptr<llvm::TargetMachine>
bsc::createTargetMachine(const TargetOptions &Opts, DiagnosticEngine &Diags) {
  initializeTargets();
  const llvm::Triple &T = Opts.Triple;
  std::string Spelled = Opts.Spelling.empty() ? T.str() : Opts.Spelling;
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
    Diags.report(llvm::SMLoc(), diag::err_unknown_target) << Spelled << Error;
    return nullptr;
  }
  for (const UnsupportedTarget &U : UnsupportedTargets)
    if (U.What == Refused::Everything && U.Matches(T)) {
      Diags.report(llvm::SMLoc(), diag::err_unsupported_target)
          << "code" << Spelled << U.Reason << "";
      return nullptr;
    }
  std::unique_ptr<llvm::MCSubtargetInfo> STI(
      Target->createMCSubtargetInfo(T.str(), "", ""));
  std::string CPU = Opts.CPU.empty() ? getDefaultCPU(T) : Opts.CPU;
  // LLVM only warns (on stderr) about an unknown CPU and then generates code
  // for a generic one; for a robot that is a silent miscompile, so check.
  // (Every default of getDefaultCPU is valid: utils/check-targets.py.)
  if (!STI || !STI->isCPUStringValid(CPU)) {
    Diags.report(llvm::SMLoc(), diag::err_unknown_cpu) << CPU << Spelled;
    return nullptr;
  }
  llvm::TargetOptions TO;
  // LLVM 19's Xtensa back end stops with "PIC relocations is not supported".
  llvm::Reloc::Model RM =
      T.getArch() == Triple::xtensa ? llvm::Reloc::Static : llvm::Reloc::PIC_;
  std::unique_ptr<llvm::TargetMachine> TM(Target->createTargetMachine(
      T.str(), CPU, /*Features=*/"", TO, RM, std::nullopt,
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
