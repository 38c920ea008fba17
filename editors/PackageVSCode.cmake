# cmake -DSOURCE_DIR=... -DBUILD_DIR=... -DSTAMP=... -DVSIX=... -DNODE=...
#       -DNPM=... -P PackageVSCode.cmake
#
# Builds the VS Code extension (run by cmake/Editors.cmake's target
# bscript-vscode): copies SOURCE_DIR (editors/vscode) to BUILD_DIR, runs
# `npm ci` there when package-lock.json differs from the one STAMP records,
# and packages VSIX with vsce, with the production dependencies
# (vscode-languageclient) inside. The source tree gets no node_modules.
#
# A failure (no registry, a broken package) is not the build's failure: it
# prints one message, removes VSIX (so that no stale one is tested or
# installed) and returns; the next build tries again.
cmake_minimum_required(VERSION 3.20)
foreach(var SOURCE_DIR BUILD_DIR STAMP VSIX NODE NPM)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "PackageVSCode.cmake: -D${var}=... is missing")
  endif()
endforeach()

get_filename_component(_editors_dir ${VSIX} DIRECTORY)
set(_log ${_editors_dir}/vscode-build.log)

# Says what went wrong, once, and leaves no extension behind.
macro(give_up what)
  file(REMOVE ${VSIX})
  message("bsc: the VS Code extension was not built: ${what}. The build goes "
          "on without it, and test/Editors reports its tests UNSUPPORTED. "
          "Details: ${_log}")
  return()
endmacro()

# vsce runs `npm list`: npm must be on PATH.
get_filename_component(_npm_dir ${NPM} DIRECTORY)
get_filename_component(_node_dir ${NODE} DIRECTORY)
set(ENV{PATH} "${_npm_dir}:${_node_dir}:$ENV{PATH}")

# A fresh copy of the sources, beside the node_modules of the last npm ci.
file(MAKE_DIRECTORY ${BUILD_DIR})
# (CMake's * matches dot files too, and never . or ..)
file(GLOB _old LIST_DIRECTORIES true ${BUILD_DIR}/*)
list(FILTER _old EXCLUDE REGEX "/node_modules$|/\\.\\.?$")
if(_old)
  file(REMOVE_RECURSE ${_old})
endif()
file(GLOB _new LIST_DIRECTORIES true ${SOURCE_DIR}/*)
list(FILTER _new EXCLUDE REGEX "/node_modules$|\\.vsix$")
file(COPY ${_new} DESTINATION ${BUILD_DIR})

# npm ci only when the lock file changed (or its result is gone).
file(SHA256 ${SOURCE_DIR}/package-lock.json _lock_hash)
set(_installed "")
if(EXISTS ${STAMP} AND EXISTS ${BUILD_DIR}/node_modules/.package-lock.json)
  file(READ ${STAMP} _installed)
endif()
if(NOT _installed STREQUAL _lock_hash)
  file(REMOVE ${STAMP})
  message(STATUS "VS Code extension: npm ci in ${BUILD_DIR}")
  # --ignore-scripts: no install script is needed to package or test the
  # extension (vsce's optional keytar would try to download or compile).
  execute_process(
    COMMAND ${NPM} ci --no-audit --no-fund --ignore-scripts
            --fetch-retries=2 --fetch-retry-mintimeout=2000 --fetch-retry-maxtimeout=10000
    WORKING_DIRECTORY ${BUILD_DIR}
    RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out
    TIMEOUT 900)
  file(WRITE ${_log} "npm ci in ${BUILD_DIR}: ${_rc}\n${_out}")
  if(NOT _rc EQUAL 0)
    give_up("`npm ci` failed (${_rc}: is the npm registry reachable?)")
  endif()
  file(WRITE ${STAMP} ${_lock_hash})
endif()

# vsce package: the manifest's files minus .vscodeignore, and the production
# dependencies from node_modules. Written beside VSIX, then renamed, so that
# an interrupted run leaves no half a file.
set(_vsce ${BUILD_DIR}/node_modules/@vscode/vsce/vsce)
if(NOT EXISTS ${_vsce})
  give_up("${_vsce} is missing after npm ci")
endif()
execute_process(
  COMMAND ${NODE} ${_vsce} package --skip-license --allow-missing-repository
          --out ${VSIX}.part
  WORKING_DIRECTORY ${BUILD_DIR}
  RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out
  TIMEOUT 300)
file(APPEND ${_log} "vsce package: ${_rc}\n${_out}")
if(NOT _rc EQUAL 0 OR NOT EXISTS ${VSIX}.part)
  file(REMOVE ${VSIX}.part)
  give_up("`vsce package` failed (${_rc})")
endif()
file(RENAME ${VSIX}.part ${VSIX})
