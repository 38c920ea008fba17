//===- BindTest.cpp - bscript/Bind.h and lib/Bind end to end --------------===//
//
// The binding sources of test/Bindings/Inputs and examples/soccer are
// compiled at build time by GCC and Clang for i586 (geode) and x86-64
// (unittests/Bind/CMakeLists.txt); these tests read the objects back and
// check what every registration form produces, the target layouts, that the
// descriptor needs no dynamic initialiser, and every reader error. forms.cpp
// is also linked into this test, so the in-process descriptor is checked
// against the reader and its thunks are called for real.
//
//===----------------------------------------------------------------------===//
#include "bsc/AST/Native.h"
#include "bsc/Bind/Bind.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Object/ELFObjectFile.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/raw_ostream.h"
#include "llvm/TargetParser/Triple.h"
#include "gtest/gtest.h"

#include <bscript/Bind.h>
#include <bscript/bscript.h>
#include <cstring>

using namespace llvm;
using namespace bsc;
using namespace bsc::bind;

namespace {

const Triple I586("i586-unknown-linux-gnu");
const Triple X64("x86_64-unknown-linux-gnu");

std::string obj(StringRef Name) { return std::string(BIND_OBJ_DIR) + "/" + Name.str(); }

bool is32(StringRef Cfg) { return Cfg.ends_with("32"); }
const Triple &tripleOf(StringRef Cfg) { return is32(Cfg) ? I586 : X64; }

BindingModel read(ArrayRef<std::string> Paths, const Triple &T) {
  Expected<BindingModel> M = readBindings(Paths, T);
  if (!M) {
    ADD_FAILURE() << toString(M.takeError());
    return BindingModel();
  }
  return std::move(*M);
}

/// The reader's error text for these inputs ("" if it succeeded).
std::string readError(ArrayRef<std::string> Paths, const Triple &T) {
  Expected<BindingModel> M = readBindings(Paths, T);
  if (M)
    return "";
  return toString(M.takeError());
}

const BoundMember &member(const BoundClass &C, StringRef Name) {
  const BoundMember *M = C.findMember(Name);
  if (!M) {
    ADD_FAILURE() << "no member " << Name.str();
    static BoundMember None;
    return None;
  }
  return *M;
}

const char *const Configs[] = {"gcc32", "gcc64", "clang32", "clang64"};

//===----------------------------------------------------------------------===//
// Every registration form, for every compiler, target and -O level
//===----------------------------------------------------------------------===//

class FormsTest : public ::testing::TestWithParam<std::tuple<const char *, const char *>> {};

TEST_P(FormsTest, ReadsEveryForm) {
  std::string Cfg = std::get<0>(GetParam());
  std::string File = "forms." + Cfg + std::get<1>(GetParam()) + ".o";
  BindingModel Model = read({obj(File)}, tripleOf(Cfg));
  ASSERT_EQ(Model.Modules.size(), 1u);
  const BoundModule &M = Model.Modules[0];
  EXPECT_EQ(M.Name, "Forms");
  EXPECT_EQ(M.Symbol, "bs_module_Forms");
  ASSERT_EQ(M.Classes.size(), 1u);
  const BoundClass &P = M.Classes[0];
  EXPECT_EQ(P.Name, "Point");
  EXPECT_EQ(P.CppName, "geo::Point");
  EXPECT_EQ(P.Key, "_ZN2bs7TypeKeyIN3geo5PointEE2idE");
  // int id; float x, y; double weight; const int version; bool flag.
  EXPECT_EQ(P.Size, is32(Cfg) ? 28u : 32u);
  EXPECT_EQ(P.Align, is32(Cfg) ? 4u : 8u);
  EXPECT_FALSE(P.Flags & CF_TriviallyCopyable); // user-provided operator=
  EXPECT_TRUE(P.Flags & CF_TriviallyDestructible);
  EXPECT_FALSE(P.Construct.empty());
  EXPECT_FALSE(P.Copy.empty());
  EXPECT_FALSE(P.Destroy.empty());

  const BoundMember &X = member(P, "x");
  EXPECT_EQ(X.Kind, MemberKind::Field);
  EXPECT_EQ(X.FieldOffset, 4u);
  EXPECT_EQ(X.Result.Code, TypeCode::Float);
  EXPECT_FALSE(X.isReadOnly());
  EXPECT_FALSE(X.Setter.empty());
  // A double field: float on the wire, 8 bytes of storage, 4-aligned on i386.
  const BoundMember &W = member(P, "weight");
  EXPECT_EQ(W.Result.Code, TypeCode::Float);
  EXPECT_EQ(W.Result.StorageSize, 8u);
  EXPECT_EQ(W.FieldOffset, is32(Cfg) ? 12u : 16u);
  const BoundMember &V = member(P, "version");
  EXPECT_TRUE(V.isReadOnly());
  EXPECT_TRUE(V.Setter.empty());
  EXPECT_TRUE(V.Result.Flags & TF_Const);
  EXPECT_EQ(member(P, "flag").Result.Code, TypeCode::Bool);
  EXPECT_EQ(member(P, "flag").Result.StorageSize, 1u);
  EXPECT_EQ(member(P, "id").FieldOffset, 0u); // of the base class

  const BoundMember &Len = member(P, "length");
  EXPECT_EQ(Len.Kind, MemberKind::Method);
  EXPECT_TRUE(Len.isConstSelf());
  EXPECT_EQ(Len.Result.Code, TypeCode::Float);
  EXPECT_TRUE(Len.Params.empty());
  EXPECT_TRUE(StringRef(Len.Thunk).starts_with("_ZN2bs6detail8CallImpl"));
  EXPECT_FALSE(member(P, "scale").isConstSelf());
  EXPECT_EQ(member(P, "getId").Result.Code, TypeCode::Int); // base member
  EXPECT_TRUE(member(P, "tag").Result.Flags & TF_Unsigned);
  EXPECT_EQ(member(P, "tag").Result.StorageSize, 2u);

  const BoundMember &Plus = member(P, "_plus_");
  EXPECT_EQ(Plus.CppName, "plus");
  EXPECT_TRUE(Plus.resultViaOut());
  EXPECT_EQ(Plus.Result.Code, TypeCode::Class);
  EXPECT_EQ(Model.getQualifiedName(Plus.Result), "Forms::Point");
  ASSERT_EQ(Plus.Params.size(), 1u);
  EXPECT_EQ(Plus.Params[0].Type.Code, TypeCode::Class);
  EXPECT_EQ(Plus.Params[0].Type.Flags, unsigned(TF_Const | TF_Ref | TF_Pointer));
  EXPECT_EQ(Model.getClass(Plus.Params[0].Type), &P);

  // Defaults restated with .defaults(1.5f, false).
  const BoundMember &Move = member(P, "move");
  ASSERT_EQ(Move.Params.size(), 3u);
  EXPECT_EQ(Move.Params[0].Default, DefaultKind::None);
  EXPECT_EQ(Move.Params[1].Default, DefaultKind::Float);
  EXPECT_EQ(Move.Params[1].DefaultFloat, 1.5f);
  EXPECT_EQ(Move.Params[2].Default, DefaultKind::Int);
  EXPECT_EQ(Move.Params[2].DefaultInt, 0);
  EXPECT_EQ(Move.Params[2].Type.Code, TypeCode::Bool);
  // ...and named with .func<&Point::move>("move", {"dx", "dy", "twice"}).
  EXPECT_EQ(Move.Params[0].Name, "dx");
  EXPECT_EQ(Move.Params[1].Name, "dy");
  EXPECT_EQ(Move.Params[2].Name, "twice");
  // Parameters registered without names have none (as in descriptors
  // written before names could be given).
  EXPECT_EQ(member(P, "scale").Params[0].Name, "");
  EXPECT_EQ(member(P, "_plus_").Params[0].Name, "");

  // Properties: a mutable-reference getter is read/write on its own.
  EXPECT_EQ(member(P, "rx").Kind, MemberKind::Property);
  EXPECT_FALSE(member(P, "rx").Setter.empty());
  EXPECT_TRUE(member(P, "crx").isReadOnly());
  EXPECT_FALSE(member(P, "py").Setter.empty());

  // Free functions and lambdas with a Point first parameter are methods.
  EXPECT_EQ(member(P, "dist").Kind, MemberKind::Method);
  EXPECT_TRUE(member(P, "dist").isConstSelf());
  EXPECT_EQ(member(P, "dist").Params.size(), 1u);
  EXPECT_EQ(member(P, "dist").Params[0].Name, "other"); // not the object's
  EXPECT_FALSE(member(P, "reset").isConstSelf());
  EXPECT_EQ(member(P, "_min_").Kind, MemberKind::Method);
  EXPECT_EQ(member(P, "_neg_").Params.size(), 0u);
  EXPECT_EQ(member(P, "origin").Kind, MemberKind::Function);

  ASSERT_EQ(M.Enums.size(), 2u);
  const BoundEnum *Color = M.findEnum("Color");
  ASSERT_TRUE(Color);
  EXPECT_EQ(Color->Size, 1u);
  EXPECT_FALSE(Color->Scoped);
  EXPECT_FALSE(Color->Signed);
  ASSERT_EQ(Color->Values.size(), 3u);
  EXPECT_EQ(Color->Values[2].Name, "blue");
  EXPECT_EQ(Color->Values[2].Number, 200);
  const BoundEnum *Mode = M.findEnum("Mode");
  ASSERT_TRUE(Mode);
  EXPECT_TRUE(Mode->Scoped);
  EXPECT_EQ(Mode->Values[0].Number, -1);

  const BoundMember *Twice = M.findFunction("twice");
  ASSERT_TRUE(Twice);
  EXPECT_EQ(Twice->CppName, "geo::twice");
  EXPECT_EQ(Twice->Params[0].DefaultInt, 4);
  EXPECT_EQ(Twice->Params[0].Name, "v"); // {"v"}, then the C++ name
  const BoundMember *Flip = M.findFunction("flip");
  ASSERT_TRUE(Flip);
  EXPECT_EQ(Model.getQualifiedName(Flip->Result), "Forms::Mode");
  EXPECT_EQ(Flip->Params[0].DefaultInt, 1);
  const BoundMember *Out = M.findFunction("outParams");
  ASSERT_TRUE(Out);
  ASSERT_EQ(Out->Params.size(), 3u);
  for (const BoundParam &Pm : Out->Params)
    EXPECT_TRUE(Pm.Type.isOutPointer());
  EXPECT_EQ(Out->Params[2].Type.StorageSize, 1u); // bool&
  EXPECT_TRUE(M.findFunction("fabs"));
  EXPECT_EQ(M.findFunction("twice2")->Thunk, Twice->Thunk); // bs::fn form
  EXPECT_EQ(M.findFunction("twice2")->Params[0].Name, "v");
  EXPECT_EQ(M.findFunction("max")->Params[0].Name, "");
  EXPECT_EQ(M.findFunction("greet")->Result.Code, TypeCode::String);
  EXPECT_TRUE(M.findFunction("max"));
}

INSTANTIATE_TEST_SUITE_P(AllConfigs, FormsTest,
                         ::testing::Combine(::testing::ValuesIn(Configs),
                                            ::testing::Values("", ".O0")));

/// GCC and Clang give the same thunk names, except for lambdas (their
/// discriminators differ: bsc reads names from the objects that get linked).
TEST(BindTest, GccAndClangAgree) {
  for (const char *Bits : {"32", "64"}) {
    const Triple &T = StringRef(Bits) == "32" ? I586 : X64;
    BindingModel G = read({obj(std::string("forms.gcc") + Bits + ".o")}, T);
    BindingModel C = read({obj(std::string("forms.clang") + Bits + ".o")}, T);
    ASSERT_EQ(G.Modules.size(), 1u);
    ASSERT_EQ(C.Modules.size(), 1u);
    EXPECT_EQ(G.Modules[0].Hash, C.Modules[0].Hash);
    const BoundClass &GP = G.Modules[0].Classes[0], &CP = C.Modules[0].Classes[0];
    ASSERT_EQ(GP.Members.size(), CP.Members.size());
    for (size_t I = 0; I < GP.Members.size(); ++I) {
      if (GP.Members[I].Thunk.find("bs_module_body") != std::string::npos)
        continue; // a lambda
      EXPECT_EQ(GP.Members[I].Thunk, CP.Members[I].Thunk);
      EXPECT_EQ(GP.Members[I].Setter, CP.Members[I].Setter);
    }
    EXPECT_EQ(GP.Construct, CP.Construct);
  }
  // The layout differs between targets, and so does the hash.
  EXPECT_NE(read({obj("forms.gcc32.o")}, I586).Modules[0].Hash,
            read({obj("forms.gcc64.o")}, X64).Modules[0].Hash);
}

//===----------------------------------------------------------------------===//
// Eigen
//===----------------------------------------------------------------------===//

TEST(BindTest, EigenLayouts) {
  for (const char *Cfg : Configs)
    for (const char *Opt : {"", ".O0"}) {
      SCOPED_TRACE(std::string(Cfg) + Opt);
      BindingModel Model =
          read({obj(std::string("eigen.") + Cfg + Opt + ".o")}, tripleOf(Cfg));
      ASSERT_EQ(Model.Modules.size(), 1u);
      const BoundModule &M = Model.Modules[0];
      const BoundClass *V2 = M.findClass("Vector2f");
      ASSERT_TRUE(V2);
      EXPECT_EQ(V2->Size, 8u);
      EXPECT_EQ(V2->Align, 4u);
      EXPECT_EQ(V2->Key, "_ZN2bs7TypeKeyIN5Eigen6MatrixIfLi2ELi1ELi0ELi2ELi1EEEE2idE");
      // Inherited, overloaded accessors selected with bs::mut / bs::cnst.
      EXPECT_FALSE(member(*V2, "x").Setter.empty());
      EXPECT_TRUE(member(*V2, "y").isReadOnly());
      EXPECT_NE(member(*V2, "abs").Thunk.find("MatrixBase"), std::string::npos);
      EXPECT_TRUE(member(*V2, "normalized").resultViaOut());
      EXPECT_FALSE(member(*V2, "normalize").isConstSelf());
      EXPECT_EQ(member(*V2, "_mul_").Params[0].Type.Code, TypeCode::Float);
      EXPECT_EQ(member(*V2, "_eq_").Result.Code, TypeCode::Bool);
      // Eigen keeps 16-byte alignment for these even on geode.
      EXPECT_EQ(M.findClass("Vector4f")->Align, 16u);
      EXPECT_EQ(M.findClass("Vector2d")->Align, 16u);
      EXPECT_EQ(member(*M.findClass("Vector2d"), "x").Result.StorageSize, 8u);
      const BoundClass *Pose = M.findClass("Pose");
      ASSERT_TRUE(Pose);
      EXPECT_EQ(member(*Pose, "translation").FieldOffset, 0u);
      EXPECT_EQ(member(*Pose, "rotation").FieldOffset, 8u);
      EXPECT_EQ(member(*Pose, "stamp").FieldOffset, is32(Cfg) ? 12u : 16u);
      EXPECT_EQ(Pose->Size, is32(Cfg) ? 20u : 24u);
      const BoundClass *Al = M.findClass("Aligned");
      EXPECT_EQ(member(*Al, "v").FieldOffset, 16u);
      EXPECT_EQ(Al->Size, 32u);
      EXPECT_EQ(Al->Align, 16u);
      EXPECT_TRUE(M.findFunction("vec")->resultViaOut());
    }
}

//===----------------------------------------------------------------------===//
// No dynamic initialiser
//===----------------------------------------------------------------------===//

/// Checks that no relocation outside the descriptors' own refers to a
/// descriptor: a dynamic initialiser would have to store into it. Returns
/// whether the object has an .init_array at all.
bool checkNoInitialiser(const std::string &Path) {
  auto Buf = MemoryBuffer::getFile(Path);
  EXPECT_TRUE(bool(Buf)) << Path;
  if (!Buf)
    return false;
  auto Bin = object::ObjectFile::createObjectFile((*Buf)->getMemBufferRef());
  EXPECT_TRUE(bool(Bin)) << Path;
  if (!Bin) {
    consumeError(Bin.takeError());
    return false;
  }
  object::ObjectFile &O = **Bin;
  bool HasInitArray = false;
  uint64_t Descriptors = ~0ull;
  for (const object::SectionRef &S : O.sections()) {
    StringRef Name = cantFail(S.getName());
    if (Name == "bs_modules") {
      Descriptors = S.getIndex();
      EXPECT_NE(object::ELFSectionRef(S).getType(), unsigned(ELF::SHT_NOBITS));
    }
    if (Name.starts_with(".init_array") || Name.starts_with(".ctors"))
      HasInitArray = true;
  }
  EXPECT_NE(Descriptors, ~0ull) << Path;
  for (const object::SectionRef &S : O.sections()) {
    auto Target = cantFail(S.getRelocatedSection());
    if (Target == O.section_end() || Target->getIndex() == Descriptors)
      continue;
    for (const object::RelocationRef &R : S.relocations()) {
      auto Sym = R.getSymbol();
      if (Sym == O.symbol_end())
        continue;
      StringRef Name = cantFail(Sym->getName());
      EXPECT_FALSE(Name.starts_with("bs_module_"))
          << Path << ": " << cantFail(Target->getName()).str()
          << " refers to " << Name.str();
      auto SymSec = cantFail(Sym->getSection());
      EXPECT_FALSE(SymSec != O.section_end() &&
                   SymSec->getIndex() == Descriptors)
          << Path << ": " << cantFail(Target->getName()).str()
          << " refers to section bs_modules";
    }
  }
  return HasInitArray;
}

TEST(BindTest, NoDynamicInitialiser) {
  for (const char *Cfg : Configs)
    for (const char *Opt : {"", ".O0"}) {
      // Without Eigen there is no .init_array at all.
      EXPECT_FALSE(checkNoInitialiser(obj(std::string("forms.") + Cfg + Opt + ".o")));
      // Eigen's own header statics add one at -O0; the descriptor has none.
      checkNoInitialiser(obj(std::string("eigen.") + Cfg + Opt + ".o"));
    }
  checkNoInitialiser(obj("soccer.gcc32.O0.o"));
}

//===----------------------------------------------------------------------===//
// The soccer world of the paper
//===----------------------------------------------------------------------===//

TEST(BindTest, SoccerBindings) {
  for (const char *Cfg : Configs) {
    SCOPED_TRACE(Cfg);
    BindingModel Model =
        read({obj(std::string("soccer.") + Cfg + ".o")}, tripleOf(Cfg));
    const BoundModule *Math = Model.findModule("Math");
    const BoundModule *World = Model.findModule("World");
    ASSERT_TRUE(Math && World);
    const BoundClass *V = Math->findClass("Vector2f");
    ASSERT_TRUE(V);
    for (const char *N : {"x", "y"}) {
      EXPECT_EQ(member(*V, N).Result.Code, TypeCode::Float);
      EXPECT_FALSE(member(*V, N).isReadOnly());
    }
    EXPECT_EQ(member(*V, "abs").Result.Code, TypeCode::Float);
    for (const char *N : {"_plus_", "_min_"}) {
      const BoundMember &Op = member(*V, N);
      EXPECT_EQ(Model.getClass(Op.Result), V);
      ASSERT_EQ(Op.Params.size(), 1u);
      EXPECT_EQ(Model.getClass(Op.Params[0].Type), V);
    }
    // Where each module is registered: BS_MODULE's file (and line: GCC
    // gives its first line, clang its last).
    EXPECT_TRUE(llvm::StringRef(Math->PlaceFile).ends_with("SoccerBindings.cpp"))
        << Math->PlaceFile;
    EXPECT_GE(Math->PlaceLine, 34u);
    EXPECT_LE(Math->PlaceLine, 66u);
    EXPECT_EQ(World->PlaceFile, Math->PlaceFile);
    EXPECT_GT(World->PlaceLine, Math->PlaceLine);
    const BoundMember *Fabs = Math->findFunction("fabs");
    ASSERT_TRUE(Fabs);
    EXPECT_EQ(Fabs->Params[0].Type.Code, TypeCode::Float);
    EXPECT_EQ(Fabs->Params[0].Name, "x");

    const BoundEnum *MT = World->findEnum("MotionType");
    ASSERT_TRUE(MT);
    ASSERT_EQ(MT->Values.size(), 3u);
    EXPECT_EQ(MT->Values[2].Name, "kick");
    EXPECT_EQ(Model.getWorldModule(), World);
    ASSERT_GE(World->InputClass, 0);
    ASSERT_GE(World->OutputClass, 0);
    const BoundClass &In = World->Classes[World->InputClass];
    const BoundClass &Out = World->Classes[World->OutputClass];
    // input.ball.position: a chain of fields across modules.
    const BoundClass *Ball = Model.getClass(member(In, "ball").Result);
    ASSERT_TRUE(Ball);
    EXPECT_EQ(Model.getClass(member(*Ball, "position").Result), V);
    EXPECT_EQ(Model.getQualifiedName(member(In, "oppGoal").Result), "Math::Vector2f");
    EXPECT_EQ(member(In, "time").Result.Code, TypeCode::Int);
    EXPECT_EQ(Model.getEnum(member(In, "executedMotion").Result), MT);
    EXPECT_EQ(Model.getEnum(member(Out, "motion").Result), MT);
    EXPECT_EQ(member(Out, "walkTarget").FieldOffset, 4u);
    EXPECT_EQ(member(Out, "headTarget").FieldOffset, 12u);

    // What Native.h can express today.
    NativeRegistry Reg;
    std::vector<std::string> Skipped = addToNativeRegistry(Model, Reg);
    const NativeModule *NM = Reg.find("Math");
    ASSERT_TRUE(NM);
    const NativeFunction *NF = NM->findFunction("fabs");
    ASSERT_TRUE(NF);
    EXPECT_EQ(NF->Symbol, Fabs->Thunk);
    EXPECT_EQ(NF->Params[0].TheCode, NativeType::Float);
    EXPECT_EQ(NF->Result.TheCode, NativeType::Float);
    EXPECT_EQ(NF->ParamNames, std::vector<std::string>{"x"});
    const NativeModule *NW = Reg.find("World");
    ASSERT_TRUE(NW && NW->findEnum("MotionType"));
    EXPECT_EQ(NW->findEnum("MotionType")->Values[1].Number, 1);
    EXPECT_TRUE(Skipped.empty());
    const NativeClass *NV = NM->findClass("Vector2f");
    ASSERT_TRUE(NV && NV->findMember("abs"));
    EXPECT_EQ(NV->findMember("abs")->Kind, NativeFunction::Method);
    EXPECT_TRUE(NV->findMember("abs")->ConstSelf);
    EXPECT_EQ(NV->Size, V->Size);
    ASSERT_TRUE(NW->Input && NW->Output);
    EXPECT_EQ(NW->Input->findMember("oppGoal")->Result.TheClass, NV);
    EXPECT_EQ(NW->Output->findMember("motion")->Result.TheEnum,
              NW->findEnum("MotionType"));
    EXPECT_EQ(Reg.getWorld(), NW);
  }
}

TEST(BindTest, ArchiveAndDump) {
  BindingModel Model = read({obj("libbindings.gcc32.a")}, I586);
  ASSERT_EQ(Model.Modules.size(), 3u);
  EXPECT_EQ(Model.findModule("Forms")->File,
            obj("libbindings.gcc32.a") + "(forms.gcc32.o)");
  std::string S;
  raw_string_ostream OS(S);
  dumpBindings(Model, OS);
  EXPECT_NE(S.find("module Math ("), std::string::npos);
  EXPECT_NE(S.find("  class Vector2f = Eigen::Vector2f size 8 align 4"), std::string::npos);
  // The soccer math is registered `.pure()` (docs/bindings.md).
  EXPECT_NE(S.find("    method abs() : float const pure = norm\n"), std::string::npos);
  EXPECT_NE(S.find("    method _plus_(Math::Vector2f const&) : Math::Vector2f const out"),
            std::string::npos);
  EXPECT_NE(S.find("    field weight : float[8] offset 12 size 8 read-write"),
            std::string::npos);
  EXPECT_NE(S.find("  enum MotionType size 4 scoped signed: stand=0 walk=1 kick=2"),
            std::string::npos);
  EXPECT_NE(S.find("  function fabs(float x) : float pure = Math::fabs"), std::string::npos);
  EXPECT_NE(S.find("BehaviorInput size 24 align 4"), std::string::npos);
  EXPECT_NE(S.find(" input\n"), std::string::npos);
  EXPECT_NE(S.find(" output\n"), std::string::npos);
}

//===----------------------------------------------------------------------===//
// Shared libraries
//===----------------------------------------------------------------------===//

/// The dump of `Model` without file names, one string per module, sorted:
/// the order of modules in a library is its section's, in an object its
/// symbol table's.
std::vector<std::string> moduleDumps(BindingModel Model) {
  for (BoundModule &M : Model.Modules)
    M.File = "F";
  std::string S;
  raw_string_ostream OS(S);
  dumpBindings(Model, OS);
  std::vector<std::string> Blocks;
  for (StringRef Line : split(S, '\n')) {
    if (Line.starts_with("module ") || Blocks.empty())
      Blocks.emplace_back();
    Blocks.back() += Line.str() + "\n";
  }
  llvm::sort(Blocks);
  return Blocks;
}

/// A library holds the descriptors of the objects linked into it, read
/// through dynamic relocations (against symbols, RELATIVE, packed RELR,
/// REL with addends in place for i386): the same model, hashes included.
TEST(BindTest, SharedLibraryMatchesObject) {
  struct Case {
    const char *Lib, *Obj;
  };
  const Case Cases[] = {
      {"forms.gcc32.so", "forms.gcc32.o"},
      {"forms.gcc64.so", "forms.gcc64.o"},
      {"forms.clang32.so", "forms.clang32.o"},
      {"forms.clang64.so", "forms.clang64.o"},
      {"forms.gcc64.relr.so", "forms.gcc64.o"},
      {"forms.clang64.relr.so", "forms.clang64.o"},
      {"forms.gcc32.symbolic.so", "forms.gcc32.o"},
      {"forms.clang64.symbolic.so", "forms.clang64.o"},
      {"soccer.gcc32.so", "soccer.gcc32.o"},
      {"soccer.gcc64.so", "soccer.gcc64.o"},
      {"soccer.clang32.so", "soccer.clang32.o"},
      {"soccer.clang64.so", "soccer.clang64.o"},
  };
  for (const Case &C : Cases) {
    SCOPED_TRACE(C.Lib);
    const Triple &T = StringRef(C.Lib).contains("32") ? I586 : X64;
    BindingModel Lib = read({obj(C.Lib)}, T);
    BindingModel Obj = read({obj(C.Obj)}, T);
    ASSERT_EQ(Lib.Modules.size(), Obj.Modules.size());
    for (const BoundModule &M : Lib.Modules) {
      EXPECT_EQ(M.File, obj(C.Lib));
      const BoundModule *O = Obj.findModule(M.Name);
      ASSERT_TRUE(O);
      EXPECT_EQ(M.Hash, O->Hash);
    }
    EXPECT_EQ(moduleDumps(Lib), moduleDumps(Obj));
  }
}

//===----------------------------------------------------------------------===//
// Reader errors
//===----------------------------------------------------------------------===//

TEST(BindTest, Errors) {
  auto Has = [](const std::string &Err, StringRef Sub) {
    EXPECT_NE(Err.find(Sub.str()), std::string::npos) << Err;
  };
  Has(readError({obj("forms.clang64.lto.o")}, X64), "compiled with -flto?");
  Has(readError({obj("forms.gcc64.lto.o")}, X64), "compiled with -flto?");
  Has(readError({obj("forms.gcc32.o")}, X64), "object built for another target");
  Has(readError({obj("forms.clang64.o")}, I586), "object built for another target");
  Has(readError({std::string(BIND_OBJ_DIR) + "/../CMakeFiles"}, I586), "cannot open");
  Has(readError({obj("../CTestTestfile.cmake")}, I586),
      "not an ELF relocatable object");
  Has(readError({obj("bad_magic.o")}, I586), "object built for another target");
  Has(readError({obj("bad_version.o")}, I586), "descriptor version 9");
  Has(readError({obj("bad_reloc.o")}, I586),
      "Bad::K: unexpected relocation type R_386_PC32");
  EXPECT_EQ(readError({obj("good_asm.o")}, I586), "");
  for (const char *Cfg : {"gcc32", "clang64"}) {
    SCOPED_TRACE(Cfg);
    const Triple &T = tripleOf(Cfg);
    auto O = [&](StringRef N) { return obj(N.str() + "." + Cfg + ".o"); };
    std::string E = readError({O("bad_static")}, T);
    Has(E, "BadStatic::hidden: thunk");
    Has(E, "has internal linkage (a static function");
    E = readError({O("bad_anon")}, T);
    Has(E, "BadAnon::Secret: type '(anonymous namespace)::Secret' has internal linkage");
    E = readError({O("bad_nslambda")}, T);
    Has(E, "BadLambda::twice: thunk");
    Has(E, "lambda at namespace scope");
    E = readError({O("bad_unregistered")}, T);
    Has(E, "BadDot::Vector2f.dot param 0: type 'Eigen::MatrixBase<Eigen::Matrix<float, 2, 1, 0, 2, 1>");
    Has(E, "is not registered in any loaded module");
    E = readError({O("dup_a"), O("dup_b")}, T);
    Has(E, "DupB::Other: class 'Shared' is registered twice: also as 'DupA::Shared'");
    // Modules registered twice (the same object given twice).
    Has(readError({O("dup_a"), O("dup_a")}, T), "module 'DupA' is also registered by");
    // A type from another module is found when that module is loaded.
    Has(readError({O("bad_static"), O("bad_unregistered")}, T), "BadStatic::hidden");
  }
  // Several errors are all reported.
  std::string Both = readError({obj("bad_version.o"), obj("bad_magic.o")}, I586);
  Has(Both, "bad_version.o");
  Has(Both, "bad_magic.o");
}

/// Constructors, constants and bs::Context parameters (descriptor version
/// 2), as GCC and Clang objects for both targets encode them.
TEST(BindTest, ConstructorsConstantsAndContext) {
  for (const char *Cfg : {"gcc32", "gcc64", "clang32", "clang64"}) {
    SCOPED_TRACE(Cfg);
    const Triple &T = tripleOf(Cfg);
    BindingModel M = read({obj(std::string("geometry.") + Cfg + ".o"),
                           obj(std::string("team.") + Cfg + ".o")},
                          T);
    const BoundModule *Geo = M.findModule("Geo");
    ASSERT_TRUE(Geo);
    EXPECT_EQ(Geo->Version, 2u);
    const BoundClass *Pose = Geo->findClass("Pose2f");
    ASSERT_TRUE(Pose);
    std::vector<const BoundMember *> Ctors;
    for (const BoundMember &Mb : Pose->Members)
      if (Mb.Kind == MemberKind::Constructor)
        Ctors.push_back(&Mb);
    ASSERT_EQ(Ctors.size(), 4u);
    EXPECT_EQ(Ctors[2]->Params.size(), 3u);
    EXPECT_EQ(Ctors[2]->Params[2].Default, DefaultKind::Float);
    EXPECT_EQ(Ctors[3]->Params[0].Type.Code, TypeCode::Int);
    EXPECT_TRUE(Ctors[0]->resultViaOut());
    EXPECT_EQ(M.getClass(Ctors[0]->Result), Pose);
    EXPECT_FALSE(Ctors[0]->hasSelf());
    EXPECT_FALSE(Ctors[0]->Thunk.empty());

    ASSERT_EQ(Geo->Constants.size(), 4u);
    EXPECT_EQ(Geo->Constants[0].Name, "off");
    EXPECT_EQ(int32_t(Geo->Constants[0].Value), 10000);
    EXPECT_EQ(Geo->Constants[1].Result.Code, TypeCode::Float);
    float Half;
    std::memcpy(&Half, &Geo->Constants[1].Value, 4);
    EXPECT_EQ(Half, 0.5f);
    EXPECT_EQ(Geo->Constants[2].Result.Code, TypeCode::Bool);
    EXPECT_EQ(Geo->Constants[2].Value, 1u);
    EXPECT_EQ(M.getEnum(Geo->Constants[3].Result), Geo->findEnum("Side"));
    EXPECT_EQ(Geo->Constants[3].Value, 2u);
    EXPECT_TRUE(Geo->Constants[0].Thunk.empty());

    const BoundModule *Team = M.findModule("Team");
    ASSERT_TRUE(Team);
    const BoundMember *Request = Team->findFunction("requestHeadMode");
    ASSERT_TRUE(Request);
    ASSERT_EQ(Request->Params.size(), 2u);
    EXPECT_EQ(Request->Params[0].Type.Code, TypeCode::Context);
    EXPECT_EQ(Request->Params[1].Type.Code, TypeCode::Enum);

    // What Sema and CodeGen see: constructors on the class, constants on
    // the module, the context not among the script's parameters.
    NativeRegistry Registry;
    addToNativeRegistry(M, Registry);
    const NativeModule *NGeo = nullptr, *NTeam = nullptr;
    for (const auto &NM : Registry.Modules) {
      if (NM->Name == "Geo")
        NGeo = NM.get();
      if (NM->Name == "Team")
        NTeam = NM.get();
    }
    ASSERT_TRUE(NGeo && NTeam);
    const NativeClass *NPose = NGeo->findClass("Pose2f");
    ASSERT_TRUE(NPose);
    EXPECT_EQ(NPose->Constructors.size(), 4u);
    EXPECT_FALSE(NPose->findMember("_ctor_"));
    const NativeConstant *Off = NGeo->findConstant("off");
    ASSERT_TRUE(Off);
    EXPECT_EQ(Off->Int, 10000);
    EXPECT_EQ(Off->Type.TheCode, NativeType::Int);
    const NativeFunction *NRequest = NTeam->findFunction("requestHeadMode");
    ASSERT_TRUE(NRequest);
    EXPECT_TRUE(NRequest->TakesContext);
    EXPECT_EQ(NRequest->Params.size(), 1u);
  }
}

/// The problems come as diagnostic kinds with the place as the first
/// argument, in the order of the files, so that the driver reports each
/// with its own kind (DiagnosticKinds.def).
TEST(BindTest, ErrorsAreDiagnosticKinds) {
  Expected<BindingModel> M = readBindings(
      {obj("bad_version.o"), std::string(BIND_OBJ_DIR) + "/no-such.o",
       obj("bad_reloc.o")},
      I586);
  ASSERT_FALSE(bool(M));
  std::vector<BindProblem> Problems;
  handleAllErrors(M.takeError(), [&](const BindingError &E) {
    Problems = E.Problems;
  });
  ASSERT_EQ(Problems.size(), 3u);
  EXPECT_EQ(Problems[0].Kind, diag::err_bind_bad_version);
  EXPECT_EQ(Problems[0].Args,
            (std::vector<std::string>{obj("bad_version.o") + ": bs_module_Bad",
                                      "9", "2"}));
  EXPECT_EQ(Problems[1].Kind, diag::err_bind_cannot_open);
  EXPECT_EQ(Problems[1].Args.size(), 2u);
  EXPECT_EQ(Problems[2].Kind, diag::err_bind_unexpected_relocation);
  EXPECT_EQ(Problems[2].Args,
            (std::vector<std::string>{obj("bad_reloc.o") + ": Bad::K",
                                      "R_386_PC32", "R_386_32", "object"}));
  EXPECT_EQ(Problems[2].format(),
            obj("bad_reloc.o") +
                ": Bad::K: unexpected relocation type R_386_PC32 (expected "
                "R_386_32); was the object built with Bind.h?");
}

//===----------------------------------------------------------------------===//
// In process: the descriptor linked into this test
//===----------------------------------------------------------------------===//

extern "C" const bs::detail::rec::Header bs_module_Forms;

/// Walks the descriptor the way a JIT host would (P fields are addresses).
struct InProcess {
  const unsigned char *Base = reinterpret_cast<const unsigned char *>(&bs_module_Forms);
  const bs::detail::rec::Header &H = bs_module_Forms;
  const char *str(uint32_t Off) const {
    return reinterpret_cast<const char *>(Base + H.stringOffset + Off);
  }
  const bs::detail::rec::Member *member(const char *Name) const {
    for (uint32_t I = 0; I < H.numMembers; ++I) {
      auto *M = reinterpret_cast<const bs::detail::rec::Member *>(
          Base + H.memberOffset + I * H.memberSize);
      if (!std::strcmp(str(M->name), Name))
        return M;
    }
    ADD_FAILURE() << "no member " << Name;
    return nullptr;
  }
  template <class Fn> Fn thunk(const char *Name, bool Setter = false) const {
    const bs::detail::rec::Member *M = member(Name);
    const void *Holder = Setter ? M->thunk2 : M->thunk;
    Fn F;
    std::memcpy(&F, Holder, sizeof F); // the holder holds a function pointer
    return F;
  }
};

TEST(BindTest, InProcessDescriptorAndThunks) {
  InProcess D;
  ASSERT_EQ(std::memcmp(D.H.magic, "BSMOD\0\0\1", 8), 0);
  EXPECT_STREQ(D.str(D.H.name), "Forms");

  // The reader's view of the very object linked here.
  BindingModel Model = read({BIND_HOST_FORMS_OBJ}, X64);
  ASSERT_EQ(Model.Modules.size(), 1u);
  // The three implementations of the hash agree: bsc's reader (relocations
  // in the file), Bind.h's and the runtime's C one (addresses in memory).
  EXPECT_EQ(Model.Modules[0].Hash, bs::moduleHash(&bs_module_Forms));
  EXPECT_EQ(Model.Modules[0].Hash, bs_binding_hash(&bs_module_Forms));
  const BoundClass &P = Model.Modules[0].Classes[0];
  std::ptrdiff_t XOff;
  std::memcpy(&XOff, D.member("x")->memptr, sizeof XOff);
  EXPECT_EQ(uint64_t(XOff), *member(P, "x").FieldOffset);
  // Parameter names: written by Bind.h into the param records' name words,
  // read back by bsc from the file ("" where none were registered).
  const bs::detail::rec::Member *Move = D.member("move");
  ASSERT_EQ(Move->numParams, 3u);
  const auto *Params = reinterpret_cast<const bs::detail::rec::Param *>(
      D.Base + D.H.paramOffset + Move->firstParam * D.H.paramSize);
  const BoundMember &ReadMove = member(P, "move");
  for (unsigned I = 0; I < 3; ++I) {
    EXPECT_STREQ(D.str(Params[I].name), ReadMove.Params[I].Name.c_str());
    EXPECT_NE(Params[I].name, 0u);
  }
  EXPECT_EQ(ReadMove.Params[0].Name, "dx");

  // Construct a Point in raw storage and use it through the thunks only.
  auto *Cls = reinterpret_cast<const bs::detail::rec::Class *>(D.Base + D.H.classOffset);
  ASSERT_LE(Cls->size, 64u);
  alignas(16) unsigned char Storage[64], Other[64], Result[64];
  using LifeFn = void (*)(void *);
  LifeFn Life[4];
  std::memcpy(Life, Cls->life, sizeof Life);
  Life[0](Storage);
  Life[0](Other);
  auto SetF = D.thunk<void (*)(void *, float)>("x", true);
  SetF(Storage, 3);
  D.thunk<void (*)(void *, float)>("y", true)(Storage, 4);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("length")(Storage), 5.0f);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("x")(Storage), 3.0f);
  EXPECT_EQ(D.thunk<int32_t (*)(const void *)>("id")(Storage), 7);
  EXPECT_EQ(D.thunk<int32_t (*)(const void *)>("getId")(Storage), 7);
  // double storage, float on the wire.
  D.thunk<void (*)(void *, float)>("weight", true)(Storage, 2.5f);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("weight")(Storage), 2.5f);
  // bool as i32.
  D.thunk<void (*)(void *, int32_t)>("flag", true)(Storage, 1);
  EXPECT_EQ(D.thunk<int32_t (*)(const void *)>("flag")(Storage), 1);
  // Properties.
  D.thunk<void (*)(void *, float)>("rx", true)(Storage, 6);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("crx")(Storage), 6.0f);
  D.thunk<void (*)(void *, float)>("py", true)(Storage, 8);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("py")(Storage), 8.0f);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("length")(Storage), 10.0f);
  // Class result through an out pointer: (6,8) + (1,2).
  SetF(Other, 1);
  D.thunk<void (*)(void *, float)>("y", true)(Other, 2);
  D.thunk<void (*)(void *, const void *, const void *)>("_plus_")(Result, Storage, Other);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("x")(Result), 7.0f);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("y")(Result), 10.0f);
  // A lambda registered as an operator.
  D.thunk<void (*)(void *, const void *, const void *)>("_min_")(Result, Storage, Other);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("x")(Result), 5.0f);
  // All arguments given (defaults are bsc's business).
  D.thunk<void (*)(void *, float, float, int32_t)>("move")(Storage, 1, 1.5f, 1);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("x")(Storage), 8.0f);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("y")(Storage), 9.5f);
  D.thunk<void (*)(void *)>("reset")(Storage);
  EXPECT_EQ(D.thunk<float (*)(const void *)>("x")(Storage), 0.0f);
  Life[3](Storage);
  Life[3](Other);

  EXPECT_EQ(D.thunk<int32_t (*)(int32_t)>("twice")(21), 42);
  EXPECT_EQ(D.thunk<int32_t (*)(int32_t)>("flip")(1), -1);
  EXPECT_EQ(D.thunk<int32_t (*)(int32_t, int32_t)>("max")(3, 9), 9);
  EXPECT_EQ(D.thunk<float (*)(float)>("fabs")(-2.5f), 2.5f);
  EXPECT_STREQ(D.thunk<const char *(*)(const char *)>("greet")("hi"), "hi");
  int I = 0;
  float F = 0;
  bool B = false;
  D.thunk<void (*)(int *, float *, bool *)>("outParams")(&I, &F, &B);
  EXPECT_EQ(I, 1);
  EXPECT_EQ(F, 2.0f);
  EXPECT_TRUE(B);
}

} // namespace
