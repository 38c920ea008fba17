# bscript_add_behavior: compiles a b-script behavior with bsc into a static
# library that a robot program links (docs/cmake.md).
#
#   bscript_add_behavior(TARGET <name>
#     SOURCES <main.bs> [<more.bs>...]
#     [BIND <target or file>...]
#     [TARGET_TRIPLE <i586 | x86_64 | LLVM triple>]
#     [ENTRIES <Module::name>...]
#     [INCLUDE_DIRS <dir>...]
#     [OPTIMIZE <0..3>]
#     [BEHAVIOR_NAME <identifier>]
#     [OPTIONS <bsc option>...])
#
# <name> is a static library holding the behavior's object. Linking it gives
# its header `<name>.h` (bsc --emit-header: bs_<name>_state,
# bs_<name>_init, one bs_<name>_call__<Module>__<entry> per entry), the
# runtime shim of the target and the BIND targets.
#
# - SOURCES: the behavior's files; the first one's module is the main one.
#   Modules they require are found beside the requiring file and in
#   INCLUDE_DIRS; bsc's dependency file makes an edit of any of them, or of
#   a binding object, rebuild the behavior.
# - BIND: the binding objects that register the robot's C++ for b-script,
#   built for the same target: an OBJECT library, a static or shared
#   library target, or a file.
# - TARGET_TRIPLE: i586 (the robot) by default when the project's compiler
#   builds 32-bit code (a toolchain file), else the host.
# - ENTRIES: the funcs and tasks the robot calls (--export); by default the
#   behavior's roots, which nothing in it calls.
# - OPTIMIZE: bsc's -O level, 2 by default.
# - BEHAVIOR_NAME: the prefix of the exported symbols, <name> by default.
function(bscript_add_behavior)
  cmake_parse_arguments(PARSE_ARGV 0 BS ""
    "TARGET;TARGET_TRIPLE;OPTIMIZE;BEHAVIOR_NAME"
    "SOURCES;BIND;ENTRIES;INCLUDE_DIRS;OPTIONS")
  if(BS_UNPARSED_ARGUMENTS)
    list(GET BS_UNPARSED_ARGUMENTS 0 first)
    message(FATAL_ERROR "bscript_add_behavior(${BS_TARGET}): unexpected "
      "'${first}'; the keywords are TARGET, SOURCES, BIND, TARGET_TRIPLE, "
      "ENTRIES, INCLUDE_DIRS, OPTIMIZE, BEHAVIOR_NAME and OPTIONS")
  endif()
  if(NOT BS_TARGET)
    message(FATAL_ERROR "bscript_add_behavior: TARGET <name> is required")
  endif()
  if(NOT BS_SOURCES)
    message(FATAL_ERROR
      "bscript_add_behavior(${BS_TARGET}): SOURCES needs at least one .bs file")
  endif()
  if(NOT DEFINED BS_OPTIMIZE)
    set(BS_OPTIMIZE 2)
  endif()
  if(NOT BS_OPTIMIZE MATCHES "^[0-3]$")
    message(FATAL_ERROR
      "bscript_add_behavior(${BS_TARGET}): OPTIMIZE must be 0..3, not '${BS_OPTIMIZE}'")
  endif()
  if(NOT BS_BEHAVIOR_NAME)
    set(BS_BEHAVIOR_NAME ${BS_TARGET})
  endif()
  # The library holds only bsc's object; CMake archives it with the tools
  # of a language the project enabled (C or C++, both archive alike). A
  # project with neither cannot link the robot program either.
  get_property(languages GLOBAL PROPERTY ENABLED_LANGUAGES)
  if("C" IN_LIST languages)
    set(archive_language C)
  elseif("CXX" IN_LIST languages)
    set(archive_language CXX)
  else()
    message(FATAL_ERROR "bscript_add_behavior(${BS_TARGET}): the project "
      "enables neither C nor C++ (project(${PROJECT_NAME} ...)); add CXX or "
      "C to its project() line, as in project(${PROJECT_NAME} CXX)")
  endif()
  if(NOT DEFINED BS_TARGET_TRIPLE)
    if(CMAKE_SIZEOF_VOID_P EQUAL 4)
      set(BS_TARGET_TRIPLE i586)
    else()
      set(BS_TARGET_TRIPLE "")
    endif()
  endif()

  # The runtime shim of the target: the robot's for 32-bit x86, else the
  # host's (other targets have none; docs/bindings.md).
  set(runtime)
  if(BS_TARGET_TRIPLE MATCHES "^(i[3-6]86|x86)($|-)")
    set(runtime bscript::runtime_i586)
  elseif(BS_TARGET_TRIPLE STREQUAL "" OR BS_TARGET_TRIPLE MATCHES "^x86_64($|-)")
    set(runtime bscript::runtime)
  endif()

  set(args -O${BS_OPTIMIZE} --behavior-name=${BS_BEHAVIOR_NAME})
  if(NOT BS_TARGET_TRIPLE STREQUAL "")
    list(APPEND args -target ${BS_TARGET_TRIPLE})
  endif()
  set(include_dirs)
  foreach(dir IN LISTS BS_INCLUDE_DIRS)
    get_filename_component(dir "${dir}" ABSOLUTE)
    list(APPEND args -I ${dir})
    list(APPEND include_dirs ${dir})
  endforeach()
  if(BS_ENTRIES)
    list(JOIN BS_ENTRIES "," entries)
    list(APPEND args --export=${entries})
  endif()
  list(APPEND args ${BS_OPTIONS})

  set(depends)
  set(bind_targets)
  foreach(bind IN LISTS BS_BIND)
    if(TARGET ${bind})
      get_target_property(type ${bind} TYPE)
      if(type STREQUAL "OBJECT_LIBRARY")
        # One --bind per object file.
        list(APPEND args
          "--bind=$<JOIN:$<TARGET_OBJECTS:${bind}>,$<SEMICOLON>--bind=>")
        list(APPEND depends $<TARGET_OBJECTS:${bind}>)
      elseif(type MATCHES "^(STATIC|SHARED)_LIBRARY$")
        list(APPEND args --bind=$<TARGET_FILE:${bind}>)
        list(APPEND depends $<TARGET_FILE:${bind}>)
      else()
        message(FATAL_ERROR "bscript_add_behavior(${BS_TARGET}): BIND "
          "'${bind}' is not a library (${type}); give the binding objects: "
          "an OBJECT, STATIC or SHARED library, or a file")
      endif()
      list(APPEND depends ${bind})
      list(APPEND bind_targets ${bind})
    else()
      get_filename_component(file "${bind}" ABSOLUTE)
      list(APPEND args --bind=${file})
      list(APPEND depends ${file})
    endif()
  endforeach()

  set(sources)
  foreach(src IN LISTS BS_SOURCES)
    get_filename_component(src "${src}" ABSOLUTE)
    list(APPEND sources ${src})
  endforeach()

  set(out ${CMAKE_CURRENT_BINARY_DIR}/${BS_TARGET}.bscript)
  set(object ${out}/${BS_TARGET}.o)
  set(header ${out}/include/${BS_TARGET}.h)
  file(MAKE_DIRECTORY ${out}/include)
  add_custom_command(OUTPUT ${object} ${header}
    COMMAND bscript::bsc -c ${args} -MD -MF ${object}.d ${sources} -o ${object}
    COMMAND bscript::bsc --emit-header ${args} ${sources} -o ${header}
    DEPENDS ${sources} ${depends} $<TARGET_FILE:bscript::bsc>
    DEPFILE ${object}.d
    COMMENT "bsc: behavior ${BS_TARGET}"
    COMMAND_EXPAND_LISTS VERBATIM)
  set_source_files_properties(${object} PROPERTIES
    EXTERNAL_OBJECT TRUE GENERATED TRUE)

  _bscript_record_for_editors("${sources}" "${BS_INCLUDE_DIRS}" "${BS_BIND}"
    "${BS_TARGET_TRIPLE}")

  add_library(${BS_TARGET} STATIC ${object} ${header})
  set_target_properties(${BS_TARGET} PROPERTIES
    LINKER_LANGUAGE ${archive_language})
  target_include_directories(${BS_TARGET} INTERFACE ${out}/include)
  target_link_libraries(${BS_TARGET} INTERFACE ${runtime} ${bind_targets})
  # What bscript_add_log_tests needs to replay recordings against it.
  set(bind_args ${args})
  list(FILTER bind_args INCLUDE REGEX "^--bind=")
  set_target_properties(${BS_TARGET} PROPERTIES
    BSCRIPT_SOURCES "${sources}"
    BSCRIPT_BIND_ARGS "${bind_args}"
    BSCRIPT_INCLUDE_DIRS "${include_dirs}"
    BSCRIPT_ENTRIES "${BS_ENTRIES}"
    BSCRIPT_OPTIMIZE "${BS_OPTIMIZE}"
    BSCRIPT_TARGET_TRIPLE "${BS_TARGET_TRIPLE}")
endfunction()

# bscript_add_log_tests: registers with CTest a `bsc replay` of recorded
# runs against a behavior of bscript_add_behavior (docs/cmake.md).
#
#   bscript_add_log_tests(NAME <test name>
#     BEHAVIOR_TARGET <target of bscript_add_behavior>
#     LOGS <folder>
#     [ENTRY <Module::name>]
#     [JOBS <N>]
#     [SHARD <K/N>]
#     [JUNIT <file.xml>]
#     [OPTIONS <bsc replay option>...])
#
# The test replays every recording (`*.jsonl`) under LOGS against the
# behavior's sources, with its binding objects, INCLUDE_DIRS and -O level,
# in bsc's host JIT, and fails if a log fails. The binding objects must be
# built for the host: in a cross build (TARGET_TRIPLE i586) the test is not
# registered, with a message; register it in the host build.
# - ENTRY: the entry to replay; by default the behavior's one ENTRIES.
# - JOBS: worker processes (`--jobs`); by default one per core.
# - SHARD, JUNIT, OPTIONS: passed on (`--shard`, `--junit`, anything else).
function(bscript_add_log_tests)
  cmake_parse_arguments(PARSE_ARGV 0 BS ""
    "NAME;BEHAVIOR_TARGET;LOGS;ENTRY;JOBS;SHARD;JUNIT" "OPTIONS")
  if(BS_UNPARSED_ARGUMENTS)
    list(GET BS_UNPARSED_ARGUMENTS 0 first)
    message(FATAL_ERROR "bscript_add_log_tests(${BS_NAME}): unexpected "
      "'${first}'; the keywords are NAME, BEHAVIOR_TARGET, LOGS, ENTRY, JOBS, "
      "SHARD, JUNIT and OPTIONS")
  endif()
  foreach(required NAME BEHAVIOR_TARGET LOGS)
    if(NOT BS_${required})
      message(FATAL_ERROR
        "bscript_add_log_tests(${BS_NAME}): ${required} is required")
    endif()
  endforeach()
  if(NOT TARGET ${BS_BEHAVIOR_TARGET})
    message(FATAL_ERROR "bscript_add_log_tests(${BS_NAME}): "
      "'${BS_BEHAVIOR_TARGET}' is not a target; BEHAVIOR_TARGET takes one "
      "of bscript_add_behavior, defined before this call")
  endif()
  get_target_property(sources ${BS_BEHAVIOR_TARGET} BSCRIPT_SOURCES)
  if(NOT sources)
    message(FATAL_ERROR "bscript_add_log_tests(${BS_NAME}): "
      "'${BS_BEHAVIOR_TARGET}' was not made by bscript_add_behavior")
  endif()
  get_target_property(triple ${BS_BEHAVIOR_TARGET} BSCRIPT_TARGET_TRIPLE)
  if(NOT triple STREQUAL "" AND NOT triple MATCHES "^x86_64($|-)")
    message(STATUS "bscript_add_log_tests(${BS_NAME}): not registered: "
      "'${BS_BEHAVIOR_TARGET}' is built for ${triple}, and bsc replays in "
      "the host JIT with host binding objects; register it in a host build")
    return()
  endif()
  get_target_property(binds ${BS_BEHAVIOR_TARGET} BSCRIPT_BIND_ARGS)
  get_target_property(include_dirs ${BS_BEHAVIOR_TARGET} BSCRIPT_INCLUDE_DIRS)
  get_target_property(entries ${BS_BEHAVIOR_TARGET} BSCRIPT_ENTRIES)
  get_target_property(optimize ${BS_BEHAVIOR_TARGET} BSCRIPT_OPTIMIZE)
  foreach(property binds include_dirs entries)
    if(NOT ${property})
      set(${property})
    endif()
  endforeach()
  if(NOT BS_ENTRY AND entries)
    list(LENGTH entries count)
    if(count GREATER 1)
      message(FATAL_ERROR "bscript_add_log_tests(${BS_NAME}): "
        "'${BS_BEHAVIOR_TARGET}' has ${count} ENTRIES; say which to replay "
        "with ENTRY")
    endif()
    set(BS_ENTRY ${entries})
  endif()

  set(args replay -O${optimize} ${binds})
  foreach(dir IN LISTS include_dirs)
    list(APPEND args -I ${dir})
  endforeach()
  if(BS_ENTRY)
    list(APPEND args --entry ${BS_ENTRY})
  endif()
  get_filename_component(logs "${BS_LOGS}" ABSOLUTE)
  list(APPEND args --logs ${logs})
  if(DEFINED BS_JOBS)
    list(APPEND args --jobs ${BS_JOBS})
  endif()
  if(BS_SHARD)
    list(APPEND args --shard ${BS_SHARD})
  endif()
  if(BS_JUNIT)
    get_filename_component(junit "${BS_JUNIT}" ABSOLUTE
      BASE_DIR ${CMAKE_CURRENT_BINARY_DIR})
    list(APPEND args --junit ${junit})
  endif()
  add_test(NAME ${BS_NAME}
    COMMAND bscript::bsc ${args} ${BS_OPTIONS} ${sources}
    COMMAND_EXPAND_LISTS)
  if(BS_JOBS MATCHES "^[1-9][0-9]*$")
    # `ctest -j` counts the cores the test's workers take.
    set_tests_properties(${BS_NAME} PROPERTIES PROCESSORS ${BS_JOBS})
  endif()
endfunction()

# The language server (`bsc lsp`, docs/editors.md) finds a behavior's
# --bind objects, -I folders and target in ${CMAKE_BINARY_DIR}/bscript.json:
# each bscript_add_behavior adds its entry, and the file is written once
# the whole project is configured (binding objects are generator
# expressions, known at generation).
function(_bscript_record_for_editors sources include_dirs binds triple)
  set(quoted)
  foreach(src IN LISTS sources)
    list(APPEND quoted "\"${src}\"")
  endforeach()
  list(JOIN quoted ", " sources_json)
  set(quoted)
  foreach(dir IN LISTS include_dirs)
    get_filename_component(dir "${dir}" ABSOLUTE)
    list(APPEND quoted "\"${dir}\"")
  endforeach()
  list(JOIN quoted ", " include_json)
  set(quoted)
  foreach(bind IN LISTS binds)
    if(TARGET ${bind})
      get_target_property(type ${bind} TYPE)
      if(type STREQUAL "OBJECT_LIBRARY")
        list(APPEND quoted
          "\"$<JOIN:$<TARGET_OBJECTS:${bind}>,\"$<COMMA> \">\"")
      else()
        list(APPEND quoted "\"$<TARGET_FILE:${bind}>\"")
      endif()
    else()
      get_filename_component(file "${bind}" ABSOLUTE)
      list(APPEND quoted "\"${file}\"")
    endif()
  endforeach()
  list(JOIN quoted ", " bind_json)
  set(entry "{\"sources\": [${sources_json}], \"include\": [${include_json}], \"bind\": [${bind_json}], \"target\": \"${triple}\"}")
  set_property(GLOBAL APPEND PROPERTY BSCRIPT_EDITOR_BEHAVIORS "${entry}")
  get_property(deferred GLOBAL PROPERTY BSCRIPT_EDITOR_FILE_DEFERRED)
  if(NOT deferred)
    set_property(GLOBAL PROPERTY BSCRIPT_EDITOR_FILE_DEFERRED TRUE)
    cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR}
      CALL _bscript_write_editor_file)
  endif()
endfunction()

function(_bscript_write_editor_file)
  get_property(entries GLOBAL PROPERTY BSCRIPT_EDITOR_BEHAVIORS)
  list(JOIN entries ",\n  " body)
  file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/bscript.json
    CONTENT "{\"behaviors\": [\n  ${body}\n]}\n")
endfunction()
