//===- AST.h - the syntax tree of b-script modules -------------*- C++ -*-===//
//
// The parser builds one ModuleAST per file; Sema fills in the fields marked
// "Sema:" (types, resolved names, call kinds, the locals of each callable)
// and never changes the shape except to wrap an operand in an implicit
// ConversionExpr. CodeGen reads the checked tree.
//
// Nodes are owned by the ASTContext; pointers between them are plain. Names
// are StringRefs into the source buffers, which the llvm::SourceMgr keeps
// alive for the whole compilation.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_AST_AST_H
#define BSC_AST_AST_H

#include "bsc/AST/Native.h"
#include "bsc/AST/Type.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Casting.h"
#include "llvm/Support/SMLoc.h"
#include "llvm/Support/StringSaver.h"
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace llvm {
class raw_ostream;
}

namespace bsc {

enum class NodeKind {
#define NODE(Class) Class,
#include "bsc/AST/ASTNodes.def"
};

enum class BinaryOp {
#define BINARY_OP(Name, Spelling, Prec) Name,
#include "bsc/AST/OperatorKinds.def"
};
enum class UnaryOp {
#define UNARY_OP(Name, Spelling) Name,
#include "bsc/AST/OperatorKinds.def"
};
enum class AssignOp {
#define ASSIGN_OP(Name, Spelling, Bin) Name,
#include "bsc/AST/OperatorKinds.def"
};

llvm::StringRef getSpelling(BinaryOp Op);
llvm::StringRef getSpelling(UnaryOp Op);
llvm::StringRef getSpelling(AssignOp Op);
/// Binding strength of a binary operator (C precedence; higher is tighter).
unsigned getPrecedence(BinaryOp Op);
/// The arithmetic operator of a compound assignment (`+=` -> Add); false
/// for plain `=`.
bool getCompoundOperator(AssignOp Op, BinaryOp &Result);
llvm::StringRef getNodeKindName(NodeKind K);

/// An identifier and where it was written.
struct Ident {
  llvm::StringRef Name;
  llvm::SMLoc Loc;
  llvm::SMRange getRange() const {
    return {Loc, llvm::SMLoc::getFromPointer(Loc.getPointer() + Name.size())};
  }
};

/// `a`, `Module::name`, `Enum::value`, `Module::Enum::value`.
struct QualifiedName {
  llvm::SmallVector<Ident, 2> Parts;

  bool empty() const { return Parts.empty(); }
  bool isQualified() const { return Parts.size() > 1; }
  llvm::SMLoc getLoc() const { return Parts.empty() ? llvm::SMLoc() : Parts[0].Loc; }
  llvm::SMRange getRange() const;
  /// The parts joined with `::`.
  std::string str() const;
};

class Node {
public:
  NodeKind getKind() const { return Kind; }
  llvm::SMRange getRange() const { return Range; }
  llvm::SMLoc getLoc() const { return Range.Start; }
  void setRange(llvm::SMRange R) { Range = R; }
  virtual ~Node() = default;

protected:
  Node(NodeKind K, llvm::SMRange R) : Kind(K), Range(R) {}

private:
  NodeKind Kind;
  llvm::SMRange Range;
};

class ModuleAST;
class BlockStmt;
class Expr;
class TaskDecl;

//===----------------------------------------------------------------------===//
// Declarations
//===----------------------------------------------------------------------===//

class Decl : public Node {
public:
  const Ident &getName() const { return Name; }
  static bool classof(const Node *N) {
    return N->getKind() >= NodeKind::FuncDecl &&
           N->getKind() <= NodeKind::EnumDecl;
  }

protected:
  Decl(NodeKind K, llvm::SMRange R, Ident Name) : Node(K, R), Name(Name) {}

private:
  Ident Name;
};

class CallableDecl;

/// A value computed at compile time, in the member its type selects (int,
/// enums and task states: Int).
struct ConstantValue {
  int32_t Int = 0;
  float Float = 0;
  bool Bool = false;
  std::string String;
};

/// A parameter of a func or task: `Math::Vector2f target`.
class ParamDecl : public Decl {
public:
  ParamDecl(llvm::SMRange R, Ident Name, QualifiedName TypeName)
      : Decl(NodeKind::ParamDecl, R, Name), TypeName(std::move(TypeName)) {}
  QualifiedName TypeName;
  CallableDecl *Owner = nullptr; ///< Set by the parser.
  unsigned Index = 0;            ///< Position in the parameter list.
  /// `float tilt = 0.38`: the default a call that leaves the argument out
  /// passes (a constant expression), or null.
  Expr *Default = nullptr;
  const Type *Ty = nullptr;      ///< Sema.
  /// Sema: the value of Default, as Ty.
  std::optional<ConstantValue> DefaultValue;
  /// Sema: a func nested in the owning task reads it, so the task keeps a
  /// copy in its frame (the task's own body reads the argument).
  bool ReadByNestedFunc = false;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::ParamDecl;
  }
};

/// A local variable: `int ballNearDist = 100` (Init may be null: the value
/// is then the type's zero).
class VarDecl : public Decl {
public:
  VarDecl(llvm::SMRange R, Ident Name, QualifiedName TypeName, Expr *Init)
      : Decl(NodeKind::VarDecl, R, Name), TypeName(std::move(TypeName)),
        Init(Init) {}
  QualifiedName TypeName;
  Expr *Init;
  /// The func or task whose body declares it (for a local of a task, the
  /// task: its storage is in the task's frame). Set by Sema.
  CallableDecl *Owner = nullptr;
  const Type *Ty = nullptr; ///< Sema.
  /// Sema, for a task's locals: whether a `yield` of the task lies in its
  /// scope after its declaration (so its value may have to outlive a
  /// call), and whether a nested func uses it; either keeps it in the
  /// task's frame.
  bool LivesAcrossYield = false;
  bool UsedByNestedFunc = false;
  /// Sema: a nested func that uses it may be called before its declaration
  /// runs, so the task's reset zeroes it (docs/language.md).
  bool ReadBeforeDeclared = false;
  /// Sema: its scope as an interval of the owner's declarations and scope
  /// ends, in source order. Two locals whose intervals do not overlap are
  /// never alive at once, so they may share storage.
  unsigned ScopeBegin = 0, ScopeEnd = 0;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::VarDecl;
  }
};

/// `const int KICK = 3` at module scope: a named value of its module,
/// usable in it and, qualified, in the modules that require it. Its value
/// is computed at compile time from literals, enum values and constants.
class ConstDecl : public Decl {
public:
  ConstDecl(llvm::SMRange R, Ident Name, QualifiedName TypeName, Expr *Init)
      : Decl(NodeKind::ConstDecl, R, Name), TypeName(std::move(TypeName)),
        Init(Init) {}
  QualifiedName TypeName;
  Expr *Init;
  ModuleAST *Module = nullptr; ///< Set by the parser.
  const Type *Ty = nullptr;    ///< Sema.
  /// Sema: the value, in the member Ty selects (int and enums: Int).
  using ValueFields = ConstantValue;
  ValueFields Value;
  /// Sema's progress: constants may use constants of other modules.
  enum class CheckState { Unchecked, Checking, Done } State =
      CheckState::Unchecked;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::ConstDecl;
  }
};

/// One enumerator of a script enum: `kick = 7`.
struct Enumerator {
  Ident Name;
  /// The `= INT` written (the parser folds a leading `-`), if any.
  std::optional<int64_t> Explicit;
  llvm::SMRange ValueRange; ///< Of the `= INT`, for diagnostics.
};

/// `enum Phase` at module scope, one enumerator per line below it: a type of
/// its module whose values are `Phase::align` (qualified by the module in
/// the modules that require it). `enum Button : TaskState` declares named
/// task states instead: its values are of type TaskState, and the name
/// `Button` is TaskState as a type.
class EnumDecl : public Decl {
public:
  EnumDecl(llvm::SMRange R, Ident Name, bool IsTaskState)
      : Decl(NodeKind::EnumDecl, R, Name), IsTaskState(IsTaskState) {}
  std::vector<Enumerator> Enumerators;
  bool IsTaskState;
  ModuleAST *Module = nullptr; ///< Set by the parser.
  /// Sema: the numbered values in the form a registered enum has, so that
  /// lookup, CodeGen and the debugger treat both alike (Module stays null).
  NativeEnum Values;
  /// Sema: the enum's type (TaskState for named task states).
  const Type *Ty = nullptr;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::EnumDecl;
  }
};

/// What funcs and tasks share: parameters, a body, a module.
class CallableDecl : public Decl {
public:
  std::vector<ParamDecl *> Params;
  BlockStmt *Body = nullptr;
  ModuleAST *Module = nullptr; ///< Set by the parser.
  /// Every local of the body, in declaration order, including those of
  /// nested blocks and `for` heads (Sema). A task's locals live in its frame.
  std::vector<VarDecl *> Locals;

  /// `Module::name`, the name diagnostics and symbols use.
  std::string getQualifiedName() const;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::FuncDecl ||
           N->getKind() == NodeKind::TaskDecl;
  }

protected:
  CallableDecl(NodeKind K, llvm::SMRange R, Ident Name) : Decl(K, R, Name) {}
};

/// `func name(params) [: type]`. A func declared in a task's body is nested:
/// it sees the task's parameters and the task's top-level locals declared
/// before it.
class FuncDecl : public CallableDecl {
public:
  FuncDecl(llvm::SMRange R, Ident Name)
      : CallableDecl(NodeKind::FuncDecl, R, Name) {}
  QualifiedName ResultTypeName; ///< Empty when no `: type` was written.
  TaskDecl *EnclosingTask = nullptr; ///< Set by the parser for nested funcs.
  const Type *ResultTy = nullptr;    ///< Sema (void without `: type`).
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::FuncDecl;
  }
};

/// `task name(params)`: a singleton generator with one context.
class TaskDecl : public CallableDecl {
public:
  TaskDecl(llvm::SMRange R, Ident Name)
      : CallableDecl(NodeKind::TaskDecl, R, Name) {}
  std::vector<FuncDecl *> NestedFuncs; ///< Set by the parser.
  /// The yields of the body in source order (Sema); their position + 1 is
  /// the resume point after each.
  std::vector<class YieldStmt *> Yields;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::TaskDecl;
  }
};

//===----------------------------------------------------------------------===//
// Statements
//===----------------------------------------------------------------------===//

class Stmt : public Node {
public:
  static bool classof(const Node *N) {
    return N->getKind() >= NodeKind::BlockStmt &&
           N->getKind() <= NodeKind::ErrorStmt;
  }

protected:
  Stmt(NodeKind K, llvm::SMRange R) : Node(K, R) {}
};

/// An indented block of statements.
class BlockStmt : public Stmt {
public:
  explicit BlockStmt(llvm::SMRange R) : Stmt(NodeKind::BlockStmt, R) {}
  std::vector<Stmt *> Stmts;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::BlockStmt;
  }
};

/// A local declaration statement.
class DeclStmt : public Stmt {
public:
  DeclStmt(llvm::SMRange R, VarDecl *Var)
      : Stmt(NodeKind::DeclStmt, R), Var(Var) {}
  VarDecl *Var;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::DeclStmt;
  }
};

/// A `func` nested in a task body, at the point where it was declared.
class FuncDeclStmt : public Stmt {
public:
  FuncDeclStmt(llvm::SMRange R, FuncDecl *Func)
      : Stmt(NodeKind::FuncDeclStmt, R), Func(Func) {}
  FuncDecl *Func;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::FuncDeclStmt;
  }
};

/// `target = value`, `target += value`, ...
class AssignStmt : public Stmt {
public:
  AssignStmt(llvm::SMRange R, AssignOp Op, Expr *Target, Expr *Value)
      : Stmt(NodeKind::AssignStmt, R), Op(Op), Target(Target), Value(Value) {}
  AssignOp Op;
  Expr *Target;
  Expr *Value;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::AssignStmt;
  }
};

/// An expression used as a statement (Sema allows only calls).
class ExprStmt : public Stmt {
public:
  ExprStmt(llvm::SMRange R, Expr *E) : Stmt(NodeKind::ExprStmt, R), E(E) {}
  Expr *E;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::ExprStmt;
  }
};

/// `if(cond)` block, optionally `else` block or `else if(...)`.
class IfStmt : public Stmt {
public:
  IfStmt(llvm::SMRange R, Expr *Cond, BlockStmt *Then, Stmt *Else)
      : Stmt(NodeKind::IfStmt, R), Cond(Cond), Then(Then), Else(Else) {}
  Expr *Cond;
  BlockStmt *Then;
  Stmt *Else; ///< Null, a BlockStmt, or an IfStmt for `else if`.
  llvm::SMLoc ElseLoc; ///< The `else` keyword, if any.
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::IfStmt;
  }
};

/// `for(init; cond; step)`; each part may be missing (null). Init is a
/// DeclStmt, AssignStmt or ExprStmt; Step an AssignStmt, ExprStmt or
/// YieldStmt. A missing Cond means true.
class ForStmt : public Stmt {
public:
  ForStmt(llvm::SMRange R, Stmt *Init, Expr *Cond, Stmt *Step,
          BlockStmt *Body)
      : Stmt(NodeKind::ForStmt, R), Init(Init), Cond(Cond), Step(Step),
        Body(Body) {}
  Stmt *Init;
  Expr *Cond;
  Stmt *Step;
  BlockStmt *Body;
  /// Sema: a task's loop whose every way round passes one of its yields,
  /// so it takes at most one pass per call of its task and cannot run
  /// away by itself: a cycle budget need not count it (CGBudget.cpp).
  bool YieldsEveryPass = false;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::ForStmt;
  }
};

class BreakStmt : public Stmt {
public:
  explicit BreakStmt(llvm::SMRange R) : Stmt(NodeKind::BreakStmt, R) {}
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::BreakStmt;
  }
};

class ContinueStmt : public Stmt {
public:
  explicit ContinueStmt(llvm::SMRange R) : Stmt(NodeKind::ContinueStmt, R) {}
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::ContinueStmt;
  }
};

/// `return [value]`.
class ReturnStmt : public Stmt {
public:
  ReturnStmt(llvm::SMRange R, Expr *Value)
      : Stmt(NodeKind::ReturnStmt, R), Value(Value) {}
  Expr *Value; ///< May be null.
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::ReturnStmt;
  }
};

/// `assert(cond)` or `assert(cond, "message")`: what must hold whenever
/// the statement runs (docs/language.md "Assertions"). The JIT checks it and
/// stops the cycle; an object checks it only with --assertions=count|trap.
class AssertStmt : public Stmt {
public:
  AssertStmt(llvm::SMRange R, Expr *Cond, class StringLiteralExpr *Message,
             bool IsAssume)
      : Stmt(NodeKind::AssertStmt, R), Cond(Cond), Message(Message),
        IsAssume(IsAssume) {}
  Expr *Cond;
  class StringLiteralExpr *Message; ///< May be null.
  /// `assume(cond)`: what the environment guarantees (`bsc verify` explores
  /// only inputs that satisfy it); it runs and fails as an `assert` does.
  bool IsAssume;
  llvm::StringRef getKeyword() const { return IsAssume ? "assume" : "assert"; }
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::AssertStmt;
  }
};

/// `yield [state]`: ends this step of the task; the next call resumes after
/// it. Without a value the state is running (1).
class YieldStmt : public Stmt {
public:
  YieldStmt(llvm::SMRange R, Expr *Value)
      : Stmt(NodeKind::YieldStmt, R), Value(Value) {}
  Expr *Value; ///< May be null.
  /// 1-based resume point of the code after this yield (Sema).
  unsigned ResumePoint = 0;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::YieldStmt;
  }
};

/// Stands for a statement that failed to parse (already diagnosed).
class ErrorStmt : public Stmt {
public:
  explicit ErrorStmt(llvm::SMRange R) : Stmt(NodeKind::ErrorStmt, R) {}
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::ErrorStmt;
  }
};

//===----------------------------------------------------------------------===//
// Expressions
//===----------------------------------------------------------------------===//

class Expr : public Node {
public:
  const Type *Ty = nullptr; ///< Sema; the error type after a diagnosed mistake.
  static bool classof(const Node *N) {
    return N->getKind() >= NodeKind::IntLiteralExpr &&
           N->getKind() <= NodeKind::ErrorExpr;
  }

protected:
  Expr(NodeKind K, llvm::SMRange R) : Node(K, R) {}
};

class IntLiteralExpr : public Expr {
public:
  IntLiteralExpr(llvm::SMRange R, int32_t Value)
      : Expr(NodeKind::IntLiteralExpr, R), Value(Value) {}
  int32_t Value;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::IntLiteralExpr;
  }
};

class FloatLiteralExpr : public Expr {
public:
  FloatLiteralExpr(llvm::SMRange R, float Value)
      : Expr(NodeKind::FloatLiteralExpr, R), Value(Value) {}
  float Value;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::FloatLiteralExpr;
  }
};

class BoolLiteralExpr : public Expr {
public:
  BoolLiteralExpr(llvm::SMRange R, bool Value)
      : Expr(NodeKind::BoolLiteralExpr, R), Value(Value) {}
  bool Value;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::BoolLiteralExpr;
  }
};

class StringLiteralExpr : public Expr {
public:
  StringLiteralExpr(llvm::SMRange R, std::string Value)
      : Expr(NodeKind::StringLiteralExpr, R), Value(std::move(Value)) {}
  std::string Value; ///< With escapes resolved.
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::StringLiteralExpr;
  }
};

/// What a NameExpr turned out to name (Sema).
enum class NameKind {
  Unresolved,
  Local,          ///< Local: a VarDecl.
  Param,          ///< Param: a ParamDecl.
  Callable,       ///< Callable: a FuncDecl or TaskDecl (only as a callee).
  NativeFunction, ///< NativeFn (only as a callee).
  EnumValue,      ///< EnumValue, of type Ty (an enum or TaskState).
  Constant,       ///< Const: a module constant, of its type.
  Input,          ///< The `input` global.
  Output,         ///< The `output` global.
};

/// A possibly qualified name: `x`, `Motion::walkTo`, `TaskState::done`.
class NameExpr : public Expr {
public:
  NameExpr(llvm::SMRange R, QualifiedName Name)
      : Expr(NodeKind::NameExpr, R), Name(std::move(Name)) {}
  QualifiedName Name;
  NameKind Kind = NameKind::Unresolved;  ///< Sema.
  VarDecl *Local = nullptr;              ///< Sema, for Local.
  ParamDecl *Param = nullptr;            ///< Sema, for Param.
  CallableDecl *Callable = nullptr;      ///< Sema, for Callable.
  const NativeFunction *NativeFn = nullptr; ///< Sema, for NativeFunction.
  int32_t EnumValue = 0;                 ///< Sema, for EnumValue.
  /// Sema, for EnumValue: written as `TaskState::done|running|failure`
  /// (a named state or a constant of the same number is not).
  bool BuiltinState = false;
  const ConstDecl *Const = nullptr;      ///< Sema, for Constant.
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::NameExpr;
  }
};

/// `base.member`: a field or property of a registered class value, or the
/// method of a method call (then the CallExpr's callee).
class MemberExpr : public Expr {
public:
  MemberExpr(llvm::SMRange R, Expr *Base, Ident Member)
      : Expr(NodeKind::MemberExpr, R), Base(Base), Member(Member) {}
  Expr *Base;
  Ident Member;
  /// Sema: the member of the base's class it names (Field, Property or
  /// Method; the class is Resolved->Owner). Ty is the field's or
  /// property's type, or for a method callee its result type.
  const NativeFunction *Resolved = nullptr;
  /// Sema, at the REPL's prompt only: `Striker.state` reads this parameter
  /// or local of the task named by Base (a VarDecl or ParamDecl kept in
  /// its frame); Resolved is then null.
  const Decl *TaskField = nullptr;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::MemberExpr;
  }
};

/// `base[index]`: an element of an array field (`output.wide[k]`,
/// `input.m[1][2]`). The base has an array type; the element is stored as
/// the field declares it (Sema's ElementStorage), Stride bytes apart.
class IndexExpr : public Expr {
public:
  IndexExpr(llvm::SMRange R, Expr *Base, Expr *Index)
      : Expr(NodeKind::IndexExpr, R), Base(Base), Index(Index) {}
  Expr *Base;
  Expr *Index;
  /// Sema: the number of elements, and the bytes between two of them.
  uint32_t Extent = 0;
  uint64_t Stride = 0;
  /// Sema: the index when it is a constant (then checked against Extent);
  /// otherwise generated code clamps it into [0, Extent - 1].
  std::optional<int32_t> ConstIndex;
  /// Sema: the array field's native type (element storage and extents).
  const NativeType *Field = nullptr;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::IndexExpr;
  }
};

/// What a call calls (Sema).
enum class CallKind {
  Unresolved,
  Func,           ///< Target, a FuncDecl.
  Task,           ///< Target, a TaskDecl.
  NativeFunction, ///< NativeFn, a module function (`io::printi`, `Math::fabs`).
  Method,         ///< NativeFn, a method of the callee MemberExpr's base.
};

/// `callee(args)`; the callee is a NameExpr (or a MemberExpr for methods).
class CallExpr : public Expr {
public:
  CallExpr(llvm::SMRange R, Expr *Callee, std::vector<Expr *> Args)
      : Expr(NodeKind::CallExpr, R), Callee(Callee), Args(std::move(Args)) {}
  Expr *Callee;
  std::vector<Expr *> Args;
  CallKind Kind = CallKind::Unresolved;   ///< Sema.
  CallableDecl *Target = nullptr;         ///< Sema, for Func and Task.
  /// Sema, for NativeFunction and Method: the registered member.
  const NativeFunction *NativeFn = nullptr;
  /// Sema: how many of the trailing Args Sema appended from the callee's
  /// defaults (a binding's `.defaults(...)`, a script parameter's `=
  /// value`), as literals typed as the parameters; the source wrote
  /// Args.size() - NumDefaultArgs of them.
  unsigned NumDefaultArgs = 0;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::CallExpr;
  }
};

class UnaryExpr : public Expr {
public:
  UnaryExpr(llvm::SMRange R, UnaryOp Op, Expr *Operand)
      : Expr(NodeKind::UnaryExpr, R), Op(Op), Operand(Operand) {}
  UnaryOp Op;
  Expr *Operand;
  /// Sema: for `-` on a class value, the method `_neg_` it calls.
  const NativeFunction *Operator = nullptr;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::UnaryExpr;
  }
};

class BinaryExpr : public Expr {
public:
  BinaryExpr(llvm::SMRange R, BinaryOp Op, Expr *LHS, Expr *RHS)
      : Expr(NodeKind::BinaryExpr, R), Op(Op), LHS(LHS), RHS(RHS) {}
  BinaryOp Op;
  Expr *LHS;
  Expr *RHS;
  /// Sema: for a class-typed LHS, the method of the LHS's class that the
  /// operator calls with RHS as its argument (`+` is `_plus_`, ...;
  /// docs/bindings.md "Operator names"). Ty is its result type.
  const NativeFunction *Operator = nullptr;
  /// Sema: `==`/`!=` between task states where one side is the named
  /// state `TaskState::running` or `TaskState::failure` test the kind of
  /// the other (> 0, < 0), not its number (docs/language.md, Tasks).
  enum class StateKindTest { None, Running, Failure } StateTest =
      StateKindTest::None;
  /// With StateTest: whether the named state is the left operand.
  bool NamedStateOnLeft = false;
  /// Sema: `!=` through `_eq_` (the class registers no `_ne_`): the result
  /// of Operator is negated.
  bool NegateOperator = false;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::BinaryExpr;
  }
};

/// `taskState(Module::task)`: the state the task left at its last call.
class TaskStateExpr : public Expr {
public:
  TaskStateExpr(llvm::SMRange R, QualifiedName TaskName)
      : Expr(NodeKind::TaskStateExpr, R), TaskName(std::move(TaskName)) {}
  QualifiedName TaskName;
  TaskDecl *Task = nullptr; ///< Sema.
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::TaskStateExpr;
  }
};

/// An explicit conversion `int(x)`, `float(x)`, `bool(x)` (TargetName set),
/// or an implicit int-to-float promotion inserted by Sema (Implicit).
class ConversionExpr : public Expr {
public:
  ConversionExpr(llvm::SMRange R, QualifiedName TargetName, Expr *Operand,
                 bool Implicit)
      : Expr(NodeKind::ConversionExpr, R), TargetName(std::move(TargetName)),
        Operand(Operand), Implicit(Implicit) {}
  QualifiedName TargetName;
  Expr *Operand;
  bool Implicit;
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::ConversionExpr;
  }
};

/// Stands for an expression that failed to parse (already diagnosed).
class ErrorExpr : public Expr {
public:
  explicit ErrorExpr(llvm::SMRange R) : Expr(NodeKind::ErrorExpr, R) {}
  static bool classof(const Node *N) {
    return N->getKind() == NodeKind::ErrorExpr;
  }
};

//===----------------------------------------------------------------------===//
// Modules and the context that owns them
//===----------------------------------------------------------------------===//

/// `requires "Name"`.
struct RequireDecl {
  std::string Name;
  llvm::SMRange Range;                  ///< The string literal.
  ModuleAST *Script = nullptr;          ///< Module loader: a .bs module...
  const NativeModule *Native = nullptr; ///< ...or a native one.
};

/// One source file.
class ModuleAST {
public:
  std::string Name;      ///< The file name without `.bs`.
  std::string Path;      ///< As given or found.
  unsigned BufferID = 0; ///< In the compilation's llvm::SourceMgr.
  /// The text of that buffer (set by the parser), so that dumpAST can turn
  /// node locations into line:col without a SourceMgr.
  llvm::StringRef Source;
  std::vector<RequireDecl> Requires;
  /// The funcs and tasks at module scope, in source order.
  std::vector<CallableDecl *> Decls;
  /// The constants, in source order.
  std::vector<ConstDecl *> Consts;
  /// The enums, in source order.
  std::vector<EnumDecl *> Enums;
  /// Given with `bsc verify --model`: its funcs stand for registered C++.
  bool IsModel = false;
};

/// Owns every node, module and type of one compilation.
class ASTContext {
public:
  template <typename T, typename... Args> T *create(Args &&...A) {
    Nodes.push_back(std::make_unique<T>(std::forward<Args>(A)...));
    return static_cast<T *>(Nodes.back().get());
  }
  ModuleAST *createModule() {
    Modules.push_back(std::make_unique<ModuleAST>());
    return Modules.back().get();
  }
  /// Modules in the order they were created.
  std::vector<ModuleAST *> getModules() const;
  TypeContext &getTypes() { return Types; }
  /// A copy of `S` that lives as long as the context: names of nodes made
  /// without source text (the REPL's lines).
  llvm::StringRef saveString(llvm::StringRef S) { return Saver.save(S); }

private:
  llvm::BumpPtrAllocator Alloc;
  llvm::StringSaver Saver{Alloc};
  std::vector<std::unique_ptr<Node>> Nodes;
  std::vector<std::unique_ptr<ModuleAST>> Modules;
  TypeContext Types;
};

/// Prints a module as an indented tree (`bsc --emit=ast`); types and
/// resolutions are shown when Sema has run.
void dumpAST(const ModuleAST &M, llvm::raw_ostream &OS);

/// Calls `Fn` on each child of `N` that is there, in source order: a
/// callable's parameters and body, a variable's initialiser, a
/// statement's statements and expressions, an expression's operands (a
/// call's arguments include those Sema appended from defaults, the
/// parameter's own default expressions). For walks that only recurse; a
/// walk that decides per node keeps an exhaustive switch. Generated from
/// ASTNodes.def: a node kind without its children does not compile.
void forEachChild(const Node &N, llvm::function_ref<void(const Node &)> Fn);

} // namespace bsc

#endif
