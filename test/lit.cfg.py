# lit configuration of the bsc regression suite.
#
# Tests are .bs programs (RUN lines in `#` comments) and .test scripts.
# Substitutions:
#   %bsc          the compiler under test
#   %python       the Python that runs lit
#   %conformance  ../shared/conformance (programs written by others)
#   %shared_bench ../shared/bench (the performance reference and its harness)
#   %bsc_src      the source tree (for scripts in utils/)
#   %bsc_libdir   the runtime shim libraries (libbscript_rt.a, _i586.a)
#   %bsc_build    the build folder (bin/bsc, lib/)
#   %bsc_include  the public headers (bscript/bscript.h for C embeddings)
#   %eigen_include Eigen's headers (the soccer bindings use Eigen::Vector2f)
#   %run-i586     runs a 32-bit x86 program (natively, else qemu-i386)
#   %browser      utils/browser.py: a page in headless Chromium, driven by
#                 the DevTools protocol (the timeline's tests)
# The suite needs ../shared (the conformance programs and the bench
# reference), gdb and chromium (dev.sh installs both): without any of them
# it stops rather than report green with less in it. Feature: i586-native (this kernel runs
# 32-bit programs itself, so gdb can debug them; elsewhere they run in
# qemu-i386 and the one gdb-on-i586 test is reported unsupported).
# Feature vscode-tools: the build made the VS Code extension (node, npm and
# the npm registry; cmake/Editors.cmake); without it test/Editors is
# reported unsupported, with a note that says why.
import os
import shutil
import subprocess
import tempfile
import lit.formats

config.name = "bsc"
config.test_format = lit.formats.ShTest(execute_external=False)
config.suffixes = [".bs", ".test"]
config.excludes = ["Inputs", "CMakeLists.txt", "lit.cfg.py", "lit.site.cfg.py"]
config.test_source_root = os.path.dirname(__file__)
config.test_exec_root = os.path.join(config.bsc_obj_root, "test")

config.substitutions.append(("%bsc_src", config.bsc_src_root))
# Before %bsc, which is a prefix of these.
config.substitutions.append(("%bsc_libdir", os.path.join(config.bsc_obj_root, "lib")))
config.substitutions.append(("%bsc_build", config.bsc_obj_root))
config.substitutions.append(("%bsc_include", os.path.join(config.bsc_src_root, "include")))
config.substitutions.append(("%eigen_include", config.eigen_include))
config.substitutions.append(("%bsc", os.path.join(config.bsc_tools_dir, "bsc")))
config.substitutions.append(("%python", config.python_executable))
config.substitutions.append(("%conformance", os.path.join(config.shared_dir, "conformance")))
config.substitutions.append(("%shared_bench", os.path.join(config.shared_dir, "bench")))

# FileCheck, not, split-file, count come from LLVM 19.
config.environment["PATH"] = os.pathsep.join(
    [config.llvm_tools_dir, config.bsc_tools_dir, config.environment.get("PATH", "")])
for needed in ("conformance/paper/fib.bs", "bench/harness.h"):
    if not os.path.isfile(os.path.join(config.shared_dir, needed)):
        lit_config.fatal("%s not found: the suite runs the programs of "
                         "../shared beside the checkout (README, Quick start)"
                         % os.path.join(config.shared_dir, needed))

# 32-bit programs run through utils/run-i586: natively where the kernel can,
# else in qemu-i386 (see the script).
config.substitutions.append(
    ("%run-i586", config.python_executable + " " +
     os.path.join(config.bsc_src_root, "utils", "run-i586")))

if not os.path.isfile(os.path.join(config.eigen_include, "Eigen", "Dense")):
    lit_config.fatal("Eigen not found (%%eigen_include is '%s'): the soccer "
                     "bindings need it (dev.sh installs it)"
                     % config.eigen_include)

if not shutil.which("gdb"):
    lit_config.fatal("gdb not found: the debug-info tests need it "
                     "(dev.sh installs it)")

if not shutil.which("genhtml"):
    lit_config.fatal("genhtml not found: the coverage tests render lcov "
                     "tracefiles with it (dev.sh installs lcov)")

if not shutil.which("chromium"):
    lit_config.fatal("chromium not found: the timeline page's tests need it "
                     "(dev.sh installs it)")
if not shutil.which("nvim"):
    lit_config.fatal("nvim not found: docs/editors.md's Neovim recipe is run "
                     "in the tests (dev.sh installs neovim)")
config.substitutions.append(
    ("%browser", config.python_executable + " " +
     os.path.join(config.bsc_src_root, "utils", "browser.py")))


def runs_i586_natively():
    """Whether a 32-bit program runs without qemu (gdb needs that)."""
    with tempfile.TemporaryDirectory() as d:
        prog = os.path.join(d, "probe")
        try:
            subprocess.run(["cc", "-m32", "-x", "c", "-", "-o", prog],
                           input=b"int main(void) { return 0; }",
                           check=True, capture_output=True)
            return subprocess.run([prog], capture_output=True).returncode == 0
        except (OSError, subprocess.CalledProcessError):
            return False


if runs_i586_natively():
    config.available_features.add("i586-native")


def vscode_tools_missing():
    """Why test/Editors cannot run, or None: they need node, and the
    extension's node_modules and .vsix that the build made."""
    # getattr: a build folder configured before cmake/Editors.cmake existed.
    if not getattr(config, "vscode_node", ""):
        return "cmake found no node and npm (dev.sh installs them)"
    modules = os.path.join(config.vscode_build_dir, "node_modules")
    if not os.path.isdir(os.path.join(modules, "vscode-tmgrammar-test")) or \
            not os.path.isfile(config.vscode_vsix):
        return ("the build did not make %s (its message says why: "
                "npm ci needs the npm registry)" % config.vscode_vsix)
    return None


vscode_missing = vscode_tools_missing()
if vscode_missing:
    lit_config.note("the VS Code extension's tests (test/Editors) are "
                    "UNSUPPORTED: " + vscode_missing)
else:
    config.available_features.add("vscode-tools")
