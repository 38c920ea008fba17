//===- ObjectReader.cpp - map a descriptor's pointers to symbols ----------===//
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
// section) as in a relocatable, so the decoder does not care.
// Generated code calls thunks by name, so in a library they must be
// exported: a thunk outside .dynsym is an error (DescriptorDecoder.cpp).
//
//===----------------------------------------------------------------------===//
#include "ObjectReader.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSet.h"
#include "llvm/Object/ELF.h"
#include "llvm/Support/Endian.h"

using namespace llvm;
using namespace llvm::object;
using namespace bsc;
using namespace bsc::bind;

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
/// table, whose entries it does not check. Fills the reader's Sections,
/// SymbolAt, DynDescriptors and RelocsBySection.
template <class ELFT> class bind::DynamicIndexer {
public:
  DynamicIndexer(ObjectReader &R, const ELFFile<ELFT> &EF) : R(R), EF(EF) {}

  void run() {
    Expected<typename ELFT::ShdrRange> Sections = EF.sections();
    if (!Sections)
      return damaged("section table", Sections.takeError());
    Secs = *Sections;
    for (const auto &S : Secs)
      if ((S.sh_flags & ELF::SHF_ALLOC) && S.sh_size)
        R.Sections.push_back({S.sh_addr, S.sh_size, uint64_t(&S - Secs.begin())});
    // Symbols: .dynsym (what is exported) and .symtab when not stripped.
    for (const auto &SymSec : Secs)
      if (SymSec.sh_type == ELF::SHT_DYNSYM || SymSec.sh_type == ELF::SHT_SYMTAB)
        indexSymbols(SymSec);
    markExported();
    for (const auto &RelSec : Secs)
      if (RelSec.sh_flags & ELF::SHF_ALLOC)
        indexRelocations(RelSec);
  }

private:
  void damaged(const Twine &What, Error E) {
    R.DynDamaged = true;
    R.Errs.add(R.File, "", diag::err_bind_damaged,
               {R.what().str(), (What + ": " + toString(std::move(E))).str()});
  }

  std::string sectionName(const typename ELFT::Shdr &S) {
    Expected<StringRef> N = EF.getSectionName(S);
    if (N)
      return N->str();
    consumeError(N.takeError());
    return "?";
  }

  void indexSymbols(const typename ELFT::Shdr &SymSec) {
    bool IsDynSym = SymSec.sh_type == ELF::SHT_DYNSYM;
    std::string SecName = sectionName(SymSec);
    Expected<typename ELFT::SymRange> Syms = EF.symbols(&SymSec);
    if (!Syms)
      return damaged("symbol table '" + SecName + "'", Syms.takeError());
    Expected<StringRef> StrTab = EF.getStringTableForSymtab(SymSec, Secs);
    if (!StrTab)
      return damaged("symbol table '" + SecName + "'", StrTab.takeError());
    for (const auto &Sym : *Syms)
      addSymbol(Sym, *StrTab, IsDynSym);
  }

  void addSymbol(const typename ELFT::Sym &Sym, StringRef StrTab,
                 bool IsDynSym) {
    Pointee Pt;
    Expected<StringRef> Name = Sym.getName(StrTab);
    if (Name)
      Pt.Name = Name->str();
    else
      consumeError(Name.takeError());
    Pt.Binding = Sym.getBinding();
    uint8_t Type = Sym.getType();
    unsigned Shndx = Sym.st_shndx;
    Pt.Defined = Shndx != ELF::SHN_UNDEF && Shndx < Secs.size() &&
                 Type != ELF::STT_SECTION && Type != ELF::STT_FILE;
    if (Pt.Defined) {
      Pt.SectionIndex = Shndx;
      Pt.Offset = Sym.st_value - Secs[Shndx].sh_addr;
      uint8_t Vis = Sym.getVisibility();
      Pt.Exported = IsDynSym && hasExternalLinkage(Pt.Binding) &&
                    (Vis == ELF::STV_DEFAULT || Vis == ELF::STV_PROTECTED);
    }
    if (IsDynSym)
      DynSyms.push_back(Pt);
    if (!Pt.Defined || Pt.Name.empty())
      return;
    if (StringRef(Pt.Name).starts_with("bs_module_") && Type != ELF::STT_FUNC) {
      auto [It, New] = Descriptors.try_emplace(
          Pt.Name, DescriptorSym{Pt.Name, Pt.SectionIndex, Pt.Offset,
                                 Pt.Exported,
                                 sectionName(Secs[Pt.SectionIndex])});
      if (!New)
        It->second.Exported |= Pt.Exported;
    }
    R.addSymbolAt(std::move(Pt));
  }

  /// A symbol of .symtab that .dynsym exports too is exported; the
  /// descriptors in the order of the object, so that messages and dumps are
  /// stable.
  void markExported() {
    StringSet<> Exported;
    for (const Pointee &Pt : DynSyms)
      if (Pt.Exported)
        Exported.insert(Pt.Name);
    for (auto &Entry : R.SymbolAt)
      Entry.second.Exported |= Exported.contains(Entry.second.Name);
    for (auto &Entry : Descriptors)
      R.DynDescriptors.push_back(Entry.second);
    llvm::sort(R.DynDescriptors,
               [](const DescriptorSym &A, const DescriptorSym &B) {
                 return std::tie(A.SectionIndex, A.Offset) <
                        std::tie(B.SectionIndex, B.Offset);
               });
  }

  void indexRelocations(const typename ELFT::Shdr &RelSec) {
    std::string RelName = sectionName(RelSec);
    auto Bad = [&](Error E) {
      damaged("relocation section '" + RelName + "'", std::move(E));
    };
    if (RelSec.sh_type == ELF::SHT_RELA) {
      Expected<typename ELFT::RelaRange> Relas = EF.relas(RelSec);
      if (!Relas)
        return Bad(Relas.takeError());
      for (const auto &Rel : *Relas)
        addRelocation(Rel.r_offset, Rel.getType(false), Rel.getSymbol(false),
                      int64_t(Rel.r_addend));
    } else if (RelSec.sh_type == ELF::SHT_REL) {
      Expected<typename ELFT::RelRange> Rels = EF.rels(RelSec);
      if (!Rels)
        return Bad(Rels.takeError());
      for (const auto &Rel : *Rels)
        addRelocation(Rel.r_offset, Rel.getType(false), Rel.getSymbol(false),
                      std::nullopt);
    } else if (RelSec.sh_type == ELF::SHT_RELR) {
      // -z pack-relative-relocs: RELATIVE relocations, addends in place.
      Expected<typename ELFT::RelrRange> Relrs = EF.relrs(RelSec);
      if (!Relrs)
        return Bad(Relrs.takeError());
      uint32_t Relative = R.Is386 ? uint32_t(ELF::R_386_RELATIVE)
                                  : uint32_t(ELF::R_X86_64_RELATIVE);
      for (const auto &Rel : EF.decode_relrs(*Relrs))
        addRelocation(Rel.r_offset, Relative, 0, std::nullopt);
    }
  }

  /// A dynamic relocation, by the place it patches.
  void addRelocation(uint64_t Where, uint32_t Type, uint32_t SymIndex,
                     std::optional<int64_t> Addend) {
    std::optional<std::pair<uint64_t, uint64_t>> Loc = R.locate(Where);
    if (!Loc)
      return; // Patches nothing that a descriptor could point at.
    Reloc &Rel = R.RelocsBySection[Loc->first][Loc->second];
    Rel = Reloc();
    Rel.Type = Type;
    if (SymIndex != 0) {
      if (SymIndex >= DynSyms.size())
        Rel.Damage = "relocation against symbol " + std::to_string(SymIndex) +
                     " outside the dynamic symbol table";
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
    Expected<StringRef> Data = R.contents(Loc->first);
    if (!Data) {
      Rel.Damage = toString(Data.takeError());
      return;
    }
    if (Loc->second + R.P > Data->size())
      return; // .bss: zero
    const char *B = Data->data() + Loc->second;
    Rel.Addend = R.P == 4 ? int64_t(support::endian::read32le(B))
                          : int64_t(support::endian::read64le(B));
  }

  ObjectReader &R;
  const ELFFile<ELFT> &EF;
  typename ELFT::ShdrRange Secs{nullptr, nullptr};
  std::vector<Pointee> DynSyms;
  StringMap<DescriptorSym> Descriptors;
};

template <class ELFT>
void ObjectReader::indexDynamic(const ELFObjectFile<ELFT> &EObj) {
  DynamicIndexer<ELFT>(*this, EObj.getELFFile()).run();
}

Expected<Pointee> ObjectReader::pointeeAt(uint64_t Sec, uint64_t Off) {
  auto It = SymbolAt.find({Sec, Off});
  if (It != SymbolAt.end())
    return It->second;
  if (!IsDyn)
    return problem(diag::err_bind_pointer_without_symbol,
                   {("section " + Twine(Sec) + " + " + Twine(Off)).str()});
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
  if (!R.Damage.empty())
    return damage(R.Damage);
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
      return damage("a pointer points outside the library (0x" +
                    Twine::utohexstr(Addr) + ")");
    return pointeeAt(Loc->first, Loc->second);
  }
  if (R.Type != Absolute && R.Type != GlobDat) {
    StringRef Name = getELFRelocationTypeName(Obj.getEMachine(), R.Type);
    return problem(diag::err_bind_unexpected_relocation,
                   {Name.str(),
                    Is386 ? "R_386_32 or R_386_RELATIVE"
                          : "R_X86_64_64 or R_X86_64_RELATIVE",
                    "library"});
  }
  if (!R.HasSym)
    return damage("relocation without a symbol");
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
  return damage("no section with index " + Twine(SectionIndex));
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
    return problem(diag::err_bind_unexpected_relocation,
                   {Name.str(), Is386 ? "R_386_32" : "R_X86_64_64", "object"});
  }
  if (!R.HasSym)
    return damage("relocation without a symbol");
  ELFSymbolRef Sym(R.Sym);
  Expected<section_iterator> Sec = Sym.getSection();
  if (!Sec)
    return Sec.takeError();
  bool Defined = *Sec != Obj.section_end();
  if (Sym.getELFType() == ELF::STT_SECTION || (Defined && R.Addend != 0)) {
    // Section-relative (or symbol + offset): find the symbol defined there.
    if (!Defined)
      return damage("relocation against an undefined section");
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
        return problem(diag::err_bind_pointer_without_relocation);
  return std::optional<Pointee>();
}

Expected<std::optional<Pointee>>
ObjectReader::followHolder(const Pointee &Holder, unsigned Slot) {
  if (!Holder.Defined)
    return damage("holder '" + Holder.Name +
                  "' is not defined in this object");
  return pointerAt(Holder.SectionIndex, Holder.Offset + Slot * P);
}

Expected<int64_t> ObjectReader::readMemberPointer(const Pointee &Holder) {
  if (!Holder.Defined)
    return damage("member pointer '" + Holder.Name +
                  "' is not defined in this object");
  Expected<StringRef> Data = contents(Holder.SectionIndex);
  if (!Data)
    return Data.takeError();
  if (Data->empty())
    return 0; // .bss: offset 0
  if (Holder.Offset + P > Data->size())
    return damage("member pointer outside its section");
  const char *B = Data->data() + Holder.Offset;
  return P == 4 ? int64_t(int32_t(support::endian::read32le(B)))
                : int64_t(support::endian::read64le(B));
}

void ObjectReader::readModules(std::vector<BoundModule> &Out) {
  if (IsDyn) {
    indexRelocations();
    if (DynDamaged)
      return;
    for (const DescriptorSym &D : DynDescriptors) {
      Expected<StringRef> Data = contents(D.SectionIndex);
      if (D.SectionName != "bs_modules") {
        Errs.add(File, D.Name, diag::err_bind_descriptor_section);
        continue;
      }
      if (!Data) {
        Errs.add(File, D.Name, Data.takeError(), what());
        continue;
      }
      if (!D.Exported) {
        // Generated code refers to the descriptor for the hash check.
        Errs.add(File, D.Name, diag::err_bind_descriptor_hidden);
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
      Errs.add(File, *Name, diag::err_bind_descriptor_section);
      continue;
    }
    Expected<StringRef> Data = (*Sec)->getContents();
    if (!Data) {
      Errs.add(File, *Name, Data.takeError(), what());
      continue;
    }
    Expected<uint64_t> Value = Sym.getValue();
    if (!Value) {
      Errs.add(File, *Name, Value.takeError(), what());
      continue;
    }
    readDescriptor(*Name, *Value, (*Sec)->getIndex(), *Data, Out);
  }
}
