//===- BindingReader.cpp - read the binding objects of a compilation ------===//
//
// readBindings opens each file (an ELF relocatable, a shared library, or an
// archive of relocatables), refuses what bsc cannot read (bitcode, GCC's
// slim LTO objects, programs, another target, damaged section headers),
// runs an ObjectReader over each ELF file (ObjectReader.cpp,
// DescriptorDecoder.cpp) and then resolves the modules against each other.
//
// Resolving is the second of two passes over all objects: pass 1 (reading)
// collects every module and the key symbol of every registered class and
// enum, pass 2 resolves each signature's keys against that table, so a
// module may use types that another module registers. Problems are
// collected, not returned at the first, so that one run reports every
// broken binding; each is a diagnostic kind of DiagnosticKinds.def.
//
//===----------------------------------------------------------------------===//
#include "ELFChecks.h"
#include "ObjectReader.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/BinaryFormat/Magic.h"
#include "llvm/Demangle/Demangle.h"
#include "llvm/Object/Archive.h"
#include "llvm/Object/ELF.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/raw_ostream.h"
#include "llvm/TargetParser/Triple.h"

using namespace llvm;
using namespace llvm::object;
using namespace bsc;
using namespace bsc::bind;

//===----------------------------------------------------------------------===//
// Problems
//===----------------------------------------------------------------------===//

char BindingError::ID;
char ProblemError::ID;

std::string BindProblem::format() const {
  return DiagnosticEngine::format(getFormat(Kind), Args);
}

void BindingError::log(raw_ostream &OS) const {
  ListSeparator NL("\n");
  for (const BindProblem &P : Problems)
    OS << NL << P.format();
}

void ProblemError::log(raw_ostream &OS) const {
  std::vector<std::string> WithPlace = Args;
  WithPlace.insert(WithPlace.begin(), "?");
  OS << DiagnosticEngine::format(getFormat(Kind), WithPlace);
}

size_t BindErrors::add(StringRef File, StringRef Path, diag::Kind Kind,
                       std::vector<std::string> Args) {
  std::string Place = File.str();
  if (!Path.empty())
    Place += ": " + Path.str();
  Args.insert(Args.begin(), std::move(Place));
  Problems.push_back({Kind, std::move(Args)});
  return Problems.size() - 1;
}

void BindErrors::add(StringRef File, StringRef Path, Error E, StringRef What) {
  handleAllErrors(
      std::move(E),
      [&](ProblemError &P) { add(File, Path, P.Kind, std::move(P.Args)); },
      [&](const ErrorInfoBase &Other) {
        add(File, Path, diag::err_bind_damaged, {What.str(), Other.message()});
      });
}

Error BindErrors::take() {
  if (Problems.empty())
    return Error::success();
  return make_error<BindingError>(std::move(Problems));
}

std::string bind::demangled(StringRef Sym) { return demangle(Sym.str()); }

std::string bind::typeOfKey(StringRef Key) {
  std::string D = demangled(Key);
  StringRef S(D);
  if (S.consume_front("bs::TypeKey<") && S.consume_back(">::id"))
    return S.rtrim().str();
  return D;
}

bool bind::hasExternalLinkage(uint8_t Binding) {
  return Binding == ELF::STB_GLOBAL || Binding == ELF::STB_WEAK ||
         Binding == ELF::STB_GNU_UNIQUE;
}

namespace {
//===----------------------------------------------------------------------===//
// Files and archives
//===----------------------------------------------------------------------===//

/// A position-independent executable is ET_DYN too; DF_1_PIE tells it from
/// a shared library.
template <class ELFT> static bool isPIE(const ELFFile<ELFT> &EF) {
  Expected<typename ELFT::DynRange> Dyn = EF.dynamicEntries();
  if (!Dyn) {
    consumeError(Dyn.takeError());
    return false;
  }
  for (const auto &D : *Dyn)
    if (D.d_tag == ELF::DT_FLAGS_1 && (D.getVal() & ELF::DF_1_PIE))
      return true;
  return false;
}

static bool isProgram(const ELFObjectFileBase &Obj) {
  if (auto *O = dyn_cast<ELF32LEObjectFile>(&Obj))
    return isPIE(O->getELFFile());
  if (auto *O = dyn_cast<ELF64LEObjectFile>(&Obj))
    return isPIE(O->getELFFile());
  return false;
}

class Reader {
public:
  Reader(const Triple &Target) : Target(Target) {}

  void readFile(StringRef Path);
  void readBuffer(MemoryBufferRef Buf, StringRef Name);
  Expected<BindingModel> finish();

private:
  const Triple &Target;
  BindErrors Errs;
  std::vector<BoundModule> Modules;

  void readBinary(Binary &Bin, StringRef Name);
  void resolve(BindingModel &Model);
};

void Reader::readFile(StringRef Path) {
  ErrorOr<std::unique_ptr<MemoryBuffer>> Buf =
      MemoryBuffer::getFile(Path, /*IsText=*/false,
                            /*RequiresNullTerminator=*/false);
  if (!Buf) {
    Errs.add(Path, "", diag::err_bind_cannot_open, {Buf.getError().message()});
    return;
  }
  readBuffer((*Buf)->getMemBufferRef(), Path); // The model copies what it keeps.
}

void Reader::readBuffer(MemoryBufferRef Buf, StringRef Name) {
  file_magic Magic = identify_magic(Buf.getBuffer());
  if (Magic == file_magic::bitcode) {
    Errs.add(Name, "", diag::err_bind_bitcode);
    return;
  }
  Expected<std::unique_ptr<Binary>> Bin = createBinary(Buf);
  if (!Bin) {
    Errs.add(Name, "", diag::err_bind_not_binary, {toString(Bin.takeError())});
    return;
  }
  readBinary(**Bin, Name);
}

void Reader::readBinary(Binary &Bin, StringRef Name) {
  if (auto *Ar = dyn_cast<Archive>(&Bin)) {
    Error Err = Error::success();
    for (const Archive::Child &C : Ar->children(Err)) {
      Expected<StringRef> CName = C.getName();
      std::string Member =
          Name.str() + "(" + (CName ? CName->str() : std::string("?")) + ")";
      if (!CName)
        consumeError(CName.takeError());
      Expected<MemoryBufferRef> CBuf = C.getMemoryBufferRef();
      if (!CBuf) {
        Errs.add(Member, "", CBuf.takeError(), "archive");
        continue;
      }
      // llvm::object::Archive checks where the next member starts, not
      // that this one ends inside the archive.
      StringRef Whole = Ar->getMemoryBufferRef().getBuffer();
      if (!Ar->isThin() &&
          (CBuf->getBufferStart() < Whole.begin() ||
           CBuf->getBufferEnd() > Whole.end())) {
        Errs.add(Member, "", diag::err_bind_damaged,
                 {"archive", "the member runs past the end of the archive"});
        break;
      }
      readBuffer(*CBuf, Member);
    }
    if (Err)
      Errs.add(Name, "", std::move(Err), "archive");
    return;
  }
  auto *Obj = dyn_cast<ELFObjectFileBase>(&Bin);
  auto NotBindable = [&] {
    Errs.add(Name, "", diag::err_bind_not_bindable);
  };
  if (!Obj ||
      (Obj->getEType() != ELF::ET_REL && Obj->getEType() != ELF::ET_DYN)) {
    NotBindable();
    return;
  }
  uint16_t WantMachine =
      Target.getArch() == Triple::x86_64 ? ELF::EM_X86_64 : ELF::EM_386;
  unsigned WantBytes = Target.isArch64Bit() ? 8 : 4;
  if (Obj->getEMachine() != WantMachine ||
      Obj->getBytesInAddress() != WantBytes) {
    Errs.add(Name, "", diag::err_bind_wrong_target,
             {Triple::getArchTypeName(Obj->getArch()).str(),
              std::to_string(Obj->getBytesInAddress() * 8), Target.str()});
    return;
  }
  // Every walk below (the PIE check, ObjectReader's, and the JIT's load of
  // the same file in `bsc run`) trusts the headers that this checks.
  if (Error E = checkSectionHeaders(*Obj)) {
    Errs.add(Name, "", std::move(E));
    return;
  }
  if (Obj->getEType() == ELF::ET_DYN && isProgram(*Obj)) {
    NotBindable();
    return;
  }
  // GCC's -flto objects hold GIMPLE, not the descriptor's bytes, unless
  // they are fat (-ffat-lto-objects): then the object code, descriptor
  // included, is there too. GCC marks slim objects with `__gnu_lto_slim`.
  bool HasLTOSections = false, HasDescriptors = false, Slim = false;
  for (const SectionRef &S : Obj->sections()) {
    Expected<StringRef> SName = S.getName();
    if (!SName) {
      consumeError(SName.takeError());
      continue;
    }
    HasLTOSections |= SName->starts_with(".gnu.lto_");
    HasDescriptors |= *SName == "bs_modules";
  }
  for (const SymbolRef &Sym : Obj->symbols()) {
    Expected<StringRef> SymName = Sym.getName();
    if (!SymName) {
      consumeError(SymName.takeError());
      continue;
    }
    Slim |= *SymName == "__gnu_lto_slim";
  }
  if (HasLTOSections && (Slim || !HasDescriptors)) {
    Errs.add(Name, "", diag::err_bind_gcc_slim_lto);
    return;
  }
  ObjectReader(*Obj, Name, Errs).readModules(Modules);
}

void Reader::resolve(BindingModel &Model) {
  // Pass 1: module names and the keys of every class and enum.
  struct Where {
    int Module, Index;
    bool IsEnum;
  };
  StringMap<Where> Keys;
  StringMap<int> Names;
  int InputModule = -1, OutputModule = -1;
  for (int MI = 0, E = int(Model.Modules.size()); MI != E; ++MI) {
    const BoundModule &M = Model.Modules[MI];
    auto [NI, NewName] = Names.try_emplace(M.Name, MI);
    if (!NewName)
      Errs.add(M.File, M.Symbol, diag::err_bind_module_twice,
               {M.Name, Model.Modules[NI->second].File});
    auto AddKey = [&](StringRef Key, int Index, bool IsEnum, StringRef Name) {
      if (Key.empty())
        return;
      auto [It, New] = Keys.try_emplace(Key, Where{MI, Index, IsEnum});
      if (New)
        return;
      const BoundModule &Other = Model.Modules[It->second.Module];
      StringRef OtherName =
          It->second.IsEnum ? StringRef(Other.Enums[It->second.Index].Name)
                            : StringRef(Other.Classes[It->second.Index].Name);
      Errs.add(M.File, M.Name + "::" + Name.str(), diag::err_bind_type_twice,
               {IsEnum ? "enum" : "class", typeOfKey(Key),
                Other.Name + "::" + OtherName.str(), Other.File});
    };
    for (int I = 0, N = int(M.Classes.size()); I != N; ++I)
      AddKey(M.Classes[I].Key, I, false, M.Classes[I].Name);
    for (int I = 0, N = int(M.Enums.size()); I != N; ++I)
      AddKey(M.Enums[I].Key, I, true, M.Enums[I].Name);
    auto World = [&](int Cls, int &Seen, StringRef What) {
      if (Cls < 0)
        return;
      if (Seen >= 0)
        Errs.add(M.File, M.Name, diag::err_bind_world_type_twice,
                 {What.str(), Model.Modules[Seen].Name,
                  Model.Modules[Seen].File});
      else
        Seen = MI;
    };
    World(M.InputClass, InputModule, "input");
    World(M.OutputClass, OutputModule, "output");
  }

  // Pass 2: every signature's types.
  auto Resolve = [&](const BoundModule &M, BoundType &T, const Twine &Path) {
    if (T.Code != TypeCode::Enum && T.Code != TypeCode::Class)
      return;
    auto It = Keys.find(T.Key);
    if (It == Keys.end() ||
        It->second.IsEnum != (T.Code == TypeCode::Enum)) {
      bool EigenBase = StringRef(T.Key).contains("MatrixBase") ||
                       StringRef(T.Key).contains("DenseBase");
      Errs.add(M.File, Path.str(), diag::err_bind_unregistered_type,
               {typeOfKey(T.Key),
                EigenBase ? " (an Eigen expression base: wrap the function "
                            "in a lambda that takes the registered type)"
                          : ""});
      return;
    }
    T.Module = It->second.Module;
    T.Index = It->second.Index;
  };
  auto ResolveMember = [&](const BoundModule &M, BoundMember &Mb,
                           const std::string &Path) {
    Resolve(M, Mb.Result, Path);
    for (size_t J = 0; J < Mb.Params.size(); ++J)
      Resolve(M, Mb.Params[J].Type, Path + " param " + std::to_string(J));
  };
  for (BoundModule &M : Model.Modules) {
    for (BoundClass &C : M.Classes)
      for (BoundMember &Mb : C.Members)
        ResolveMember(M, Mb, M.Name + "::" + C.Name + "." + Mb.Name);
    for (BoundMember &Mb : M.Functions)
      ResolveMember(M, Mb, M.Name + "::" + Mb.Name);
    for (BoundMember &Mb : M.Constants)
      ResolveMember(M, Mb, M.Name + "::" + Mb.Name);
  }
}

Expected<BindingModel> Reader::finish() {
  BindingModel Model;
  Model.PointerSize = Target.isArch64Bit() ? 8 : 4;
  Model.Modules = std::move(Modules);
  resolve(Model);
  if (!Errs.empty())
    return Errs.take();
  return Model;
}

} // namespace

Expected<BindingModel> bind::readBindings(ArrayRef<std::string> Paths,
                                          const Triple &Target) {
  Reader R(Target);
  for (const std::string &Path : Paths)
    R.readFile(Path);
  return R.finish();
}

Expected<BindingModel>
bind::readBindingBuffers(ArrayRef<MemoryBufferRef> Buffers,
                         const Triple &Target) {
  Reader R(Target);
  for (MemoryBufferRef B : Buffers)
    R.readBuffer(B, B.getBufferIdentifier());
  return R.finish();
}
