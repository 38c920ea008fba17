//===- CodeGen.h - a checked behavior to LLVM IR ---------------*- C++ -*-===//
//
// Lowers a checked Behavior to one LLVM module for one target. The target
// matters already here: frames and the behavior state are laid out with the
// target's DataLayout, and their sizes are part of the object's interface
// (include/bscript/bscript.h).
//
// THE DESIGN (also docs/design/backend.md; code generation follows it):
// - ABI: include/bscript/bscript.h (read it; C header robot code includes) and include/bsc/CodeGen/CodeGen.h (`emitLLVM`, `CodeGenOptions`, `BehaviorLayout`, `getEntrySymbol`). Keep these; extend only compatibly, and report changes.
// - State: one LLVM struct type `%bs.state` = { bs_state_header fields: i32 cycle, i32 reserved, ptr input, ptr output } followed by one frame struct per task, laid out with the TARGET's DataLayout (i586: 4-byte pointers). Frame struct `%bs.frame.<Module>.<task>` = { i32 resume, i32 state, i32 last_call, params..., locals... } (field order: header, the params in order, then CallableDecl::Locals in order, each only if ModuleEmitter::keepsInFrame: read by a nested func, a local in scope at a yield, a class value, or everything with Probes; scalar locals of disjoint scopes share a field except with Probes; bool stored as i8, int i32, float float, string ptr, enum i32, TaskState i32). No heap, no LLVM coroutine intrinsics: identical frame sizes at -O0..-O3 and in the JIT.
// - Every generated function takes `ptr %state` (the behavior state) as its FIRST parameter: funcs `(ptr state, params...) -> result`, nested funcs the same (they reach their task's frame through state), tasks `(ptr state, params...) -> void`. Internal functions have internal linkage; exported entries (CodeGenOptions::Exports, by default the behavior's roots: top-level funcs and tasks whose params are int/float/bool that no func or task calls) are external functions named getEntrySymbol(BehaviorName, Decl) = `bs_<Behavior>__<Module>__<name>`, default visibility; bool params/results of entries travel as i32 (0/1). Also export a constant `bs_<Behavior>_info` of type bs_behavior_info {abi_version=5, state_size, state_align, num_tasks, ptr to constant array of {ptr name "Module::task", i32 frame_offset}, num_modules, ptr to constant array of bs_binding_module {ptr name, ptr @bs_module_<Name>, i64 descriptor hash} for every binding module of Behavior::BindingModules (null when none), ptr destroy (the behavior's destroy function, null when nothing needs destruction), ptr debug_tables (with --instrument the debugger's tables as JSON in section .bs_debug_tables, else null)}.
// - Task call: the caller evaluates the arguments and calls the task function; lib/CodeGen/CGTask.cpp documents the lowering (the reset check on the last call, which stores a yield makes). `taskState(T)` loads T's frame.state (0 if never called because the state starts zeroed). bs_state_init zeroes the state and sets every frame's last_call to BS_LAST_CALL_ENDED (ended in cycle 0); bs_begin_cycle does cycle += 1 (first cycle is 1) and stores input/output.
// - Runtime safety: x / 0 == 0 and x % 0 == x (so a == (a/b)*b + a%b still holds); INT_MIN / -1 == INT_MIN, INT_MIN % -1 == 0; lower with a divisor of 1 substituted and selects, never a trap or UB. + - * wrap (no nsw/nuw flags). int(float) uses llvm.fptosi.sat.i32.f32 (NaN -> 0, saturating). No `unreachable` terminators on reachable paths, no llvm.trap. Locals are always initialised (zero / false / 0.0 / "" when there is no initialiser).
// - No libc in the generated object: no memset/memcpy calls (mark functions "no-builtins" so loop idioms never become memset; never use CreateMemSet/CreateMemCpy); no libm. Its undefined symbols are only the runtime shim's and the bindings' thunks (the standard `io` module's thunks are in the runtime archive) — plus `_GLOBAL_OFFSET_TABLE_` which i386 PIC objects reference and the linker provides. No mutable global in the generated object (constants only: strings, the info struct).
// - Native calls (io and bindings): call NativeFunction::Symbol (a thunk) with C ABI: int -> i32, float -> float, bool -> i32 (0/1), string -> ptr to a private constant NUL-terminated string.
// - Registered class values (docs/bindings.md): in memory Size bytes with the class's alignment (`[Size x i8]`, or an array of Align-sized units — i32, i128, <A x i8> — whose ABI alignment on the target is Align, so frames, the state and allocas get the class's alignment from the DataLayout); in registers a pointer to the value's storage. Constructing zeroes the storage with explicit stores, then runs the construct thunk (if any); copies are i32/i16/i8 loads and stores when the class copies as bytes (trivially copyable or copyAsBytes), else the copy thunk into raw storage and the assign thunk onto a constructed value (without an assign thunk: destroy, then copy thunk). Sema refuses every copy of a class with neither (err_class_not_copyable). Fields by offset from the base's storage (`input`/`output`: the pointers in the state header), loads/stores by the C++ storage size (double fields convert); properties through getter/setter thunks. Thunk calls: `[R *out,] [T *self,] wire args...`; a class result goes to a fresh aligned alloca; class arguments pass the pointer to the value. Operators on classes call Sema's resolved member (`!=` through `_eq_` negated). A func with a class result takes a hidden `ptr result` after the state and returns void (not exported).
// - Lifetimes of class values whose destructor is not trivial (NativeClass::TriviallyDestructible false; the destroy thunk ends them; trivially destructible values are never destroyed and nothing below is emitted for them): (a) temporaries (class results of calls, operators and getters) are destroyed at the end of their full expression (statement, condition, `return`/`yield` value, newest first); those of the right operand of `&&`/`||` at the end of that operand, on its branch, so only the temporaries of the operand that ran are destroyed and no flags are needed. (b) A func's class parameters are copy-constructed from the argument at entry; its locals are constructed by their declaration (copy thunk from the initialiser, or default) and destroyed at the end of their block, and on the way out of `break`/`continue` (the loop body's) and `return` (all, newest first, after the result is complete); the for-head's local at the loop's end. Every exit knows statically what is alive. (c) A task's class parameters and locals live in its frame from the reset (constructed there, parameters first) to the task's end (`return` or falling off): a frame holding such values ends with an `i8 live` field (1 while constructed; 0 in a zeroed state) and has `void bs.<M>.<task>.destroy(ptr state)`: if live, destroy locals then parameters, newest first, and clear live. The reset calls it first (a running task that missed a cycle), the task's end calls it; a declaration without initialiser destroys and re-constructs, one with an initialiser assigns. Sema guarantees that every class default-constructed here (task parameters and locals, func locals without initialiser) has a construct thunk, or may start as zero bytes (copies as bytes, trivially destructible). (d) The behavior's `void bs.destroy(ptr state)` calls every frame's destroy function (the last task's first); bs_behavior_info.destroy points to it, null when no frame needs one; bs_state_destroy(state, &info) calls it. Frames without such values keep their layout (no live byte).
// - Standalone program (CodeGenOptions::ProgramEntry): emitLLVM additionally emits `i32 @main()` that allocas the state (aligned to the state alignment), calls bs_state_init(state, &info) — a non-zero result returns bs_report_init_failure(&info, result) (stale bindings: status 1 and the runtime's message) — then, when the behavior has a world module (Behavior::World), allocas its `input` and `output` classes (NativeClass Size and Align, as class values) and constructs each as any class value (zero stores, then the construct thunk if any; the driver refuses a class that has no default constructor and cannot start as zero bytes: err_world_not_default_constructible), then for ProgramCycles cycles calls bs_begin_cycle(state, input, output) (null for what the world lacks, both null without one) and the entry (args: an entry with parameters cannot be a program entry — the driver reports that), then bs_state_destroy(state, &info), then the destroy thunks of input and output (those needing destruction, input first, as `bsc run` does), returns 0.
// - Targets: `-target i586` means triple i586-unknown-linux-gnu with -mcpu=geode by default (x87 floats, no CMOV, no SSE), PIC (reloc model PIC_), ELF32; `-target x86_64` = x86_64-unknown-linux-gnu; default = host triple; any other string is an LLVM triple (unknown → diagnostic). Optimisation -O0..-O3 through the new pass manager (PassBuilder::buildPerModuleDefaultPipeline / buildO0DefaultPipeline).
// - The runtime shim lib/Runtime (C, tiny): bscript.c (bs_state_init, bs_state_destroy, bs_begin_cycle, bs_task_state, bs_check_bindings, bs_binding_hash; no libc except what is unavoidable — write loops, not memset) io.c (bs_io_* with stdio), report.c (bs_report_init_failure, stdio) and io_module.cpp (the standard module `io`: io.c registered with bscript/Bind.h; C++20 without exceptions/RTTI, no libstdc++). Built twice by CMake: host static library `bscript_rt` and i586 static library `bscript_rt_i586` (compile flags -m32 -march=i586 -mtune=geode -fPIC -O2; gcc-multilib is installed), both output to build/lib/.
// - i586 programs: this machine's kernel has 32-bit emulation DISABLED at boot (dmesg: "32-bit emulation disabled"), so 32-bit programs fail with "Exec format error". The project runs them through utils/run-i586 (exists or to be written by the target/runtime helper): execs the program natively if the kernel can, else through `qemu-i386` (Debian package qemu-user, installed). Tests call it as `%run-i586 %t.prog`.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_CODEGEN_CODEGEN_H
#define BSC_CODEGEN_CODEGEN_H

#include "bsc/Sema/Sema.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/IR/DataLayout.h"
#include "llvm/IR/LLVMContext.h"
#include "llvm/IR/Module.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/TargetParser/Triple.h"
#include <memory>
#include <optional>
#include <string>

namespace bsc {

struct CodeGenOptions {
  /// Prefix of every exported symbol (`bs_<Name>_info`, `bs_<Name>__M__f`).
  std::string BehaviorName;
  /// When set, also emit `int main(void)` that initialises a state on its
  /// stack and calls this entry once per cycle for `ProgramCycles` cycles
  /// (standalone programs and `bsc run`).
  const CallableDecl *ProgramEntry = nullptr;
  unsigned ProgramCycles = 1;
  /// Funcs and tasks (and frames' destroy functions) get external linkage
  /// under their internal names (`bs.M.f`), so that the REPL's lines,
  /// compiled later into the same JIT (emitReplLine), can call them.
  /// Results do not change; only the REPL sets it.
  bool ExternalFunctions = false;
  /// Debugging probes for the JIT (docs/repl.md): each loop's head stores
  /// its site number into the i32 global `bs.probe.loop`, and each call of
  /// registered C++ stores its site into `bs.probe.native` before the call
  /// and 0 after it, so that a watchdog or a crash handler can name the
  /// loop that ran away or the binding that crashed. Values computed do
  /// not change; robot objects never have probes (no mutable globals).
  bool Probes = false;
  /// `--instrument`: bs_behavior_info.debug_tables points to the static
  /// tables of the debugger (task names, yield lines, frame fields, the
  /// call graph; bsc/Debug/Trace.h) as JSON, in the section
  /// DebugTablesSection, so that a robot's trace log can be decoded offline.
  /// The code of tasks and funcs does not change.
  bool Instrument = false;
  /// Floats on the x87 unit (usesX87Floats): every float that an operation
  /// computes (arithmetic, conversion from int, a result of registered C++)
  /// goes through a float in memory before it is used, so that it has a
  /// float's precision and range, as on every other target
  /// (docs/language.md, "Floats").
  bool NarrowX87Floats = false;
  /// `-g`: DWARF for the behavior (lib/CodeGen/CGDebugInfo.cpp): a line
  /// table, a subprogram per func and task, their parameters and locals
  /// (frame fields included) with b-script types, registered classes with
  /// their C++ layouts. `Sources` maps the AST's locations to lines; it
  /// must be set with DebugInfo. At -O1 and above the code generated does
  /// not change; at -O0 the state pointer and task parameters that are
  /// only arguments are also stored on the stack, where the debugger reads
  /// them all along.
  bool DebugInfo = false;
  const llvm::SourceMgr *Sources = nullptr;
  /// The -O level the module will be optimised at. Only the debug
  /// information depends on it: how a frame variable's place is described
  /// (CGDebugInfo.cpp) and whether the unit says it is optimised.
  unsigned OptLevel = 0;
  /// The top-level funcs and tasks exported as entries (`bs_<Name>__M__f`),
  /// each callable from C (isCallableFromC). Everything else is internal,
  /// so the optimiser may inline it into its callers. Unset: the behavior's
  /// roots (findBehaviorRoots).
  std::optional<std::vector<const CallableDecl *>> Exports;
};

/// The section holding the debug tables of an instrumented object.
inline constexpr const char *DebugTablesSection = ".bs_debug_tables";

/// A place in the behavior a probe names (BehaviorLayout::Sites).
struct DebugSite {
  enum SiteKind { Loop, NativeCall };
  SiteKind Kind;
  const CallableDecl *In; ///< The func or task whose body holds it.
  llvm::SMLoc Loc;        ///< The `for`, or the statement making the call.
  std::string Native;     ///< NativeCall: the registered C++ (`Math::fabs`).
};

/// The probe globals of CodeGenOptions::Probes.
inline constexpr const char *LoopProbeSymbol = "bs.probe.loop";
inline constexpr const char *NativeProbeSymbol = "bs.probe.native";

/// Where things ended up; what --emit-header and the JIT need.
struct BehaviorLayout {
  uint64_t StateSize = 0;
  uint64_t StateAlign = 1;
  /// A parameter or local a task keeps in its frame.
  struct FrameField {
    const Decl *D; ///< ParamDecl or VarDecl.
    const Type *Ty;
    uint64_t Offset; ///< From the start of the state.
  };
  struct Task {
    const TaskDecl *Decl;
    uint64_t FrameOffset;
    uint64_t FrameSize; ///< Of its frame struct, without padding after it.
    /// Parameters in order, then locals in declaration order.
    std::vector<FrameField> Fields;
    /// The task's yields leave it running (1) or end it with a constant
    /// state <= 0, so its code takes a state > 0 to be 1: a frame may only
    /// be carried into such a task (the REPL's :reload) from one that is
    /// too.
    bool OnlyRunningStates = false;
  };
  std::vector<Task> Tasks;
  struct Entry {
    const CallableDecl *Decl;
    std::string Symbol;
  };
  /// The exported entries (CodeGenOptions::Exports), in that order.
  std::vector<Entry> Entries;
  std::string InfoSymbol; ///< `bs_<Name>_info`.
  /// With CodeGenOptions::Probes: the sites, numbered from 1 (0 in a probe
  /// global means "none").
  std::vector<DebugSite> Sites;
  /// With CodeGenOptions::Instrument: the declared symbol of the tables.
  std::string DebugTablesSymbol;
};

/// Defines the debug tables an instrumented module declares
/// (BehaviorLayout::DebugTablesSymbol) as the NUL-terminated `JSON`. Call
/// it after emitLLVM and before optimising.
void defineDebugTables(llvm::Module &M, const BehaviorLayout &Layout,
                       llvm::StringRef JSON);

/// Builds the IR of a REPL line (ReplChecker::Line::Func) as
/// `void @<Symbol>(ptr state)` in a module of its own that only declares the
/// behavior's funcs and tasks: it runs in the JIT that holds the behavior,
/// compiled with CodeGenOptions::ExternalFunctions. `Slots` gives the
/// addresses of the REPL's variables (the line's result among them), which
/// live in the REPL rather than on the stack and are not destroyed by the
/// line. The line has probes like the behavior (CodeGenOptions::Probes,
/// which the behavior's module must have had); its sites are appended to
/// `Sites`, the behavior's (BehaviorLayout::Sites) and earlier lines'.
std::unique_ptr<llvm::Module>
emitReplLine(const Behavior &B, const FuncDecl &Line, llvm::StringRef Symbol,
             llvm::LLVMContext &Ctx, const llvm::Triple &Triple,
             const llvm::DataLayout &DL,
             const llvm::DenseMap<const Decl *, uint64_t> &Slots,
             std::vector<DebugSite> &Sites);

/// Builds the IR of `B` for `Triple`/`DL`. Never fails on a behavior that
/// Sema accepted.
std::unique_ptr<llvm::Module> emitLLVM(const Behavior &B, llvm::LLVMContext &Ctx,
                                       const llvm::Triple &Triple,
                                       const llvm::DataLayout &DL,
                                       const CodeGenOptions &Opts,
                                       BehaviorLayout &Layout);

/// `bs_<Behavior>__<Module>__<name>`.
std::string getEntrySymbol(llvm::StringRef BehaviorName, const CallableDecl &D);

} // namespace bsc

#endif
