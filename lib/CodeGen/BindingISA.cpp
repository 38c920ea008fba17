//===- BindingISA.cpp - instructions a binding object's CPU lacks ---------===//
//
// A binding object compiled for a newer CPU than the robot's (the default
// -march of a 32-bit x86 compiler is often i686, which has CMOV) links
// fine and then dies of SIGILL on the Geode the first time the behavior
// calls it. bsc disassembles the objects it is given for such a target and
// names the function holding the first instruction the CPU lacks.
//
// Which instructions: those test/Target/i586-isa.test keeps out of bsc's
// own output, each with the CPU feature it needs: CMOV, FCMOV and the P6
// x87 compares (cmov), and any SSE/AVX register (sse, avx, avx512f).
//
//===----------------------------------------------------------------------===//
#include "bsc/CodeGen/Target.h"
#include "llvm/Demangle/Demangle.h"
#include "llvm/MC/MCAsmInfo.h"
#include "llvm/MC/MCContext.h"
#include "llvm/MC/MCDisassembler/MCDisassembler.h"
#include "llvm/MC/MCInst.h"
#include "llvm/MC/MCInstPrinter.h"
#include "llvm/MC/MCInstrInfo.h"
#include "llvm/MC/MCRegisterInfo.h"
#include "llvm/MC/MCSubtargetInfo.h"
#include "llvm/MC/MCTargetOptions.h"
#include "llvm/MC/TargetRegistry.h"
#include "llvm/Object/Archive.h"
#include "llvm/Object/ELFObjectFile.h"
#include "llvm/Object/ObjectFile.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;

namespace {
/// An instruction (by its AT&T text) and the feature it needs.
struct NeedsFeature {
  llvm::StringRef Pattern; ///< A mnemonic prefix, or a register prefix.
  bool IsRegister;
  const char *Feature;
};
const NeedsFeature Checks[] = {
    {"cmov", false, "cmov"},   {"fcmov", false, "cmov"},
    {"fcomi", false, "cmov"},  {"fucomi", false, "cmov"},
    {"xmm", true, "sse"},      {"ymm", true, "avx"},
    {"zmm", true, "avx512f"},
};

/// Disassembles the functions of one object file.
class Scanner {
public:
  Scanner(const llvm::TargetMachine &TM, CPUMismatch &Result)
      : TM(TM), Result(Result) {}

  llvm::Error scan(const llvm::object::ObjectFile &Obj) {
    const llvm::Target &T = TM.getTarget();
    const llvm::Triple &TT = TM.getTargetTriple();
    const llvm::MCSubtargetInfo &STI = *TM.getMCSubtargetInfo();
    std::unique_ptr<llvm::MCRegisterInfo> MRI(T.createMCRegInfo(TT.str()));
    llvm::MCTargetOptions Options;
    std::unique_ptr<llvm::MCAsmInfo> MAI(
        T.createMCAsmInfo(*MRI, TT.str(), Options));
    std::unique_ptr<llvm::MCInstrInfo> MII(T.createMCInstrInfo());
    if (!MRI || !MAI || !MII)
      return llvm::createStringError("no disassembler for " + TT.str());
    llvm::MCContext Ctx(TT, MAI.get(), MRI.get(), &STI);
    std::unique_ptr<llvm::MCDisassembler> Dis(
        T.createMCDisassembler(STI, Ctx));
    // Intel syntax: mnemonics without AT&T's size suffixes (`cmovl`).
    std::unique_ptr<llvm::MCInstPrinter> Printer(T.createMCInstPrinter(
        TT, /*Intel*/ 1, *MAI, *MII, *MRI));
    if (!Dis || !Printer)
      return llvm::createStringError("no disassembler for " + TT.str());

    for (const llvm::object::SymbolRef &Sym : Obj.symbols()) {
      llvm::Expected<llvm::object::SymbolRef::Type> Type = Sym.getType();
      if (!Type || *Type != llvm::object::SymbolRef::ST_Function) {
        if (!Type)
          llvm::consumeError(Type.takeError());
        continue;
      }
      llvm::Expected<llvm::object::section_iterator> Sec = Sym.getSection();
      llvm::Expected<uint64_t> Addr = Sym.getAddress();
      llvm::Expected<llvm::StringRef> Name = Sym.getName();
      if (!Sec || !Addr || !Name || *Sec == Obj.section_end()) {
        llvm::consumeError(Sec.takeError());
        llvm::consumeError(Addr.takeError());
        llvm::consumeError(Name.takeError());
        continue;
      }
      llvm::Expected<llvm::StringRef> Contents = (*Sec)->getContents();
      if (!Contents) {
        llvm::consumeError(Contents.takeError());
        continue;
      }
      uint64_t Start = *Addr - (*Sec)->getAddress();
      uint64_t Size = llvm::object::ELFSymbolRef(Sym).getSize();
      if (Start > Contents->size() || Size > Contents->size() - Start)
        continue; // Damaged; the binding reader reports such objects.
      scanFunction(*Dis, *Printer, STI,
                   llvm::arrayRefFromStringRef(Contents->substr(Start, Size)),
                   *Name);
    }
    return llvm::Error::success();
  }

private:
  void scanFunction(llvm::MCDisassembler &Dis, llvm::MCInstPrinter &Printer,
                    const llvm::MCSubtargetInfo &STI,
                    llvm::ArrayRef<uint8_t> Bytes, llvm::StringRef Name) {
    for (uint64_t At = 0; At < Bytes.size();) {
      llvm::MCInst Inst;
      uint64_t Length = 0;
      if (Dis.getInstruction(Inst, Length, Bytes.slice(At), At,
                             llvm::nulls()) !=
          llvm::MCDisassembler::Success) {
        At += Length ? Length : 1;
        continue;
      }
      At += Length;
      std::string Text;
      llvm::raw_string_ostream OS(Text);
      Printer.printInst(&Inst, At, "", STI, OS);
      llvm::StringRef Trimmed = llvm::StringRef(Text).trim();
      for (const NeedsFeature &C : Checks) {
        bool Hit = C.IsRegister ? Trimmed.contains(C.Pattern)
                                : Trimmed.starts_with(C.Pattern);
        if (!Hit || STI.checkFeatures(std::string("+") + C.Feature))
          continue;
        if (Result.Count++ == 0) {
          Result.Function = llvm::demangle(Name.str());
          Result.Instruction = Trimmed.split('\t').first.str();
        }
        break;
      }
    }
  }

  const llvm::TargetMachine &TM;
  CPUMismatch &Result;
};
} // namespace

llvm::Expected<CPUMismatch>
bsc::findInstructionsCPULacks(const llvm::TargetMachine &TM,
                              llvm::StringRef Path) {
  CPUMismatch Result;
  auto Buf = llvm::MemoryBuffer::getFile(Path);
  if (!Buf)
    return llvm::createStringError(Buf.getError(), "cannot read " + Path);
  Scanner S(TM, Result);
  auto ScanBinary = [&](llvm::MemoryBufferRef Ref) -> llvm::Error {
    auto Obj = llvm::object::ObjectFile::createObjectFile(Ref);
    if (!Obj) {
      // Not an object of ours (the binding reader reports what matters).
      llvm::consumeError(Obj.takeError());
      return llvm::Error::success();
    }
    return S.scan(**Obj);
  };
  if (llvm::StringRef((*Buf)->getBuffer()).starts_with("!<arch>\n")) {
    auto Ar = llvm::object::Archive::create((*Buf)->getMemBufferRef());
    if (!Ar) {
      llvm::consumeError(Ar.takeError());
      return Result;
    }
    llvm::Error Err = llvm::Error::success();
    for (const llvm::object::Archive::Child &C : (*Ar)->children(Err)) {
      auto Ref = C.getMemoryBufferRef();
      if (!Ref) {
        llvm::consumeError(Ref.takeError());
        continue;
      }
      if (llvm::Error E = ScanBinary(*Ref))
        return E;
    }
    llvm::consumeError(std::move(Err));
    return Result;
  }
  if (llvm::Error E = ScanBinary((*Buf)->getMemBufferRef()))
    return E;
  return Result;
}
