//===- JSON.cpp - reading JSON text with a bounded nesting depth ----------===//
//
// The depth scan runs before llvm::json::parse, not inside it: the parser
// is LLVM's, and its recursion is what must not be reached. The scan only
// needs to know which brackets are outside strings; everything else about
// the text is left for the parser to judge.
//
//===----------------------------------------------------------------------===//
#include "bsc/Basic/JSON.h"
#include "llvm/ADT/StringExtras.h"
#include <cerrno>
#include <cstdlib>
#include "bsc/Basic/Diagnostic.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;

char JSONReadError::ID;

void JSONReadError::log(llvm::raw_ostream &OS) const {
  OS << Line << ':' << Column << ": " << Message;
}

/// The offset of the first `[` or `{` outside strings that opens level
/// `Limit + 1`; npos if the text never nests that deep.
static size_t findTooDeep(llvm::StringRef Text, unsigned Limit) {
  unsigned Depth = 0;
  bool InString = false;
  for (size_t I = 0, E = Text.size(); I < E; ++I) {
    char C = Text[I];
    if (InString) {
      if (C == '\\')
        ++I; // The escaped byte (a quote, a backslash) ends nothing.
      else if (C == '"')
        InString = false;
      continue;
    }
    switch (C) {
    case '"':
      InString = true;
      break;
    case '[':
    case '{':
      if (++Depth > Limit)
        return I;
      break;
    case ']':
    case '}':
      // A stray closer is the parser's error to report; never let it buy
      // room for deeper nesting later.
      if (Depth)
        --Depth;
      break;
    default:
      break;
    }
  }
  return llvm::StringRef::npos;
}

/// A number of the plain form `-?D+(.D+)?([eE][+-]?D+)?`, which strtod
/// reads whole (and strtoll too, when it is an integer that fits): a
/// replay's lines are full of them, and the C library's calls cost more
/// than the rest of the check.
static bool isPlainNumber(llvm::StringRef T) {
  size_t I = 0, N = T.size();
  auto Digits = [&] {
    size_t From = I;
    while (I < N && llvm::isDigit(T[I]))
      ++I;
    return I > From;
  };
  if (I < N && T[I] == '-')
    ++I;
  if (!Digits())
    return false;
  if (I < N && T[I] == '.') {
    ++I;
    if (!Digits())
      return false;
  }
  if (I < N && (T[I] == 'e' || T[I] == 'E')) {
    ++I;
    if (I < N && (T[I] == '+' || T[I] == '-'))
      ++I;
    if (!Digits())
      return false;
  }
  return I == N;
}

/// The bytes a string holds as they are: not a quote, a backslash, a
/// control character or the start of a multi-byte sequence.
static const struct PlainStringBytes {
  bool Table[256];
  constexpr PlainStringBytes() : Table() {
    for (unsigned C = 0x20; C < 0x80; ++C)
      Table[C] = C != '"' && C != '\\';
  }
  bool operator[](unsigned char C) const { return Table[C]; }
} PlainStringByte;

namespace {
/// Checks JSON (RFC 8259, as llvm::json::parse reads it) without building
/// values: one pass, no allocation for the usual numbers. It refuses text
/// nested deeper than MaxJSONDepth where it gets there (its recursion is
/// bounded by it).
class JSONChecker {
public:
  JSONChecker(llvm::StringRef Text, JSONMemberFn OnMember)
      : Text(Text), OnMember(OnMember) {}
  bool document() {
    if (!value())
      return false;
    space();
    return At == Text.size();
  }

private:
  static bool isSpace(char C) {
    return C == ' ' || C == '\t' || C == '\r' || C == '\n';
  }
  static bool isNumberChar(char C) {
    return llvm::isDigit(C) || C == '+' || C == '-' || C == '.' || C == 'e' ||
           C == 'E';
  }
  void space() {
    while (At < Text.size() && isSpace(Text[At]))
      ++At;
  }
  bool eat(char C) {
    space();
    if (At < Text.size() && Text[At] == C)
      return ++At, true;
    return false;
  }
  /// A number as llvm::json reads one: a run of `0-9 + - . e E` that
  /// strtoll, strtoull or strtod reads whole (so `01`, `1.` and `+1` are
  /// numbers, `1e` is not).
  bool number() {
    size_t Start = At;
    while (At < Text.size() && isNumberChar(Text[At]))
      ++At;
    if (isPlainNumber(Text.slice(Start, At)))
      return true;
    std::string Token = Text.slice(Start, At).str();
    const char *End = Token.c_str() + Token.size();
    char *Stop;
    errno = 0;
    (void)std::strtoll(Token.c_str(), &Stop, 10);
    if (Stop == End && errno != ERANGE)
      return true;
    if (Token[0] != '-') {
      errno = 0;
      (void)std::strtoull(Token.c_str(), &Stop, 10);
      if (Stop == End && errno != ERANGE)
        return true;
    }
    (void)std::strtod(Token.c_str(), &Stop);
    return Stop == End;
  }
  bool string() {
    size_t Start = ++At;
    bool ASCII = true; // Then it is UTF-8, without asking isUTF8.
    for (; At < Text.size(); ++At) {
      // Most of a line is plain string bytes: skip them a table look-up
      // each.
      while (At < Text.size() && PlainStringByte[(unsigned char)Text[At]])
        ++At;
      if (At == Text.size())
        return false;
      unsigned char C = Text[At];
      if (C == '"') {
        llvm::StringRef S = Text.slice(Start, At++);
        return ASCII || llvm::json::isUTF8(S);
      }
      if (C < 0x20)
        return false;
      if (C >= 0x80)
        ASCII = false;
      if (C != '\\')
        continue;
      if (++At >= Text.size())
        return false;
      char E = Text[At];
      if (E == 'u') {
        for (int I = 0; I < 4; ++I)
          if (++At >= Text.size() || !llvm::isHexDigit(Text[At]))
            return false;
      } else if (!llvm::StringRef("\"\\/bfnrt").contains(E)) {
        return false;
      }
    }
    return false;
  }
  bool value() {
    space();
    if (At >= Text.size())
      return false;
    char C = Text[At];
    if (C == '"')
      return string();
    if (C == '+' || C == '-' || C == '.' || llvm::isDigit(C))
      return number();
    if (C == 't' || C == 'f' || C == 'n') {
      llvm::StringRef Word = C == 't' ? "true" : C == 'f' ? "false" : "null";
      if (!Text.substr(At).starts_with(Word))
        return false;
      At += Word.size();
      return true;
    }
    if (C != '{' && C != '[')
      return false;
    ++At;
    char Close = C == '{' ? '}' : ']';
    bool TopObject = C == '{' && Level == 0;
    if (++Level > MaxJSONDepth)
      return false;
    if (eat(Close))
      return --Level, true;
    do {
      size_t KeyStart = 0;
      if (C == '{') {
        space();
        KeyStart = At;
        if (At >= Text.size() || Text[At] != '"' || !string() || !eat(':'))
          return false;
      }
      size_t KeyEnd = At;
      space();
      size_t ValueStart = At;
      if (!value())
        return false;
      if (TopObject && OnMember) {
        llvm::StringRef Key = Text.slice(KeyStart, KeyEnd).rtrim(" \t\r\n:");
        OnMember(Key.drop_front().drop_back(), Text.slice(ValueStart, At));
      }
    } while (eat(','));
    --Level;
    return eat(Close);
  }

  llvm::StringRef Text;
  JSONMemberFn OnMember;
  size_t At = 0;
  unsigned Level = 0;
};
} // namespace

bool bsc::isJSON(llvm::StringRef Text, JSONMemberFn OnMember) {
  return JSONChecker(Text, OnMember).document();
}

/// A JSONReadError at byte `Offset` of `Text`.
static llvm::Error makeError(llvm::StringRef Text, size_t Offset,
                             std::string Message) {
  llvm::StringRef Before = Text.take_front(Offset);
  unsigned Line = 1 + Before.count('\n');
  size_t LineStart = Before.rfind('\n');
  unsigned Column =
      Offset - (LineStart == llvm::StringRef::npos ? 0 : LineStart + 1) + 1;
  return llvm::make_error<JSONReadError>(std::move(Message), Offset, Line,
                                         Column);
}

/// llvm::json's error as a JSONReadError. Its fields are private; its text
/// is `[LINE:COLUMN, byte=OFFSET]: MESSAGE`.
static llvm::Error convertParseError(llvm::StringRef Text, llvm::Error E) {
  std::string Full = llvm::toString(std::move(E));
  llvm::StringRef Rest = Full;
  size_t Offset = 0;
  auto [Place, What] = Rest.split("]: ");
  if (!What.empty() && Place.contains("byte=") &&
      !Place.split("byte=").second.getAsInteger(10, Offset) &&
      Offset <= Text.size())
    return makeError(Text, Offset, What.str());
  return makeError(Text, 0, Full);
}

llvm::Expected<llvm::json::Value> bsc::parseJSON(llvm::StringRef Text) {
  size_t Deep = findTooDeep(Text, MaxJSONDepth);
  if (Deep != llvm::StringRef::npos)
    return makeError(Text, Deep,
                     "nesting deeper than " + std::to_string(MaxJSONDepth) +
                         " levels");
  llvm::Expected<llvm::json::Value> V = llvm::json::parse(Text);
  if (!V)
    return convertParseError(Text, V.takeError());
  return V;
}

std::optional<llvm::json::Value> bsc::parseJSONLine(DiagnosticEngine &Diags,
                                                    llvm::StringRef Line) {
  llvm::Expected<llvm::json::Value> V = parseJSON(Line);
  if (V)
    return std::move(*V);
  llvm::handleAllErrors(V.takeError(), [&](const JSONReadError &E) {
    Diags.report(llvm::SMLoc::getFromPointer(Line.data() + E.Offset),
                 diag::err_replay_json)
        << E.Message;
  });
  return std::nullopt;
}
