//===- Values.cpp - b-script values in memory as JSON ---------------------===//
//
// Numbers as recordings spell them, values printed and compared. Reading
// values from memory is ValueRead.cpp, writing them ValueWrite.cpp, and a
// replay's fast paths along a recording's text ValueText.cpp.
//
//===----------------------------------------------------------------------===//
#include "bsc/Debug/Values.h"
#include "bsc/AST/Native.h"
#include "bsc/Basic/JSON.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/Format.h"
#include "llvm/Support/MemAlloc.h"
#include "llvm/Support/raw_ostream.h"
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <utility>

using namespace bsc;
using namespace bsc::debug;
using llvm::json::Value;

//===----------------------------------------------------------------------===//
// Numbers
//===----------------------------------------------------------------------===//

Value debug::floatToJSON(double F) {
  if (std::isnan(F))
    return "NaN";
  if (std::isinf(F))
    return F > 0 ? "Infinity" : "-Infinity";
  return F;
}

std::optional<double> debug::floatFromJSON(const Value &V) {
  if (std::optional<double> D = V.getAsNumber())
    return *D;
  if (std::optional<llvm::StringRef> S = V.getAsString()) {
    if (*S == "NaN")
      return std::nan("");
    if (*S == "Infinity")
      return HUGE_VAL;
    if (*S == "-Infinity")
      return -HUGE_VAL;
  }
  return std::nullopt;
}

/// The shortest decimal that reads back as `D` (as a float when `D` is
/// one, which every b-script float is): `%g` of the least precision that
/// does. No precision below the digits of std::to_chars's shortest form
/// can, so the search starts there (a page of a long run prints millions).
static std::string formatNumber(double D) {
  if (D == 0 && std::signbit(D))
    return "-0.0";
  if (D == std::trunc(D) && std::fabs(D) < 1e15)
    return llvm::formatv("{0}", (long long)D).str();
  bool IsFloat = double(float(D)) == D;
  char S[64];
  char *End = IsFloat ? std::to_chars(S, S + sizeof S, float(D),
                                      std::chars_format::scientific)
                            .ptr
                      : std::to_chars(S, S + sizeof S, D,
                                      std::chars_format::scientific)
                            .ptr;
  int Digits = llvm::count_if(llvm::StringRef(S, End - S).split('e').first,
                              llvm::isDigit);
  for (int Precision = std::max(Digits, 1); Precision <= 17; ++Precision) {
    End = std::to_chars(S, S + sizeof S, D, std::chars_format::general,
                        Precision)
              .ptr;
    double Back = 0;
    std::from_chars(S, End, Back);
    if (IsFloat ? float(Back) == float(D) : Back == D)
      return std::string(S, End);
  }
  std::snprintf(S, sizeof S, "%.17g", D);
  return S;
}

void debug::printJSON(llvm::raw_ostream &OS, const Value &V) {
  switch (V.kind()) {
  case Value::Null:
  case Value::Boolean:
  case Value::String:
    OS << V;
    return;
  case Value::Number:
    if (std::optional<int64_t> I = V.getAsInteger(); I && *I != 0)
      OS << *I;
    else
      OS << formatNumber(*V.getAsNumber());
    return;
  case Value::Array: {
    OS << '[';
    llvm::ListSeparator Sep(",");
    for (const Value &E : *V.getAsArray()) {
      OS << Sep;
      printJSON(OS, E);
    }
    OS << ']';
    return;
  }
  case Value::Object: {
    const llvm::json::Object &O = *V.getAsObject();
    std::vector<llvm::StringRef> Keys;
    for (const auto &KV : O)
      Keys.push_back(KV.first);
    llvm::sort(Keys);
    OS << '{';
    llvm::ListSeparator Sep(",");
    for (llvm::StringRef K : Keys) {
      OS << Sep << Value(K) << ':';
      printJSON(OS, *O.get(K));
    }
    OS << '}';
    return;
  }
  }
}

std::string debug::formatValue(const Type *T, const llvm::json::Value &V) {
  if (T->isEnum())
    if (std::optional<llvm::StringRef> Name = V.getAsString())
      return Name->str();
  return toJSONString(V);
}

std::string debug::toJSONString(const Value &V) {
  std::string S;
  llvm::raw_string_ostream OS(S);
  printJSON(OS, V);
  return S;
}

/// Appends the places where `Got` differs from `Recorded` to `Out`, objects
/// in key order and arrays in index order; with `FirstOnly`, stops after
/// the first. Returns whether it found one.
static bool collectDifferences(const Value &Recorded, const Value &Got,
                               llvm::StringRef Path, bool FirstOnly,
                               std::vector<Difference> &Out) {
  size_t Before = Out.size();
  auto Done = [&] { return FirstOnly && Out.size() > Before; };
  if (const llvm::json::Object *R = Recorded.getAsObject()) {
    if (const llvm::json::Object *G = Got.getAsObject()) {
      std::vector<llvm::StringRef> Keys;
      for (const auto &KV : *R)
        Keys.push_back(KV.first);
      llvm::sort(Keys);
      for (llvm::StringRef K : Keys) {
        const Value *GV = G->get(K);
        std::string Sub = (Path + "." + K).str();
        if (!GV)
          Out.push_back({Sub, toJSONString(*R->get(K)), "nothing"});
        else
          collectDifferences(*R->get(K), *GV, Sub, FirstOnly, Out);
        if (Done())
          break;
      }
      return Out.size() > Before;
    }
  }
  if (const llvm::json::Array *R = Recorded.getAsArray()) {
    // An array field: element by element, named `output.wide[3]`.
    const llvm::json::Array *G = Got.getAsArray();
    if (G && G->size() == R->size()) {
      for (size_t I = 0; I < R->size() && !Done(); ++I)
        collectDifferences((*R)[I], (*G)[I],
                           (Path + "[" + llvm::Twine(I) + "]").str(),
                           FirstOnly, Out);
      return Out.size() > Before;
    }
  }
  // Numbers compare as the floats (or ints) they are; a number written as
  // a float's shortest decimal reads back as that float.
  std::optional<double> RN = floatFromJSON(Recorded), GN = floatFromJSON(Got);
  std::optional<int64_t> RI = Recorded.getAsInteger(), GI = Got.getAsInteger();
  bool Same;
  if (RI && GI) // Zero's sign is the only thing an int cannot show.
    Same = *RI == *GI && (*RI != 0 || std::signbit(*RN) == std::signbit(*GN));
  else if (RN && GN) // Every non-integer number here is a b-script float.
    Same = (std::isnan(*RN) && std::isnan(*GN)) || float(*RN) == float(*GN);
  else
    Same = Recorded == Got;
  if (Same)
    return false;
  Out.push_back({Path.str(), toJSONString(Recorded), toJSONString(Got)});
  return true;
}

std::optional<Difference> debug::findDifference(const Value &Recorded,
                                                const Value &Got,
                                                llvm::StringRef Path) {
  std::vector<Difference> Found;
  if (!collectDifferences(Recorded, Got, Path, /*FirstOnly=*/true, Found))
    return std::nullopt;
  return std::move(Found.front());
}

std::vector<Difference> debug::findDifferences(const Value &Recorded,
                                               const Value &Got,
                                               llvm::StringRef Path) {
  std::vector<Difference> Found;
  collectDifferences(Recorded, Got, Path, /*FirstOnly=*/false, Found);
  return Found;
}
