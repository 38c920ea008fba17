//===- ObjectReader.h - one ELF file's descriptors, for the reader -*- C++ -*-===//
//
// Internal to lib/Bind. readBindings (BindingReader.cpp) opens files and
// archives and resolves types across modules; for each ELF object or
// shared library it runs one ObjectReader, which maps pointer fields back
// to symbols (ObjectReader.cpp) and decodes each descriptor's records into
// a BoundModule (DescriptorDecoder.cpp). Problems are collected in a
// BindErrors, each as a diagnostic kind with its arguments, so that one run
// reports every broken binding.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_BIND_OBJECTREADER_H
#define BSC_LIB_BIND_OBJECTREADER_H

#include "bsc/Bind/Bind.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/BinaryFormat/ELF.h"
#include "llvm/Object/ELFObjectFile.h"
#include <optional>
#include <string>
#include <vector>

namespace bsc {
namespace bind {

//===----------------------------------------------------------------------===//
// Problems
//===----------------------------------------------------------------------===//

/// A problem found below the code that knows where it is (a pointer of some
/// record): the helpers that return Expected carry it up as this error, and
/// BindErrors::add puts the place in front.
class ProblemError : public llvm::ErrorInfo<ProblemError> {
public:
  static char ID;
  ProblemError(diag::Kind Kind, std::vector<std::string> Args)
      : Kind(Kind), Args(std::move(Args)) {}
  diag::Kind Kind;
  std::vector<std::string> Args; ///< Without the place.
  void log(llvm::raw_ostream &OS) const override;
  std::error_code convertToErrorCode() const override {
    return llvm::inconvertibleErrorCode();
  }
};

inline llvm::Error problem(diag::Kind Kind, std::vector<std::string> Args = {}) {
  return llvm::make_error<ProblemError>(Kind, std::move(Args));
}

/// Collects the problems of one readBindings call.
struct BindErrors {
  std::vector<BindProblem> Problems;

  /// Reports `Kind` at `File` (and `Path` inside it, if any); returns its
  /// index in Problems.
  size_t add(llvm::StringRef File, llvm::StringRef Path, diag::Kind Kind,
             std::vector<std::string> Args = {});
  /// Reports an error of a helper: a ProblemError as itself, anything else
  /// (llvm::object's messages) as damage to the `What` ("object", "shared
  /// library", "archive").
  void add(llvm::StringRef File, llvm::StringRef Path, llvm::Error E,
           llvm::StringRef What = "object");
  bool empty() const { return Problems.empty(); }
  size_t size() const { return Problems.size(); }
  /// All problems as one BindingError, or success.
  llvm::Error take();
};

std::string demangled(llvm::StringRef Sym);
/// The C++ type of a key symbol `bs::TypeKey<T>::id`.
std::string typeOfKey(llvm::StringRef Key);
bool hasExternalLinkage(uint8_t Binding);

//===----------------------------------------------------------------------===//
// One ELF file
//===----------------------------------------------------------------------===//

/// Where a pointer field points: a symbol, and the place it is defined.
struct Pointee {
  std::string Name;
  uint8_t Binding = llvm::ELF::STB_LOCAL;
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
  llvm::object::SymbolRef Sym;
  int64_t Addend = 0;
  /// Shared libraries: the symbol, read when indexing (the relocation's
  /// symbol index is checked there, which SymbolRef would not be), or the
  /// damage that makes the relocation unusable.
  Pointee DynSym;
  std::string Damage;
};

/// A descriptor symbol `bs_module_*` and where it is defined.
struct DescriptorSym {
  std::string Name;
  uint64_t SectionIndex = 0;
  uint64_t Offset = 0;
  bool Exported = true;
  std::string SectionName;
};

class DescriptorDecoder;
template <class ELFT> class DynamicIndexer;

class ObjectReader {
public:
  ObjectReader(const llvm::object::ELFObjectFileBase &Obj, llvm::StringRef File,
               BindErrors &Errs)
      : Obj(Obj), File(File.str()), Errs(Errs), P(Obj.getBytesInAddress()),
        Is386(Obj.getEMachine() == llvm::ELF::EM_386),
        IsDyn(Obj.getEType() == llvm::ELF::ET_DYN) {}

  /// Reads every descriptor of the object into `Out` (ObjectReader.cpp).
  void readModules(std::vector<BoundModule> &Out);

private:
  friend class DescriptorDecoder;                  // DescriptorDecoder.cpp
  template <class ELFT> friend class DynamicIndexer; // ObjectReader.cpp
  const llvm::object::ELFObjectFileBase &Obj;
  std::string File;
  BindErrors &Errs;
  unsigned P;
  bool Is386;
  bool IsDyn; ///< A shared library: dynamic relocations, addresses.

  // Per section: relocations by offset.
  llvm::DenseMap<uint64_t, llvm::DenseMap<uint64_t, Reloc>> RelocsBySection;
  bool RelocsIndexed = false;
  // Defined symbols by (section index, offset), for section-relative
  // relocations; the best (exported, then external, before local) wins.
  llvm::DenseMap<std::pair<uint64_t, uint64_t>, Pointee> SymbolAt;
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

  /// "object" or "shared library", for messages.
  llvm::StringRef what() const { return IsDyn ? "shared library" : "object"; }
  /// Damage found below the place it is reported at.
  llvm::Error damage(const llvm::Twine &Detail) const {
    return problem(diag::err_bind_damaged, {what().str(), Detail.str()});
  }

  void indexRelocations();
  void addSymbolAt(Pointee Pt);
  template <class ELFT>
  void indexDynamic(const llvm::object::ELFObjectFile<ELFT> &EObj);
  /// Shared libraries: the place of address `Addr`.
  std::optional<std::pair<uint64_t, uint64_t>> locate(uint64_t Addr) const;
  llvm::Expected<Pointee> pointeeAt(uint64_t Sec, uint64_t Off);
  llvm::Expected<Pointee> resolveDynamic(const Reloc &R);
  llvm::Expected<llvm::StringRef> contents(uint64_t SectionIndex);
  llvm::Expected<Pointee> resolve(const Reloc &R);
  /// The pointer field at `Off` of section `Sec`: std::nullopt if null.
  llvm::Expected<std::optional<Pointee>> pointerAt(uint64_t Sec, uint64_t Off);
  /// Slot `Slot` of a holder object: the thunk it points at.
  llvm::Expected<std::optional<Pointee>> followHolder(const Pointee &Holder,
                                                      unsigned Slot);
  llvm::Expected<int64_t> readMemberPointer(const Pointee &Holder);

  /// Decodes the descriptor `SymName` at `Base` of section `Sec`, whose
  /// bytes are `Data` (DescriptorDecoder.cpp).
  void readDescriptor(llvm::StringRef SymName, uint64_t Base, uint64_t Sec,
                      llvm::StringRef Data, std::vector<BoundModule> &Out);
};

} // namespace bind
} // namespace bsc

#endif
