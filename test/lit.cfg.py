# lit configuration of the bsc regression suite.
#
# Tests are .bs programs (RUN lines in `#` comments) and .test scripts.
# Substitutions:
#   %bsc          the compiler under test
#   %python       the Python that runs lit
#   %conformance  ../shared/conformance (programs written by others)
#   %bsc_src      the source tree (for scripts in utils/)
import os
import lit.formats

config.name = "bsc"
config.test_format = lit.formats.ShTest(execute_external=False)
config.suffixes = [".bs", ".test"]
config.excludes = ["Inputs", "CMakeLists.txt", "lit.cfg.py", "lit.site.cfg.py"]
config.test_source_root = os.path.dirname(__file__)
config.test_exec_root = os.path.join(config.bsc_obj_root, "test")

config.substitutions.append(("%bsc_src", config.bsc_src_root))
config.substitutions.append(("%bsc", os.path.join(config.bsc_tools_dir, "bsc")))
config.substitutions.append(("%python", config.python_executable))
config.substitutions.append(("%conformance", os.path.join(config.shared_dir, "conformance")))

# FileCheck, not, split-file, count come from LLVM 19.
config.environment["PATH"] = os.pathsep.join(
    [config.llvm_tools_dir, config.bsc_tools_dir, config.environment.get("PATH", "")])
if os.path.isdir(os.path.join(config.shared_dir, "conformance")):
    config.available_features.add("conformance")
