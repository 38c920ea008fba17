//===- Target.h - target machines, optimisation, object emission -*- C++ -*-===//
//
// The part of the back end after IR generation: which machine a behavior is
// compiled for (`-target`, `-mcpu`), the optimisation pipeline (`-O0..-O3`)
// and writing assembly or an object file. It is separate from emitLLVM
// because the JIT (`bsc run`) and the driver share it, and because emitLLVM
// only needs the DataLayout, not the machine.
//
// The robot target is `-target i586`: i586-unknown-linux-gnu with
// `-mcpu=geode` (the paper's Nao V3.3: no CMOV, no SSE, x87 floats),
// position-independent code (Reloc::PIC_) so the object links into a shared
// library without text relocations.
//
// Nothing here prints: failures are reported into a DiagnosticEngine.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_CODEGEN_TARGET_H
#define BSC_CODEGEN_TARGET_H

#include "bsc/Basic/Diagnostic.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"
#include "llvm/Target/TargetMachine.h"
#include "llvm/TargetParser/Triple.h"
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace llvm {
class DiagnosticInfo;
class LLVMContext;
class Module;
class raw_pwrite_stream;
} // namespace llvm

namespace bsc {

/// What the user asked for on the command line.
struct TargetOptions {
  /// The target triple (the driver resolves `-target`: ToolChain.h).
  llvm::Triple Triple;
  /// `-target` as the user wrote it, for messages; empty for the host.
  std::string Spelling;
  /// `-mcpu`: empty for the target's default (geode for i586).
  std::string CPU;
  /// `-O0`..`-O3`.
  unsigned OptLevel = 0;
};

/// The highest `-O` level.
constexpr unsigned MaxOptLevel = 3;

/// Registers every back end bsc links (all of Debian's LLVM 19) with LLVM.
/// Idempotent.
void initializeTargets();

/// The CPU used when `-mcpu` is not given: "geode" for i586 triples (the
/// robot), "x86-64" for x86_64, the oldest supported model for back ends
/// without a "generic" CPU (NVPTX, AVR), "generic" otherwise.
std::string getDefaultCPU(const llvm::Triple &T);

/// Parses an `-O` value ("0".."3"); std::nullopt if it is not one.
std::optional<unsigned> parseOptLevel(llvm::StringRef Value);

/// Whether `TM` computes floats on the x87 unit (32-bit x86 without SSE:
/// the robot's Geode), where a value in a register has 64 mantissa bits
/// and a wider exponent than a float (CodeGenOptions::NarrowX87Floats).
bool usesX87Floats(const llvm::TargetMachine &TM);

/// What findInstructionsCPULacks found: how many instructions the target
/// CPU lacks, and the first one with its function.
struct CPUMismatch {
  unsigned Count = 0;
  std::string Function;    ///< Demangled.
  std::string Instruction; ///< Its mnemonic (`cmovl`).
};

/// Disassembles the functions of a binding object, archive or shared
/// library built for x86 and counts the instructions that `TM`'s CPU lacks
/// (CMOV and the P6 x87 compares, SSE and AVX registers: a Geode has none
/// of them). Files that are not objects count nothing; the binding reader
/// reports them.
llvm::Expected<CPUMismatch> findInstructionsCPULacks(const llvm::TargetMachine &TM,
                                                     llvm::StringRef Path);

/// Whether LLVM can write DWARF into machine code for `T` (`-g`): not
/// into GOFF objects (z/OS), where LLVM 19's writer crashes on it.
bool supportsDebugInfo(const llvm::Triple &T);

/// Creates the machine for `Opts`, PIC, with the CPU checked against the
/// target's list. Refuses the targets bsc's IR generator does not support
/// (AMDGPU: UnsupportedTargets in Target.cpp). Reports an unknown or refused
/// triple or CPU into `Diags` and returns null.
std::unique_ptr<llvm::TargetMachine>
createTargetMachine(const TargetOptions &Opts, DiagnosticEngine &Diags);

/// Checks `M` with the IR verifier. A broken module is a bug in bsc, never
/// in the user's program, so it is an llvm::Error (the driver prints it as
/// an internal error) rather than a diagnostic of the table.
llvm::Error verifyGeneratedModule(const llvm::Module &M);

/// Reports (and returns false for) the triples whose assembly or object
/// files LLVM 19 crashes on writing instead of reporting an error: the
/// UnsupportedTargets table in Target.cpp. emitMachineCode checks it.
bool checkMachineCodeSupport(const llvm::Triple &T, llvm::CodeGenFileType Kind,
                             DiagnosticEngine &Diags);

/// Runs the new pass manager's default pipeline for `OptLevel` over `M`.
/// Library-call recognition is disabled (the generated object must not call
/// memset/memcpy or libm), so the pipeline never introduces libc calls.
/// `TM` may be null (then no target-specific analyses are used).
void optimizeModule(llvm::Module &M, llvm::TargetMachine *TM,
                    unsigned OptLevel);

/// Writes `M` as assembly or as an object file through the legacy code
/// generation pass manager. Reports a target without an object writer (or
/// an assembly printer) into `Diags` and returns false; errors of the back
/// end itself come through a BackendErrorReporter.
bool emitMachineCode(llvm::Module &M, llvm::TargetMachine &TM,
                     llvm::CodeGenFileType Kind, llvm::raw_pwrite_stream &OS,
                     DiagnosticEngine &Diags);

/// While it lives, turns the errors of the LLVM back end into
/// err_backend_failed: the errors LLVM reports through `Ctx` (an
/// unsupported construct on some targets) and report_fatal_error. LLVM
/// cannot go on after a fatal error, so then `PrintAndExit` is called to
/// print the diagnostics, and the process exits with status 1 (output files
/// opened with ToolOutputFile are removed). Warnings of the back end are
/// dropped, as clang drops them without -W flags.
class BackendErrorReporter {
public:
  BackendErrorReporter(llvm::LLVMContext &Ctx, DiagnosticEngine &Diags,
                       std::string Target, std::function<void()> PrintAndExit);
  ~BackendErrorReporter();
  BackendErrorReporter(const BackendErrorReporter &) = delete;
  BackendErrorReporter &operator=(const BackendErrorReporter &) = delete;

private:
  static void handleFatal(void *Self, const char *Reason, bool GenCrashDiag);
  static void handleDiagnostic(const llvm::DiagnosticInfo *DI, void *Self);
  llvm::LLVMContext &Ctx;
  DiagnosticEngine &Diags;
  std::string Target;
  std::function<void()> PrintAndExit;
};

} // namespace bsc

#endif
