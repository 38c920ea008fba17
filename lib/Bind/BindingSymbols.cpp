//===- BindingSymbols.cpp - which binding symbols the link will find -----===//
//
// A behavior calls thunks and refers to descriptors by name. When the
// binding objects that get linked lack one of them, the linker or the JIT
// would only say "undefined symbol" with a 150-character template name;
// the driver checks first and says what it means: the script is stale
// against the bindings' signatures (docs/bindings.md, staleness).
//
//===----------------------------------------------------------------------===//
#include "ELFChecks.h"
#include "ObjectReader.h"
#include "bsc/AST/Native.h"
#include "bsc/Bind/Bind.h"
#include "llvm/ADT/StringSet.h"
#include "llvm/Object/Archive.h"
#include "llvm/Object/ELFObjectFile.h"
#include "llvm/Object/ObjectFile.h"

using namespace llvm;
using namespace bsc;

std::vector<std::string>
bind::getBindingSymbols(ArrayRef<const NativeModule *> Modules) {
  std::vector<std::string> Out;
  auto Add = [&](const std::string &S) {
    if (!S.empty())
      Out.push_back(S);
  };
  auto AddMembers = [&](const std::vector<NativeFunction> &Members) {
    for (const NativeFunction &F : Members) {
      Add(F.Symbol);
      Add(F.Setter);
    }
  };
  for (const NativeModule *M : Modules) {
    Add("bs_module_" + M->Name);
    AddMembers(M->Functions);
    for (const NativeClass &C : M->Classes) {
      AddMembers(C.Members);
      for (const std::string *S : {&C.Construct, &C.Copy, &C.Assign, &C.Destroy})
        Add(*S);
    }
  }
  return Out;
}

/// Adds the global and weak symbols that `Bin` defines to `Defined`.
static void addDefinedSymbols(object::Binary &Bin, StringSet<> &Defined) {
  auto AddFrom = [&](auto Symbols) {
    for (const object::SymbolRef &Sym : Symbols) {
      Expected<uint32_t> Flags = Sym.getFlags();
      Expected<StringRef> Name = Sym.getName();
      if (!Flags || !Name) {
        consumeError(Flags.takeError());
        consumeError(Name.takeError());
        continue;
      }
      if (!(*Flags & object::SymbolRef::SF_Undefined) &&
          (*Flags & (object::SymbolRef::SF_Global | object::SymbolRef::SF_Weak)))
        Defined.insert(*Name);
    }
  };
  if (auto *Ar = dyn_cast<object::Archive>(&Bin)) {
    Error Err = Error::success();
    for (const object::Archive::Child &C : Ar->children(Err)) {
      Expected<std::unique_ptr<object::Binary>> Member = C.getAsBinary();
      if (!Member) {
        consumeError(Member.takeError());
        continue;
      }
      addDefinedSymbols(**Member, Defined);
    }
    consumeError(std::move(Err));
    return;
  }
  // A shared library exports through its dynamic symbol table only: its
  // .symtab also lists what -fvisibility=hidden or a version script hid,
  // which a program cannot link against.
  auto *ELF = dyn_cast<object::ELFObjectFileBase>(&Bin);
  // The symbol walks trust the section headers; the binding reader has
  // reported a damaged file already.
  if (ELF) {
    if (Error E = bind::checkSectionHeaders(*ELF)) {
      consumeError(std::move(E));
      return;
    }
  }
  if (ELF && ELF->getEType() == ELF::ET_DYN) {
    AddFrom(ELF->getDynamicSymbolIterators());
    return;
  }
  if (auto *Obj = dyn_cast<object::ObjectFile>(&Bin))
    AddFrom(Obj->symbols());
}

std::vector<std::string>
bind::findUndefinedSymbols(ArrayRef<std::string> Paths,
                           ArrayRef<std::string> Wanted) {
  StringSet<> Defined;
  for (const std::string &Path : Paths) {
    Expected<object::OwningBinary<object::Binary>> Bin =
        object::createBinary(Path);
    if (!Bin) {
      consumeError(Bin.takeError());
      continue;
    }
    addDefinedSymbols(*Bin->getBinary(), Defined);
  }
  std::vector<std::string> Missing;
  for (const std::string &S : Wanted)
    if (!Defined.count(S))
      Missing.push_back(S);
  return Missing;
}

std::vector<std::string>
bind::getBindingImports(ArrayRef<const NativeModule *> Modules,
                        ArrayRef<std::string> Undefined) {
  StringSet<> BindingSymbols;
  for (const std::string &S : getBindingSymbols(Modules))
    BindingSymbols.insert(S);
  std::vector<std::string> Imports;
  for (const std::string &S : Undefined)
    if (BindingSymbols.contains(S))
      Imports.push_back(S);
  return Imports;
}

bool bind::checkBindingImports(DiagnosticEngine &Diags,
                               ArrayRef<std::string> Imports,
                               ArrayRef<std::string> Paths) {
  std::vector<std::string> Missing = findUndefinedSymbols(Paths, Imports);
  for (const std::string &S : Missing)
    Diags.report(SMLoc(), diag::err_stale_binding_symbol) << demangled(S);
  return Missing.empty();
}
