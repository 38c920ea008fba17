//===- ELFChecks.cpp - refuse damaged section headers before reading ------===//
//
// See ELFChecks.h for why. The checks are the preconditions of the
// ELFObjectFile walks the binding reader and the driver use, each stated
// with an ELFFile accessor that checks it (getSectionContentsAsArray:
// sh_entsize equals the entry size, sh_size is a multiple of it and
// sh_offset + sh_size lies in the file), plus what those walks take on
// trust: sh_link of a symbol or relocation table, the symbol index of
// every relocation, symbol names inside their string table, the type of
// `bs_modules`. `bsc run` then hands the file to the JIT, which runs its
// code: so sections may not overlap each other or the headers, code may
// not be SHT_NOBITS, relocations must patch a section with contents, and
// zero-filled data has a size limit (found by fuzzing every header field
// through `bsc run`). Only the first
// problem of a file is reported: the rest would be follow-on noise.
//
//===----------------------------------------------------------------------===//
#include "ELFChecks.h"
#include "ObjectReader.h"
#include "llvm/ADT/STLExtras.h"
#include "llvm/BinaryFormat/ELF.h"
#include "llvm/Object/ELF.h"

using namespace llvm;
using namespace llvm::object;

namespace {

/// The largest zero-filled (SHT_NOBITS) section of a relocatable: 256 MiB,
/// more than a robot has memory. The JIT allocates and zeroes what the
/// header says, and crashes or takes minutes on sizes near 4 GiB.
constexpr uint64_t MaxZeroFillSize = uint64_t(1) << 28;

template <class ELFT> class SectionChecker {
public:
  using Shdr = typename ELFT::Shdr;

  SectionChecker(const ELFFile<ELFT> &EF) : EF(EF) {}

  Error run();

private:
  Error checkProgramHeaders();
  Error checkSection(const Shdr &S);
  Error checkSymbols(const Shdr &S);
  Error checkOverlaps();

  const ELFFile<ELFT> &EF;
  typename ELFT::ShdrRange Secs;
  /// The bytes of the file each section (or header: Sec null) occupies.
  struct Extent {
    uint64_t Offset, Size;
    const Shdr *Sec;
  };
  std::vector<Extent> Extents;

  std::string nameOf(const Shdr &S) const {
    Expected<StringRef> N = EF.getSectionName(S);
    if (N)
      return N->str();
    consumeError(N.takeError());
    return "?";
  }
  std::string indexOf(const Shdr &S) const {
    return "section [index " + std::to_string(&S - Secs.begin()) + "]";
  }
  /// `<kind> 'name': Msg`, the kind by the section's type.
  Error damaged(const Shdr &S, const Twine &Msg) const {
    StringRef Kind = "section";
    switch (S.sh_type) {
    case ELF::SHT_SYMTAB:
    case ELF::SHT_DYNSYM:
      Kind = "symbol table";
      break;
    case ELF::SHT_REL:
    case ELF::SHT_RELA:
    case ELF::SHT_RELR:
    case ELF::SHT_CREL:
      Kind = "relocation section";
      break;
    default:
      break;
    }
    return createStringError(inconvertibleErrorCode(),
                             Kind + " '" + nameOf(S) + "': " + Msg);
  }
  Error damaged(const Shdr &S, Error E) const {
    return damaged(S, toString(std::move(E)));
  }

  /// Number of symbols of the symbol table that the sh_link of `S`
  /// names, or an error if it names none.
  Expected<uint64_t> linkedSymbols(const Shdr &S) const;
  template <class RelT>
  Error checkRelocations(const Shdr &S, Expected<ArrayRef<RelT>> Rels) const;
};

template <class ELFT>
Expected<uint64_t>
SectionChecker<ELFT>::linkedSymbols(const Shdr &S) const {
  if (S.sh_link == 0 || S.sh_link >= Secs.size())
    return createStringError(inconvertibleErrorCode(),
                             indexOf(S) + " has sh_link " + Twine(S.sh_link) +
                                 ", which is not a symbol table");
  // A relocatable's relocations use its .symtab (ELFObjectFile reads only
  // that one); a library's dynamic relocations use .dynsym.
  const Shdr &Link = Secs[S.sh_link];
  if (Link.sh_type != ELF::SHT_SYMTAB &&
      (Link.sh_type != ELF::SHT_DYNSYM ||
       EF.getHeader().e_type == ELF::ET_REL))
    return createStringError(inconvertibleErrorCode(),
                             indexOf(S) + " has sh_link " + Twine(S.sh_link) +
                                 ", which is not a symbol table");
  // Checked whole by the first pass of run().
  return uint64_t(Link.sh_size / sizeof(typename ELFT::Sym));
}

template <class ELFT>
template <class RelT>
Error SectionChecker<ELFT>::checkRelocations(
    const Shdr &S, Expected<ArrayRef<RelT>> Rels) const {
  if (!Rels)
    return damaged(S, Rels.takeError());
  if (S.sh_info >= Secs.size())
    return damaged(S,
                   indexOf(S) + " has sh_info " + Twine(S.sh_info) +
                       ", which is not a section");
  // The section the relocations patch (a relocatable's, or one that
  // SHF_INFO_LINK names) must have bytes to patch: the JIT writes into it.
  bool Patches = EF.getHeader().e_type == ELF::ET_REL ||
                 (S.sh_flags & ELF::SHF_INFO_LINK);
  if (Patches && S.sh_info != 0 &&
      Secs[S.sh_info].sh_type == ELF::SHT_NOBITS)
    return damaged(S, indexOf(S) + " patches section [index " +
                          Twine(S.sh_info) + "], which has no contents");
  // ELFObjectFile takes a relocation's symbol index on trust (and so do
  // its accessors that end the process when the symbol is not there).
  std::optional<uint64_t> NumSyms;
  for (const RelT &R : *Rels) {
    uint32_t Sym = R.getSymbol(false);
    if (Sym == 0)
      continue;
    if (!NumSyms) {
      Expected<uint64_t> N = linkedSymbols(S);
      if (!N)
        return damaged(S, N.takeError());
      NumSyms = *N;
    }
    if (Sym >= *NumSyms)
      return damaged(S,
                     "relocation against symbol " + Twine(Sym) +
                         " outside its symbol table of " + Twine(*NumSyms) +
                         " symbols");
  }
  return Error::success();
}

template <class ELFT> Error SectionChecker<ELFT>::run() {
  // e_shoff, e_shentsize and the number of headers against the file.
  Expected<typename ELFT::ShdrRange> SecsOrErr = EF.sections();
  if (!SecsOrErr)
    return createStringError(inconvertibleErrorCode(),
                             "section table: " +
                                 toString(SecsOrErr.takeError()));
  Secs = *SecsOrErr;
  if (Error E = checkProgramHeaders())
    return E;
  // No section table (e_shoff 0): nothing to walk; the reader then finds no
  // descriptors.
  if (Secs.empty())
    return Error::success();
  // Section 0 is the null section; its size, link and info fields may
  // extend the ELF header, but its type must stay SHT_NULL: ELFObjectFile
  // takes any section of type SHT_SYMTAB for the symbol table, this one too.
  if (Secs[0].sh_type != ELF::SHT_NULL)
    return createStringError(
        inconvertibleErrorCode(),
        "section 0 has type " +
            getELFSectionTypeName(EF.getHeader().e_machine, Secs[0].sh_type) +
            " (expected SHT_NULL)");
  for (const Shdr &S : Secs.drop_front())
    if (Error E = checkSection(S))
      return E;
  if (Error E = checkOverlaps())
    return E;
  // Relocations last: their symbols are counted in tables checked above,
  // and a damaged symbol table is reported as itself.
  for (const Shdr &S : Secs.drop_front()) {
    Error E = S.sh_type == ELF::SHT_REL    ? checkRelocations(S, EF.rels(S))
              : S.sh_type == ELF::SHT_RELA ? checkRelocations(S, EF.relas(S))
                                           : Error::success();
    if (E)
      return E;
  }
  return Error::success();
}

/// Segments of a shared library: ELFFile::dynamicEntries (which the
/// reader's PIE check and the loader use) takes PT_DYNAMIC's offset and
/// size on trust. A relocatable object's program headers are never read.
template <class ELFT> Error SectionChecker<ELFT>::checkProgramHeaders() {
  if (EF.getHeader().e_type != ELF::ET_DYN)
    return Error::success();
  Expected<typename ELFT::PhdrRange> Phdrs = EF.program_headers();
  if (!Phdrs)
    return createStringError(inconvertibleErrorCode(),
                             "program header table: " +
                                 toString(Phdrs.takeError()));
  for (const auto &P : *Phdrs)
    if (P.p_offset > EF.getBufSize() ||
        P.p_filesz > EF.getBufSize() - P.p_offset)
      return createStringError(
          inconvertibleErrorCode(),
          "program header " + std::to_string(&P - Phdrs->begin()) +
              " describes bytes beyond the end of the file");
  return Error::success();
}

/// One section's header: its fields, its bytes, and its table if it is a
/// symbol table.
template <class ELFT>
Error SectionChecker<ELFT>::checkSection(const Shdr &S) {
  // A section of type SHT_NULL, like section 0: nothing reads it.
  if (S.sh_type == ELF::SHT_NULL)
    return Error::success();
  if (S.sh_addralign & (S.sh_addralign - 1))
    return damaged(S, indexOf(S) + " has sh_addralign " +
                          Twine(uint64_t(S.sh_addralign)) +
                          ", which is not a power of two");
  if (S.sh_link >= Secs.size())
    return damaged(S, indexOf(S) + " has sh_link " + Twine(S.sh_link) +
                          ", which is not a section");
  // The descriptors are data in the file (bindings.md).
  if (S.sh_type != ELF::SHT_PROGBITS && nameOf(S) == "bs_modules")
    return createStringError(
        inconvertibleErrorCode(),
        "section 'bs_modules': " + indexOf(S) + " has type " +
            getELFSectionTypeName(EF.getHeader().e_machine, S.sh_type) +
            " (expected SHT_PROGBITS)");
  // Code without bytes: the JIT would run zeros.
  if (S.sh_type == ELF::SHT_NOBITS && (S.sh_flags & ELF::SHF_EXECINSTR))
    return damaged(S, indexOf(S) + " holds code but has type SHT_NOBITS");
  if (S.sh_type == ELF::SHT_NOBITS && EF.getHeader().e_type == ELF::ET_REL &&
      S.sh_size > MaxZeroFillSize)
    return damaged(S, indexOf(S) + " has sh_size 0x" +
                          Twine::utohexstr(S.sh_size) +
                          ", more than bsc allows for zero-filled data (0x" +
                          Twine::utohexstr(MaxZeroFillSize) + ")");
  if (S.sh_type != ELF::SHT_NOBITS) {
    Expected<ArrayRef<uint8_t>> Contents = EF.getSectionContents(S);
    if (!Contents)
      return damaged(S, Contents.takeError());
    if (S.sh_size)
      Extents.push_back({uint64_t(S.sh_offset), uint64_t(S.sh_size), &S});
  }
  switch (S.sh_type) {
  case ELF::SHT_SYMTAB:
  case ELF::SHT_DYNSYM:
    return checkSymbols(S);
  case ELF::SHT_RELR:
    if (Expected<typename ELFT::RelrRange> Relrs = EF.relrs(S); !Relrs)
      return damaged(S, Relrs.takeError());
    return Error::success();
  case ELF::SHT_CREL:
    // ELFObjectFile decodes these with cantFail; no compiler bsc supports
    // emits them unasked.
    return damaged(S, indexOf(S) + " has type SHT_CREL, which bsc does not "
                                   "read (build without --crel)");
  default:
    return Error::success();
  }
}

template <class ELFT>
Error SectionChecker<ELFT>::checkSymbols(const Shdr &S) {
  Expected<typename ELFT::SymRange> Syms = EF.symbols(&S);
  if (!Syms)
    return damaged(S, Syms.takeError());
  Expected<StringRef> Strings = EF.getStringTableForSymtab(S, Secs);
  if (!Strings)
    return damaged(S, Strings.takeError());
  if (S.sh_info > Syms->size())
    return damaged(S, indexOf(S) + " has sh_info " + Twine(S.sh_info) +
                          " beyond its " + Twine(Syms->size()) + " symbols");
  // The walks skip a symbol whose name cannot be read, which would
  // silently lose a descriptor or a thunk.
  for (const auto &Sym : *Syms) {
    std::string Which = "symbol " + std::to_string(&Sym - Syms->begin());
    if (Sym.st_name >= Strings->size())
      return damaged(S, Which + " has its name outside the string table");
    // A section index must name a section (or be one of the reserved ones
    // bsc reads: undefined, absolute, common); a section symbol is named
    // after its section, which ELFObjectFile looks up without checking.
    uint16_t Shndx = Sym.st_shndx;
    bool Reserved = Shndx >= ELF::SHN_LORESERVE;
    if (Shndx == ELF::SHN_XINDEX || (!Reserved && Shndx >= Secs.size()) ||
        (Sym.getType() == ELF::STT_SECTION && (Shndx == 0 || Reserved)))
      return damaged(S, Which + " has section index " + Twine(Shndx) +
                            ", which is not a section");
  }
  return Error::success();
}

/// No two sections share bytes, and none holds the ELF header or the
/// section header table (compilers and linkers lay them out apart; a
/// header whose sh_offset moved makes the JIT load other bytes as code).
template <class ELFT> Error SectionChecker<ELFT>::checkOverlaps() {
  const auto &H = EF.getHeader();
  Extents.push_back({0, uint64_t(H.e_ehsize), nullptr});
  Extents.push_back(
      {uint64_t(H.e_shoff), uint64_t(Secs.size()) * sizeof(Shdr), nullptr});
  llvm::sort(Extents, [](const Extent &A, const Extent &B) {
    return A.Offset < B.Offset;
  });
  for (size_t I = 1; I < Extents.size(); ++I) {
    const Extent &Prev = Extents[I - 1], &Cur = Extents[I];
    if (Cur.Offset - Prev.Offset >= Prev.Size)
      continue;
    if (!Cur.Sec && !Prev.Sec)
      return createStringError(inconvertibleErrorCode(),
                               "the section header table overlaps the ELF "
                               "header");
    const Extent &Named = Cur.Sec ? Cur : Prev;
    const Extent &Other = Cur.Sec ? Prev : Cur;
    return damaged(*Named.Sec,
                   indexOf(*Named.Sec) + " overlaps " +
                       (Other.Sec ? indexOf(*Other.Sec)
                                  : std::string("the ELF header or the "
                                                "section header table")));
  }
  return Error::success();
}

template <class ELFT>
Error check(const ELFObjectFile<ELFT> &Obj) {
  return SectionChecker<ELFT>(Obj.getELFFile()).run();
}

} // namespace

Error bsc::bind::checkSectionHeaders(const ELFObjectFileBase &Obj) {
  Error E = Error::success();
  if (auto *O = dyn_cast<ELF32LEObjectFile>(&Obj))
    E = check(*O);
  else if (auto *O = dyn_cast<ELF64LEObjectFile>(&Obj))
    E = check(*O);
  else if (auto *O = dyn_cast<ELF32BEObjectFile>(&Obj))
    E = check(*O);
  else if (auto *O = dyn_cast<ELF64BEObjectFile>(&Obj))
    E = check(*O);
  if (!E)
    return E;
  StringRef What =
      Obj.getEType() == ELF::ET_DYN ? "shared library" : "object";
  return problem(diag::err_bind_damaged, {What.str(), toString(std::move(E))});
}
