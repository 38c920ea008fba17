//===- Token.cpp - names and spellings of token kinds ---------------------===//
//
// Both tables come from TokenKinds.def, so a new token kind gets its name and
// spelling here without touching this file.
//
//===----------------------------------------------------------------------===//
#include "bsc/Parse/Token.h"
#include "llvm/Support/ErrorHandling.h"

using namespace bsc;

llvm::StringRef tok::getName(Kind K) {
  switch (K) {
#define TOK(Name)                                                              \
  case Name:                                                                   \
    return #Name;
#include "bsc/Parse/TokenKinds.def"
  case NumKinds:
    break;
  }
  llvm_unreachable("invalid token kind");
}

llvm::StringRef tok::getSpelling(Kind K) {
  switch (K) {
#define TOK(Name)                                                              \
  case Name:                                                                   \
    return "";
#define KEYWORD(Spelling)                                                      \
  case kw_##Spelling:                                                          \
    return #Spelling;
#define PUNCT(Name, Spelling)                                                  \
  case Name:                                                                   \
    return Spelling;
#include "bsc/Parse/TokenKinds.def"
  case NumKinds:
    break;
  }
  llvm_unreachable("invalid token kind");
}
