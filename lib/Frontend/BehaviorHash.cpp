//===- BehaviorHash.cpp - the identity a recording names --------------------===//
//
// A recording, a binary log and a robot's flight recorder name the behavior
// that made them by a hash of what decides the calls a cycle makes: its
// sources as read, what its binding modules register (names, kinds, types
// and flags, not where thunks lie: the same on every target) and its entry.
// A log whose hash is the loaded behavior's replays exactly.
//
//===----------------------------------------------------------------------===//
#include "bsc/Frontend/Frontend.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/xxhash.h"

using namespace bsc;

/// A registered type as the behavior sees it.
static void describeType(const NativeType &T, std::string &Text) {
  Text += std::to_string(T.TheCode) + T.Name + (T.MutableRef ? "&" : "") +
          (T.Unsigned ? "u" : "");
  for (uint32_t E : T.Extents)
    Text += "[" + std::to_string(E) + "]";
}

/// A registered function or member as the behavior sees it: its name,
/// kind, types and flags, not its thunk or where its bytes lie.
static void describeFunction(const NativeFunction &F, std::string &Text) {
  Text += std::to_string(F.Kind) + " " + F.Name + "(";
  for (const NativeType &P : F.Params) {
    describeType(P, Text);
    Text += ",";
  }
  Text += ")";
  describeType(F.Result, Text);
  for (const NativeDefault &D : F.Defaults)
    Text += D.IsFloat ? " =" + std::to_string(D.Float)
                      : " =" + std::to_string(D.Int);
  Text += std::string(" ") + char('0' + F.ConstSelf) + char('0' + F.ReadOnly) +
          char('0' + F.ResultViaOut) + char('0' + F.TakesContext) +
          char('0' + F.Pure) + "\n";
}

/// What a binding module registers, the same on every target (a
/// descriptor's own hash sees its sizes and offsets, which differ between
/// the robot's i586 object and the workstation's): the robot's log and the
/// workstation's build of the same bindings name one behavior.
static void describeModule(const NativeModule &M, std::string &Text) {
  Text += "module " + M.Name + "\n";
  for (const NativeConstant &K : M.Constants) {
    Text += "const " + K.Name + " ";
    describeType(K.Type, Text);
    Text += " " + std::to_string(K.Int) + " " + std::to_string(K.Float) + "\n";
  }
  for (const NativeEnum &E : M.Enums) {
    Text += "enum " + E.Name;
    for (const NativeEnum::Value &V : E.Values)
      Text += " " + V.Name + "=" + std::to_string(V.Number);
    Text += "\n";
  }
  for (const NativeFunction &F : M.Functions)
    describeFunction(F, Text);
  for (const NativeClass &K : M.Classes) {
    Text += "class " + K.Name + " " + char('0' + K.DefaultConstructible) +
            char('0' + K.TriviallyDestructible) + char('0' + K.CopiesAsBytes) +
            "\n";
    for (const NativeFunction &F : K.Members)
      describeFunction(F, Text);
    for (const NativeFunction &F : K.Constructors)
      describeFunction(F, Text);
  }
  Text += std::string("world ") + (M.Input ? M.Input->Name : "") + " " +
          (M.Output ? M.Output->Name : "") + "\n";
}

std::string bsc::computeBehaviorHash(const Compilation &C,
                                    const CallableDecl &Entry) {
  // The sources as read, what the binding modules register and the entry:
  // what decides the calls a cycle makes, on any target.
  std::string Text = "bsc-behavior-2\n" + Entry.getQualifiedName() + "\n";
  for (const ModuleAST *M : C.Modules) {
    if (M->IsModel) // bsc verify's: the behavior never calls them.
      continue;
    Text += M->Name + "\n";
    Text += C.SM.getMemoryBuffer(M->BufferID)->getBuffer().str();
    Text += "\n";
  }
  for (const NativeModule *NM : C.Checked.NativeModules)
    describeModule(*NM, Text);
  return llvm::utohexstr(llvm::xxh3_64bits(Text), /*LowerCase=*/true, 16);
}
