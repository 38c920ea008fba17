//===- BindingReader.cpp - read bs_module_* descriptors from objects ------===//
//
// bindings.md "How bsc finds modules": every defined symbol `bs_module_*` in
// section `bs_modules` of an ELF relocatable is one descriptor written by
// bscript/Bind.h. Its pointer-sized fields ("P") are zero in the file and
// filled by relocations, so the reader indexes the relocations of a section
// by offset and maps each one back to the symbol it points at: type keys
// directly, thunks through one more step, because a P field points at a
// "holder" object whose single relocation names the thunk. Only R_386_32
// (REL, addend in the data) and R_X86_64_64 (RELA) can appear in such data;
// anything else means the object is not what this reader expects.
//
// A shared library (ET_DYN) holds the same descriptor; its P fields are
// filled by dynamic relocations instead: against a symbol (R_X86_64_64,
// R_386_32, GLOB_DAT) when the target may be preempted, or RELATIVE (the
// target address in the addend, in place for i386) when the linker bound it
// locally. Everything is then located by (section index, offset in that
// section) as in a relocatable, so the rest of the reader does not care.
// Generated code calls thunks by name, so in a library they must be
// exported: a thunk outside .dynsym is an error.
//
// Reading is two passes over all objects of a compilation: pass 1 collects
// every module and the key symbol of every registered class and enum, pass
// 2 resolves each signature's keys against that table, so a module may use
// types that another module registers. Errors are collected, not returned
// at the first, so that one run reports every broken binding.
//
// The record layout mirrors bs::detail::rec in include/bscript/Bind.h.
//
//===----------------------------------------------------------------------===//
#include "ELFChecks.h"
#include "bsc/Bind/Bind.h"
#include "bscript/descriptor.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSet.h"
#include "llvm/BinaryFormat/ELF.h"
#include "llvm/BinaryFormat/Magic.h"
#include "llvm/Demangle/Demangle.h"
#include "llvm/Object/Archive.h"
#include "llvm/Object/ELF.h"
#include "llvm/Object/ELFObjectFile.h"
#include "llvm/Support/Endian.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/TargetParser/Triple.h"

using namespace llvm;
using namespace llvm::object;
using namespace bsc;
using namespace bsc::bind;

namespace {

//===----------------------------------------------------------------------===//
// The descriptor layout (bscript/descriptor.h)
//===----------------------------------------------------------------------===//

constexpr const char *Magic = BS_DESCRIPTOR_MAGIC;
constexpr uint32_t NoIndex = BS_NO_INDEX;
constexpr uint32_t HeaderSize = BS_DESCRIPTOR_HEADER_SIZE;

enum Table {
  T_Class = BS_TABLE_CLASSES,
  T_Member = BS_TABLE_MEMBERS,
  T_Param = BS_TABLE_PARAMS,
  T_Enum = BS_TABLE_ENUMS,
  T_Value = BS_TABLE_VALUES,
  NumTables = BS_NUM_TABLES
};

/// Number of P fields that start each record, and the u32 fields after
/// them (the minimum record size is Ptrs * P + 4 * Words).
constexpr unsigned TablePtrs[NumTables] = BS_TABLE_POINTERS;
constexpr unsigned TableWords[NumTables] = BS_TABLE_MIN_WORDS;

const char *const TableNames[NumTables] = {"class", "member", "param", "enum",
                                           "value"};

//===----------------------------------------------------------------------===//
// Errors
//===----------------------------------------------------------------------===//

/// Collects the messages of one readBindings call.
struct BindErrors {
  std::vector<std::string> Messages;
  void add(StringRef File, StringRef Path, const Twine &Msg) {
    std::string S = File.str() + ": ";
    if (!Path.empty())
      S += Path.str() + ": ";
    S += Msg.str();
    Messages.push_back(std::move(S));
  }
  void add(StringRef File, StringRef Path, Error E) {
    add(File, Path, toString(std::move(E)));
  }
  bool empty() const { return Messages.empty(); }
  Error take() {
    if (Messages.empty())
      return Error::success();
    std::string All = join(Messages, "\n");
    Messages.clear();
    return createStringError(inconvertibleErrorCode(), All);
  }
};

std::string demangled(StringRef Sym) { return demangle(Sym.str()); }

/// The C++ type of a key symbol `bs::TypeKey<T>::id`.
std::string typeOfKey(StringRef Key) {
  std::string D = demangled(Key);
  StringRef S(D);
  if (S.consume_front("bs::TypeKey<") && S.consume_back(">::id"))
    return S.rtrim().str();
  return D;
}

bool hasExternalLinkage(uint8_t Binding) {
  return Binding == ELF::STB_GLOBAL || Binding == ELF::STB_WEAK ||
         Binding == ELF::STB_GNU_UNIQUE;
}

//===----------------------------------------------------------------------===//
// One ELF relocatable
//===----------------------------------------------------------------------===//

/// Where a pointer field points: a symbol, and the place it is defined.
struct Pointee {
  std::string Name;
  uint8_t Binding = ELF::STB_LOCAL;
  bool Defined = false;
  uint64_t SectionIndex = 0;
  uint64_t Offset = 0; ///< In its section.
  /// Shared libraries: defined in .dynsym with default or protected
  /// visibility, so that code outside the library can refer to it.
  bool Exported = false;
};

struct Reloc {
  uint32_t Type = 0;
  bool HasSym = false;
  SymbolRef Sym;
  int64_t Addend = 0;
  /// Shared libraries: the symbol, read when indexing (the relocation's
  /// symbol index is checked there, which SymbolRef would not be), or why
  /// the relocation cannot be used.
  Pointee DynSym;
  std::string Error;
};

/// A descriptor symbol `bs_module_*` and where it is defined.
struct DescriptorSym {
  std::string Name;
  uint64_t SectionIndex = 0;
  uint64_t Offset = 0;
  bool Exported = true;
  std::string SectionName;
};

class ObjectReader {
public:
  ObjectReader(const ELFObjectFileBase &Obj, StringRef File, BindErrors &Errs)
      : Obj(Obj), File(File.str()), Errs(Errs),
        P(Obj.getBytesInAddress()),
        Is386(Obj.getEMachine() == ELF::EM_386),
        IsDyn(Obj.getEType() == ELF::ET_DYN) {}

  /// Reads every descriptor of the object into `Out`.
  void readModules(std::vector<BoundModule> &Out);

private:
  const ELFObjectFileBase &Obj;
  std::string File;
  BindErrors &Errs;
  unsigned P;
  bool Is386;
  bool IsDyn; ///< A shared library: dynamic relocations, addresses.

  // Per section: relocations by offset, and contents.
  DenseMap<uint64_t, DenseMap<uint64_t, Reloc>> RelocsBySection;
  bool RelocsIndexed = false;
  // Defined symbols by (section index, offset), for section-relative
  // relocations; the best (exported, then external, before local) wins.
  DenseMap<std::pair<uint64_t, uint64_t>, Pointee> SymbolAt;
  /// Shared libraries: the allocated sections by address.
  struct SectionRange {
    uint64_t Addr, Size, Index;
  };
  std::vector<SectionRange> Sections;
  /// Shared libraries: the descriptors, found while indexing.
  std::vector<DescriptorSym> DynDescriptors;
  /// Shared libraries: a table could not be read (reported); reading the
  /// descriptors would only add follow-on errors.
  bool DynDamaged = false;

  void indexRelocations();
  void addSymbolAt(Pointee Pt);
  template <class ELFT> void indexDynamic(const ELFObjectFile<ELFT> &EObj);
  /// Shared libraries: the place of address `Addr`.
  std::optional<std::pair<uint64_t, uint64_t>> locate(uint64_t Addr) const;
  Expected<Pointee> pointeeAt(uint64_t Sec, uint64_t Off);
  Expected<Pointee> resolveDynamic(const Reloc &R);
  Expected<StringRef> contents(uint64_t SectionIndex);
  /// The pointer field at `Off` of section `Sec`: std::nullopt if null.
  Expected<std::optional<Pointee>> pointerAt(uint64_t Sec, uint64_t Off);
  Expected<Pointee> resolve(const Reloc &R);
  /// Slot `Slot` of a holder object: the thunk it points at.
  Expected<std::optional<Pointee>> followHolder(const Pointee &Holder,
                                                unsigned Slot);
  Expected<int64_t> readMemberPointer(const Pointee &Holder);

  void readDescriptor(StringRef SymName, uint64_t Base, uint64_t Sec,
                      StringRef Data, std::vector<BoundModule> &Out);
};

static Pointee pointeeOf(const ELFSymbolRef &Sym, uint64_t SecIndex,
                         uint64_t Offset);

void ObjectReader::addSymbolAt(Pointee Pt) {
  auto Rank = [](const Pointee &X) {
    return 2 * X.Exported + hasExternalLinkage(X.Binding);
  };
  auto [It, New] = SymbolAt.try_emplace({Pt.SectionIndex, Pt.Offset}, Pt);
  if (!New && Rank(Pt) > Rank(It->second))
    It->second = std::move(Pt);
}

std::optional<std::pair<uint64_t, uint64_t>>
ObjectReader::locate(uint64_t Addr) const {
  for (const SectionRange &S : Sections)
    if (Addr >= S.Addr && Addr - S.Addr < S.Size)
      return std::make_pair(S.Index, Addr - S.Addr);
  return std::nullopt;
}

/// Reads the symbols and dynamic relocations of a shared library through
/// ELFFile, whose accessors check every table against the file (a damaged
/// library is an error, never a read out of bounds). The relocation
/// sections are the allocated SHT_REL/RELA/RELR sections: what
/// ELFObjectFile::dynamic_relocation_sections finds through the dynamic
/// table, whose entries it does not check.
template <class ELFT>
void ObjectReader::indexDynamic(const ELFObjectFile<ELFT> &EObj) {
  const ELFFile<ELFT> &EF = EObj.getELFFile();
  auto Damaged = [&](const Twine &What, Error E) {
    DynDamaged = true;
    Errs.add(File, "", "damaged shared library: " + What + ": " +
                           toString(std::move(E)));
  };
  Expected<typename ELFT::ShdrRange> Secs = EF.sections();
  if (!Secs)
    return Damaged("section table", Secs.takeError());
  auto SectionName = [&](const typename ELFT::Shdr &S) -> std::string {
    Expected<StringRef> N = EF.getSectionName(S);
    if (N)
      return N->str();
    consumeError(N.takeError());
    return "?";
  };
  for (const auto &S : *Secs)
    if ((S.sh_flags & ELF::SHF_ALLOC) && S.sh_size)
      Sections.push_back({S.sh_addr, S.sh_size, uint64_t(&S - Secs->begin())});

  // Symbols: .dynsym (what is exported) and .symtab when not stripped.
  std::vector<Pointee> DynSyms;
  StringMap<DescriptorSym> Descriptors;
  for (const auto &SymSec : *Secs) {
    bool IsDynSym = SymSec.sh_type == ELF::SHT_DYNSYM;
    if (!IsDynSym && SymSec.sh_type != ELF::SHT_SYMTAB)
      continue;
    std::string SecName = SectionName(SymSec);
    Expected<typename ELFT::SymRange> Syms = EF.symbols(&SymSec);
    if (!Syms) {
      Damaged("symbol table '" + SecName + "'", Syms.takeError());
      continue;
    }
    Expected<StringRef> StrTab = EF.getStringTableForSymtab(SymSec, *Secs);
    if (!StrTab) {
      Damaged("symbol table '" + SecName + "'", StrTab.takeError());
      continue;
    }
    for (const auto &Sym : *Syms) {
      Pointee Pt;
      Expected<StringRef> Name = Sym.getName(*StrTab);
      if (Name)
        Pt.Name = Name->str();
      else
        consumeError(Name.takeError());
      Pt.Binding = Sym.getBinding();
      uint8_t Type = Sym.getType();
      unsigned Shndx = Sym.st_shndx;
      Pt.Defined = Shndx != ELF::SHN_UNDEF && Shndx < Secs->size() &&
                   Type != ELF::STT_SECTION && Type != ELF::STT_FILE;
      if (Pt.Defined) {
        Pt.SectionIndex = Shndx;
        Pt.Offset = Sym.st_value - (*Secs)[Shndx].sh_addr;
        uint8_t Vis = Sym.getVisibility();
        Pt.Exported = IsDynSym && hasExternalLinkage(Pt.Binding) &&
                      (Vis == ELF::STV_DEFAULT || Vis == ELF::STV_PROTECTED);
      }
      if (IsDynSym)
        DynSyms.push_back(Pt);
      if (!Pt.Defined || Pt.Name.empty())
        continue;
      if (StringRef(Pt.Name).starts_with("bs_module_") &&
          Type != ELF::STT_FUNC) {
        auto [It, New] = Descriptors.try_emplace(
            Pt.Name,
            DescriptorSym{Pt.Name, Pt.SectionIndex, Pt.Offset, Pt.Exported,
                          SectionName((*Secs)[Pt.SectionIndex])});
        if (!New)
          It->second.Exported |= Pt.Exported;
      }
      addSymbolAt(std::move(Pt));
    }
  }
  // A symbol of .symtab that .dynsym exports too is exported.
  StringSet<> Exported;
  for (const Pointee &Pt : DynSyms)
    if (Pt.Exported)
      Exported.insert(Pt.Name);
  for (auto &Entry : SymbolAt)
    Entry.second.Exported |= Exported.contains(Entry.second.Name);
  for (auto &Entry : Descriptors)
    DynDescriptors.push_back(Entry.second);
  // In the order of the object, so that messages and dumps are stable.
  llvm::sort(DynDescriptors, [](const DescriptorSym &A, const DescriptorSym &B) {
    return std::tie(A.SectionIndex, A.Offset) <
           std::tie(B.SectionIndex, B.Offset);
  });

  // Dynamic relocations, by the place they patch.
  auto Add = [&](uint64_t Where, uint32_t Type, uint32_t SymIndex,
                 std::optional<int64_t> Addend) {
    std::optional<std::pair<uint64_t, uint64_t>> Loc = locate(Where);
    if (!Loc)
      return; // Patches nothing that a descriptor could point at.
    Reloc &Rel = RelocsBySection[Loc->first][Loc->second];
    Rel = Reloc();
    Rel.Type = Type;
    if (SymIndex != 0) {
      if (SymIndex >= DynSyms.size())
        Rel.Error = "relocation against symbol " + std::to_string(SymIndex) +
                    " outside the dynamic symbol table: damaged library";
      else {
        Rel.HasSym = true;
        Rel.DynSym = DynSyms[SymIndex];
      }
    }
    if (Addend) {
      Rel.Addend = *Addend;
      return;
    }
    // REL (i386) and RELR: the addend is the pointer-sized value in place.
    Expected<StringRef> Data = contents(Loc->first);
    if (!Data) {
      Rel.Error = toString(Data.takeError());
      return;
    }
    if (Loc->second + P > Data->size())
      return; // .bss: zero
    const char *B = Data->data() + Loc->second;
    Rel.Addend = P == 4 ? int64_t(support::endian::read32le(B))
                        : int64_t(support::endian::read64le(B));
  };
  for (const auto &RelSec : *Secs) {
    if (!(RelSec.sh_flags & ELF::SHF_ALLOC))
      continue;
    std::string RelName = SectionName(RelSec);
    auto Bad = [&](Error E) {
      Damaged("relocation section '" + RelName + "'", std::move(E));
    };
    if (RelSec.sh_type == ELF::SHT_RELA) {
      Expected<typename ELFT::RelaRange> Relas = EF.relas(RelSec);
      if (!Relas) {
        Bad(Relas.takeError());
        continue;
      }
      for (const auto &R : *Relas)
        Add(R.r_offset, R.getType(false), R.getSymbol(false),
            int64_t(R.r_addend));
    } else if (RelSec.sh_type == ELF::SHT_REL) {
      Expected<typename ELFT::RelRange> Rels = EF.rels(RelSec);
      if (!Rels) {
        Bad(Rels.takeError());
        continue;
      }
      for (const auto &R : *Rels)
        Add(R.r_offset, R.getType(false), R.getSymbol(false), std::nullopt);
    } else if (RelSec.sh_type == ELF::SHT_RELR) {
      // -z pack-relative-relocs: RELATIVE relocations, addends in place.
      Expected<typename ELFT::RelrRange> Relrs = EF.relrs(RelSec);
      if (!Relrs) {
        Bad(Relrs.takeError());
        continue;
      }
      uint32_t Relative = Is386 ? uint32_t(ELF::R_386_RELATIVE)
                                : uint32_t(ELF::R_X86_64_RELATIVE);
      for (const auto &R : EF.decode_relrs(*Relrs))
        Add(R.r_offset, Relative, 0, std::nullopt);
    }
  }
}

Expected<Pointee> ObjectReader::pointeeAt(uint64_t Sec, uint64_t Off) {
  auto It = SymbolAt.find({Sec, Off});
  if (It != SymbolAt.end())
    return It->second;
  if (!IsDyn)
    return createStringError(inconvertibleErrorCode(),
                             "no symbol is defined where a pointer points "
                             "(section " +
                                 Twine(Sec) + " + " + Twine(Off) + ")");
  // A stripped library: a place without a name. Holders and member
  // pointers are read by place; a thunk or key needs its name (checked by
  // the caller).
  Pointee Pt;
  Pt.Defined = true;
  Pt.SectionIndex = Sec;
  Pt.Offset = Off;
  return Pt;
}

Expected<Pointee> ObjectReader::resolveDynamic(const Reloc &R) {
  if (!R.Error.empty())
    return createStringError(inconvertibleErrorCode(), R.Error);
  uint32_t Relative = Is386 ? uint32_t(ELF::R_386_RELATIVE)
                            : uint32_t(ELF::R_X86_64_RELATIVE);
  uint32_t Absolute =
      Is386 ? uint32_t(ELF::R_386_32) : uint32_t(ELF::R_X86_64_64);
  uint32_t GlobDat =
      Is386 ? uint32_t(ELF::R_386_GLOB_DAT) : uint32_t(ELF::R_X86_64_GLOB_DAT);
  if (R.Type == Relative) {
    uint64_t Addr = P == 4 ? uint64_t(uint32_t(R.Addend)) : uint64_t(R.Addend);
    std::optional<std::pair<uint64_t, uint64_t>> Loc = locate(Addr);
    if (!Loc)
      return createStringError(inconvertibleErrorCode(),
                               "a pointer points outside the library (0x" +
                                   Twine::utohexstr(Addr) + ")");
    return pointeeAt(Loc->first, Loc->second);
  }
  if (R.Type != Absolute && R.Type != GlobDat) {
    StringRef Name = getELFRelocationTypeName(Obj.getEMachine(), R.Type);
    return createStringError(
        inconvertibleErrorCode(),
        "unexpected relocation type " + Name + " (expected " +
            (Is386 ? "R_386_32 or R_386_RELATIVE"
                   : "R_X86_64_64 or R_X86_64_RELATIVE") +
            "); was the library built with Bind.h?");
  }
  if (!R.HasSym)
    return createStringError(inconvertibleErrorCode(),
                             "relocation without a symbol");
  const Pointee &Sym = R.DynSym;
  int64_t Addend = R.Type == GlobDat ? 0 : R.Addend;
  if (!Sym.Defined || Addend == 0)
    return Sym; // Undefined: another library defines it.
  return pointeeAt(Sym.SectionIndex, Sym.Offset + Addend);
}

void ObjectReader::indexRelocations() {
  if (RelocsIndexed)
    return;
  RelocsIndexed = true;
  if (IsDyn) {
    if (auto *O = dyn_cast<ELF32LEObjectFile>(&Obj))
      indexDynamic(*O);
    else if (auto *O = dyn_cast<ELF64LEObjectFile>(&Obj))
      indexDynamic(*O);
    return;
  }
  for (const SectionRef &S : Obj.sections()) {
    Expected<section_iterator> Target = S.getRelocatedSection();
    if (!Target) {
      consumeError(Target.takeError());
      continue;
    }
    if (*Target == Obj.section_end())
      continue;
    // Only REL and RELA (checkSectionHeaders refused CREL, and checked
    // that the entries, their symbols and the sh_link are all there).
    uint32_t Type = ELFSectionRef(S).getType();
    if (Type != ELF::SHT_REL && Type != ELF::SHT_RELA)
      continue;
    uint64_t TargetIndex = (*Target)->getIndex();
    auto &Map = RelocsBySection[TargetIndex];
    bool IsRela = Type == ELF::SHT_RELA;
    for (const RelocationRef &R : S.relocations()) {
      int64_t Addend = 0;
      if (IsRela) {
        Expected<int64_t> A = ELFRelocationRef(R).getAddend();
        if (A)
          Addend = *A;
        else
          consumeError(A.takeError());
      } else {
        // REL: the addend is the value in the data. Only 32-bit fields can
        // carry a REL relocation that this reader accepts.
        Expected<StringRef> Data = (*Target)->getContents();
        if (Data && R.getOffset() + 4 <= Data->size())
          Addend = static_cast<int32_t>(
              support::endian::read32le(Data->data() + R.getOffset()));
        else if (!Data)
          consumeError(Data.takeError());
      }
      Reloc &Rel = Map[R.getOffset()];
      Rel.Type = static_cast<uint32_t>(R.getType());
      symbol_iterator SI = R.getSymbol();
      Rel.HasSym = SI != Obj.symbol_end();
      if (Rel.HasSym)
        Rel.Sym = *SI;
      Rel.Addend = Addend;
    }
  }
  for (const ELFSymbolRef &Sym : Obj.symbols()) {
    uint8_t Type = Sym.getELFType();
    if (Type == ELF::STT_SECTION || Type == ELF::STT_FILE)
      continue;
    Expected<section_iterator> Sec = Sym.getSection();
    if (!Sec) {
      consumeError(Sec.takeError());
      continue;
    }
    if (*Sec == Obj.section_end())
      continue;
    Expected<uint64_t> Value = Sym.getValue();
    if (!Value) {
      consumeError(Value.takeError());
      continue;
    }
    addSymbolAt(pointeeOf(Sym, (*Sec)->getIndex(), *Value));
  }
}

Expected<StringRef> ObjectReader::contents(uint64_t SectionIndex) {
  for (const SectionRef &S : Obj.sections())
    if (S.getIndex() == SectionIndex) {
      if (ELFSectionRef(S).getType() == ELF::SHT_NOBITS)
        return StringRef(); // zero-filled
      return S.getContents();
    }
  return createStringError(inconvertibleErrorCode(),
                           "no section with index " + Twine(SectionIndex));
}

static Pointee pointeeOf(const ELFSymbolRef &Sym, uint64_t SecIndex,
                         uint64_t Offset) {
  Pointee Pt;
  if (Expected<StringRef> N = Sym.getName())
    Pt.Name = N->str();
  else
    consumeError(N.takeError());
  Pt.Binding = Sym.getBinding();
  Pt.Defined = true;
  Pt.SectionIndex = SecIndex;
  Pt.Offset = Offset;
  return Pt;
}

Expected<Pointee> ObjectReader::resolve(const Reloc &R) {
  if (IsDyn)
    return resolveDynamic(R);
  uint32_t Want = Is386 ? uint32_t(ELF::R_386_32) : uint32_t(ELF::R_X86_64_64);
  if (R.Type != Want) {
    StringRef Name = getELFRelocationTypeName(Obj.getEMachine(), R.Type);
    return createStringError(
        inconvertibleErrorCode(),
        "unexpected relocation type " + Name + " (expected " +
            (Is386 ? "R_386_32" : "R_X86_64_64") +
            "); was the object built with Bind.h?");
  }
  if (!R.HasSym)
    return createStringError(inconvertibleErrorCode(),
                             "relocation without a symbol");
  ELFSymbolRef Sym(R.Sym);
  Expected<section_iterator> Sec = Sym.getSection();
  if (!Sec)
    return Sec.takeError();
  bool Defined = *Sec != Obj.section_end();
  if (Sym.getELFType() == ELF::STT_SECTION || (Defined && R.Addend != 0)) {
    // Section-relative (or symbol + offset): find the symbol defined there.
    if (!Defined)
      return createStringError(inconvertibleErrorCode(),
                               "relocation against an undefined section");
    uint64_t Base = 0;
    if (Sym.getELFType() != ELF::STT_SECTION) {
      Expected<uint64_t> V = Sym.getValue();
      if (!V)
        return V.takeError();
      Base = *V;
    }
    return pointeeAt((*Sec)->getIndex(), Base + R.Addend);
  }
  if (!Defined) {
    Pointee Pt;
    if (Expected<StringRef> N = Sym.getName())
      Pt.Name = N->str();
    else
      return N.takeError();
    Pt.Binding = Sym.getBinding();
    return Pt;
  }
  Expected<uint64_t> V = Sym.getValue();
  if (!V)
    return V.takeError();
  return pointeeOf(Sym, (*Sec)->getIndex(), *V);
}

Expected<std::optional<Pointee>> ObjectReader::pointerAt(uint64_t Sec,
                                                         uint64_t Off) {
  indexRelocations();
  auto SI = RelocsBySection.find(Sec);
  if (SI != RelocsBySection.end()) {
    auto RI = SI->second.find(Off);
    if (RI != SI->second.end()) {
      Expected<Pointee> Pt = resolve(RI->second);
      if (!Pt)
        return Pt.takeError();
      return std::optional<Pointee>(std::move(*Pt));
    }
  }
  // No relocation: the field must be null.
  Expected<StringRef> Data = contents(Sec);
  if (!Data)
    return Data.takeError();
  if (Off + P <= Data->size())
    for (unsigned I = 0; I < P; ++I)
      if ((*Data)[Off + I] != 0)
        return createStringError(inconvertibleErrorCode(),
                                 "a pointer field has no relocation");
  return std::optional<Pointee>();
}

Expected<std::optional<Pointee>>
ObjectReader::followHolder(const Pointee &Holder, unsigned Slot) {
  if (!Holder.Defined)
    return createStringError(inconvertibleErrorCode(),
                             "holder '" + Holder.Name +
                                 "' is not defined in this object");
  return pointerAt(Holder.SectionIndex, Holder.Offset + Slot * P);
}

Expected<int64_t> ObjectReader::readMemberPointer(const Pointee &Holder) {
  if (!Holder.Defined)
    return createStringError(inconvertibleErrorCode(),
                             "member pointer '" + Holder.Name +
                                 "' is not defined in this object");
  Expected<StringRef> Data = contents(Holder.SectionIndex);
  if (!Data)
    return Data.takeError();
  if (Data->empty())
    return 0; // .bss: offset 0
  if (Holder.Offset + P > Data->size())
    return createStringError(inconvertibleErrorCode(),
                             "member pointer outside its section");
  const char *B = Data->data() + Holder.Offset;
  return P == 4 ? int64_t(int32_t(support::endian::read32le(B)))
                : int64_t(support::endian::read64le(B));
}

/// Bounds-checked little-endian access to one descriptor.
class DescriptorView {
public:
  DescriptorView(StringRef Bytes) : Bytes(Bytes) {}
  uint32_t u32(uint64_t Off) const {
    return Off + 4 <= Bytes.size()
               ? support::endian::read32le(Bytes.data() + Off)
               : 0;
  }
  StringRef Bytes;
};

void ObjectReader::readDescriptor(StringRef SymName, uint64_t Base,
                                  uint64_t Sec, StringRef Data,
                                  std::vector<BoundModule> &Out) {
  auto Fail = [&](const Twine &Msg) { Errs.add(File, SymName, Msg); };
  if (Base + HeaderSize > Data.size()) {
    Fail("descriptor is truncated");
    return;
  }
  DescriptorView D(Data.substr(Base));
  if (std::memcmp(D.Bytes.data(), Magic, 8) != 0) {
    Fail("bad descriptor magic: object built for another target, or not "
         "by bscript/Bind.h");
    return;
  }
  uint32_t Version = D.u32(BS_HDR_VERSION);
  if (Version == 0 || Version > SupportedVersion) {
    Fail("descriptor version " + Twine(Version) + " is not supported (bsc "
         "reads version " + Twine(SupportedVersion) +
         "): object built for another target or with another bscript/Bind.h");
    return;
  }
  if (D.u32(BS_HDR_PTR_SIZE) != P) {
    Fail("descriptor pointer size " + Twine(D.u32(BS_HDR_PTR_SIZE)) +
         " does not match the " + Twine(P * 8) +
         "-bit object: object built for another target");
    return;
  }
  uint32_t Total = D.u32(BS_HDR_TOTAL_SIZE);
  if (D.u32(BS_HDR_HEADER_SIZE) < HeaderSize || Total > D.Bytes.size()) {
    Fail("descriptor is truncated");
    return;
  }
  D.Bytes = D.Bytes.take_front(Total);

  // Tables.
  uint32_t Count[NumTables], Offset[NumTables], Size[NumTables];
  for (unsigned T = 0; T < NumTables; ++T) {
    Count[T] = D.u32(BS_HDR_TABLE(T));
    Offset[T] = D.u32(BS_HDR_TABLE(T) + 4);
    Size[T] = D.u32(BS_HDR_TABLE(T) + 8);
    uint32_t Min = TablePtrs[T] * P + 4 * TableWords[T];
    if (Size[T] < Min || uint64_t(Offset[T]) + uint64_t(Count[T]) * Size[T] >
                             Total) {
      Fail(Twine("bad ") + TableNames[T] + " table in the descriptor");
      return;
    }
  }
  uint32_t StrOff = D.u32(BS_HDR_STRING_OFFSET), StrSize = D.u32(BS_HDR_STRING_SIZE);
  if (uint64_t(StrOff) + StrSize > Total || StrSize == 0) {
    Fail("bad string table in the descriptor");
    return;
  }
  StringRef Strings = D.Bytes.substr(StrOff, StrSize);
  bool BadString = false;
  auto Str = [&](uint32_t Off) -> std::string {
    if (Off >= Strings.size()) {
      BadString = true;
      return "";
    }
    size_t End = Strings.find('\0', Off);
    if (End == StringRef::npos) {
      BadString = true;
      return "";
    }
    return Strings.slice(Off, End).str();
  };
  auto Rec = [&](Table T, uint32_t I) -> uint64_t {
    return Offset[T] + uint64_t(I) * Size[T];
  };
  // Word W (0-based, after the P fields) of record I of table T.
  auto Word = [&](Table T, uint32_t I, unsigned W) {
    return D.u32(Rec(T, I) + TablePtrs[T] * P + 4 * W);
  };
  // P field K of record I of table T, as a pointee.
  auto Ptr = [&](Table T, uint32_t I, unsigned K,
                 const Twine &Path) -> std::optional<Pointee> {
    Expected<std::optional<Pointee>> Pt =
        pointerAt(Sec, Base + Rec(T, I) + K * P);
    if (!Pt) {
      Errs.add(File, Path.str(), Pt.takeError());
      return std::nullopt;
    }
    return *Pt;
  };

  BoundModule M;
  M.File = File;
  M.Symbol = SymName.str();
  M.Version = Version;
  M.Name = Str(D.u32(BS_HDR_NAME));
  StringRef Want = StringRef(SymName).drop_front(strlen("bs_module_"));
  if (M.Name != Want) {
    Fail("descriptor names module '" + M.Name + "'");
    return;
  }

  // A linked library turns hidden symbols into locals, so there only the
  // name tells an anonymous namespace.
  auto InternalKey = [&](const Pointee &Pt) {
    return IsDyn ? Pt.Name.empty() || StringRef(Pt.Name).contains("_GLOBAL__N")
                 : !hasExternalLinkage(Pt.Binding);
  };
  // A key field: the symbol of bs::TypeKey<T>::id, which must be external.
  auto Key = [&](std::optional<Pointee> Pt, const Twine &Path) -> std::string {
    if (!Pt)
      return "";
    if (IsDyn && Pt->Name.empty()) {
      Errs.add(File, Path.str(),
               "the type key has no symbol (a stripped library whose key is "
               "not exported); bsc identifies types by their key's name: "
               "keep the symbol table or give bs::TypeKey default "
               "visibility");
      return "";
    }
    if (InternalKey(*Pt))
      Errs.add(File, Path.str(),
               "type '" + typeOfKey(Pt->Name) +
                   "' has internal linkage (declared in an anonymous "
                   "namespace or local to a function?); bsc cannot identify "
                   "it across objects");
    return Pt->Name;
  };
  // Once a class's key has internal linkage, so has every thunk of the
  // class: report the class once.
  bool QuietLinkage = false;
  // Hidden thunks of a shared library have one cause (its visibility):
  // the first is reported, with the count of the others added at the end.
  std::optional<size_t> HiddenThunkMessage;
  unsigned HiddenThunks = 0;
  // A thunk through its holder: must be callable by name.
  auto Thunk = [&](std::optional<Pointee> Holder, unsigned Slot,
                   const Twine &Path) -> std::string {
    if (!Holder)
      return "";
    Expected<std::optional<Pointee>> T = followHolder(*Holder, Slot);
    if (!T) {
      Errs.add(File, Path.str(), T.takeError());
      return "";
    }
    if (!*T)
      return "";
    if (IsDyn) {
      // Undefined: another library is to define it, which the driver
      // checks against the libraries it links (findUndefinedSymbols).
      if ((*T)->Defined && !(*T)->Exported && !QuietLinkage &&
          HiddenThunks++ == 0) {
        HiddenThunkMessage = Errs.Messages.size();
        Errs.add(File, Path.str(),
                 "thunk '" +
                     ((*T)->Name.empty()
                          ? "at 0x" + Twine::utohexstr((*T)->Offset) +
                                " in section " + Twine((*T)->SectionIndex)
                          : Twine(demangled((*T)->Name))) +
                     "' is not exported by the shared library (built with "
                     "-fvisibility=hidden, hidden by a version script, or "
                     "a static function?); generated code calls it by "
                     "name: give the thunks default visibility (build the "
                     "bindings without -fvisibility=hidden, or list "
                     "bs::detail::* as global in the version script) or "
                     "link the binding objects statically");
      }
      return (*T)->Name;
    }
    if (!hasExternalLinkage((*T)->Binding) && !QuietLinkage)
      Errs.add(File, Path.str(),
               "thunk '" + demangled((*T)->Name) +
                   "' has internal linkage (a static function, a type in an "
                   "anonymous namespace, or a lambda at namespace scope?); "
                   "generated code cannot call it by name: give the callee "
                   "external linkage or write the lambda inside BS_MODULE");
    return (*T)->Name;
  };

  // Classes.
  uint32_t NumClasses = Count[T_Class];
  std::vector<bool> InternalClass;
  for (uint32_t I = 0; I < NumClasses; ++I) {
    BoundClass C;
    C.Name = Str(Word(T_Class, I, BS_CLASS_NAME));
    C.CppName = Str(Word(T_Class, I, BS_CLASS_CPP_NAME));
    std::string Path = M.Name + "::" + C.Name;
    C.Size = Word(T_Class, I, BS_CLASS_SIZE);
    C.Align = Word(T_Class, I, BS_CLASS_ALIGN);
    C.Flags = Word(T_Class, I, BS_CLASS_FLAGS);
    size_t ErrorsBefore = Errs.Messages.size();
    std::optional<Pointee> KeyPt = Ptr(T_Class, I, BS_CLASS_KEY, Path);
    C.Key = Key(KeyPt, Path);
    if (C.Key.empty() && Errs.Messages.size() == ErrorsBefore)
      Errs.add(File, Path, "class without a type key");
    InternalClass.push_back(KeyPt && InternalKey(*KeyPt));
    QuietLinkage = InternalClass.back();
    if (std::optional<Pointee> Life = Ptr(T_Class, I, BS_CLASS_LIFE, Path)) {
      C.Construct = Thunk(Life, 0, Path + " construct");
      C.Copy = Thunk(Life, 1, Path + " copy");
      C.Assign = Thunk(Life, 2, Path + " assign");
      C.Destroy = Thunk(Life, 3, Path + " destroy");
    }
    if (C.Align == 0 || (C.Align & (C.Align - 1)))
      Errs.add(File, Path, "alignment " + Twine(C.Align) +
                               " is not a power of two");
    M.Classes.push_back(std::move(C));
    QuietLinkage = false;
  }

  // Members.
  uint32_t NumParams = Count[T_Param];
  for (uint32_t I = 0; I < Count[T_Member]; ++I) {
    BoundMember Mb;
    uint32_t Kind = Word(T_Member, I, BS_MEMBER_KIND);
    uint32_t Owner = Word(T_Member, I, BS_MEMBER_OWNER);
    Mb.Name = Str(Word(T_Member, I, BS_MEMBER_NAME));
    Mb.CppName = Str(Word(T_Member, I, BS_MEMBER_CPP_NAME));
    std::string Path = M.Name + "::";
    if (Owner != NoIndex) {
      if (Owner >= NumClasses) {
        Errs.add(File, Path + Mb.Name, "member of an unknown class");
        continue;
      }
      Path += M.Classes[Owner].Name + ".";
    }
    Path += Mb.Name;
    if (Kind > uint32_t(MemberKind::Function)) {
      Errs.add(File, Path, "unknown member kind " + Twine(Kind));
      continue;
    }
    Mb.Kind = MemberKind(Kind);
    if (Owner == NoIndex && Mb.Kind != MemberKind::Function) {
      Errs.add(File, Path, "a module member must be a function");
      continue;
    }
    uint32_t RCode = Word(T_Member, I, BS_MEMBER_RESULT_CODE);
    if (RCode > uint32_t(TypeCode::Class)) {
      Errs.add(File, Path, "unknown type code " + Twine(RCode));
      continue;
    }
    Mb.Result.Code = TypeCode(RCode);
    Mb.Result.Flags = Word(T_Member, I, BS_MEMBER_RESULT_FLAGS);
    Mb.Result.StorageSize = Word(T_Member, I, BS_MEMBER_RESULT_SIZE);
    Mb.Flags = Word(T_Member, I, BS_MEMBER_FLAGS);
    QuietLinkage = Owner != NoIndex && InternalClass[Owner];
    uint32_t First = Word(T_Member, I, BS_MEMBER_FIRST_PARAM), N = Word(T_Member, I, BS_MEMBER_NUM_PARAMS);
    // An array field's extents: words appended to the record, so a shorter
    // record (an older Bind.h) has none.
    for (unsigned W = BS_MEMBER_EXTENT;
         W < BS_MEMBER_EXTENT + BS_MEMBER_MAX_EXTENTS &&
         TablePtrs[T_Member] * P + 4 * (W + 1) <= Size[T_Member];
         ++W) {
      uint32_t Extent = Word(T_Member, I, W);
      if (Extent == 0)
        break;
      Mb.Result.Extents.push_back(Extent);
    }
    size_t ErrorsBeforeThunk = Errs.Messages.size();
    Mb.Thunk = Thunk(Ptr(T_Member, I, BS_MEMBER_THUNK, Path), 0, Path);
    Mb.Setter = Thunk(Ptr(T_Member, I, BS_MEMBER_SETTER, Path + " setter"), 0,
                      Path + " setter");
    if (std::optional<Pointee> MP = Ptr(T_Member, I, BS_MEMBER_MEMPTR, Path)) {
      Expected<int64_t> Off = readMemberPointer(*MP);
      if (!Off)
        Errs.add(File, Path, Off.takeError());
      else
        Mb.FieldOffset = uint64_t(*Off);
    }
    if (Mb.Result.isArray()) {
      // Arrays are reached only by offset, element by element.
      if (Mb.Kind != MemberKind::Field || !Mb.FieldOffset ||
          Mb.Result.Code == TypeCode::Void) {
        if (Errs.Messages.size() == ErrorsBeforeThunk)
          Errs.add(File, Path, "an array member must be a data field");
        continue;
      }
      // Generated code indexes within the array; the array must lie within
      // its object.
      uint64_t Bytes = Mb.Result.StorageSize;
      for (uint32_t Extent : Mb.Result.Extents)
        Bytes = std::min<uint64_t>(Bytes * Extent, uint64_t(1) << 40);
      if (Bytes == 0 || *Mb.FieldOffset + Bytes > M.Classes[Owner].Size) {
        Errs.add(File, Path, "array field outside its object");
        continue;
      }
    } else if (Mb.Thunk.empty() && !QuietLinkage &&
               Errs.Messages.size() == ErrorsBeforeThunk) {
      Errs.add(File, Path, "member without a thunk");
    }
    if (Mb.Result.Code == TypeCode::Enum || Mb.Result.Code == TypeCode::Class)
      Mb.Result.Key = Key(Ptr(T_Member, I, BS_MEMBER_RESULT_KEY, Path), Path);
    if (uint64_t(First) + N > NumParams) {
      Errs.add(File, Path, "parameters outside the parameter table");
      continue;
    }
    for (uint32_t J = 0; J < N; ++J) {
      uint32_t PI = First + J;
      std::string PPath = Path + " param " + std::to_string(J);
      BoundParam Pm;
      uint32_t Code = Word(T_Param, PI, BS_PARAM_CODE);
      if (Code == 0 || Code > uint32_t(TypeCode::Class)) {
        Errs.add(File, PPath, "unknown type code " + Twine(Code));
        continue;
      }
      Pm.Type.Code = TypeCode(Code);
      Pm.Type.Flags = Word(T_Param, PI, BS_PARAM_FLAGS);
      Pm.Type.StorageSize = Word(T_Param, PI, BS_PARAM_SIZE);
      Pm.Name = Str(Word(T_Param, PI, BS_PARAM_NAME));
      uint32_t DK = Word(T_Param, PI, BS_PARAM_DEFAULT_KIND);
      Pm.Default = DK == BS_DEFAULT_INT     ? DefaultKind::Int
                   : DK == BS_DEFAULT_FLOAT ? DefaultKind::Float
                                            : DefaultKind::None;
      Pm.DefaultInt = int32_t(Word(T_Param, PI, BS_PARAM_DEFAULT_INT));
      uint32_t FBits = Word(T_Param, PI, BS_PARAM_DEFAULT_FLOAT);
      std::memcpy(&Pm.DefaultFloat, &FBits, 4);
      if (Pm.Type.Code == TypeCode::Enum || Pm.Type.Code == TypeCode::Class)
        Pm.Type.Key = Key(Ptr(T_Param, PI, BS_PARAM_KEY, PPath), PPath);
      Mb.Params.push_back(std::move(Pm));
    }
    if (Owner == NoIndex)
      M.Functions.push_back(std::move(Mb));
    else
      M.Classes[Owner].Members.push_back(std::move(Mb));
  }

  // Enums.
  for (uint32_t I = 0; I < Count[T_Enum]; ++I) {
    BoundEnum E;
    E.Name = Str(Word(T_Enum, I, BS_ENUM_NAME));
    E.CppName = Str(Word(T_Enum, I, BS_ENUM_CPP_NAME));
    std::string Path = M.Name + "::" + E.Name;
    E.Size = Word(T_Enum, I, BS_ENUM_SIZE);
    uint32_t Flags = Word(T_Enum, I, BS_ENUM_FLAGS);
    E.Scoped = Flags & BS_ENUM_SCOPED;
    E.Signed = Flags & BS_ENUM_SIGNED;
    uint32_t First = Word(T_Enum, I, BS_ENUM_FIRST_VALUE), N = Word(T_Enum, I, BS_ENUM_NUM_VALUES);
    E.Key = Key(Ptr(T_Enum, I, BS_ENUM_KEY, Path), Path);
    if (uint64_t(First) + N > Count[T_Value]) {
      Errs.add(File, Path, "values outside the value table");
      continue;
    }
    for (uint32_t J = 0; J < N; ++J)
      E.Values.push_back({Str(Word(T_Value, First + J, BS_VALUE_NAME)),
                          int32_t(Word(T_Value, First + J, BS_VALUE_VALUE))});
    M.Enums.push_back(std::move(E));
  }

  uint32_t In = D.u32(BS_HDR_INPUT_CLASS), OutC = D.u32(BS_HDR_OUTPUT_CLASS);
  if (In != NoIndex && In >= NumClasses)
    Fail("input class index out of range");
  else if (In != NoIndex)
    M.InputClass = int(In);
  if (OutC != NoIndex && OutC >= NumClasses)
    Fail("output class index out of range");
  else if (OutC != NoIndex)
    M.OutputClass = int(OutC);
  if (BadString)
    Fail("bad string offset in the descriptor");

  // The hash, as Bind.h and the runtime compute it (bs_descriptor_hash),
  // with the field offsets from the holders' relocations.
  struct FieldOffsets {
    ObjectReader &R;
    uint64_t Sec, Members;
    unsigned P;
    uint32_t RecordSize;
  } Ctx{*this, Sec, Base + Offset[T_Member], P, Size[T_Member]};
  auto FieldOffset = [](void *C, uint32_t I, int64_t *Off) -> int {
    auto &F = *static_cast<FieldOffsets *>(C);
    Expected<std::optional<Pointee>> MP = F.R.pointerAt(
        F.Sec, F.Members + uint64_t(I) * F.RecordSize + BS_MEMBER_MEMPTR * F.P);
    if (!MP) {
      consumeError(MP.takeError()); // Reported with the member above.
      return 0;
    }
    if (!*MP)
      return 0;
    Expected<int64_t> Offset = F.R.readMemberPointer(**MP);
    if (!Offset) {
      consumeError(Offset.takeError());
      return 0;
    }
    *Off = *Offset;
    return 1;
  };
  uint64_t Hash = bs_descriptor_hash(
      reinterpret_cast<const unsigned char *>(D.Bytes.data()), FieldOffset,
      &Ctx);
  M.Hash = Hash;
  if (HiddenThunkMessage && HiddenThunks > 1)
    Errs.Messages[*HiddenThunkMessage] +=
        " (" + std::to_string(HiddenThunks - 1) +
        " more thunks of this module are hidden the same way)";
  Out.push_back(std::move(M));
}

void ObjectReader::readModules(std::vector<BoundModule> &Out) {
  if (IsDyn) {
    indexRelocations();
    if (DynDamaged)
      return;
    for (const DescriptorSym &D : DynDescriptors) {
      Expected<StringRef> Data = contents(D.SectionIndex);
      if (D.SectionName != "bs_modules") {
        Errs.add(File, D.Name, "descriptor is not in section 'bs_modules'");
        continue;
      }
      if (!Data) {
        Errs.add(File, D.Name, Data.takeError());
        continue;
      }
      if (!D.Exported) {
        // Generated code refers to the descriptor for the hash check.
        Errs.add(File, D.Name,
                 "descriptor is not exported by the shared library (hidden "
                 "by a version script?); list bs_module_* as global");
        continue;
      }
      readDescriptor(D.Name, D.Offset, D.SectionIndex, *Data, Out);
    }
    return;
  }
  for (const ELFSymbolRef &Sym : Obj.symbols()) {
    Expected<StringRef> Name = Sym.getName();
    if (!Name) {
      consumeError(Name.takeError());
      continue;
    }
    // Descriptors are data: a function so named is not one.
    if (!Name->starts_with("bs_module_") || Sym.getELFType() == ELF::STT_FUNC)
      continue;
    Expected<section_iterator> Sec = Sym.getSection();
    if (!Sec) {
      consumeError(Sec.takeError());
      continue;
    }
    if (*Sec == Obj.section_end())
      continue; // a reference, not a definition
    Expected<StringRef> SecName = (*Sec)->getName();
    if (!SecName || *SecName != "bs_modules") {
      if (!SecName)
        consumeError(SecName.takeError());
      Errs.add(File, *Name, "descriptor is not in section 'bs_modules'");
      continue;
    }
    Expected<StringRef> Data = (*Sec)->getContents();
    if (!Data) {
      Errs.add(File, *Name, Data.takeError());
      continue;
    }
    Expected<uint64_t> Value = Sym.getValue();
    if (!Value) {
      Errs.add(File, *Name, Value.takeError());
      continue;
    }
    readDescriptor(*Name, *Value, (*Sec)->getIndex(), *Data, Out);
  }
}

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

  void readBuffer(MemoryBufferRef Buf, StringRef Name);
  Expected<BindingModel> finish();

private:
  const Triple &Target;
  BindErrors Errs;
  std::vector<BoundModule> Modules;

  void readBinary(Binary &Bin, StringRef Name);
  void resolve(BindingModel &Model);
};

void Reader::readBuffer(MemoryBufferRef Buf, StringRef Name) {
  file_magic Magic = identify_magic(Buf.getBuffer());
  if (Magic == file_magic::bitcode) {
    Errs.add(Name, "",
             "is LLVM bitcode, not an ELF object (compiled with -flto?); "
             "build the binding objects without -flto");
    return;
  }
  Expected<std::unique_ptr<Binary>> Bin = createBinary(Buf);
  if (!Bin) {
    Errs.add(Name, "",
             "not an ELF relocatable object, shared library or archive (" +
                 toString(Bin.takeError()) + ")");
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
        Errs.add(Member, "", CBuf.takeError());
        continue;
      }
      // llvm::object::Archive checks where the next member starts, not
      // that this one ends inside the archive.
      StringRef Whole = Ar->getMemoryBufferRef().getBuffer();
      if (!Ar->isThin() &&
          (CBuf->getBufferStart() < Whole.begin() ||
           CBuf->getBufferEnd() > Whole.end())) {
        Errs.add(Member, "", "the member runs past the end of the archive");
        break;
      }
      readBuffer(*CBuf, Member);
    }
    if (Err)
      Errs.add(Name, "", std::move(Err));
    return;
  }
  auto *Obj = dyn_cast<ELFObjectFileBase>(&Bin);
  auto NotBindable = [&] {
    Errs.add(Name, "",
             "not an ELF relocatable object or shared library (bsc reads the "
             "binding objects that will be linked: built with -c, in an "
             "archive, or linked with -shared)");
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
    Errs.add(Name, "",
             "object built for another target (" +
                 Triple::getArchTypeName(Obj->getArch()) + ", " +
                 Twine(Obj->getBytesInAddress() * 8) + "-bit; bsc compiles for " +
                 Target.str() + ")");
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
    Errs.add(Name, "",
             "is a GCC LTO object without object code (compiled with "
             "-flto?); build the binding objects without -flto or with "
             "-ffat-lto-objects");
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
      Errs.add(M.File, M.Symbol,
               "module '" + M.Name + "' is also registered by '" +
                   Model.Modules[NI->second].File + "'");
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
      Errs.add(M.File, M.Name + "::" + Name.str(),
               Twine(IsEnum ? "enum" : "class") + " '" + typeOfKey(Key) +
                   "' is registered twice: also as '" + Other.Name + "::" +
                   OtherName + "' in '" + Other.File + "'");
    };
    for (int I = 0, N = int(M.Classes.size()); I != N; ++I)
      AddKey(M.Classes[I].Key, I, false, M.Classes[I].Name);
    for (int I = 0, N = int(M.Enums.size()); I != N; ++I)
      AddKey(M.Enums[I].Key, I, true, M.Enums[I].Name);
    auto World = [&](int Cls, int &Seen, StringRef What) {
      if (Cls < 0)
        return;
      if (Seen >= 0)
        Errs.add(M.File, M.Name,
                 "the '" + What + "' type is also declared by module '" +
                     Model.Modules[Seen].Name + "' ('" +
                     Model.Modules[Seen].File + "')");
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
      Errs.add(M.File, Path.str(),
               "type '" + typeOfKey(T.Key) +
                   "' is not registered in any loaded module" +
                   (StringRef(T.Key).contains("MatrixBase") ||
                            StringRef(T.Key).contains("DenseBase")
                        ? " (an Eigen expression base: wrap the function in "
                          "a lambda that takes the registered type)"
                        : ""));
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
  std::vector<std::unique_ptr<MemoryBuffer>> Buffers;
  BindErrors OpenErrs;
  for (const std::string &Path : Paths) {
    ErrorOr<std::unique_ptr<MemoryBuffer>> Buf =
        MemoryBuffer::getFile(Path, /*IsText=*/false,
                              /*RequiresNullTerminator=*/false);
    if (!Buf) {
      OpenErrs.add(Path, "", "cannot open: " + Buf.getError().message());
      continue;
    }
    R.readBuffer((*Buf)->getMemBufferRef(), Path);
    Buffers.push_back(std::move(*Buf));
  }
  Expected<BindingModel> Model = R.finish();
  if (!OpenErrs.empty()) {
    Error E = OpenErrs.take();
    if (!Model)
      return joinErrors(std::move(E), Model.takeError());
    return E;
  }
  return Model;
}

Expected<BindingModel>
bind::readBindingBuffers(ArrayRef<MemoryBufferRef> Buffers,
                         const Triple &Target) {
  Reader R(Target);
  for (MemoryBufferRef B : Buffers)
    R.readBuffer(B, B.getBufferIdentifier());
  return R.finish();
}

//===----------------------------------------------------------------------===//
// Model queries
//===----------------------------------------------------------------------===//

/// The element of `Range` whose Name is `N`, or null: every model lookup.
template <typename RangeT>
static auto findNamed(const RangeT &Range, StringRef N)
    -> decltype(&*std::begin(Range)) {
  for (const auto &Element : Range)
    if (Element.Name == N)
      return &Element;
  return nullptr;
}

const BoundMember *BoundClass::findMember(StringRef N) const {
  return findNamed(Members, N);
}

const BoundClass *BoundModule::findClass(StringRef N) const {
  return findNamed(Classes, N);
}

const BoundEnum *BoundModule::findEnum(StringRef N) const {
  return findNamed(Enums, N);
}

const BoundMember *BoundModule::findFunction(StringRef N) const {
  return findNamed(Functions, N);
}

const BoundModule *BindingModel::findModule(StringRef N) const {
  return findNamed(Modules, N);
}

const BoundModule *BindingModel::getWorldModule() const {
  for (const BoundModule &M : Modules)
    if (M.InputClass >= 0)
      return &M;
  for (const BoundModule &M : Modules)
    if (M.OutputClass >= 0)
      return &M;
  return nullptr;
}

const BoundClass *BindingModel::getClass(const BoundType &T) const {
  if (T.Code != TypeCode::Class || T.Module < 0)
    return nullptr;
  return &Modules[T.Module].Classes[T.Index];
}

const BoundEnum *BindingModel::getEnum(const BoundType &T) const {
  if (T.Code != TypeCode::Enum || T.Module < 0)
    return nullptr;
  return &Modules[T.Module].Enums[T.Index];
}

std::string BindingModel::getQualifiedName(const BoundType &T) const {
  if (const BoundClass *C = getClass(T))
    return Modules[T.Module].Name + "::" + C->Name;
  if (const BoundEnum *E = getEnum(T))
    return Modules[T.Module].Name + "::" + E->Name;
  return "";
}
