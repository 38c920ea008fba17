//===- CommandLine.cpp - checking bsc's words before llvm::cl -------------===//
#include "bsc/Driver/CommandLine.h"
#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/FileSystem.h"
#include <optional>
#include <string>
#include <vector>

using namespace bsc;
namespace cl = llvm::cl;

bool bsc::checkSubcommandOptions(DiagnosticEngine &Diags, cl::SubCommand &Sub) {
  const auto &RunOptions = cl::getRegisteredOptions(Sub);
  bool OK = true;
  for (const auto &[Name, Opt] :
       cl::getRegisteredOptions(cl::SubCommand::getTopLevel())) {
    if (Opt->getNumOccurrences() == 0 || RunOptions.count(Name))
      continue;
    Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
        << ("-" + Name.str()) << Sub.getName();
    OK = false;
  }
  return OK;
}

/// The option `Name` (without dashes and `=value`) as `Sub` parses it: its
/// own, else the top level's (llvm::cl falls back to them, and
/// checkSubcommandOptions names those a subcommand does not take), else a
/// Prefix option written with its value attached (`-O2`, `-Ifolder`).
/// `Attached` says whether the value is part of `Name`.
static cl::Option *findOption(cl::SubCommand &Sub, llvm::StringRef Name,
                              bool &Attached) {
  Attached = false;
  for (cl::SubCommand *S : {&Sub, &cl::SubCommand::getTopLevel()}) {
    const auto &Options = cl::getRegisteredOptions(*S);
    if (cl::Option *O = Options.lookup(Name))
      return O;
    for (const auto &[Key, O] : Options)
      if (O->getFormattingFlag() == cl::Prefix && Name.starts_with(Key)) {
        Attached = true;
        return O;
      }
  }
  return nullptr;
}

/// The name of the tool's own option (of `Category`) nearest to a misspelt
/// `Name`, if one is at most a third of its length away.
static std::optional<std::string> findNearOption(cl::SubCommand &Sub,
                                                 llvm::StringRef Name,
                                                 cl::OptionCategory &Category) {
  std::optional<std::string> Best;
  unsigned BestDistance = std::max<size_t>(1, Name.size() / 3) + 1;
  for (const auto &[Key, O] : cl::getRegisteredOptions(Sub)) {
    if (!llvm::is_contained(O->Categories, &Category) || Key.size() < 2)
      continue;
    unsigned D = Name.edit_distance(Key, true, BestDistance);
    if (D < BestDistance) {
      BestDistance = D;
      Best = "--" + Key.str();
    }
  }
  return Best;
}

/// The subcommand `Args` names (the top level if none), and the index of
/// its first option. Reports a word in the subcommand's place that is
/// neither a subcommand nor a file and returns null.
static cl::SubCommand *findSubcommand(DiagnosticEngine &Diags,
                                      llvm::ArrayRef<const char *> Args,
                                      size_t &I) {
  cl::SubCommand *Sub = &cl::SubCommand::getTopLevel();
  I = 1;
  std::vector<std::string> SubNames;
  for (cl::SubCommand *S : cl::getRegisteredSubcommands()) {
    if (S->getName().empty())
      continue; // The top level and "all".
    SubNames.push_back("'" + S->getName().str() + "'");
    if (Args.size() > 1 && S->getName() == Args[1]) {
      Sub = S;
      I = 2;
    }
  }
  if (I == 1 && Args.size() > 1) {
    llvm::StringRef First = Args[1];
    bool Word = !First.empty() && llvm::all_of(First, [](char Ch) {
      return llvm::isAlnum(Ch) || Ch == '-' || Ch == '_';
    });
    if (Word && First[0] != '-' && !llvm::sys::fs::exists(First)) {
      llvm::sort(SubNames);
      Diags.report(llvm::SMLoc(), diag::err_unknown_subcommand)
          << First << llvm::join(SubNames, ", ");
      return nullptr;
    }
  }
  return Sub;
}

bool bsc::checkCommandLine(DiagnosticEngine &Diags,
                           llvm::ArrayRef<const char *> Args,
                           cl::OptionCategory &Category) {
  size_t I;
  cl::SubCommand *Sub = findSubcommand(Diags, Args, I);
  if (!Sub)
    return false;
  bool OK = true;
  for (; I < Args.size(); ++I) {
    llvm::StringRef Arg = Args[I];
    if (Arg == "--")
      break;
    if (Arg.size() < 2 || Arg[0] != '-')
      continue;
    auto [Name, Value] =
        Arg.drop_front(Arg.starts_with("--") ? 2 : 1).split('=');
    // `-h` is llvm::cl's alias of --help, registered while it parses.
    if (Name == "h")
      continue;
    bool Attached;
    cl::Option *O = findOption(*Sub, Name, Attached);
    if (!O) {
      std::string Command = Sub->getName().empty()
                                ? std::string("bsc")
                                : ("bsc " + Sub->getName()).str();
      Diags.report(llvm::SMLoc(), diag::err_unknown_option) << Arg << Command;
      if (std::optional<std::string> Near = findNearOption(*Sub, Name, Category))
        Diags.report(llvm::SMLoc(), diag::note_did_you_mean) << *Near;
      OK = false;
      continue;
    }
    // `-O2` given to a subcommand: llvm::cl finds attached values only
    // among the subcommand's own options and would print its own error.
    if (Attached && Sub != &cl::SubCommand::getTopLevel() &&
        !cl::getRegisteredOptions(*Sub).count(O->ArgStr)) {
      Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
          << ("-" + O->ArgStr.str()) << Sub->getName();
      OK = false;
      continue;
    }
    // `-o FILE`: the next word is the value, whatever it looks like.
    if (O->getValueExpectedFlag() == cl::ValueRequired && !Attached &&
        !Arg.contains('='))
      ++I;
  }
  return OK;
}
