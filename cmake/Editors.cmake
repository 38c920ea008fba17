# The VS Code extension (editors/vscode; docs/editors.md). With node and npm
# the build copies editors/vscode to build/editors/vscode, installs its npm
# packages there (`npm ci`, again only when package-lock.json changes) and
# packages build/editors/bscript-VERSION.vsix (editors/PackageVSCode.cmake).
# Without node or npm, or when the npm registry cannot be reached, the build
# goes on without the extension, says so once, and test/Editors reports its
# tests UNSUPPORTED (lit feature vscode-tools, test/lit.cfg.py).
#
# `cmake --install` puts into P/share/bscript/editors/vscode/
#   bscript.tmLanguage.json  the TextMate grammar (always)
#   bscript-VERSION.vsix     the extension, when it was built:
#                            code --install-extension bscript-VERSION.vsix
option(BSC_VSCODE_EXTENSION
  "Build the VS Code extension (needs node, npm and the npm registry)" ON)

set(BSC_VSCODE_SOURCE_DIR ${CMAKE_SOURCE_DIR}/editors/vscode)
set(BSC_VSCODE_INSTALL_DIR share/bscript/editors/vscode)
file(READ ${BSC_VSCODE_SOURCE_DIR}/package.json _bsc_vscode_manifest)
string(JSON BSC_VSCODE_VERSION GET "${_bsc_vscode_manifest}" version)
# set_property: re-running cmake notices a new version.
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
  ${BSC_VSCODE_SOURCE_DIR}/package.json)

install(FILES ${BSC_VSCODE_SOURCE_DIR}/syntaxes/bscript.tmLanguage.json
  DESTINATION ${BSC_VSCODE_INSTALL_DIR})

# What test/lit.site.cfg.py passes on to test/Editors: empty when the
# extension is not built.
set(BSC_VSCODE_NODE "")
set(BSC_VSCODE_BUILD_DIR "")
set(BSC_VSCODE_VSIX "")

find_program(BSC_NODE_EXECUTABLE NAMES node nodejs)
find_program(BSC_NPM_EXECUTABLE NAMES npm)
if(NOT BSC_VSCODE_EXTENSION)
  message(STATUS "VS Code extension: off (BSC_VSCODE_EXTENSION); its tests are UNSUPPORTED")
elseif(NOT BSC_NODE_EXECUTABLE OR NOT BSC_NPM_EXECUTABLE)
  message(STATUS "VS Code extension: not built, node or npm not found "
                 "(Debian: apt install nodejs npm); its tests are UNSUPPORTED")
else()
  set(BSC_VSCODE_NODE ${BSC_NODE_EXECUTABLE})
  set(BSC_VSCODE_BUILD_DIR ${CMAKE_BINARY_DIR}/editors/vscode)
  set(BSC_VSCODE_VSIX ${CMAKE_BINARY_DIR}/editors/bscript-${BSC_VSCODE_VERSION}.vsix)
  message(STATUS "VS Code extension: ${BSC_VSCODE_VSIX} (node ${BSC_NODE_EXECUTABLE})")

  # Every file of the extension's source, so that an edit repackages it; a
  # node_modules someone made in the source tree is not part of it.
  file(GLOB_RECURSE _bsc_vscode_sources CONFIGURE_DEPENDS
    LIST_DIRECTORIES false ${BSC_VSCODE_SOURCE_DIR}/*)
  list(FILTER _bsc_vscode_sources EXCLUDE REGEX "/editors/vscode/node_modules/|\\.vsix$")

  add_custom_command(OUTPUT ${BSC_VSCODE_VSIX}
    COMMAND ${CMAKE_COMMAND}
            -DSOURCE_DIR=${BSC_VSCODE_SOURCE_DIR}
            -DBUILD_DIR=${BSC_VSCODE_BUILD_DIR}
            -DSTAMP=${CMAKE_BINARY_DIR}/editors/npm-ci.stamp
            -DVSIX=${BSC_VSCODE_VSIX}
            -DNODE=${BSC_NODE_EXECUTABLE}
            -DNPM=${BSC_NPM_EXECUTABLE}
            -P ${CMAKE_SOURCE_DIR}/editors/PackageVSCode.cmake
    DEPENDS ${_bsc_vscode_sources} ${CMAKE_SOURCE_DIR}/editors/PackageVSCode.cmake
    COMMENT "VS Code extension bscript-${BSC_VSCODE_VERSION}.vsix"
    VERBATIM)
  add_custom_target(bscript-vscode ALL DEPENDS ${BSC_VSCODE_VSIX})

  # OPTIONAL: a build without the registry has no .vsix, and says so.
  install(FILES ${BSC_VSCODE_VSIX} DESTINATION ${BSC_VSCODE_INSTALL_DIR} OPTIONAL)
  install(CODE "
    if(NOT EXISTS \"${BSC_VSCODE_VSIX}\")
      message(STATUS \"Not installing the VS Code extension: ${BSC_VSCODE_VSIX} was not built (see the build's message)\")
    endif()")
endif()
