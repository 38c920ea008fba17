//===- DescriptorDecoder.cpp - a descriptor's records into a BoundModule --===//
//
// The bytes of one `bs_module_*` descriptor (bscript/descriptor.h: a header,
// five tables of fixed-size records, a string table) become a BoundModule:
// classes, members with their thunk symbols and field offsets, parameters,
// enums. Every count, offset and index is checked against the descriptor's
// own size before it is used; pointer fields go through ObjectReader, which
// knows the object's relocations. Type keys and thunks must be callable and
// identifiable by name from generated code, so internal linkage and hidden
// library symbols are reported here.
//
//===----------------------------------------------------------------------===//
#include "ObjectReader.h"
#include "bscript/descriptor.h"
#include "llvm/Support/Endian.h"
#include <cstring>

using namespace llvm;
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

} // namespace

void ObjectReader::readDescriptor(StringRef SymName, uint64_t Base,
                                  uint64_t Sec, StringRef Data,
                                  std::vector<BoundModule> &Out) {
  // A problem of a record, or an error of a helper about it.
  auto ReportAt = [&](const Twine &Path, diag::Kind Kind,
                      std::vector<std::string> Args = {}) {
    return Errs.add(File, Path.str(), Kind, std::move(Args));
  };
  // ...of the descriptor as a whole, at its symbol.
  auto Fail = [&](diag::Kind Kind, std::vector<std::string> Args = {}) {
    ReportAt(SymName, Kind, std::move(Args));
  };
  auto Damaged = [&](const Twine &Detail) {
    Fail(diag::err_bind_damaged_descriptor, {Detail.str()});
  };
  auto ErrorAt = [&](const Twine &Path, Error E) {
    Errs.add(File, Path.str(), std::move(E), what());
  };
  // A result's or parameter's type code (void only for results).
  auto CodeOf = [&](uint32_t Code, bool AllowVoid,
                    const Twine &Path) -> std::optional<TypeCode> {
    if ((Code == uint32_t(TypeCode::Void) && !AllowVoid) ||
        Code > uint32_t(TypeCode::Class)) {
      ReportAt(Path, diag::err_bind_damaged_descriptor,
               {"unknown type code " + std::to_string(Code)});
      return std::nullopt;
    }
    return TypeCode(Code);
  };
  if (Base + HeaderSize > Data.size()) {
    Damaged("the descriptor is truncated");
    return;
  }
  DescriptorView D(Data.substr(Base));
  if (std::memcmp(D.Bytes.data(), Magic, 8) != 0) {
    Fail(diag::err_bind_bad_magic);
    return;
  }
  uint32_t Version = D.u32(BS_HDR_VERSION);
  if (Version == 0 || Version > SupportedVersion) {
    Fail(diag::err_bind_bad_version,
         {std::to_string(Version), std::to_string(SupportedVersion)});
    return;
  }
  if (D.u32(BS_HDR_PTR_SIZE) != P) {
    Fail(diag::err_bind_bad_pointer_size,
         {std::to_string(D.u32(BS_HDR_PTR_SIZE)), std::to_string(P * 8)});
    return;
  }
  uint32_t Total = D.u32(BS_HDR_TOTAL_SIZE);
  if (D.u32(BS_HDR_HEADER_SIZE) < HeaderSize || Total > D.Bytes.size()) {
    Damaged("the descriptor is truncated");
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
      Damaged(Twine("the ") + TableNames[T] +
              " table lies outside the descriptor or has short records");
      return;
    }
  }
  uint32_t StrOff = D.u32(BS_HDR_STRING_OFFSET), StrSize = D.u32(BS_HDR_STRING_SIZE);
  if (uint64_t(StrOff) + StrSize > Total || StrSize == 0) {
    Damaged("the string table lies outside the descriptor");
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
      ErrorAt(Path, Pt.takeError());
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
    Fail(diag::err_bind_module_name_mismatch, {M.Name});
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
      ReportAt(Path, diag::err_bind_stripped_key);
      return "";
    }
    if (InternalKey(*Pt))
      ReportAt(Path, diag::err_bind_internal_type, {typeOfKey(Pt->Name)});
    return Pt->Name;
  };
  // Once a class's key has internal linkage, so has every thunk of the
  // class: report the class once.
  bool QuietLinkage = false;
  // Hidden thunks of a shared library have one cause (its visibility):
  // the first is reported, with the count of the others added at the end.
  std::optional<size_t> HiddenThunkProblem;
  unsigned HiddenThunks = 0;
  // A thunk through its holder: must be callable by name.
  auto Thunk = [&](std::optional<Pointee> Holder, unsigned Slot,
                   const Twine &Path) -> std::string {
    if (!Holder)
      return "";
    Expected<std::optional<Pointee>> T = followHolder(*Holder, Slot);
    if (!T) {
      ErrorAt(Path, T.takeError());
      return "";
    }
    if (!*T)
      return "";
    if (IsDyn) {
      // Undefined: another library is to define it, which the driver
      // checks against the libraries it links (findUndefinedSymbols).
      if ((*T)->Defined && !(*T)->Exported && !QuietLinkage &&
          HiddenThunks++ == 0) {
        std::string Thunk =
            (*T)->Name.empty()
                ? ("at 0x" + Twine::utohexstr((*T)->Offset) + " in section " +
                   Twine((*T)->SectionIndex))
                      .str()
                : demangled((*T)->Name);
        HiddenThunkProblem =
            ReportAt(Path, diag::err_bind_hidden_thunk, {Thunk, ""});
      }
      return (*T)->Name;
    }
    if (!hasExternalLinkage((*T)->Binding) && !QuietLinkage)
      ReportAt(Path, diag::err_bind_internal_thunk, {demangled((*T)->Name)});
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
    size_t ErrorsBefore = Errs.size();
    std::optional<Pointee> KeyPt = Ptr(T_Class, I, BS_CLASS_KEY, Path);
    C.Key = Key(KeyPt, Path);
    if (C.Key.empty() && Errs.size() == ErrorsBefore)
      ReportAt(Path, diag::err_bind_class_without_key);
    InternalClass.push_back(KeyPt && InternalKey(*KeyPt));
    QuietLinkage = InternalClass.back();
    if (std::optional<Pointee> Life = Ptr(T_Class, I, BS_CLASS_LIFE, Path)) {
      C.Construct = Thunk(Life, 0, Path + " construct");
      C.Copy = Thunk(Life, 1, Path + " copy");
      C.Assign = Thunk(Life, 2, Path + " assign");
      C.Destroy = Thunk(Life, 3, Path + " destroy");
    }
    if (C.Align == 0 || (C.Align & (C.Align - 1)))
      ReportAt(Path, diag::err_bind_bad_alignment, {std::to_string(C.Align)});
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
        ReportAt(Path + Mb.Name, diag::err_bind_damaged_descriptor,
                 {"member of class " + std::to_string(Owner) + " of " +
                  std::to_string(NumClasses)});
        continue;
      }
      Path += M.Classes[Owner].Name + ".";
    }
    Path += Mb.Name;
    if (Kind > uint32_t(MemberKind::Constant)) {
      ReportAt(Path, diag::err_bind_damaged_descriptor,
               {"unknown member kind " + std::to_string(Kind)});
      continue;
    }
    Mb.Kind = MemberKind(Kind);
    if (Owner == NoIndex && Mb.Kind != MemberKind::Function &&
        Mb.Kind != MemberKind::Constant) {
      ReportAt(Path, diag::err_bind_module_member_not_function);
      continue;
    }
    if (Owner != NoIndex && Mb.Kind == MemberKind::Constant) {
      ReportAt(Path, diag::err_bind_damaged_descriptor,
               {"a constant that belongs to a class"});
      continue;
    }
    if (Owner == NoIndex && Mb.Kind == MemberKind::Constructor) {
      ReportAt(Path, diag::err_bind_damaged_descriptor,
               {"a constructor of no class"});
      continue;
    }
    std::optional<TypeCode> RCode = CodeOf(
        Word(T_Member, I, BS_MEMBER_RESULT_CODE), /*AllowVoid=*/true, Path);
    if (!RCode)
      continue;
    Mb.Result.Code = *RCode;
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
    if (Mb.Kind == MemberKind::Constant) {
      // Version 2 records carry the value; a constant is nothing else.
      if (TablePtrs[T_Member] * P + 4 * (BS_MEMBER_VALUE + 1) >
          Size[T_Member]) {
        ReportAt(Path, diag::err_bind_damaged_descriptor,
                 {"a constant without a value"});
        continue;
      }
      Mb.Value = Word(T_Member, I, BS_MEMBER_VALUE);
      if (Mb.Result.Code == TypeCode::Void ||
          Mb.Result.Code == TypeCode::String ||
          Mb.Result.Code == TypeCode::Class) {
        ReportAt(Path, diag::err_bind_damaged_descriptor,
                 {"a constant that is not an int, float, bool or enum"});
        continue;
      }
      Mb.Result.Key = Key(Ptr(T_Member, I, BS_MEMBER_RESULT_KEY, Path), Path);
      M.Constants.push_back(std::move(Mb));
      continue;
    }
    size_t ErrorsBeforeThunk = Errs.size();
    Mb.Thunk = Thunk(Ptr(T_Member, I, BS_MEMBER_THUNK, Path), 0, Path);
    Mb.Setter = Thunk(Ptr(T_Member, I, BS_MEMBER_SETTER, Path + " setter"), 0,
                      Path + " setter");
    if (std::optional<Pointee> MP = Ptr(T_Member, I, BS_MEMBER_MEMPTR, Path)) {
      Expected<int64_t> Off = readMemberPointer(*MP);
      if (!Off)
        ErrorAt(Path, Off.takeError());
      else
        Mb.FieldOffset = uint64_t(*Off);
    }
    if (Mb.Result.isArray()) {
      // Arrays are reached only by offset, element by element.
      if (Mb.Kind != MemberKind::Field || !Mb.FieldOffset ||
          Mb.Result.Code == TypeCode::Void) {
        if (Errs.size() == ErrorsBeforeThunk)
          ReportAt(Path, diag::err_bind_array_not_field);
        continue;
      }
      // Generated code indexes within the array; the array must lie within
      // its object.
      uint64_t Bytes = Mb.Result.StorageSize;
      for (uint32_t Extent : Mb.Result.Extents)
        Bytes = std::min<uint64_t>(Bytes * Extent, uint64_t(1) << 40);
      if (Bytes == 0 || *Mb.FieldOffset + Bytes > M.Classes[Owner].Size) {
        ReportAt(Path, diag::err_bind_array_outside_object);
        continue;
      }
    } else if (Mb.Thunk.empty() && !QuietLinkage &&
               Errs.size() == ErrorsBeforeThunk) {
      ReportAt(Path, diag::err_bind_member_without_thunk);
    }
    if (Mb.Result.Code == TypeCode::Enum || Mb.Result.Code == TypeCode::Class)
      Mb.Result.Key = Key(Ptr(T_Member, I, BS_MEMBER_RESULT_KEY, Path), Path);
    if (uint64_t(First) + N > NumParams) {
      ReportAt(Path, diag::err_bind_damaged_descriptor,
               {"parameters outside the parameter table"});
      continue;
    }
    for (uint32_t J = 0; J < N; ++J) {
      uint32_t PI = First + J;
      std::string PPath = Path + " param " + std::to_string(J);
      BoundParam Pm;
      uint32_t RawCode = Word(T_Param, PI, BS_PARAM_CODE);
      std::optional<TypeCode> Code =
          RawCode == BS_CODE_CONTEXT && J == 0
              ? std::optional<TypeCode>(TypeCode::Context)
              : CodeOf(RawCode, /*AllowVoid=*/false, PPath);
      if (!Code)
        continue;
      Pm.Type.Code = *Code;
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
      ReportAt(Path, diag::err_bind_damaged_descriptor,
               {"values outside the value table"});
      continue;
    }
    for (uint32_t J = 0; J < N; ++J)
      E.Values.push_back({Str(Word(T_Value, First + J, BS_VALUE_NAME)),
                          int32_t(Word(T_Value, First + J, BS_VALUE_VALUE))});
    M.Enums.push_back(std::move(E));
  }

  uint32_t In = D.u32(BS_HDR_INPUT_CLASS), OutC = D.u32(BS_HDR_OUTPUT_CLASS);
  if (In != NoIndex && In >= NumClasses)
    Damaged("input class index out of range");
  else if (In != NoIndex)
    M.InputClass = int(In);
  if (OutC != NoIndex && OutC >= NumClasses)
    Damaged("output class index out of range");
  else if (OutC != NoIndex)
    M.OutputClass = int(OutC);
  if (BadString)
    Damaged("a name lies outside the string table");

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
  if (HiddenThunkProblem && HiddenThunks > 1)
    Errs.Problems[*HiddenThunkProblem].Args.back() =
        " (" + std::to_string(HiddenThunks - 1) +
        " more thunks of this module are hidden the same way)";
  Out.push_back(std::move(M));
}
