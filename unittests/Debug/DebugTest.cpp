//===- DebugTest.cpp - values as JSON, activation trees, trace logs -------===//
#include "bsc/AST/Native.h"
#include "bsc/Debug/Trace.h"
#include "bsc/Debug/Values.h"
#include "gtest/gtest.h"
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

using namespace bsc;
using namespace bsc::debug;

namespace {

TEST(DebugValuesTest, FloatsPrintShortestAndReadBackExactly) {
  for (float F : {0.1f, 1000.5f, -3.25e-5f, 1.0f / 3.0f, 16777217.0f, 1e30f,
                  -0.0f, 1.17549435e-38f}) {
    std::string S = toJSONString(floatToJSON(F));
    llvm::Expected<llvm::json::Value> V = llvm::json::parse(S);
    ASSERT_TRUE(bool(V)) << S;
    std::optional<double> D = floatFromJSON(*V);
    ASSERT_TRUE(D.has_value());
    float Back = float(*D);
    EXPECT_EQ(0, std::memcmp(&Back, &F, sizeof F)) << S;
  }
  EXPECT_EQ("0.1", toJSONString(floatToJSON(0.1f)));
  EXPECT_EQ("1000.5", toJSONString(floatToJSON(1000.5f)));
  EXPECT_EQ("3", toJSONString(floatToJSON(3.0f)));
}

TEST(DebugValuesTest, NonFiniteFloatsAreStrings) {
  EXPECT_EQ("\"NaN\"", toJSONString(floatToJSON(std::nan(""))));
  EXPECT_EQ("\"Infinity\"", toJSONString(floatToJSON(HUGE_VAL)));
  EXPECT_EQ("\"-Infinity\"", toJSONString(floatToJSON(-HUGE_VAL)));
  EXPECT_TRUE(std::isnan(*floatFromJSON("NaN")));
  EXPECT_FALSE(floatFromJSON("nan").has_value());
}

TEST(DebugValuesTest, DifferencesNameThePathAndCompareAsFloats) {
  llvm::json::Value Recorded =
      llvm::json::Object{{"a", 1}, {"b", llvm::json::Object{{"x", 0.1}}}};
  llvm::json::Value Same =
      llvm::json::Object{{"a", 1}, {"b", llvm::json::Object{{"x", double(0.1f)}}}};
  EXPECT_FALSE(findDifference(Recorded, Same, "output").has_value());
  llvm::json::Value Other =
      llvm::json::Object{{"a", 2}, {"b", llvm::json::Object{{"x", 0.1}}}};
  std::optional<Difference> D = findDifference(Recorded, Other, "output");
  ASSERT_TRUE(D.has_value());
  EXPECT_EQ("output.a", D->Path);
  EXPECT_EQ("1", D->Recorded);
  EXPECT_EQ("2", D->Got);
  // NaN equals NaN; members the recording lacks are not compared.
  EXPECT_FALSE(findDifference(llvm::json::Object{{"n", "NaN"}},
                              llvm::json::Object{{"n", "NaN"}, {"m", 1}}, "o"));
}

/// A replay names every field that differs, not only the first: keys in
/// sorted order, array elements by index, a missing member as "nothing".
TEST(DebugValuesTest, AllDifferencesInKeyAndIndexOrder) {
  llvm::json::Value Recorded = llvm::json::Object{
      {"z", 1},
      {"a", llvm::json::Array{1, 2, 3}},
      {"m", "walk"},
      {"p", llvm::json::Object{{"y", 0.5}, {"x", 0.1}}},
      {"gone", true}};
  llvm::json::Value Got = llvm::json::Object{
      {"z", 2},
      {"a", llvm::json::Array{1, 5, 6}},
      {"m", "walk"},
      {"p", llvm::json::Object{{"y", -0.5}, {"x", double(0.1f)}}}};
  std::vector<Difference> Ds = findDifferences(Recorded, Got, "output");
  ASSERT_EQ(5u, Ds.size());
  EXPECT_EQ("output.a[1]", Ds[0].Path);
  EXPECT_EQ("2", Ds[0].Recorded);
  EXPECT_EQ("5", Ds[0].Got);
  EXPECT_EQ("output.a[2]", Ds[1].Path);
  EXPECT_EQ("output.gone", Ds[2].Path);
  EXPECT_EQ("true", Ds[2].Recorded);
  EXPECT_EQ("nothing", Ds[2].Got);
  // output.m is equal and output.p.x is the same float.
  EXPECT_EQ("output.p.y", Ds[3].Path);
  EXPECT_EQ("0.5", Ds[3].Recorded);
  EXPECT_EQ("-0.5", Ds[3].Got);
  EXPECT_EQ("output.z", Ds[4].Path);
  // findDifference is the first of them.
  std::optional<Difference> First = findDifference(Recorded, Got, "output");
  ASSERT_TRUE(First.has_value());
  EXPECT_EQ("output.a[1]", First->Path);
  EXPECT_TRUE(findDifferences(Recorded, Recorded, "output").empty());
  // An array of another length differs as a whole.
  Ds = findDifferences(llvm::json::Array{1, 2}, llvm::json::Array{1}, "w");
  ASSERT_EQ(1u, Ds.size());
  EXPECT_EQ("w", Ds[0].Path);
  EXPECT_EQ("[1,2]", Ds[0].Recorded);
  EXPECT_EQ("[1]", Ds[0].Got);
}

/// Adds a field `Name` at `Offset` to `C`: an array of `Extents` if given.
void addField(NativeClass &C, const char *Name, NativeType::Code Code,
              uint64_t Offset, uint32_t Size,
              std::vector<uint32_t> Extents = {}) {
  NativeFunction F;
  F.Kind = NativeFunction::Field;
  F.Name = Name;
  F.FieldOffset = Offset;
  F.Result.TheCode = Code;
  F.Result.StorageSize = Size;
  F.Result.Extents = std::move(Extents);
  C.Members.push_back(F);
}

/// A class {int32 i; double d (a b-script float); bool b} read and written
/// at its offsets, as the JIT's values are.
TEST(DebugValuesTest, FieldsByOffset) {
  struct Obj {
    int32_t I;
    double D;
    bool B;
  } O = {7, 0.5, true};
  NativeClass C;
  C.Name = "Obj";
  C.QualifiedName = "M::Obj";
  addField(C, "i", NativeType::Int, offsetof(Obj, I), 4);
  addField(C, "d", NativeType::Float, offsetof(Obj, D), 8);
  addField(C, "b", NativeType::Bool, offsetof(Obj, B), 1);
  ValueIO IO([](llvm::StringRef) -> void * { return nullptr; });
  EXPECT_EQ("{\"b\":true,\"d\":0.5,\"i\":7}", toJSONString(IO.readClass(C, &O)));
  llvm::Error E = IO.writeClass(
      C, &O, llvm::json::Object{{"i", -3}, {"d", 0.1}}, "input");
  ASSERT_FALSE(bool(E));
  EXPECT_EQ(-3, O.I);
  EXPECT_EQ(double(0.1f), O.D); // Stored as the b-script float it is.
  EXPECT_TRUE(O.B);
  E = IO.writeClass(C, &O, llvm::json::Object{{"i", "x"}}, "input");
  EXPECT_EQ("input.i must be an integer, not \"x\"", llvm::toString(std::move(E)));
  E = IO.writeClass(C, &O, llvm::json::Object{{"j", 1}}, "input");
  EXPECT_EQ("input.j: M::Obj has no field 'j' (it has i, d, b)",
            llvm::toString(std::move(E)));
}

/// Numbers a member cannot hold are refused: written, they would become
/// another number (or infinity), and the replay would feed the behavior
/// what the recording does not say.
TEST(DebugValuesTest, NumbersBeyondTheMemberAreRefused) {
  struct Obj {
    int32_t I;
    uint8_t U;
    int16_t S;
    float F;
  } O = {};
  NativeClass C;
  C.Name = "Obj";
  C.QualifiedName = "M::Obj";
  addField(C, "i", NativeType::Int, offsetof(Obj, I), 4);
  addField(C, "u", NativeType::Int, offsetof(Obj, U), 1);
  C.Members.back().Result.Unsigned = true;
  addField(C, "s", NativeType::Int, offsetof(Obj, S), 2);
  addField(C, "f", NativeType::Float, offsetof(Obj, F), 4);
  ValueIO IO([](llvm::StringRef) -> void * { return nullptr; });
  auto Write = [&](llvm::StringRef Key, llvm::json::Value V) {
    return llvm::toString(
        IO.writeClass(C, &O, llvm::json::Object{{Key, std::move(V)}}, "in"));
  };
  EXPECT_EQ("", Write("i", int64_t(INT32_MIN)));
  EXPECT_EQ("", Write("u", 255));
  EXPECT_EQ("", Write("s", -32768));
  EXPECT_EQ("", Write("f", 3.4028234663852886e38)); // FLT_MAX
  EXPECT_EQ(3.4028234663852886e38f, O.F);
  EXPECT_EQ("", Write("f", "-Infinity"));
  EXPECT_EQ(INT32_MIN, O.I);
  EXPECT_EQ(255, O.U);
  EXPECT_EQ(-32768, O.S);
  EXPECT_EQ(-HUGE_VALF, O.F);
  EXPECT_EQ("in.i must be from -2147483648 to 2147483647, not 4294967296",
            Write("i", int64_t(1) << 32));
  EXPECT_EQ("in.u must be from 0 to 255, not 256", Write("u", 256));
  EXPECT_EQ("in.u must be from 0 to 255, not -1", Write("u", -1));
  EXPECT_EQ("in.s must be from -32768 to 32767, not 32768", Write("s", 32768));
  EXPECT_EQ("in.f must be a number within a float's range (or \"Infinity\"), "
            "not 1e+39",
            Write("f", 1e39));
  // Nothing refused was stored.
  EXPECT_EQ(INT32_MIN, O.I);
  EXPECT_EQ(255, O.U);
  EXPECT_EQ(-32768, O.S);
  EXPECT_EQ(-HUGE_VALF, O.F);
}

/// A null string pointer reads as null, so it must write back as one: a
/// recording of it replays.
TEST(DebugValuesTest, NullStringsRoundTrip) {
  struct Obj {
    const char *S;
  } O = {nullptr};
  NativeClass C;
  C.Name = "Obj";
  C.QualifiedName = "M::Obj";
  addField(C, "s", NativeType::String, offsetof(Obj, S), sizeof(char *));
  ValueIO IO([](llvm::StringRef) -> void * { return nullptr; });
  llvm::json::Value Recorded = IO.readClass(C, &O);
  EXPECT_EQ("{\"s\":null}", toJSONString(Recorded));
  ASSERT_FALSE(bool(IO.writeClass(C, &O, llvm::json::Object{{"s", "x"}}, "in")));
  ASSERT_STREQ("x", O.S);
  ASSERT_FALSE(bool(IO.writeClass(C, &O, Recorded, "in")));
  EXPECT_EQ(nullptr, O.S);
}

/// Array fields: `int16_t s[3]` and `double m[2][2]` (a b-script float
/// each), as nested JSON arrays; a write must give every element.
TEST(DebugValuesTest, ArrayFieldsAreJSONArrays) {
  struct Obj {
    int16_t S[3];
    double M[2][2];
  } O = {{-1, 2, 300}, {{0.5, 1}, {2, -4}}};
  NativeClass C;
  C.Name = "Obj";
  C.QualifiedName = "M::Obj";
  addField(C, "s", NativeType::Int, offsetof(Obj, S), 2, {3});
  addField(C, "m", NativeType::Float, offsetof(Obj, M), 8, {2, 2});
  ValueIO IO([](llvm::StringRef) -> void * { return nullptr; });
  EXPECT_EQ("{\"m\":[[0.5,1],[2,-4]],\"s\":[-1,2,300]}",
            toJSONString(IO.readClass(C, &O)));
  llvm::json::Value New = llvm::json::Object{
      {"s", llvm::json::Array{7, 8, 9}},
      {"m", llvm::json::Array{llvm::json::Array{1, 2},
                              llvm::json::Array{3, 0.1}}}};
  ASSERT_FALSE(bool(IO.writeClass(C, &O, New, "input")));
  EXPECT_EQ(9, O.S[2]);
  EXPECT_EQ(3.0, O.M[1][0]);
  EXPECT_EQ(double(0.1f), O.M[1][1]);
  llvm::Error E = IO.writeClass(
      C, &O, llvm::json::Object{{"s", llvm::json::Array{1, 2}}}, "input");
  EXPECT_EQ("input.s must be an array of 3 elements, not [1,2]",
            llvm::toString(std::move(E)));
  E = IO.writeClass(
      C, &O,
      llvm::json::Object{{"m", llvm::json::Array{llvm::json::Array{1, 2},
                                                 llvm::json::Array{3, "x"}}}},
      "input");
  EXPECT_EQ("input.m[1][1] must be a number, not \"x\"",
            llvm::toString(std::move(E)));
  // A difference names the element.
  llvm::json::Value Got = IO.readClass(C, &O);
  llvm::json::Value Recorded = llvm::json::Object{
      {"s", llvm::json::Array{7, 8, 9}},
      {"m", llvm::json::Array{llvm::json::Array{1, 2},
                              llvm::json::Array{3, 0.2}}}};
  std::optional<Difference> D = findDifference(Recorded, Got, "output");
  ASSERT_TRUE(D.has_value());
  EXPECT_EQ("output.m[1][1]", D->Path);
}

/// walk (0) is called by look (1) and main (2); look and head (3) by main.
/// Each has two yields: `yield` and `yield TaskState::failure`, but walk's
/// second yields a value computed at run time (its trace record's word).
DebugTables makeTables() {
  DebugTables T;
  T.Tasks.resize(4);
  T.RecordSize = 8;
  T.SlotBytes = 1;
  const char *Names[] = {"walk", "look", "main", "head"};
  for (unsigned I = 0; I < 4; ++I) {
    T.Tasks[I].Name = std::string("M::") + Names[I];
    T.Tasks[I].ShortName = Names[I];
    T.Tasks[I].File = "M.bs";
    T.Tasks[I].Line = 10 * (I + 1);
    T.Tasks[I].YieldLines = {10 * I + 11, 10 * I + 12};
    T.Tasks[I].YieldValues = {1, -1};
  }
  T.Tasks[0].YieldValues[1] = std::nullopt;
  T.Tasks[0].StateWord = 4;
  T.Tasks[0].Callers = {1, 2};
  T.Tasks[1].Callers = {2};
  T.Tasks[3].Callers = {2};
  return T;
}

TEST(DebugTraceTest, ParentIsTheFirstActiveCaller) {
  DebugTables T = makeTables();
  // Every task on the path shows its state and the yield it waits at
  // (main's first yield is line 31, look's 21, walk's 11).
  EXPECT_EQ("main [running, M.bs:31] > look [running, M.bs:21] > "
            "walk [running, M.bs:11]",
            formatTraceLine(T, {{0, 1, 1}, {1, 1, 1}, {2, 1, 1}}));
  // main is done but was called: it is walk's parent (look did not run).
  EXPECT_EQ("main [done] > walk [state 3, M.bs:12]",
            formatTraceLine(T, {{0, 2, 3}, {2, 0, 0}}));
  // A parent's own state and line, under a leaf that stays the same.
  EXPECT_EQ("main [failure, M.bs:32] > look [running, M.bs:21] > walk [done]",
            formatTraceLine(T, {{0, 0, 0}, {1, 1, 1}, {2, 2, -1}}));
  // Two leaves: a path each, children in table order, the shared parent
  // described on both.
  EXPECT_EQ("main [running, M.bs:31] > look [running, M.bs:21]; "
            "main [running, M.bs:31] > head [done]",
            formatTraceLine(T, {{1, 1, 1}, {2, 1, 1}, {3, 0, 0}}));
  EXPECT_EQ("look [failure, M.bs:22]",
            formatTraceLine(T, {{1, 2, -1}}));
  // A yield of a named task state (`enum Done : TaskState`) names it.
  T.Tasks[1].YieldStates = {"", "Done::lost"};
  EXPECT_EQ("look [Done::lost, M.bs:22]", formatTraceLine(T, {{1, 2, -1}}));
  EXPECT_EQ("look [running, M.bs:21]", formatTraceLine(T, {{1, 1, 1}}));
  EXPECT_EQ("idle", formatTraceLine(T, {}));
  // Records of unknown tasks are dropped rather than trusted.
  EXPECT_EQ("idle", formatTraceLine(T, {{7, 1, 1}}));
}

/// `--trace=changes` prints the first cycle and then only the cycles
/// whose line differs from the one before; plain `--trace` every cycle.
TEST(DebugTraceTest, FilterPrintsOnlyChanges) {
  TraceFilter Changes(TraceMode::Changes);
  EXPECT_TRUE(Changes.shouldPrint("main [running, M.bs:31]"));
  EXPECT_FALSE(Changes.shouldPrint("main [running, M.bs:31]"));
  EXPECT_TRUE(Changes.shouldPrint("main [running, M.bs:32]"));
  EXPECT_TRUE(Changes.shouldPrint("main [running, M.bs:31]"));
  EXPECT_TRUE(Changes.shouldPrint("idle"));
  EXPECT_FALSE(Changes.shouldPrint("idle"));
  // The first line is printed even when it is empty-looking.
  TraceFilter FirstIdle(TraceMode::Changes);
  EXPECT_TRUE(FirstIdle.shouldPrint("idle"));
  TraceFilter Every(TraceMode::EveryCycle);
  EXPECT_TRUE(Every.shouldPrint("idle"));
  EXPECT_TRUE(Every.shouldPrint("idle"));
  TraceFilter Off(TraceMode::Off);
  EXPECT_FALSE(Off.shouldPrint("idle"));
}

TEST(DebugTraceTest, TablesSurviveJSON) {
  DebugTables T = makeTables();
  T.Tasks[0].Fields = {{"n", "int", true}, {"i", "float", false}};
  T.Tasks[1].YieldStates = {"", "Done::lost"};
  llvm::Expected<DebugTables> Back =
      parseDebugTables(toJSONString(toJSON(T)));
  ASSERT_TRUE(bool(Back));
  EXPECT_EQ(std::vector<std::string>({"", "Done::lost"}),
            Back->Tasks[1].YieldStates);
  EXPECT_TRUE(Back->Tasks[0].YieldStates.empty());
  ASSERT_EQ(4u, Back->Tasks.size());
  EXPECT_EQ("M::look", Back->Tasks[1].Name);
  EXPECT_EQ(std::vector<unsigned>({1, 2}), Back->Tasks[0].Callers);
  EXPECT_EQ(std::vector<unsigned>({21, 22}), Back->Tasks[1].YieldLines);
  EXPECT_EQ("float", Back->Tasks[0].Fields[1].Type);
  EXPECT_FALSE(Back->Tasks[0].Fields[1].IsParam);
  EXPECT_EQ(8u, Back->RecordSize);
  EXPECT_EQ(1u, Back->SlotBytes);
  EXPECT_EQ(std::optional<uint64_t>(4), Back->Tasks[0].StateWord);
  EXPECT_FALSE(Back->Tasks[1].StateWord);
  EXPECT_EQ((std::vector<std::optional<int32_t>>{1, std::nullopt}),
            Back->Tasks[0].YieldValues);
  EXPECT_EQ((std::vector<std::optional<int32_t>>{1, -1}),
            Back->Tasks[1].YieldValues);
  // A task of the right shape, for the damaged variants below.
  std::string Good = "{\"name\":\"a\",\"short\":\"a\",\"file\":\"f\","
                     "\"line\":1,\"yields\":[3],\"callers\":[],"
                     "\"fields\":[],";
  auto Tables = [](const std::string &Record, const std::string &Task) {
    return "{\"version\":3,\"record\":" + Record + ",\"tasks\":[" + Task +
           "]}";
  };
  std::string Layout = "{\"size\":8,\"slotBytes\":1}";
  ASSERT_TRUE(bool(parseDebugTables(
      Tables(Layout, Good + "\"yieldValues\":[null],\"stateWord\":4}"))));
  for (std::string Bad :
       {std::string(), std::string("[]"),
        std::string("{\"version\":1,\"tasks\":[]}"),
        Tables(Layout, "{\"name\":\"a\"}"),
        Tables(Layout, Good + "\"yieldValues\":[1],\"callers\":[5]}"),
        // The record: missing, too small for the slots, odd slots.
        Tables("{}", Good + "\"yieldValues\":[1]}"),
        Tables("{\"size\":0,\"slotBytes\":1}", Good + "\"yieldValues\":[1]}"),
        Tables("{\"size\":4,\"slotBytes\":3}", Good + "\"yieldValues\":[1]}"),
        // Yield values: missing, too few, a string; a computed one
        // without a word; a word inside the slots or past the end.
        Tables(Layout, Good + "\"x\":0}"),
        Tables(Layout, Good + "\"yieldValues\":[]}"),
        Tables(Layout, Good + "\"yieldValues\":[\"1\"]}"),
        Tables(Layout, Good + "\"yieldValues\":[null]}"),
        Tables(Layout, Good + "\"yieldValues\":[null],\"stateWord\":0}"),
        Tables(Layout, Good + "\"yieldValues\":[null],\"stateWord\":8}")}) {
    llvm::Expected<DebugTables> R = parseDebugTables(Bad);
    EXPECT_FALSE(bool(R)) << Bad;
    llvm::consumeError(R.takeError());
  }
}

TEST(DebugTraceTest, DeeplyNestedTablesAreDamaged) {
  // A damaged object's tables: refused, not parsed (the parser recurses).
  // `{"tasks":` is level 1 and 9 bytes; the 256th '[' is level 257.
  llvm::Expected<DebugTables> T =
      parseDebugTables("{\"tasks\":" + std::string(100000, '['));
  ASSERT_FALSE(bool(T));
  EXPECT_EQ("damaged debug tables: 1:265: nesting deeper than 256 levels",
            llvm::toString(T.takeError()));
}

TEST(DebugTraceTest, TraceRecordsDecodeToActivations) {
  DebugTables T = makeTables();
  // Cycle 5: walk stopped at its second yield with the state 7 (its
  // word), look at its first (running), main was not called, head
  // finished. Cycle 6: look failed at its second yield.
  const char Log[] = "\5\0\0\0"
                     "\2\1\0\xff\7\0\0\0"
                     "\6\0\0\0"
                     "\0\2\0\0\0\0\0\0";
  auto Cycles = parseTraceLog(llvm::StringRef(Log, 24), T);
  ASSERT_TRUE(bool(Cycles));
  ASSERT_EQ(2u, Cycles->size());
  EXPECT_EQ(5u, (*Cycles)[0].Cycle);
  const std::vector<Activation> &C5 = (*Cycles)[0].Records;
  ASSERT_EQ(3u, C5.size());
  EXPECT_EQ(0u, C5[0].Task);
  EXPECT_EQ(2u, C5[0].Resume);
  EXPECT_EQ(7, C5[0].State);
  EXPECT_EQ(1u, C5[1].Task);
  EXPECT_EQ(1u, C5[1].Resume);
  EXPECT_EQ(1, C5[1].State);
  EXPECT_EQ(3u, C5[2].Task);
  EXPECT_EQ(0u, C5[2].Resume);
  EXPECT_EQ(0, C5[2].State);
  EXPECT_EQ("look [running, M.bs:21] > walk [state 7, M.bs:12]; head [done]",
            formatTraceLine(T, C5));
  EXPECT_EQ("look [failure, M.bs:22]",
            formatTraceLine(T, (*Cycles)[1].Records));
  // A log cut inside a cycle.
  for (size_t Cut : {2, 4, 11, 14}) {
    auto R = parseTraceLog(llvm::StringRef(Log, Cut), T);
    EXPECT_FALSE(bool(R)) << Cut;
    llvm::consumeError(R.takeError());
  }
  // A slot naming a yield the task does not have.
  const char Bad[] = "\1\0\0\0\3\0\0\0\0\0\0\0";
  auto R = parseTraceLog(llvm::StringRef(Bad, 12), T);
  ASSERT_FALSE(bool(R));
  EXPECT_EQ("byte 0: cycle 1: task M::walk stopped at yield 3, but it has 2",
            llvm::toString(R.takeError()));
}

/// `--cycle-budget` with `--instrument`: the record's budget word names the
/// loop that ran out (1 + its index), and a task the budget failed has the
/// slot one below "finished"; the tables carry both through JSON.
TEST(DebugTraceTest, BudgetWordNamesTheLoopThatRanOut) {
  DebugTables T = makeTables();
  T.RecordSize = 12;
  T.Budget = 1000;
  T.BudgetWord = 8;
  T.Loops = {{"M::walk", "M.bs", 13}, {"M::main", "M.bs", 33}};
  auto Back = parseDebugTables(toJSONString(toJSON(T)));
  ASSERT_TRUE(bool(Back)) << llvm::toString(Back.takeError());
  EXPECT_EQ(1000u, Back->Budget);
  EXPECT_EQ(std::optional<uint64_t>(8), Back->BudgetWord);
  ASSERT_EQ(2u, Back->Loops.size());
  EXPECT_EQ("M::main", Back->Loops[1].Owner);
  EXPECT_EQ(33u, Back->Loops[1].Line);
  // Cycle 9: walk failed by the budget (0xfe), main waits at its first
  // yield; loop 1 (walk's) ran out. Cycle 10: nothing ran out.
  const char Log[] = "\x09\0\0\0"
                     "\xfe\0\1\0\0\0\0\0\1\0\0\0"
                     "\x0a\0\0\0"
                     "\0\0\1\0\0\0\0\0\0\0\0\0";
  auto Cycles = parseTraceLog(llvm::StringRef(Log, 32), *Back);
  ASSERT_TRUE(bool(Cycles)) << llvm::toString(Cycles.takeError());
  ASSERT_EQ(2u, Cycles->size());
  EXPECT_EQ("main [running, M.bs:31] > walk [failure]",
            formatTraceLine(*Back, (*Cycles)[0].Records));
  EXPECT_EQ(1u, (*Cycles)[0].BudgetLoop);
  EXPECT_EQ("cycle 9 ran out of its budget of 1000 loop passes in the loop "
            "of 'M::walk' at M.bs:13",
            formatBudgetLine(*Back, (*Cycles)[0]));
  EXPECT_EQ("", formatBudgetLine(*Back, (*Cycles)[1]));
  // A word naming a loop the tables do not have.
  const char Bad[] = "\x09\0\0\0\0\0\0\0\0\0\0\0\3\0\0\0";
  auto R = parseTraceLog(llvm::StringRef(Bad, 16), *Back);
  ASSERT_FALSE(bool(R));
  EXPECT_EQ("byte 0: cycle 9: the budget ran out in loop 3, but there are 2",
            llvm::toString(R.takeError()));
  // Damaged budgets: no passes, a loop without its line, a word outside.
  std::string JSON = toJSONString(toJSON(T));
  for (auto [From, To] : {std::pair<std::string, std::string>{
                              "\"passes\":1000", "\"passes\":0"},
                          {"\"line\":13", "\"lines\":13"},
                          {"\"word\":8", "\"word\":12"}}) {
    std::string Damaged = JSON;
    size_t At = Damaged.find(From);
    ASSERT_NE(std::string::npos, At) << From;
    Damaged.replace(At, From.size(), To);
    auto D = parseDebugTables(Damaged);
    EXPECT_FALSE(bool(D)) << Damaged;
    llvm::consumeError(D.takeError());
  }
}

} // namespace

namespace {
TEST(DebugValuesTest, NegativeZeroIsNotZero) {
  EXPECT_EQ("-0.0", toJSONString(floatToJSON(-0.0f)));
  EXPECT_TRUE(findDifference(floatToJSON(0.0f), floatToJSON(-0.0f), "x"));
  EXPECT_FALSE(findDifference(floatToJSON(-0.0f), floatToJSON(-0.0f), "x"));
}
} // namespace

namespace {
/// A class with a member of each kind the replay's fast paths take: ints
/// of two sizes, a float, a bool, a string, an enum, an int array and a
/// nested class.
struct Inner {
  float X;
};
struct Fast {
  int32_t I;
  uint8_t U;
  float F;
  bool B;
  const char *S;
  int32_t E;
  int16_t A[2];
  Inner In;
};

struct FastClass {
  NativeEnum Enum;
  NativeClass InnerC, C;
  FastClass() {
    Enum.Name = "Mode";
    Enum.Values = {{"off", 0}, {"on", 5}};
    InnerC.Name = InnerC.QualifiedName = "Inner";
    addField(InnerC, "x", NativeType::Float, offsetof(Inner, X), 4);
    C.Name = C.QualifiedName = "Fast";
    addField(C, "i", NativeType::Int, offsetof(Fast, I), 4);
    addField(C, "u", NativeType::Int, offsetof(Fast, U), 1);
    C.Members.back().Result.Unsigned = true;
    addField(C, "f", NativeType::Float, offsetof(Fast, F), 4);
    addField(C, "b", NativeType::Bool, offsetof(Fast, B), 1);
    addField(C, "s", NativeType::String, offsetof(Fast, S), sizeof(char *));
    addField(C, "e", NativeType::Enum, offsetof(Fast, E), 4);
    C.Members.back().Result.TheEnum = &Enum;
    addField(C, "a", NativeType::Int, offsetof(Fast, A), 2, {2});
    addField(C, "in", NativeType::Class, offsetof(Fast, In), sizeof(Inner));
    C.Members.back().Result.TheClass = &InnerC;
  }
};
} // namespace

/// matchesClassText agrees with findDifferences where it answers, without
/// a tree of the object.
TEST(DebugValuesTest, MatchesClassTextIsFindDifferences) {
  FastClass FC;
  Fast O = {-7, 200, 0.1f, true, "ab", 5, {-1, 3}, {-0.0f}};
  ValueIO IO([](llvm::StringRef) -> void * { return nullptr; });
  std::string Text = toJSONString(IO.readClass(FC.C, &O));
  EXPECT_TRUE(IO.matchesClassText(FC.C, &O, Text)) << Text;
  // The same values spelled otherwise, and members left out.
  EXPECT_TRUE(IO.matchesClassText(FC.C, &O, " { \"e\" : \"on\", \"f\":0.100000001 } "));
  // Differences, each where findDifferences finds one.
  for (llvm::StringRef Other :
       {"{\"i\":-6}", "{\"in\":{\"x\":0}}", "{\"a\":[-1,4]}",
        "{\"s\":\"ac\"}", "{\"e\":\"off\"}", "{\"b\":false}",
        "{\"f\":0.2}", "{\"u\":null}"}) {
    llvm::Expected<llvm::json::Value> R = llvm::json::parse(Other);
    ASSERT_TRUE(bool(R));
    ASSERT_FALSE(findDifferences(*R, IO.readClass(FC.C, &O), "o").empty())
        << Other.str();
    EXPECT_FALSE(IO.matchesClassText(FC.C, &O, Other)) << Other.str();
  }
  // Not the plain form: no answer (false), though the values are the same.
  EXPECT_FALSE(IO.matchesClassText(FC.C, &O, "{\"i\":-7,\"b\":true}"));
  EXPECT_FALSE(IO.matchesClassText(FC.C, &O, "{\"s\":\"\\u0061b\"}"));
}

/// writeClassText stores what writeClass of the parsed text stores, for
/// the form a recording has; anything else it leaves to writeClass.
TEST(DebugValuesTest, WriteClassTextTakesTheRecordedForm) {
  FastClass FC;
  ValueIO IO([](llvm::StringRef) -> void * { return nullptr; });
  llvm::StringRef Text =
      "{\"a\":[4,-5],\"b\":true,\"e\":\"on\",\"f\":0.1,\"i\":-7,"
      "\"in\":{\"x\":\"-Infinity\"},\"s\":\"hi\",\"u\":255}";
  Fast ByText = {}, ByTree = {};
  ASSERT_TRUE(IO.writeClassText(FC.C, &ByText, Text));
  llvm::Expected<llvm::json::Value> Tree = llvm::json::parse(Text);
  ASSERT_TRUE(bool(Tree));
  ASSERT_FALSE(bool(IO.writeClass(FC.C, &ByTree, *Tree, "input")));
  EXPECT_EQ(toJSONString(IO.readClass(FC.C, &ByTree)),
            toJSONString(IO.readClass(FC.C, &ByText)));
  EXPECT_EQ(0.1f, ByText.F);
  EXPECT_EQ(-HUGE_VALF, ByText.In.X);
  EXPECT_STREQ("hi", ByText.S);
  // Members left out keep their values; spaces are fine; an enum by number.
  ASSERT_TRUE(IO.writeClassText(FC.C, &ByText, " { \"e\" : 0 , \"i\":3 } "));
  EXPECT_EQ(0, ByText.E);
  EXPECT_EQ(3, ByText.I);
  EXPECT_EQ(255, ByText.U);
  // Not the recorded form, or not a fit: writeClass's turn.
  for (llvm::StringRef Other :
       {"{\"i\":1,\"f\":2}",          // keys not sorted
        "{\"i\":1,\"i\":2}",          // a key twice
        "{\"s\":\"a\\nb\"}",          // an escape
        "{\"i\":1.5}",                // not an int
        "{\"u\":256}",                // beyond the member
        "{\"f\":1e39}",               // beyond a float
        "{\"e\":\"dim\"}",            // no such enum value
        "{\"a\":[1]}",                // too few elements
        "{\"j\":1}",                  // no such member
        "{\"in\":null}",              // not an object
        "[1]"})
    EXPECT_FALSE(IO.writeClassText(FC.C, &ByText, Other)) << Other.str();
}

namespace {
/// readLeaves gives what readClass holds, leaf by leaf: a nested class's
/// fields and an array's elements, named as the timeline names them.
TEST(DebugValuesTest, ReadLeavesAreTheLeavesOfReadClass) {
  struct Inner {
    double X, Y;
  };
  struct Obj {
    int16_t S[3];
    Inner In;
    bool B;
  } O = {{-1, 2, 300}, {0.5, -2}, true};
  NativeClass InnerClass;
  InnerClass.Name = "Inner";
  InnerClass.QualifiedName = "M::Inner";
  addField(InnerClass, "x", NativeType::Float, offsetof(Inner, X), 8);
  addField(InnerClass, "y", NativeType::Float, offsetof(Inner, Y), 8);
  NativeClass C;
  C.Name = "Obj";
  C.QualifiedName = "M::Obj";
  addField(C, "s", NativeType::Int, offsetof(Obj, S), 2, {3});
  addField(C, "in", NativeType::Class, offsetof(Obj, In), sizeof(Inner));
  C.Members.back().Result.TheClass = &InnerClass;
  addField(C, "b", NativeType::Bool, offsetof(Obj, B), 1);
  ValueIO IO([](llvm::StringRef) -> void * { return nullptr; });
  std::map<std::string, std::string> ByRead, ByClass;
  std::string Path = "input";
  IO.readLeaves(C, &O, Path, [&](llvm::StringRef P, const llvm::json::Value &V) {
    ByRead[P.str()] = toJSONString(V);
  });
  EXPECT_EQ(Path, "input");
  forEachJSONLeaf(Path, IO.readClass(C, &O),
                  [&](llvm::StringRef P, const llvm::json::Value &V) {
                    ByClass[P.str()] = toJSONString(V);
                  });
  EXPECT_EQ(ByRead, ByClass);
  EXPECT_EQ(ByRead.size(), 6u);
  EXPECT_EQ(ByRead["input.s[2]"], "300");
  EXPECT_EQ(ByRead["input.in.y"], "-2");
  EXPECT_EQ(ByRead["input.b"], "true");
}

/// Numbers print as `%.*g` of the least precision that reads back (as a
/// float, for a float): the form recordings have always had, which the
/// search from std::to_chars's shortest digits must keep.
TEST(DebugValuesTest, NumbersPrintAsTheLeastPrecisionThatReadsBack) {
  auto Reference = [](double D) {
    bool IsFloat = double(float(D)) == D;
    char S[40];
    for (int Precision = 1; Precision <= 17; ++Precision) {
      std::snprintf(S, sizeof S, "%.*g", Precision, D);
      double Back = std::strtod(S, nullptr);
      if (IsFloat ? float(Back) == float(D) : Back == D)
        return std::string(S);
    }
    std::snprintf(S, sizeof S, "%.17g", D);
    return std::string(S);
  };
  EXPECT_EQ("1e-05", toJSONString(floatToJSON(1e-5f)));
  EXPECT_EQ("0.0001", toJSONString(floatToJSON(1e-4f)));
  EXPECT_EQ("1.5e+20", toJSONString(floatToJSON(1.5e20f)));
  EXPECT_EQ("0.1", toJSONString(llvm::json::Value(0.1)));
  uint32_t Bits = 12345;
  for (int I = 0; I < 100000; ++I) {
    Bits = Bits * 1664525u + 1013904223u; // Any float, by its bits.
    float F;
    std::memcpy(&F, &Bits, 4);
    if (!std::isfinite(F) || F == std::trunc(F))
      continue;
    ASSERT_EQ(Reference(F), toJSONString(floatToJSON(F))) << Bits;
    double D = double(F) * (1 + 1e-9); // Not a float: a double's digits.
    ASSERT_EQ(Reference(D), toJSONString(llvm::json::Value(D))) << Bits;
  }
}

/// The lister over a run's cycles gives what listActiveTasks gives for
/// each, as the active tasks and their activations change and stay.
TEST(DebugTraceTest, ListerIsListActiveTasksCycleAfterCycle) {
  DebugTables T = makeTables();
  T.Tasks[1].YieldStates = {"", "Done::lost"};
  std::vector<std::vector<Activation>> Cycles = {
      {{0, 1, 1}, {1, 1, 1}, {2, 1, 1}},
      {{0, 1, 1}, {1, 1, 1}, {2, 1, 1}},  // The same.
      {{0, 2, 3}, {1, 2, -1}, {2, 1, 1}}, // Other activations.
      {{0, 2, 3}, {2, 0, 0}},             // look is gone: walk under main.
      {{1, 1, 1}, {2, 1, 1}, {3, 0, 0}},
      {{1, 1, 1}, {2, 1, 1}, {3, 0, 0}},
      {},
      {{7, 1, 1}}, // An unknown task.
      {{0, 1, 1}, {1, 1, 1}, {2, 1, 1}}};
  ActiveTaskLister Lister(T);
  for (size_t C = 0; C < Cycles.size(); ++C) {
    std::vector<RecordedTask> Want = listActiveTasks(T, Cycles[C]);
    const std::vector<RecordedTask> &Got = Lister.list(Cycles[C]);
    ASSERT_EQ(Got.size(), Want.size()) << "cycle " << C;
    for (size_t I = 0; I < Want.size(); ++I) {
      EXPECT_EQ(Got[I].Record.Task, Want[I].Record.Task) << C;
      EXPECT_EQ(Got[I].Record.Resume, Want[I].Record.Resume) << C;
      EXPECT_EQ(Got[I].Record.State, Want[I].Record.State) << C;
      EXPECT_EQ(Got[I].Parent, Want[I].Parent) << C;
      EXPECT_EQ(Got[I].State, Want[I].State) << C;
      EXPECT_EQ(Got[I].Place, Want[I].Place) << C;
    }
  }
}
} // namespace
