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

/// Decodes one descriptor: the header, then each table by its method, then
/// the hash. Every problem is reported into the reader's BindErrors at the
/// path of what it concerns (`Soccer::Vec.x param 0`); a record with a
/// problem is left out and the others are read, so one run reports all.
class bind::DescriptorDecoder {
public:
  DescriptorDecoder(ObjectReader &R, StringRef SymName, uint64_t Base,
                    uint64_t Sec, StringRef Data)
      : R(R), SymName(SymName), Base(Base), Sec(Sec), Data(Data),
        D(StringRef()) {}

  void decode(std::vector<BoundModule> &Out) {
    if (!readHeader() || !readTables() || !readName() || !readPlace())
      return;
    readClasses();
    for (uint32_t I = 0; I < Count[T_Member]; ++I)
      readMember(I);
    readEnums();
    readInputOutput();
    if (BadString)
      damaged("a name lies outside the string table");
    M.Hash = computeHash();
    if (HiddenThunkProblem && HiddenThunks > 1)
      R.Errs.Problems[*HiddenThunkProblem].Args.back() =
          " (" + std::to_string(HiddenThunks - 1) +
          " more thunks of this module are hidden the same way)";
    Out.push_back(std::move(M));
  }

private:
  //===--------------------------------------------------------------------===//
  // Reporting
  //===--------------------------------------------------------------------===//

  /// A problem of a record, or an error of a helper about it.
  size_t reportAt(const Twine &Path, diag::Kind Kind,
                  std::vector<std::string> Args = {}) {
    return R.Errs.add(R.File, Path.str(), Kind, std::move(Args));
  }
  /// ...of the descriptor as a whole, at its symbol.
  void fail(diag::Kind Kind, std::vector<std::string> Args = {}) {
    reportAt(SymName, Kind, std::move(Args));
  }
  void damaged(const Twine &Detail) {
    fail(diag::err_bind_damaged_descriptor, {Detail.str()});
  }
  void errorAt(const Twine &Path, Error E) {
    R.Errs.add(R.File, Path.str(), std::move(E), R.what());
  }

  //===--------------------------------------------------------------------===//
  // The header and the tables
  //===--------------------------------------------------------------------===//

  bool readHeader() {
    if (Base + HeaderSize > Data.size()) {
      damaged("the descriptor is truncated");
      return false;
    }
    D = DescriptorView(Data.substr(Base));
    if (std::memcmp(D.Bytes.data(), Magic, 8) != 0) {
      fail(diag::err_bind_bad_magic);
      return false;
    }
    Version = D.u32(BS_HDR_VERSION);
    if (Version == 0 || Version > SupportedVersion) {
      fail(diag::err_bind_bad_version,
           {std::to_string(Version), std::to_string(SupportedVersion)});
      return false;
    }
    if (D.u32(BS_HDR_PTR_SIZE) != R.P) {
      fail(diag::err_bind_bad_pointer_size,
           {std::to_string(D.u32(BS_HDR_PTR_SIZE)), std::to_string(R.P * 8)});
      return false;
    }
    Total = D.u32(BS_HDR_TOTAL_SIZE);
    if (D.u32(BS_HDR_HEADER_SIZE) < HeaderSize || Total > D.Bytes.size()) {
      damaged("the descriptor is truncated");
      return false;
    }
    D.Bytes = D.Bytes.take_front(Total);
    return true;
  }

  bool readTables() {
    for (unsigned T = 0; T < NumTables; ++T) {
      Count[T] = D.u32(BS_HDR_TABLE(T));
      Offset[T] = D.u32(BS_HDR_TABLE(T) + 4);
      Size[T] = D.u32(BS_HDR_TABLE(T) + 8);
      uint32_t Min = TablePtrs[T] * R.P + 4 * TableWords[T];
      if (Size[T] < Min ||
          uint64_t(Offset[T]) + uint64_t(Count[T]) * Size[T] > Total) {
        damaged(Twine("the ") + TableNames[T] +
                " table lies outside the descriptor or has short records");
        return false;
      }
    }
    uint32_t StrOff = D.u32(BS_HDR_STRING_OFFSET),
             StrSize = D.u32(BS_HDR_STRING_SIZE);
    if (uint64_t(StrOff) + StrSize > Total || StrSize == 0) {
      damaged("the string table lies outside the descriptor");
      return false;
    }
    Strings = D.Bytes.substr(StrOff, StrSize);
    return true;
  }

  /// Where BS_MODULE is (BS_HDR_PLACE): `file:line` after the strings,
  /// or nothing in objects of an older Bind.h.
  bool readPlace() {
    uint32_t At = D.u32(BS_HDR_PLACE);
    if (!At)
      return true;
    uint64_t StringsEnd = D.u32(BS_HDR_STRING_OFFSET) + uint64_t(Strings.size());
    if (At < StringsEnd || uint64_t(At) + BS_PLACE_SIZE > Total) {
      damaged("the place of registration lies outside the descriptor");
      return false;
    }
    StringRef Place = D.Bytes.substr(At, BS_PLACE_SIZE);
    Place = Place.take_until([](char C) { return C == 0; });
    auto [File, Line] = Place.rsplit(':');
    unsigned N;
    if (!File.empty() && !Line.getAsInteger(10, N)) {
      M.PlaceFile = File.str();
      M.PlaceLine = N;
    }
    return true;
  }

  bool readName() {
    M.File = R.File;
    M.Symbol = SymName.str();
    M.Version = Version;
    M.Name = str(D.u32(BS_HDR_NAME));
    StringRef Want = SymName.drop_front(strlen("bs_module_"));
    if (M.Name != Want) {
      fail(diag::err_bind_module_name_mismatch, {M.Name});
      return false;
    }
    return true;
  }

  //===--------------------------------------------------------------------===//
  // Fields of records
  //===--------------------------------------------------------------------===//

  std::string str(uint32_t Off) {
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
  }
  uint64_t rec(Table T, uint32_t I) const {
    return Offset[T] + uint64_t(I) * Size[T];
  }
  /// Word W (0-based, after the P fields) of record I of table T.
  uint32_t word(Table T, uint32_t I, unsigned W) const {
    return D.u32(rec(T, I) + TablePtrs[T] * R.P + 4 * W);
  }
  /// Whether record I of table T is long enough to hold word W (words
  /// appended by later versions).
  bool hasWord(Table T, unsigned W) const {
    return TablePtrs[T] * R.P + 4 * (W + 1) <= Size[T];
  }
  /// P field K of record I of table T, as a pointee.
  std::optional<Pointee> ptr(Table T, uint32_t I, unsigned K,
                             const Twine &Path) {
    Expected<std::optional<Pointee>> Pt =
        R.pointerAt(Sec, Base + rec(T, I) + K * R.P);
    if (!Pt) {
      errorAt(Path, Pt.takeError());
      return std::nullopt;
    }
    return *Pt;
  }
  /// A result's or parameter's type code (void only for results).
  std::optional<TypeCode> codeOf(uint32_t Code, bool AllowVoid,
                                 const Twine &Path) {
    if ((Code == uint32_t(TypeCode::Void) && !AllowVoid) ||
        Code > uint32_t(TypeCode::Class)) {
      reportAt(Path, diag::err_bind_damaged_descriptor,
               {"unknown type code " + std::to_string(Code)});
      return std::nullopt;
    }
    return TypeCode(Code);
  }

  /// A linked library turns hidden symbols into locals, so there only the
  /// name tells an anonymous namespace.
  bool internalKey(const Pointee &Pt) const {
    return R.IsDyn
               ? Pt.Name.empty() || StringRef(Pt.Name).contains("_GLOBAL__N")
               : !hasExternalLinkage(Pt.Binding);
  }
  /// A key field: the symbol of bs::TypeKey<T>::id, which must be external.
  std::string key(std::optional<Pointee> Pt, const Twine &Path) {
    if (!Pt)
      return "";
    if (R.IsDyn && Pt->Name.empty()) {
      reportAt(Path, diag::err_bind_stripped_key);
      return "";
    }
    if (internalKey(*Pt))
      reportAt(Path, diag::err_bind_internal_type, {typeOfKey(Pt->Name)});
    return Pt->Name;
  }
  /// A thunk through its holder: must be callable by name.
  std::string thunk(std::optional<Pointee> Holder, unsigned Slot,
                    const Twine &Path) {
    if (!Holder)
      return "";
    Expected<std::optional<Pointee>> T = R.followHolder(*Holder, Slot);
    if (!T) {
      errorAt(Path, T.takeError());
      return "";
    }
    if (!*T)
      return "";
    if (R.IsDyn) {
      // Undefined: another library is to define it, which the driver
      // checks against the libraries it links (findUndefinedSymbols).
      if ((*T)->Defined && !(*T)->Exported && !QuietLinkage &&
          HiddenThunks++ == 0) {
        std::string Name =
            (*T)->Name.empty()
                ? ("at 0x" + Twine::utohexstr((*T)->Offset) + " in section " +
                   Twine((*T)->SectionIndex))
                      .str()
                : demangled((*T)->Name);
        HiddenThunkProblem =
            reportAt(Path, diag::err_bind_hidden_thunk, {Name, ""});
      }
      return (*T)->Name;
    }
    if (!hasExternalLinkage((*T)->Binding) && !QuietLinkage)
      reportAt(Path, diag::err_bind_internal_thunk, {demangled((*T)->Name)});
    return (*T)->Name;
  }

  //===--------------------------------------------------------------------===//
  // The tables' records
  //===--------------------------------------------------------------------===//

  void readClasses() {
    for (uint32_t I = 0; I < Count[T_Class]; ++I) {
      BoundClass C;
      C.Name = str(word(T_Class, I, BS_CLASS_NAME));
      C.CppName = str(word(T_Class, I, BS_CLASS_CPP_NAME));
      std::string Path = M.Name + "::" + C.Name;
      C.Size = word(T_Class, I, BS_CLASS_SIZE);
      C.Align = word(T_Class, I, BS_CLASS_ALIGN);
      C.Flags = word(T_Class, I, BS_CLASS_FLAGS);
      size_t ErrorsBefore = R.Errs.size();
      std::optional<Pointee> KeyPt = ptr(T_Class, I, BS_CLASS_KEY, Path);
      C.Key = key(KeyPt, Path);
      if (C.Key.empty() && R.Errs.size() == ErrorsBefore)
        reportAt(Path, diag::err_bind_class_without_key);
      // Once a class's key has internal linkage, so has every thunk of the
      // class: the class is reported once.
      InternalClass.push_back(KeyPt && internalKey(*KeyPt));
      QuietLinkage = InternalClass.back();
      if (std::optional<Pointee> Life = ptr(T_Class, I, BS_CLASS_LIFE, Path)) {
        C.Construct = thunk(Life, 0, Path + " construct");
        C.Copy = thunk(Life, 1, Path + " copy");
        C.Assign = thunk(Life, 2, Path + " assign");
        C.Destroy = thunk(Life, 3, Path + " destroy");
      }
      if (C.Align == 0 || (C.Align & (C.Align - 1)))
        reportAt(Path, diag::err_bind_bad_alignment, {std::to_string(C.Align)});
      M.Classes.push_back(std::move(C));
      QuietLinkage = false;
    }
  }

  /// Member I: a function, constructor, field, property or constant of the
  /// module or of a class.
  void readMember(uint32_t I) {
    BoundMember Mb;
    uint32_t Owner = word(T_Member, I, BS_MEMBER_OWNER);
    Mb.Name = str(word(T_Member, I, BS_MEMBER_NAME));
    Mb.CppName = str(word(T_Member, I, BS_MEMBER_CPP_NAME));
    std::string Path;
    if (!readMemberKind(I, Owner, Mb, Path))
      return;
    std::optional<TypeCode> RCode = codeOf(
        word(T_Member, I, BS_MEMBER_RESULT_CODE), /*AllowVoid=*/true, Path);
    if (!RCode)
      return;
    Mb.Result.Code = *RCode;
    Mb.Result.Flags = word(T_Member, I, BS_MEMBER_RESULT_FLAGS);
    Mb.Result.StorageSize = word(T_Member, I, BS_MEMBER_RESULT_SIZE);
    Mb.Flags = word(T_Member, I, BS_MEMBER_FLAGS);
    QuietLinkage = Owner != NoIndex && InternalClass[Owner];
    // An array field's extents: words appended to the record, so a shorter
    // record (an older Bind.h) has none.
    for (unsigned W = BS_MEMBER_EXTENT;
         W < BS_MEMBER_EXTENT + BS_MEMBER_MAX_EXTENTS && hasWord(T_Member, W);
         ++W) {
      uint32_t Extent = word(T_Member, I, W);
      if (Extent == 0)
        break;
      Mb.Result.Extents.push_back(Extent);
    }
    if (Mb.Kind == MemberKind::Constant) {
      if (readConstant(I, Mb, Path))
        M.Constants.push_back(std::move(Mb));
      return;
    }
    if (!readCallable(I, Owner, Mb, Path) || !readParams(I, Mb, Path))
      return;
    if (Owner == NoIndex)
      M.Functions.push_back(std::move(Mb));
    else
      M.Classes[Owner].Members.push_back(std::move(Mb));
  }

  /// The member's kind and owner, checked together; `Path` names it.
  bool readMemberKind(uint32_t I, uint32_t Owner, BoundMember &Mb,
                      std::string &Path) {
    uint32_t Kind = word(T_Member, I, BS_MEMBER_KIND);
    Path = M.Name + "::";
    if (Owner != NoIndex) {
      if (Owner >= Count[T_Class]) {
        reportAt(Path + Mb.Name, diag::err_bind_damaged_descriptor,
                 {"member of class " + std::to_string(Owner) + " of " +
                  std::to_string(Count[T_Class])});
        return false;
      }
      Path += M.Classes[Owner].Name + ".";
    }
    Path += Mb.Name;
    if (Kind > uint32_t(MemberKind::Constant)) {
      reportAt(Path, diag::err_bind_damaged_descriptor,
               {"unknown member kind " + std::to_string(Kind)});
      return false;
    }
    Mb.Kind = MemberKind(Kind);
    if (Owner == NoIndex && Mb.Kind != MemberKind::Function &&
        Mb.Kind != MemberKind::Constant) {
      reportAt(Path, diag::err_bind_module_member_not_function);
      return false;
    }
    if (Owner != NoIndex && Mb.Kind == MemberKind::Constant) {
      reportAt(Path, diag::err_bind_damaged_descriptor,
               {"a constant that belongs to a class"});
      return false;
    }
    if (Owner == NoIndex && Mb.Kind == MemberKind::Constructor) {
      reportAt(Path, diag::err_bind_damaged_descriptor,
               {"a constructor of no class"});
      return false;
    }
    return true;
  }

  /// A registered constant: version 2 records carry its value; it is
  /// nothing else.
  bool readConstant(uint32_t I, BoundMember &Mb, const std::string &Path) {
    if (!hasWord(T_Member, BS_MEMBER_VALUE)) {
      reportAt(Path, diag::err_bind_damaged_descriptor,
               {"a constant without a value"});
      return false;
    }
    Mb.Value = word(T_Member, I, BS_MEMBER_VALUE);
    if (Mb.Result.Code == TypeCode::Void ||
        Mb.Result.Code == TypeCode::String ||
        Mb.Result.Code == TypeCode::Class) {
      reportAt(Path, diag::err_bind_damaged_descriptor,
               {"a constant that is not an int, float, bool or enum"});
      return false;
    }
    Mb.Result.Key = key(ptr(T_Member, I, BS_MEMBER_RESULT_KEY, Path), Path);
    return true;
  }

  /// A member reached through thunks or a field offset: those, and an
  /// array field's bounds.
  bool readCallable(uint32_t I, uint32_t Owner, BoundMember &Mb,
                    const std::string &Path) {
    size_t ErrorsBeforeThunk = R.Errs.size();
    Mb.Thunk = thunk(ptr(T_Member, I, BS_MEMBER_THUNK, Path), 0, Path);
    Mb.Setter = thunk(ptr(T_Member, I, BS_MEMBER_SETTER, Path + " setter"), 0,
                      Path + " setter");
    if (std::optional<Pointee> MP = ptr(T_Member, I, BS_MEMBER_MEMPTR, Path)) {
      Expected<int64_t> Off = R.readMemberPointer(*MP);
      if (!Off)
        errorAt(Path, Off.takeError());
      else
        Mb.FieldOffset = uint64_t(*Off);
    }
    if (Mb.Result.isArray()) {
      // Arrays are reached only by offset, element by element.
      if (Mb.Kind != MemberKind::Field || !Mb.FieldOffset ||
          Mb.Result.Code == TypeCode::Void) {
        if (R.Errs.size() == ErrorsBeforeThunk)
          reportAt(Path, diag::err_bind_array_not_field);
        return false;
      }
      // Generated code indexes within the array; the array must lie within
      // its object.
      uint64_t Bytes = Mb.Result.StorageSize;
      for (uint32_t Extent : Mb.Result.Extents)
        Bytes = std::min<uint64_t>(Bytes * Extent, uint64_t(1) << 40);
      if (Bytes == 0 || *Mb.FieldOffset + Bytes > M.Classes[Owner].Size) {
        reportAt(Path, diag::err_bind_array_outside_object);
        return false;
      }
    } else if (Mb.Thunk.empty() && !QuietLinkage &&
               R.Errs.size() == ErrorsBeforeThunk) {
      reportAt(Path, diag::err_bind_member_without_thunk);
    }
    if (Mb.Result.Code == TypeCode::Enum || Mb.Result.Code == TypeCode::Class)
      Mb.Result.Key = key(ptr(T_Member, I, BS_MEMBER_RESULT_KEY, Path), Path);
    return true;
  }

  /// The member's parameters, records of the parameter table.
  bool readParams(uint32_t I, BoundMember &Mb, const std::string &Path) {
    uint32_t First = word(T_Member, I, BS_MEMBER_FIRST_PARAM),
             N = word(T_Member, I, BS_MEMBER_NUM_PARAMS);
    if (uint64_t(First) + N > Count[T_Param]) {
      reportAt(Path, diag::err_bind_damaged_descriptor,
               {"parameters outside the parameter table"});
      return false;
    }
    for (uint32_t J = 0; J < N; ++J) {
      uint32_t PI = First + J;
      std::string PPath = Path + " param " + std::to_string(J);
      BoundParam Pm;
      uint32_t RawCode = word(T_Param, PI, BS_PARAM_CODE);
      std::optional<TypeCode> Code =
          RawCode == BS_CODE_CONTEXT && J == 0
              ? std::optional<TypeCode>(TypeCode::Context)
              : codeOf(RawCode, /*AllowVoid=*/false, PPath);
      if (!Code)
        continue;
      Pm.Type.Code = *Code;
      Pm.Type.Flags = word(T_Param, PI, BS_PARAM_FLAGS);
      Pm.Type.StorageSize = word(T_Param, PI, BS_PARAM_SIZE);
      Pm.Name = str(word(T_Param, PI, BS_PARAM_NAME));
      uint32_t DK = word(T_Param, PI, BS_PARAM_DEFAULT_KIND);
      Pm.Default = DK == BS_DEFAULT_INT     ? DefaultKind::Int
                   : DK == BS_DEFAULT_FLOAT ? DefaultKind::Float
                                            : DefaultKind::None;
      Pm.DefaultInt = int32_t(word(T_Param, PI, BS_PARAM_DEFAULT_INT));
      uint32_t FBits = word(T_Param, PI, BS_PARAM_DEFAULT_FLOAT);
      std::memcpy(&Pm.DefaultFloat, &FBits, 4);
      if (Pm.Type.Code == TypeCode::Enum || Pm.Type.Code == TypeCode::Class)
        Pm.Type.Key = key(ptr(T_Param, PI, BS_PARAM_KEY, PPath), PPath);
      Mb.Params.push_back(std::move(Pm));
    }
    return true;
  }

  void readEnums() {
    for (uint32_t I = 0; I < Count[T_Enum]; ++I) {
      BoundEnum E;
      E.Name = str(word(T_Enum, I, BS_ENUM_NAME));
      E.CppName = str(word(T_Enum, I, BS_ENUM_CPP_NAME));
      std::string Path = M.Name + "::" + E.Name;
      E.Size = word(T_Enum, I, BS_ENUM_SIZE);
      uint32_t Flags = word(T_Enum, I, BS_ENUM_FLAGS);
      E.Scoped = Flags & BS_ENUM_SCOPED;
      E.Signed = Flags & BS_ENUM_SIGNED;
      uint32_t First = word(T_Enum, I, BS_ENUM_FIRST_VALUE),
               N = word(T_Enum, I, BS_ENUM_NUM_VALUES);
      E.Key = key(ptr(T_Enum, I, BS_ENUM_KEY, Path), Path);
      if (uint64_t(First) + N > Count[T_Value]) {
        reportAt(Path, diag::err_bind_damaged_descriptor,
                 {"values outside the value table"});
        continue;
      }
      for (uint32_t J = 0; J < N; ++J)
        E.Values.push_back({str(word(T_Value, First + J, BS_VALUE_NAME)),
                            int32_t(word(T_Value, First + J, BS_VALUE_VALUE))});
      M.Enums.push_back(std::move(E));
    }
  }

  void readInputOutput() {
    uint32_t In = D.u32(BS_HDR_INPUT_CLASS), Out = D.u32(BS_HDR_OUTPUT_CLASS);
    if (In != NoIndex && In >= Count[T_Class])
      damaged("input class index out of range");
    else if (In != NoIndex)
      M.InputClass = int(In);
    if (Out != NoIndex && Out >= Count[T_Class])
      damaged("output class index out of range");
    else if (Out != NoIndex)
      M.OutputClass = int(Out);
  }

  /// The hash, as Bind.h and the runtime compute it (bs_descriptor_hash),
  /// with the field offsets from the holders' relocations.
  uint64_t computeHash() {
    struct FieldOffsets {
      ObjectReader &R;
      uint64_t Sec, Members;
      unsigned P;
      uint32_t RecordSize;
    } Ctx{R, Sec, Base + Offset[T_Member], R.P, Size[T_Member]};
    auto FieldOffset = [](void *C, uint32_t I, int64_t *Off) -> int {
      auto &F = *static_cast<FieldOffsets *>(C);
      Expected<std::optional<Pointee>> MP =
          F.R.pointerAt(F.Sec, F.Members + uint64_t(I) * F.RecordSize +
                                   BS_MEMBER_MEMPTR * F.P);
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
    return bs_descriptor_hash(
        reinterpret_cast<const unsigned char *>(D.Bytes.data()), FieldOffset,
        &Ctx);
  }

  ObjectReader &R;
  StringRef SymName;
  uint64_t Base, Sec; ///< Where the descriptor is in the object.
  StringRef Data;     ///< Its section's bytes.
  DescriptorView D;   ///< The descriptor, from readHeader on.
  uint32_t Version = 0, Total = 0;
  uint32_t Count[NumTables] = {}, Offset[NumTables] = {}, Size[NumTables] = {};
  StringRef Strings;
  bool BadString = false;
  BoundModule M;
  /// Per class: its key has internal linkage.
  std::vector<bool> InternalClass;
  /// Set while reading a class whose key has internal linkage: its thunks
  /// are not reported again.
  bool QuietLinkage = false;
  /// Hidden thunks of a shared library have one cause (its visibility):
  /// the first is reported, with the count of the others added at the end.
  std::optional<size_t> HiddenThunkProblem;
  unsigned HiddenThunks = 0;
};

void ObjectReader::readDescriptor(StringRef SymName, uint64_t Base,
                                  uint64_t Sec, StringRef Data,
                                  std::vector<BoundModule> &Out) {
  DescriptorDecoder(*this, SymName, Base, Sec, Data).decode(Out);
}
