//===- CGExplain.cpp - records of the conditions a cycle evaluated --------===//
//
// CodeGenOptions::Explain, for the REPL's `:why` (docs/repl.md): which way
// each `if` and `for` went in the last cycle, and why, as the values of
// the condition's sub-expressions. The JIT's code writes them into one log
// as it runs; the table of sites (BehaviorLayout::ExplainSites) says how
// to read it. So the values shown are those the behavior computed, not a
// re-evaluation after the cycle (which could differ: the input may have
// changed, and a func or a registered C++ function may have effects).
//
//   entry:      if (log.cycle != state.cycle) { log.cycle = state.cycle;
//                                               log.used = 0;
//                                               log.overflow = 0 }
//               log.active = 1; call the entry; log.active = 0
//   condition:  rec = bs.explain.begin(site, size)  (site, mask = 0)
//               each operand as it is computed: rec[offset] = value;
//                                              rec.mask |= 1 << k
//   task call:  bs.explain.begin(start site) at the top; before each
//               `ret`, a record of the state and resume point it leaves
//
// A record is reserved before its condition runs, so a func called in the
// condition writes its own records after it: the log is in the order the
// conditions began. The task marks let the reader attribute every
// condition to the task call that evaluated it (a func's conditions to its
// caller's), count the calls, and say how each call ended, without a
// caller in any record.
//
// The operands are the sub-expressions whose values say something: names
// of variables, members, elements, calls, operators, `taskState`, explicit
// conversions. Literals, constants and implicit conversions add nothing
// to the text; the objects of a data path (`input.ball` in
// `input.ball.position.x`) are left to its end. Only operands that ran
// have their bit in the mask: the right side of `&&` when the left was
// true, and so on.
//
// The log is a fixed global (ExplainLogHeader, then ExplainLogCapacity
// bytes of records and room for one scratch record): no allocation in
// generated code. A record that does not fit is counted, written to the
// scratch room, and closes the log for the rest of the cycle, so the log
// is always a prefix of the cycle's records. Calls made outside the entry
// (a REPL line, a watch) write to the scratch room too.
//
// Only the JIT's modules have it, like the probes: what the code computes
// does not change (the records only store values already computed), and
// objects for the robot never have the log. The stores carry no TBAA tag
// (they may alias anything), which costs the JIT's optimiser a little and
// keeps them from ever being reordered past what they record.
//
//===----------------------------------------------------------------------===//
#include "FunctionEmitter.h"
#include "llvm/IR/Constants.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/SourceMgr.h"
#include <cstddef>

using namespace bsc;
using namespace bsc::codegen;

static_assert(sizeof(ExplainLogHeader) == 16, "four uint32 words");
static_assert(offsetof(ExplainLogHeader, Cycle) == 0);
static_assert(offsetof(ExplainLogHeader, Active) == 4);
static_assert(offsetof(ExplainLogHeader, Used) == 8);
static_assert(offsetof(ExplainLogHeader, Overflow) == 12);

namespace {
/// The header's words, as fields of the log's IR type.
enum LogField { LogCycle, LogActive, LogUsed, LogOverflow, LogRecords };

/// The largest record: the header and 64 operands of the largest size.
constexpr uint32_t MaxRecordSize =
    ExplainRecordHeaderSize + MaxExplainOperands * MaxExplainedClassSize;
} // namespace

/// What a condition being lowered records: its site, the record's address
/// and where each operand goes.
struct FunctionEmitter::ExplainRecord {
  unsigned Site = 0; ///< Its number.
  llvm::Value *Record = nullptr;
  /// Operand -> index in Site->Operands.
  llvm::DenseMap<const Expr *, unsigned> Index;
  /// The operand whose value is being emitted: emitExpr of it emits it.
  const Expr *Current = nullptr;
};

//===----------------------------------------------------------------------===//
// The table: operands and their text
//===----------------------------------------------------------------------===//

/// The source text of a token-sized node (a literal).
static std::string getSourceText(const Node &N) {
  llvm::SMRange R = N.getRange();
  if (!R.Start.isValid() || !R.End.isValid() ||
      R.End.getPointer() < R.Start.getPointer())
    return "?";
  return std::string(R.Start.getPointer(),
                     R.End.getPointer() - R.Start.getPointer());
}

/// The number of source arguments of a call (Sema appends the defaults).
static llvm::ArrayRef<Expr *> getWrittenArgs(const CallExpr &C) {
  return llvm::ArrayRef<Expr *>(C.Args).drop_back(C.NumDefaultArgs);
}

/// A binding strength for parenthesising: binary operators by precedence,
/// unary and postfix ones above them all.
static unsigned getStrength(const Expr *E) {
  if (const auto *C = llvm::dyn_cast<ConversionExpr>(E))
    if (C->Implicit)
      return getStrength(C->Operand);
  if (const auto *B = llvm::dyn_cast<BinaryExpr>(E))
    return getPrecedence(B->Op);
  if (llvm::isa<UnaryExpr>(E))
    return 100;
  return 200;
}

/// `E` as b-script, with the parentheses its structure needs. Written out
/// from the tree rather than cut from the source: a node's range starts at
/// its first operand, inside any parenthesis before it.
static std::string printExpr(const Expr *E) {
  auto Wrap = [](const Expr *Child, bool Paren) {
    std::string S = printExpr(Child);
    return Paren ? "(" + S + ")" : S;
  };
  switch (E->getKind()) {
  case NodeKind::IntLiteralExpr:
  case NodeKind::FloatLiteralExpr:
  case NodeKind::StringLiteralExpr:
    return getSourceText(*E);
  case NodeKind::BoolLiteralExpr:
    return llvm::cast<BoolLiteralExpr>(E)->Value ? "true" : "false";
  case NodeKind::NameExpr:
    return llvm::cast<NameExpr>(E)->Name.str();
  case NodeKind::MemberExpr: {
    const auto *M = llvm::cast<MemberExpr>(E);
    return Wrap(M->Base, getStrength(M->Base) < 200) + "." +
           M->Member.Name.str();
  }
  case NodeKind::IndexExpr: {
    const auto *I = llvm::cast<IndexExpr>(E);
    return Wrap(I->Base, getStrength(I->Base) < 200) + "[" +
           printExpr(I->Index) + "]";
  }
  case NodeKind::CallExpr: {
    const auto *C = llvm::cast<CallExpr>(E);
    std::string S = Wrap(C->Callee, getStrength(C->Callee) < 200) + "(";
    llvm::ArrayRef<Expr *> Args = getWrittenArgs(*C);
    for (size_t I = 0; I < Args.size(); ++I)
      S += (I ? ", " : "") + printExpr(Args[I]);
    return S + ")";
  }
  case NodeKind::UnaryExpr: {
    const auto *U = llvm::cast<UnaryExpr>(E);
    return getSpelling(U->Op).str() +
           Wrap(U->Operand, getStrength(U->Operand) < 100);
  }
  case NodeKind::BinaryExpr: {
    // Left-associative: a right operand of the same strength needs them.
    const auto *B = llvm::cast<BinaryExpr>(E);
    unsigned P = getPrecedence(B->Op);
    return Wrap(B->LHS, getStrength(B->LHS) < P) + " " +
           getSpelling(B->Op).str() + " " +
           Wrap(B->RHS, getStrength(B->RHS) <= P);
  }
  case NodeKind::TaskStateExpr:
    return "taskState(" + llvm::cast<TaskStateExpr>(E)->TaskName.str() + ")";
  case NodeKind::ConversionExpr: {
    const auto *C = llvm::cast<ConversionExpr>(E);
    if (C->Implicit)
      return printExpr(C->Operand);
    return C->TargetName.str() + "(" + printExpr(C->Operand) + ")";
  }
  case NodeKind::ErrorExpr:
    break;
#define DECL(Class) case NodeKind::Class:
#define STMT(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    break;
  }
  llvm_unreachable("Sema leaves only expressions in conditions");
}

/// The bytes a value of `T` takes in a record, with its alignment; 0 for
/// values that are not recorded.
static std::pair<uint32_t, uint32_t> getRecordedSize(const Type *T) {
  if (!T)
    return {0, 0};
  if (T->isInt() || T->isFloat() || T->isBool() || T->isTaskState() ||
      T->isEnum())
    return {4, 4};
  if (T->isClass()) {
    const NativeClass *C = T->getClass();
    // A copy of its bytes is a value the debugger can read (its getters
    // run on the copy) only for classes that copy as bytes.
    if (C->CopiesAsBytes && C->Size > 0 && C->Size <= MaxExplainedClassSize &&
        C->Align <= 8)
      return {uint32_t(C->Size), uint32_t(std::max<uint64_t>(C->Align, 1))};
  }
  return {0, 0};
}

/// Whether `E` is an operand worth a value: see the file comment.
static bool isExplained(const Expr *E) {
  switch (E->getKind()) {
  case NodeKind::NameExpr: {
    NameKind K = llvm::cast<NameExpr>(E)->Kind;
    return K == NameKind::Local || K == NameKind::Param;
  }
  case NodeKind::ConversionExpr:
    return !llvm::cast<ConversionExpr>(E)->Implicit;
  case NodeKind::MemberExpr:
  case NodeKind::IndexExpr:
  case NodeKind::CallExpr:
  case NodeKind::UnaryExpr:
  case NodeKind::BinaryExpr:
  case NodeKind::TaskStateExpr:
    return true;
  case NodeKind::IntLiteralExpr: // Its value is in its text.
  case NodeKind::FloatLiteralExpr:
  case NodeKind::BoolLiteralExpr:
  case NodeKind::StringLiteralExpr:
  case NodeKind::ErrorExpr:
    return false;
#define DECL(Class) case NodeKind::Class:
#define STMT(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    break;
  }
  llvm_unreachable("not an expression");
}

/// Calls `Part` with `E` and each operand below it worth a value, in the
/// order they run, with the index its enclosing operand got (-1: none);
/// `Part` returns the index `E` gets, or `Parent` if it takes none.
/// `DataBase`: E is the object of a data member or element, whose value
/// the member's shows.
static void walkOperands(const Expr *E, int Parent, bool DataBase,
                         llvm::function_ref<int(const Expr *, int)> Part) {
  if (!DataBase && isExplained(E))
    Parent = Part(E, Parent);
  auto Walk = [&](const Expr *Child, bool IsDataBase = false) {
    walkOperands(Child, Parent, IsDataBase, Part);
  };
  switch (E->getKind()) {
  case NodeKind::MemberExpr:
    Walk(llvm::cast<MemberExpr>(E)->Base, /*IsDataBase=*/true);
    return;
  case NodeKind::IndexExpr: {
    const auto *I = llvm::cast<IndexExpr>(E);
    Walk(I->Base, /*IsDataBase=*/true);
    Walk(I->Index);
    return;
  }
  case NodeKind::CallExpr: {
    // A method's object is a value of its own (`p.abs()`: which p).
    const auto *C = llvm::cast<CallExpr>(E);
    if (C->Kind == CallKind::Method)
      Walk(llvm::cast<MemberExpr>(C->Callee)->Base);
    for (const Expr *A : getWrittenArgs(*C))
      Walk(A);
    return;
  }
  case NodeKind::UnaryExpr:
    Walk(llvm::cast<UnaryExpr>(E)->Operand);
    return;
  case NodeKind::BinaryExpr:
    Walk(llvm::cast<BinaryExpr>(E)->LHS);
    Walk(llvm::cast<BinaryExpr>(E)->RHS);
    return;
  case NodeKind::ConversionExpr:
    Walk(llvm::cast<ConversionExpr>(E)->Operand);
    return;
  case NodeKind::IntLiteralExpr: // No operands.
  case NodeKind::FloatLiteralExpr:
  case NodeKind::BoolLiteralExpr:
  case NodeKind::StringLiteralExpr:
  case NodeKind::NameExpr:
  case NodeKind::TaskStateExpr: // Its task is no value.
  case NodeKind::ErrorExpr:
    return;
#define DECL(Class) case NodeKind::Class:
#define STMT(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    break;
  }
  llvm_unreachable("not an expression");
}

/// Adds the condition `E` and the operands below it that a record can
/// hold to `Site`.
static void collectOperands(ExplainSite &Site, const Expr *E) {
  walkOperands(E, -1, false, [&](const Expr *Op, int Parent) {
    if (Site.Operands.size() >= MaxExplainOperands ||
        !getRecordedSize(Op->Ty).first)
      return Parent;
    Site.Operands.push_back({Op, printExpr(Op), Op->Ty, Parent, 0});
    return int(Site.Operands.size() - 1);
  });
}

std::vector<ExpressionPart> bsc::listExpressionParts(const Expr &E) {
  std::vector<ExpressionPart> Parts;
  walkOperands(&E, -1, false, [&](const Expr *Op, int Parent) {
    Parts.push_back({Op, printExpr(Op), Parent});
    return int(Parts.size() - 1);
  });
  return Parts;
}

/// Places the operands' values after the record's header.
static void layoutRecord(ExplainSite &Site) {
  uint32_t Offset = ExplainRecordHeaderSize;
  for (ExplainSite::Operand &O : Site.Operands) {
    auto [Size, Align] = getRecordedSize(O.Ty);
    Offset = llvm::alignTo(Offset, Align);
    O.Offset = Offset;
    Offset += Size;
  }
  Site.RecordSize = llvm::alignTo(Offset, 8);
  assert(Site.RecordSize <= MaxRecordSize && "the scratch room holds it");
}

/// A site at `Loc` in `In`, with its file and line.
static ExplainSite makeSite(ExplainSite::SiteKind Kind, const CallableDecl &In,
                            llvm::SMLoc Loc, const llvm::SourceMgr *SM) {
  ExplainSite Site{Kind, &In, Loc, "", 0, {}, 0};
  assert(SM && "CodeGenOptions::Explain needs the sources");
  if (unsigned Buffer = SM->FindBufferContainingLoc(Loc)) {
    Site.File = llvm::sys::path::filename(
                    SM->getMemoryBuffer(Buffer)->getBufferIdentifier())
                    .str();
    Site.Line = SM->FindLineNumber(Loc, Buffer);
  }
  return Site;
}

//===----------------------------------------------------------------------===//
// The log
//===----------------------------------------------------------------------===//

unsigned ModuleEmitter::addExplainSite(ExplainSite Site) {
  Layout.ExplainSites.push_back(std::move(Site));
  return Layout.ExplainSites.size();
}

/// `bs.explain.log`: the header words, then the records and the scratch
/// room, 8-aligned (records hold class values of up to 8-byte alignment).
static llvm::GlobalVariable *getExplainLog(llvm::Module &M) {
  if (llvm::GlobalVariable *G = M.getGlobalVariable(ExplainLogSymbol))
    return G;
  llvm::LLVMContext &Ctx = M.getContext();
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  auto *Ty = llvm::StructType::get(
      Ctx, {I32, I32, I32, I32,
            llvm::ArrayType::get(llvm::Type::getInt8Ty(Ctx),
                                 ExplainLogCapacity + MaxRecordSize)});
  auto *G = new llvm::GlobalVariable(
      M, Ty, /*isConstant=*/false, llvm::GlobalValue::ExternalLinkage,
      llvm::Constant::getNullValue(Ty), ExplainLogSymbol);
  G->setAlignment(llvm::Align(8));
  return G;
}

static llvm::Value *getLogField(llvm::IRBuilderBase &IRB,
                                llvm::GlobalVariable *Log, LogField F) {
  return IRB.CreateConstInBoundsGEP2_32(Log->getValueType(), Log, 0, F);
}

llvm::Function *ModuleEmitter::getExplainBegin() {
  const char *Name = "bs.explain.begin";
  if (llvm::Function *F = M.getFunction(Name))
    return F;
  llvm::GlobalVariable *Log = getExplainLog(M);
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  auto *F =
      llvm::Function::Create(llvm::FunctionType::get(Ptr, {I32, I32}, false),
                             llvm::GlobalValue::InternalLinkage, Name, M);
  addCommonAttributes(F);
  llvm::Value *Site = F->getArg(0), *Size = F->getArg(1);
  Site->setName("site");
  Size->setName("size");
  auto Block = [&](const char *N) {
    return llvm::BasicBlock::Create(Ctx, N, F);
  };
  llvm::BasicBlock *Entry = Block("entry"), *Try = Block("try"),
                   *Take = Block("take"), *Full = Block("full"),
                   *Init = Block("init");
  llvm::IRBuilder<> IRB(Entry);
  llvm::Value *Records = getLogField(IRB, Log, LogRecords);
  llvm::Value *Scratch = IRB.CreateConstInBoundsGEP1_32(
      IRB.getInt8Ty(), Records, ExplainLogCapacity, "scratch");
  llvm::Value *Active = IRB.CreateLoad(I32, getLogField(IRB, Log, LogActive));
  IRB.CreateCondBr(IRB.CreateICmpNE(Active, IRB.getInt32(0)), Try, Init);

  // The log's next Size bytes, if it has them (unsigned: no overflow).
  IRB.SetInsertPoint(Try);
  llvm::Value *UsedAddr = getLogField(IRB, Log, LogUsed);
  llvm::Value *Used = IRB.CreateLoad(I32, UsedAddr, "used");
  llvm::Value *Left = IRB.CreateSub(IRB.getInt32(ExplainLogCapacity), Used);
  IRB.CreateCondBr(IRB.CreateICmpULE(Size, Left, "fits"), Take, Full);

  IRB.SetInsertPoint(Take);
  IRB.CreateStore(IRB.CreateAdd(Used, Size), UsedAddr);
  llvm::Value *Taken =
      IRB.CreateInBoundsGEP(IRB.getInt8Ty(), Records, Used, "record");
  IRB.CreateBr(Init);

  // Full: counted, and closed for the rest of the cycle.
  IRB.SetInsertPoint(Full);
  llvm::Value *OverflowAddr = getLogField(IRB, Log, LogOverflow);
  IRB.CreateStore(
      IRB.CreateAdd(IRB.CreateLoad(I32, OverflowAddr), IRB.getInt32(1)),
      OverflowAddr);
  IRB.CreateStore(IRB.getInt32(ExplainLogCapacity), UsedAddr);
  IRB.CreateBr(Init);

  IRB.SetInsertPoint(Init);
  llvm::PHINode *Record = IRB.CreatePHI(Ptr, 3, "record");
  Record->addIncoming(Scratch, Entry);
  Record->addIncoming(Taken, Take);
  Record->addIncoming(Scratch, Full);
  IRB.CreateAlignedStore(Site, Record, llvm::Align(8));
  IRB.CreateAlignedStore(
      IRB.getInt64(0),
      IRB.CreateConstInBoundsGEP1_32(IRB.getInt8Ty(), Record, 8),
      llvm::Align(8));
  IRB.CreateRet(Record);
  return F;
}

void ModuleEmitter::emitExplainEntryStart(llvm::IRBuilderBase &IRB,
                                          llvm::Value *State) {
  if (!Opts.Explain)
    return;
  llvm::GlobalVariable *Log = getExplainLog(M);
  llvm::Type *I32 = IRB.getInt32Ty();
  llvm::Value *Cycle = IRB.CreateLoad(
      I32, IRB.CreateConstInBoundsGEP2_32(StateTy, State, 0, StateCycle),
      "cycle");
  llvm::Value *CycleAddr = getLogField(IRB, Log, LogCycle);
  llvm::Value *Same = IRB.CreateICmpEQ(IRB.CreateLoad(I32, CycleAddr), Cycle);
  // Without branches: the same cycle keeps what the log holds.
  IRB.CreateStore(Cycle, CycleAddr);
  for (LogField F : {LogUsed, LogOverflow}) {
    llvm::Value *Addr = getLogField(IRB, Log, F);
    IRB.CreateStore(
        IRB.CreateSelect(Same, IRB.CreateLoad(I32, Addr), IRB.getInt32(0)),
        Addr);
  }
  IRB.CreateStore(IRB.getInt32(1), getLogField(IRB, Log, LogActive));
}

void ModuleEmitter::emitExplainEntryEnd(llvm::IRBuilderBase &IRB) {
  if (Opts.Explain)
    IRB.CreateStore(IRB.getInt32(0),
                    getLogField(IRB, getExplainLog(M), LogActive));
}

//===----------------------------------------------------------------------===//
// Conditions and task calls
//===----------------------------------------------------------------------===//

llvm::Value *FunctionEmitter::emitCondition(const Stmt &S, const Expr *Cond) {
  llvm::Value *Holds = emitExplainedCondition(S, Cond);
  emitBranchCount(S, Cond, Holds);
  return Holds;
}

llvm::Value *FunctionEmitter::emitExplainedCondition(const Stmt &S,
                                                     const Expr *Cond) {
  // `for(; true; yield)` says all there is to say.
  if (!CGM.getOptions().Explain || Explaining ||
      llvm::isa<BoolLiteralExpr>(Cond))
    return emitFullCond(Cond);
  return emitRecordedCond(
      llvm::isa<ForStmt>(S) ? ExplainSite::For : ExplainSite::If, S.getLoc(),
      Cond, [&](unsigned Number, uint32_t Size) -> llvm::Value * {
        return Builder.CreateCall(
            CGM.getExplainBegin(),
            {Builder.getInt32(Number), Builder.getInt32(Size)}, "explain");
      });
}

llvm::Value *FunctionEmitter::emitRecordedCond(
    ExplainSite::SiteKind Kind, llvm::SMLoc Loc, const Expr *Cond,
    llvm::function_ref<llvm::Value *(unsigned, uint32_t)> BeginRecord) {
  ExplainSite Site = makeSite(Kind, D, Loc, CGM.getOptions().Sources);
  collectOperands(Site, Cond);
  // The condition is always operand 0, whose value says which way it
  // went; one that is not an operand by itself (a constant's name) comes
  // first with nothing under it.
  if (Site.Operands.empty() || Site.Operands[0].E != Cond) {
    Site.Operands.insert(Site.Operands.begin(),
                         {Cond, printExpr(Cond), Cond->Ty, -1, 0});
    for (ExplainSite::Operand &O : llvm::drop_begin(Site.Operands))
      if (O.Parent >= 0)
        ++O.Parent;
  }
  layoutRecord(Site);
  uint32_t Size = Site.RecordSize;
  unsigned Number = CGM.addExplainSite(std::move(Site));

  ExplainRecord R;
  R.Site = Number;
  const ExplainSite &Added = CGM.getLayout().ExplainSites[Number - 1];
  for (unsigned I = 0; I < Added.Operands.size(); ++I)
    R.Index[Added.Operands[I].E] = I;
  R.Record = BeginRecord(Number, Size);
  Explaining = &R;
  llvm::Value *V = emitFullCond(Cond);
  Explaining = nullptr;
  return V;
}

llvm::Value *FunctionEmitter::emitExplainedOperand(const Expr *E) {
  ExplainRecord &R = *Explaining;
  auto It = R.Index.find(E);
  if (It == R.Index.end() || R.Current == E)
    return nullptr;
  const Expr *Outer = R.Current;
  R.Current = E;
  llvm::Value *V = emitExpr(E);
  R.Current = Outer;
  // (Emitting E adds no site, so the table stays where it is.)
  const ExplainSite::Operand &O =
      CGM.getLayout().ExplainSites[R.Site - 1].Operands[It->second];

  llvm::Value *Slot = Builder.CreateConstInBoundsGEP1_32(
      Builder.getInt8Ty(), R.Record, O.Offset, "explain.value");
  if (O.Ty->isClass()) {
    // The value is its storage: a copy of its bytes.
    for (uint32_t Off = 0; Off < O.Ty->getClass()->Size; ++Off)
      Builder.CreateStore(
          Builder.CreateLoad(
              Builder.getInt8Ty(),
              Builder.CreateConstInBoundsGEP1_32(Builder.getInt8Ty(), V, Off)),
          Builder.CreateConstInBoundsGEP1_32(Builder.getInt8Ty(), Slot, Off));
  } else {
    llvm::Value *Stored = V;
    if (V->getType()->isIntegerTy(1)) // As a variable holds it.
      Stored = Builder.CreateZExt(V, Builder.getInt8Ty());
    Builder.CreateAlignedStore(Stored, Slot, llvm::Align(4));
  }
  llvm::Value *MaskAddr = Builder.CreateConstInBoundsGEP1_32(
      Builder.getInt8Ty(), R.Record, 8, "explain.mask");
  llvm::Value *Mask =
      Builder.CreateAlignedLoad(Builder.getInt64Ty(), MaskAddr, llvm::Align(8));
  Builder.CreateAlignedStore(
      Builder.CreateOr(Mask, Builder.getInt64(uint64_t(1) << It->second)),
      MaskAddr, llvm::Align(8));
  return V;
}

void FunctionEmitter::emitExplainTaskMarks() {
  const llvm::SourceMgr *SM = CGM.getOptions().Sources;
  ExplainSite StartSite = makeSite(ExplainSite::TaskStart, D, D.getLoc(), SM);
  StartSite.RecordSize = ExplainRecordHeaderSize;
  unsigned Start = CGM.addExplainSite(std::move(StartSite));
  ExplainSite EndSite = makeSite(ExplainSite::TaskEnd, D, D.getLoc(), SM);
  EndSite.RecordSize = llvm::alignTo(ExplainTaskEndResume + 4, 8);
  uint32_t EndSize = EndSite.RecordSize;
  unsigned End = CGM.addExplainSite(std::move(EndSite));
  llvm::Function *Begin = CGM.getExplainBegin();

  // The instructions go where they run, with that place's line (a call in
  // a function with debug information needs one).
  llvm::IRBuilderBase::InsertPointGuard Guard(Builder);
  llvm::Instruction *First = EntryPoint->getNextNode();
  Builder.SetInsertPoint(First);
  Builder.SetCurrentDebugLocation(First->getDebugLoc());
  Builder.CreateCall(Begin, {Builder.getInt32(Start),
                             Builder.getInt32(ExplainRecordHeaderSize)});

  llvm::SmallVector<llvm::ReturnInst *, 8> Returns;
  for (llvm::BasicBlock &BB : *Fn)
    if (auto *Ret = llvm::dyn_cast<llvm::ReturnInst>(BB.getTerminator()))
      Returns.push_back(Ret);
  for (llvm::ReturnInst *Ret : Returns) {
    Builder.SetInsertPoint(Ret);
    Builder.SetCurrentDebugLocation(Ret->getDebugLoc());
    llvm::Value *Record = Builder.CreateCall(
        Begin, {Builder.getInt32(End), Builder.getInt32(EndSize)}, "explain");
    Builder.CreateAlignedStore(
        loadTaskState(Task, "explain.state"),
        Builder.CreateConstInBoundsGEP1_32(Builder.getInt8Ty(), Record,
                                           ExplainTaskEndState),
        llvm::Align(4));
    Builder.CreateAlignedStore(
        Builder.CreateZExt(loadResume(Task), Builder.getInt32Ty()),
        Builder.CreateConstInBoundsGEP1_32(Builder.getInt8Ty(), Record,
                                           ExplainTaskEndResume),
        llvm::Align(4));
  }
}
