//===- ValueText.cpp - a replay's fast paths along a recording's text -----===//
#include "ValuesImpl.h"
#include "bsc/Basic/JSON.h"
#include "llvm/ADT/StringExtras.h"
#include <cerrno>
#include <cstdlib>
#include <string>

using namespace bsc;
using namespace bsc::debug;
using llvm::json::Value;

//===----------------------------------------------------------------------===//
// A replay's fast paths
//===----------------------------------------------------------------------===//
//
// Both walk the text of an object in the form a recording has: keys sorted
// and distinct, strings of ASCII without escapes, plain numbers. A member
// that is a registered class held in place is walked into; any other
// value becomes a JSON value (a scalar read straight from its token, an
// array parsed) and goes through what writeClass and findDifferences
// do with it, so the results are theirs. Text of any other form makes them
// give up, and the caller takes the slow way.

/// The reading half: tokens of the plain form, by hand (StringRef's
/// searches build a table per call, which costs more than a token).
class ValueIO::TextWalker {
public:
  TextWalker(ValueIO &IO, llvm::StringRef Text) : IO(IO), Rest(Text) {}

  /// Calls `Member(C, M, Obj)` at each member of the object at the front,
  /// with its value next; false if the object is not of the plain form, a
  /// key is not a data member of `C`, or `Member` returns false.
  template <typename Fn>
  bool walkObject(const NativeClass &C, Fn Member) {
    if (!take('{'))
      return false;
    llvm::StringRef Previous;
    for (bool First = true; !take('}'); First = false) {
      llvm::StringRef Key;
      if ((!First && !take(',')) || !takeString(Key) || !take(':'))
        return false;
      // writeClass goes through the keys in order (and a key twice is
      // the last one's): the same when they are sorted and distinct.
      if (!First && Key <= Previous)
        return false;
      Previous = Key;
      const NativeFunction *M = C.findMember(Key);
      if (!M || !M->isData() || !Member(*M))
        return false;
    }
    return true;
  }
  /// Whether the value at the front is an object: a registered class held
  /// in place is walked into rather than read as a value.
  bool atObject() { return peek() == '{'; }
  /// The value at the front, as llvm::json would read it.
  std::optional<Value> takeValue();
  bool atEnd() {
    skipSpace();
    return Rest.empty();
  }

private:
  char peek() {
    skipSpace();
    return Rest.empty() ? 0 : Rest.front();
  }
  bool take(char Ch) {
    if (peek() != Ch)
      return false;
    Rest = Rest.drop_front();
    return true;
  }
  void skipSpace() {
    size_t I = 0;
    while (I < Rest.size() && (Rest[I] == ' ' || Rest[I] == '\t' ||
                               Rest[I] == '\r' || Rest[I] == '\n'))
      ++I;
    Rest = Rest.drop_front(I);
  }
  /// A string of ASCII without escapes: its text between the quotes.
  bool takeString(llvm::StringRef &S);
  std::optional<Value> takeNumber();

  ValueIO &IO;
  llvm::StringRef Rest;
};

bool ValueIO::TextWalker::takeString(llvm::StringRef &S) {
  if (!take('"'))
    return false;
  for (size_t I = 0; I < Rest.size(); ++I) {
    unsigned char Ch = Rest[I];
    if (Ch == '"') {
      S = Rest.take_front(I);
      Rest = Rest.drop_front(I + 1);
      return true;
    }
    if (Ch == '\\' || Ch < 0x20 || Ch >= 0x80)
      return false;
  }
  return false;
}

std::optional<Value> ValueIO::TextWalker::takeNumber() {
  size_t End = 0;
  bool Integer = true;
  for (; End < Rest.size(); ++End) {
    char Ch = Rest[End];
    if (Ch == '.' || Ch == 'e' || Ch == 'E' || Ch == '+')
      Integer = false;
    else if (!llvm::isDigit(Ch) && Ch != '-')
      break;
  }
  llvm::StringRef Token = Rest.take_front(End);
  Rest = Rest.drop_front(End);
  llvm::StringRef Digits = Token;
  bool Negative = Digits.consume_front("-");
  if (Integer) {
    // llvm::json reads an integer that fits into an int64; 18 digits do.
    if (Digits.empty() || Digits.size() > 18 ||
        !llvm::all_of(Digits, llvm::isDigit))
      return std::nullopt;
    int64_t N = 0;
    for (char D : Digits)
      N = N * 10 + (D - '0');
    return Value(Negative ? -N : N);
  }
  char Buf[64];
  if (Token.size() >= sizeof Buf)
    return std::nullopt;
  std::memcpy(Buf, Token.data(), Token.size());
  Buf[Token.size()] = 0;
  char *After;
  double D = std::strtod(Buf, &After);
  if (After != Buf + Token.size())
    return std::nullopt;
  return Value(D);
}

std::optional<Value> ValueIO::TextWalker::takeValue() {
  char Ch = peek();
  if (Ch == '"') {
    llvm::StringRef S;
    if (!takeString(S))
      return std::nullopt;
    return Value(S);
  }
  if (Ch == '-' || llvm::isDigit(Ch))
    return takeNumber();
  for (llvm::StringRef Word : {"true", "false", "null"})
    if (Rest.consume_front(Word))
      return Word == "null" ? Value(nullptr) : Value(Word == "true");
  if (Ch != '[')
    return std::nullopt;
  // An array field: parsed whole (its elements are what a member of its
  // type takes; this is rarer than scalars). The walker's text is checked
  // JSON, so the array ends at its bracket.
  unsigned Depth = 0;
  bool InString = false;
  for (size_t I = 0; I < Rest.size(); ++I) {
    char C = Rest[I];
    if (InString) {
      if (C == '\\')
        ++I;
      else if (C == '"')
        InString = false;
    } else if (C == '"') {
      InString = true;
    } else if (C == '[' || C == '{') {
      ++Depth;
    } else if ((C == ']' || C == '}') && --Depth == 0) {
      llvm::Expected<Value> V = parseJSON(Rest.take_front(I + 1));
      Rest = Rest.drop_front(I + 1);
      if (!V) {
        llvm::consumeError(V.takeError());
        return std::nullopt;
      }
      return std::move(*V);
    }
  }
  return std::nullopt;
}

/// A member that is a registered class held at an offset: walked into.
static const NativeClass *getClassInPlace(const NativeFunction &M) {
  const NativeType &NT = M.Result;
  if (M.FieldOffset && !M.ReadOnly && NT.TheCode == NativeType::Class &&
      NT.Extents.empty())
    return NT.TheClass;
  return nullptr;
}

bool ValueIO::writeObjectText(TextWalker &W, const NativeClass &C, void *Obj) {
  return W.walkObject(C, [&](const NativeFunction &M) {
    if (const NativeClass *Inner = getClassInPlace(M); Inner && W.atObject())
      return writeObjectText(W, *Inner,
                             static_cast<char *>(Obj) + *M.FieldOffset);
    std::optional<Value> V = W.takeValue();
    if (!V)
      return false;
    llvm::Error E = writeMember(C, M, Obj, *V, "");
    if (!E)
      return true;
    llvm::consumeError(std::move(E));
    return false;
  });
}

bool ValueIO::writeClassText(const NativeClass &C, void *Obj,
                             llvm::StringRef Text) {
  TextWalker W(*this, Text);
  return writeObjectText(W, C, Obj) && W.atEnd();
}

bool ValueIO::matchObjectText(TextWalker &W, const NativeClass &C,
                              const void *Obj) {
  return W.walkObject(C, [&](const NativeFunction &M) {
    if (const NativeClass *Inner = getClassInPlace(M); Inner && W.atObject())
      return matchObjectText(W, *Inner,
                             static_cast<const char *>(Obj) + *M.FieldOffset);
    std::optional<Value> Recorded = W.takeValue();
    return Recorded &&
           !findDifference(*Recorded, readMember(C, M, Obj), "").has_value();
  });
}

bool ValueIO::matchesClassText(const NativeClass &C, const void *Obj,
                               llvm::StringRef Text) {
  TextWalker W(*this, Text);
  return matchObjectText(W, C, Obj) && W.atEnd();
}
