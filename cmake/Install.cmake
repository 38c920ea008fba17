# `cmake --install build [--prefix P]`: what a robot project needs, laid out
# so that bsc finds its runtimes relative to itself (ToolChain.h):
#   P/bin/bsc, bsread
#   P/lib/bscript/libbscript_rt.a, libbscript_rt_i586.a
#   P/include/bscript/Bind.h (BindDetail.h), bscript.h, descriptor.h,
#                         flight.h, world.h
#   P/lib/cmake/bscript/  the package: find_package(bscript 0.1 REQUIRED)
#   P/share/doc/bscript/  README.md, docs/ and examples/embedding, in the
#                         source tree's layout so that their links work
#   P/share/bscript/gdb/bscript_printers.py  gdb's pretty-printer of
#                         registered classes (docs/repl.md, "gdb: -g")
include(CMakePackageConfigHelpers)

set(BSC_PACKAGE_DIR lib/cmake/bscript)
set_target_properties(bsc PROPERTIES EXPORT_NAME bsc)
install(TARGETS bsc bsread bscript_rt bscript_rt_i586 bscript_bind
  EXPORT bscriptTargets
  RUNTIME DESTINATION bin
  ARCHIVE DESTINATION lib/bscript)
install(FILES include/bscript/Bind.h include/bscript/BindDetail.h
              include/bscript/bscript.h
              include/bscript/descriptor.h include/bscript/flight.h
              include/bscript/world.h
  DESTINATION include/bscript)
# Every document the README links to, and the example embedding.md links
# to, where the links expect them (test/Install/installed-docs.test).
install(FILES README.md DESTINATION share/doc/bscript)
install(DIRECTORY docs/ DESTINATION share/doc/bscript/docs
  FILES_MATCHING PATTERN "*.md" PATTERN "*.png")
install(DIRECTORY examples/embedding DESTINATION share/doc/bscript/examples)
install(FILES tools/gdb/bscript_printers.py DESTINATION share/bscript/gdb)
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
