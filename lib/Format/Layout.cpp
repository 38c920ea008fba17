//===- Layout.cpp - one statement line in the canonical layout ------------===//
//
// The spaces between two tokens follow from the two tokens alone (and, for
// `-`, whether it is unary). A statement that does not fit is broken after
// its outermost call's `(`, one argument per line; one with comments inside
// `( )` is broken where they stand. Either way the tokens stay in order.
//
//===----------------------------------------------------------------------===//
#include "FormatImpl.h"

using namespace bsc;
using namespace bsc::format;

/// Whether a token ends an operand, so that a `-` after it is binary and a
/// `(` or `[` after it calls or indexes it.
static bool endsOperand(tok::Kind K) {
  switch (K) {
  case tok::identifier:
  case tok::int_literal:
  case tok::float_literal:
  case tok::string_literal:
  case tok::r_paren:
  case tok::r_square:
  case tok::kw_true:
  case tok::kw_false:
    return true;
  default:
    return false;
  }
}

namespace {
/// Writes the tokens of one statement, deciding the space before each.
class LineWriter {
public:
  explicit LineWriter(const Item &S) : S(S) {
    // A `-` or `!` that starts an operand.
    Unary.resize(S.Tokens.size());
    for (size_t I = 0; I < S.Tokens.size(); ++I) {
      tok::Kind K = S.Tokens[I].Tok.Kind;
      Unary[I] = K == tok::exclaim ||
                 (K == tok::minus &&
                  (I == 0 || !endsOperand(S.Tokens[I - 1].Tok.Kind)));
    }
  }

  /// Whether a space goes between token I-1 and token I on one line.
  bool spaceBefore(size_t I) const {
    tok::Kind P = S.Tokens[I - 1].Tok.Kind, T = S.Tokens[I].Tok.Kind;
    if (P == tok::l_paren || P == tok::l_square || Unary[I - 1])
      return false;
    if (T == tok::r_paren || T == tok::r_square || T == tok::comma ||
        T == tok::semi)
      return false;
    // A number and a `.` beside it stay apart (`1.5 .w`, `a. 1`: errors
    // the parser reports): `1.5.w` and `.1` would lex as other tokens.
    auto IsNumber = [](tok::Kind K) {
      return K == tok::int_literal || K == tok::float_literal;
    };
    if ((T == tok::period && IsNumber(P)) || (P == tok::period && IsNumber(T)))
      return true;
    if (P == tok::period || P == tok::coloncolon || T == tok::period ||
        T == tok::coloncolon)
      return false;
    if (T == tok::l_paren)
      return !(endsOperand(P) || P == tok::kw_if || P == tok::kw_for ||
               P == tok::kw_taskState || P == tok::kw_assert ||
               P == tok::kw_assume);
    if (T == tok::l_square)
      return !endsOperand(P);
    return true; // Words, `,` and `;`, and the spaced operators.
  }

  /// Tokens [From, To) on the current line.
  void write(size_t From, size_t To) {
    for (size_t I = From; I < To; ++I) {
      if (I != From && !AtLineStart && spaceBefore(I))
        Out += ' ';
      AtLineStart = false;
      Out += S.Tokens[I].Tok.Text;
    }
  }

  void newLine(unsigned Columns) {
    Out += '\n';
    Out.append(Columns, ' ');
    AtLineStart = true;
  }

  std::string Out;
  bool AtLineStart = true;

private:
  const Item &S;
  std::vector<bool> Unary;
};
} // namespace

/// The single-line text of tokens [From, To).
static std::string oneLine(const Item &S, size_t From, size_t To) {
  LineWriter W(S);
  W.write(From, To);
  return std::move(W.Out);
}

/// The call to break a long statement at: the outermost one that ends the
/// statement (only `)` after it) and holds most of it, as in
/// `Motion::walkTo(...)`, `x = f(...)` or `if(g(...))`. A statement of
/// several calls side by side has none: outside `( )` a line cannot be
/// continued, and breaking the last call alone reads badly.
static std::optional<std::pair<size_t, size_t>> findCallToBreak(const Item &S) {
  size_t End = S.Tokens.size();
  while (End > 0 && S.Tokens[End - 1].Tok.is(tok::r_paren))
    --End;
  std::vector<size_t> Open;
  for (size_t I = 0; I < S.Tokens.size(); ++I) {
    tok::Kind K = S.Tokens[I].Tok.Kind;
    if (K == tok::l_paren) {
      Open.push_back(I);
    } else if (K == tok::r_paren && !Open.empty()) {
      size_t L = Open.back();
      Open.pop_back();
      bool IsCall = L > 0 && S.Tokens[L - 1].Tok.is(tok::identifier);
      if (IsCall && I >= End && I > L + 1 && 2 * (I - L) > S.Tokens.size())
        return std::pair(L, I);
    }
  }
  return std::nullopt;
}

/// A statement too long for one line: broken after the `(` of its
/// outermost call, each argument on a line of its own.
static std::string breakAtCall(const Item &S, unsigned Indent,
                               std::pair<size_t, size_t> Call) {
  auto [L, R] = Call;
  LineWriter W(S);
  W.Out.append(Indent, ' ');
  W.write(0, L + 1);
  // The arguments: split at the commas at the call's own depth.
  size_t ArgStart = L + 1;
  int Nesting = 0;
  for (size_t I = L + 1; I <= R; ++I) {
    tok::Kind K = S.Tokens[I].Tok.Kind;
    if (I == R || (K == tok::comma && Nesting == 0)) {
      W.newLine(Indent + ContinuationWidth);
      W.write(ArgStart, I == R ? R : I + 1);
      ArgStart = I + 1;
    } else if (K == tok::l_paren || K == tok::l_square) {
      ++Nesting;
    } else if (K == tok::r_paren || K == tok::r_square) {
      --Nesting;
    }
  }
  // `)` and the rest of the statement after the last argument.
  W.AtLineStart = true;
  W.write(R, S.Tokens.size());
  return std::move(W.Out);
}

/// A statement with comments inside `( )`: a line ends after each comment
/// that follows a token, and a comment line goes before the token it
/// precedes.
static std::string breakAtComments(const Item &S, unsigned Indent) {
  LineWriter W(S);
  W.Out.append(Indent, ' ');
  unsigned Continued = Indent + ContinuationWidth;
  size_t N = S.Tokens.size();
  for (size_t I = 0; I < N; ++I) {
    const LineToken &T = S.Tokens[I];
    if (!T.Leading.empty()) {
      if (!W.AtLineStart)
        W.newLine(Continued);
      for (llvm::StringRef C : T.Leading) {
        W.Out += C;
        W.newLine(Continued);
      }
    }
    if (I != 0 && !W.AtLineStart && W.spaceBefore(I))
      W.Out += ' ';
    W.Out += T.Tok.Text;
    W.AtLineStart = false;
    if (!T.Trailing.empty()) {
      W.Out += "  ";
      W.Out += T.Trailing;
      if (I + 1 != N)
        W.newLine(Continued);
    }
  }
  return std::move(W.Out);
}

std::string format::layoutStatement(const Item &S) {
  unsigned Indent = S.Depth * IndentWidth;
  size_t N = S.Tokens.size();
  bool InnerComments = false;
  for (size_t I = 0; I < N; ++I)
    InnerComments |= !S.Tokens[I].Leading.empty() ||
                     (I + 1 != N && !S.Tokens[I].Trailing.empty());
  std::string Text;
  if (InnerComments) {
    Text = breakAtComments(S, Indent);
  } else {
    std::string Line = oneLine(S, 0, N);
    auto Call = findCallToBreak(S);
    if (Indent + Line.size() > ColumnLimit && Call)
      Text = breakAtCall(S, Indent, *Call);
    else
      Text = std::string(Indent, ' ') + Line;
    if (!S.Tokens.back().Trailing.empty())
      Text += "  " + S.Tokens.back().Trailing.str();
  }
  return Text + "\n";
}
