//===- ViewDifference.cpp - the first value where two views differ -------===//
//
// A re-run (the REPL's time travel, an exact replay) checks itself against
// the live run by the bytes of the state, `input` and `output`; when they
// differ, the user is told the first value that differs by its name, not a
// byte offset: a task's field, its state or resume point, or a member of
// `input` or `output`.
//
//===----------------------------------------------------------------------===//
#include "bsc/Run/Run.h"
#include "bsc/AST/AST.h"
#include <cstring>

using namespace bsc;

/// `Task.field`, or the task word, holding state byte `Off`; empty if none.
static std::string describeStateByte(debug::ValueIO &Values,
                                     const LoadedBehavior &L, uint64_t Off,
                                     const unsigned char *Live,
                                     const unsigned char *Rerun) {
  auto Word = [&](const char *What, const BehaviorLayout::Task &T,
                  uint64_t At, unsigned Bytes) -> std::string {
    int64_t A = 0, B = 0;
    std::memcpy(&A, Live + At, Bytes);
    std::memcpy(&B, Rerun + At, Bytes);
    return std::string(What) + " of task '" + T.Decl->getQualifiedName() +
           "' is " + std::to_string(B) + "; the live run left " +
           std::to_string(A);
  };
  for (const BehaviorLayout::Task &T : L.Layout.Tasks) {
    if (Off < T.FrameOffset || Off >= T.FrameOffset + T.FrameSize)
      continue;
    if (Off >= T.State.Offset && Off < T.State.Offset + T.State.Bytes)
      return Word("the state", T, T.State.Offset, T.State.Bytes);
    if (Off >= T.Resume.Offset && Off < T.Resume.Offset + T.Resume.Bytes)
      return Word("the resume point", T, T.Resume.Offset, T.Resume.Bytes);
    if (Off < T.FrameOffset + 4)
      return Word("the last call", T, T.FrameOffset, 4);
    const BehaviorLayout::FrameField *Field = nullptr;
    for (const BehaviorLayout::FrameField &F : T.Fields)
      if (F.Offset <= Off && (!Field || F.Offset > Field->Offset))
        Field = &F;
    if (!Field)
      break;
    std::string Name = T.Decl->getQualifiedName() + "." +
                       Field->D->getName().Name.str();
    return "'" + Name + "' is " +
           debug::formatValue(Field->Ty,
                              Values.read(Field->Ty, Rerun + Field->Offset)) +
           "; the live run left " +
           debug::formatValue(Field->Ty,
                              Values.read(Field->Ty, Live + Field->Offset));
  }
  if (Off < sizeof(bs_state_header))
    return "the state's header (cycle, input, output, user pointer) differs";
  return "byte " + std::to_string(Off) + " of the state differs";
}

std::string bsc::describeViewDifference(debug::ValueIO &Values,
                                        const LoadedBehavior &L,
                                        const BehaviorSession &S,
                                        llvm::ArrayRef<unsigned char> Live) {
  size_t Sizes[3];
  S.getViewSizes(Sizes);
  const void *Blocks[3] = {S.getState(), S.getInput(), S.getOutput()};
  size_t Base = 0;
  for (unsigned B = 0; B < 3; ++B) {
    const auto *Now = static_cast<const unsigned char *>(Blocks[B]);
    const unsigned char *Then = Live.data() + Base;
    for (size_t I = 0; I < Sizes[B]; ++I) {
      if (Now[I] == Then[I])
        continue;
      if (B == 0)
        return describeStateByte(Values, L, I, Then, Now);
      const NativeClass *C = B == 1 ? L.InputClass : L.OutputClass;
      const char *Name = B == 1 ? "input" : "output";
      if (C)
        if (std::optional<debug::Difference> D = debug::findDifference(
                Values.readClass(*C, Then), Values.readClass(*C, Now), Name))
          return D->Path + " is " + D->Got + "; the live run left " +
                 D->Recorded;
      return "byte " + std::to_string(I) + " of '" + Name +
             "' differs (a member bsc does not show)";
    }
    Base += Sizes[B];
  }
  return "";
}
