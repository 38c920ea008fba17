# `cmake --install build [--prefix P]`: what a robot project needs, laid out
# so that bsc finds its runtimes relative to itself (ToolChain.h):
#   P/bin/bsc
#   P/lib/bscript/libbscript_rt.a, libbscript_rt_i586.a
#   P/include/bscript/Bind.h, bscript.h, descriptor.h
#   P/lib/cmake/bscript/  the package: find_package(bscript 0.1 REQUIRED)
#   P/share/doc/bscript/  the user documentation
include(CMakePackageConfigHelpers)

set(BSC_PACKAGE_DIR lib/cmake/bscript)
set_target_properties(bsc PROPERTIES EXPORT_NAME bsc)
install(TARGETS bsc bscript_rt bscript_rt_i586 bscript_bind
  EXPORT bscriptTargets
  RUNTIME DESTINATION bin
  ARCHIVE DESTINATION lib/bscript)
install(FILES include/bscript/Bind.h include/bscript/bscript.h
              include/bscript/descriptor.h
  DESTINATION include/bscript)
install(FILES README.md docs/language.md docs/bindings.md docs/embedding.md
              docs/repl.md docs/cmake.md
  DESTINATION share/doc/bscript)
install(EXPORT bscriptTargets NAMESPACE bscript::
  DESTINATION ${BSC_PACKAGE_DIR})
configure_package_config_file(cmake/bscriptConfig.cmake.in
  ${CMAKE_BINARY_DIR}/cmake/bscriptConfig.cmake
  INSTALL_DESTINATION ${BSC_PACKAGE_DIR})
# 0.x: a new minor version may change the language or the descriptor.
# Architecture independent: the package serves 32-bit (robot) builds as
# well as the host's, with a runtime for each.
write_basic_package_version_file(
  ${CMAKE_BINARY_DIR}/cmake/bscriptConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion ARCH_INDEPENDENT)
install(FILES ${CMAKE_BINARY_DIR}/cmake/bscriptConfig.cmake
              ${CMAKE_BINARY_DIR}/cmake/bscriptConfigVersion.cmake
              cmake/bscriptFunctions.cmake
  DESTINATION ${BSC_PACKAGE_DIR})
