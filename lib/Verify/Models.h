//===- Models.h - `bsc verify --model`: b-script funcs for C++ ---*- C++
//-*-===//
//
// Registered C++ is unknown to the verifier: a call may return anything. A
// model stands for it: a func of a module given with `--model`, named
// after what it models (`Math_abs` for `Math::abs`, `Math_Vector2f_norm`
// for the method `norm` of `Math::Vector2f`, which takes the object as
// its first parameter), taking and returning what the C++ does. The
// verifier's code calls the model instead (CodeGenOptions::Models).
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_VERIFY_MODELS_H
#define BSC_LIB_VERIFY_MODELS_H

#include "bsc/Frontend/Frontend.h"
#include <map>

namespace bsc::verify {

using ModelMap = std::map<const NativeFunction *, const FuncDecl *>;

/// The models of the `--model` modules of `C` (ModuleAST::IsModel). A func
/// whose name starts with a registered module's name and `_` is a model:
/// one that names no registered function, or whose parameters or result
/// differ from the C++'s, is an error in C.Diags (false). Others are
/// helpers.
bool findModels(Compilation &C, ModelMap &Models);

} // namespace bsc::verify

#endif
