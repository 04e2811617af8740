# Helper functions every folder CMakeLists.txt uses, and the layer rule.
#
#   rover_add_module(NAME <target> SOURCES ... [DEPS ...] [LAYER <layer>] [SIMBODY])
#       A library. Its layer is the top-level folder it lives in (idl, core, ddl, dl, apl, sim,
#       deploy, tests) unless LAYER overrides it. Public headers live in <folder>/include.
#   rover_add_service(NAME <exe> SOURCES ... [DEPS ...] [LAYER <layer>] [SIMBODY])
#       A service: a process that joins the bus (RunServiceMain, --help-params), with a page
#       docs/services/<exe>.md. Written to ${CMAKE_BINARY_DIR}/bin like the two below.
#   rover_add_tool(...)       same arguments: a command-line tool for people (roverctl, rover-drive)
#   rover_add_benchmark(...)  same arguments: prints figures beside a baseline measured in the
#       same run; `ninja benchmarks` builds them all. rover_write_executable_lists() writes
#       build/rover_executables.txt (kind and name per line) for the consistency tests.
#   rover_add_test(NAME <test> SOURCES ... [DEPS ...] [LABELS ...] [TIMEOUT s] [COST s] [SIMBODY]
#                  [GROUP_SUITES <suite>... | ONE_ENTRY])
#       A GoogleTest executable. Every test case is its own CTest entry <test>.<Suite>.<Case>
#       (listed after the build by gtest_discover_tests), with the executable's labels,
#       environment and TIMEOUT (per case). Cases that share an expensive fixture stay together:
#       GROUP_SUITES makes each named suite one entry <test>.<Suite> (a SetUpTestSuite that
#       renders or loads once); ONE_ENTRY makes the whole executable one entry <test> (cases that
#       must not run beside each other, or that all start the same service sets). COST (about
#       the seconds an entry takes) makes CTest start long entries first, so that a fresh checkout
#       (no timing history yet) does not end on one long test running alone.
#   rover_check_layers()
#       Called once at the end of the top-level CMakeLists.txt: fails the configure step if any
#       module links a module of a layer it may not use, naming both targets.
#
# Layer rule (docs/architecture.md): idl < core < {ddl, dl, apl, sim}; ddl, dl, apl and sim may
# use core and idl and modules of their own layer, never each other's code (they talk over
# topics). deploy (roverctl and tools) may use core, idl and sim (the judge). Tests may use
# anything. In addition, a *library* in ddl, dl, apl or sim holds algorithms and may not link
# DDS (rover_runtime, rover_idl or CycloneDDS::ddsc): only its service executable binds topics.

include_guard(GLOBAL)
include(GoogleTest)

set_property(GLOBAL PROPERTY ROVER_MODULES "")

set(ROVER_LAYERS idl core ddl dl apl sim deploy tests)
set(ROVER_ALLOWED_idl idl)
set(ROVER_ALLOWED_core idl core)
set(ROVER_ALLOWED_ddl idl core ddl)
set(ROVER_ALLOWED_dl idl core dl)
set(ROVER_ALLOWED_apl idl core apl)
set(ROVER_ALLOWED_sim idl core sim)
set(ROVER_ALLOWED_deploy idl core sim deploy)
set(ROVER_ALLOWED_tests ${ROVER_LAYERS})
# Targets that carry DDS; algorithm libraries of the four stack layers may not link them.
set(ROVER_DDS_TARGETS rover_runtime rover_idl CycloneDDS::ddsc)

function(_rover_layer_of out)
  cmake_parse_arguments(L "" "LAYER" "" ${ARGN})
  if(L_LAYER)
    set(layer "${L_LAYER}")
  else()
    file(RELATIVE_PATH rel "${PROJECT_SOURCE_DIR}" "${CMAKE_CURRENT_SOURCE_DIR}")
    string(REGEX REPLACE "/.*" "" layer "${rel}")
  endif()
  if(NOT layer IN_LIST ROVER_LAYERS)
    message(FATAL_ERROR "rover: cannot tell the layer of ${CMAKE_CURRENT_SOURCE_DIR} "
                        "(got '${layer}'); expected one of: ${ROVER_LAYERS}")
  endif()
  set(${out} "${layer}" PARENT_SCOPE)
endfunction()

function(_rover_common_target_setup target simbody)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE ${ROVER_WARNING_FLAGS})
  if(ROVER_UNITY_BUILD)
    # Sources of one target share a batch, so file-local names (anonymous namespaces, statics)
    # must be unique within the target.
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON
                                               UNITY_BUILD_BATCH_SIZE ${ROVER_UNITY_BATCH})
  endif()
  if(simbody)
    # Debian's Simbody 3.7 is built without NDEBUG; its headers change class layouts with it.
    # A translation unit that includes them with -DNDEBUG crashes in realizeTopology.
    target_compile_options(${target} PRIVATE -UNDEBUG)
  endif()
endfunction()

function(_rover_register target layer kind)
  set_property(GLOBAL APPEND PROPERTY ROVER_MODULES ${target})
  set_target_properties(${target} PROPERTIES ROVER_LAYER ${layer} ROVER_KIND ${kind}
                                             ROVER_SOURCE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
endfunction()

function(rover_add_module)
  cmake_parse_arguments(M "SIMBODY;INTERFACE" "NAME;LAYER" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  if(NOT M_NAME)
    message(FATAL_ERROR "rover_add_module: NAME is required")
  endif()
  _rover_layer_of(layer LAYER "${M_LAYER}")
  if(M_INTERFACE OR NOT M_SOURCES)
    add_library(${M_NAME} INTERFACE)
    if(EXISTS "${CMAKE_CURRENT_SOURCE_DIR}/include")
      target_include_directories(${M_NAME} INTERFACE "${CMAKE_CURRENT_SOURCE_DIR}/include")
    endif()
    target_link_libraries(${M_NAME} INTERFACE ${M_DEPS})
    target_compile_features(${M_NAME} INTERFACE cxx_std_20)
  else()
    add_library(${M_NAME} STATIC ${M_SOURCES})
    if(EXISTS "${CMAKE_CURRENT_SOURCE_DIR}/include")
      target_include_directories(${M_NAME} PUBLIC "${CMAKE_CURRENT_SOURCE_DIR}/include")
    endif()
    target_include_directories(${M_NAME} PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}")
    target_link_libraries(${M_NAME} PUBLIC ${M_DEPS} PRIVATE ${M_PRIVATE_DEPS})
    _rover_common_target_setup(${M_NAME} "${M_SIMBODY}")
  endif()
  _rover_register(${M_NAME} ${layer} library)
endfunction()

# One executable of `kind` (service, tool or benchmark), written to ${CMAKE_BINARY_DIR}/bin.
function(_rover_add_executable kind)
  cmake_parse_arguments(S "SIMBODY" "NAME;LAYER;OUTPUT_NAME" "SOURCES;DEPS" ${ARGN})
  if(NOT S_NAME OR NOT S_SOURCES)
    message(FATAL_ERROR "rover_add_${kind}: NAME and SOURCES are required")
  endif()
  _rover_layer_of(layer LAYER "${S_LAYER}")
  add_executable(${S_NAME} ${S_SOURCES})
  target_include_directories(${S_NAME} PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}")
  target_link_libraries(${S_NAME} PRIVATE ${S_DEPS})
  set_target_properties(${S_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/bin")
  if(S_OUTPUT_NAME)
    set_target_properties(${S_NAME} PROPERTIES OUTPUT_NAME ${S_OUTPUT_NAME})
  endif()
  _rover_common_target_setup(${S_NAME} "${S_SIMBODY}")
  _rover_register(${S_NAME} ${layer} ${kind})
  set_property(GLOBAL APPEND PROPERTY ROVER_EXECUTABLES_${kind} ${S_NAME})
  if(kind STREQUAL "benchmark" AND NOT ROVER_BUILD_BENCHMARKS)
    set_target_properties(${S_NAME} PROPERTIES EXCLUDE_FROM_ALL ON)
    return()
  endif()
  install(TARGETS ${S_NAME} RUNTIME DESTINATION bin)
endfunction()

function(rover_add_service)
  _rover_add_executable(service ${ARGN})
endfunction()
function(rover_add_tool)
  _rover_add_executable(tool ${ARGN})
endfunction()
function(rover_add_benchmark)
  _rover_add_executable(benchmark ${ARGN})
endfunction()

function(rover_add_test)
  cmake_parse_arguments(T "SIMBODY;NO_GTEST_MAIN;ONE_ENTRY" "NAME;TIMEOUT;LAYER;COST"
                        "SOURCES;DEPS;LABELS;ARGS;GROUP_SUITES" ${ARGN})
  if(NOT T_NAME OR NOT T_SOURCES)
    message(FATAL_ERROR "rover_add_test: NAME and SOURCES are required")
  endif()
  if(T_ONE_ENTRY AND T_GROUP_SUITES)
    message(FATAL_ERROR "rover_add_test(${T_NAME}): ONE_ENTRY and GROUP_SUITES exclude each other")
  endif()
  if(NOT BUILD_TESTING)
    return()
  endif()
  _rover_layer_of(layer LAYER "${T_LAYER}")
  add_executable(${T_NAME} ${T_SOURCES})
  target_include_directories(${T_NAME} PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}")
  if(T_NO_GTEST_MAIN)
    target_link_libraries(${T_NAME} PRIVATE ${T_DEPS} GTest::gtest GTest::gmock)
  else()
    target_link_libraries(${T_NAME} PRIVATE ${T_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
  endif()
  set_target_properties(${T_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/tests")
  _rover_common_target_setup(${T_NAME} "${T_SIMBODY}")
  if(ROVER_TEST_OPT_FLAG AND NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
    target_compile_options(${T_NAME} PRIVATE ${ROVER_TEST_OPT_FLAG})  # after the -O2 of the build type
  endif()
  target_compile_definitions(${T_NAME} PRIVATE
    ROVER_SOURCE_DIR="${PROJECT_SOURCE_DIR}" ROVER_BINARY_DIR="${CMAKE_BINARY_DIR}"
    ROVER_SHARED_DATA_DIR="${ROVER_SHARED_DATA_DIR}")
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 120)
  endif()
  if(NOT T_LABELS)
    set(T_LABELS unit)
  endif()
  if(NOT T_COST)
    set(T_COST 0)
  endif()
  set(env "ROVER_BIN_DIR=${CMAKE_BINARY_DIR}/bin" "ROVER_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
  if(T_ONE_ENTRY)
    add_test(NAME ${T_NAME} COMMAND ${T_NAME} ${T_ARGS})
    set_tests_properties(${T_NAME} PROPERTIES TIMEOUT ${T_TIMEOUT} LABELS "${T_LABELS}"
                         ENVIRONMENT "${env}" COST ${T_COST})
  else()
    set(grouped "")
    foreach(suite IN LISTS T_GROUP_SUITES)
      add_test(NAME ${T_NAME}.${suite} COMMAND ${T_NAME} --gtest_filter=${suite}.* ${T_ARGS})
      # A suite name that matches no case would pass silently.
      set_tests_properties(${T_NAME}.${suite} PROPERTIES TIMEOUT ${T_TIMEOUT} COST ${T_COST}
                           LABELS "${T_LABELS}" ENVIRONMENT "${env}"
                           FAIL_REGULAR_EXPRESSION "Running 0 tests")
      list(APPEND grouped "${suite}.*")
    endforeach()
    set(filter "")
    if(grouped)
      list(JOIN grouped ":" excluded)
      set(filter TEST_FILTER "-${excluded}")
    endif()
    gtest_discover_tests(${T_NAME} EXTRA_ARGS ${T_ARGS} TEST_PREFIX "${T_NAME}." ${filter}
                         TEST_LIST ${T_NAME}_CASES DISCOVERY_TIMEOUT 120)
    # The cases' properties are set by a script CTest reads after the discovered list:
    # gtest_discover_tests(PROPERTIES) cannot pass a value that is itself a list (ENVIRONMENT).
    set(props "${CMAKE_CURRENT_BINARY_DIR}/${T_NAME}_case_properties.cmake")
    file(WRITE "${props}"
      "if(${T_NAME}_CASES)\n"
      "  set_tests_properties(\${${T_NAME}_CASES} PROPERTIES TIMEOUT ${T_TIMEOUT} COST ${T_COST}\n"
      "    LABELS [==[${T_LABELS}]==] ENVIRONMENT [==[${env}]==])\n"
      "endif()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${props}")
  endif()
  _rover_register(${T_NAME} ${layer} test)
endfunction()

# Returns in `out` the rover modules that `target` links directly.
function(_rover_direct_deps target out)
  set(deps "")
  foreach(prop LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
    get_target_property(libs ${target} ${prop})
    if(libs)
      foreach(lib IN LISTS libs)
        # Strip generator expressions such as $<LINK_ONLY:x>.
        string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" lib "${lib}")
        list(APPEND deps "${lib}")
      endforeach()
    endif()
  endforeach()
  list(REMOVE_DUPLICATES deps)
  set(${out} "${deps}" PARENT_SCOPE)
endfunction()

function(rover_check_layers)
  get_property(modules GLOBAL PROPERTY ROVER_MODULES)
  set(errors "")
  foreach(target IN LISTS modules)
    get_target_property(layer ${target} ROVER_LAYER)
    get_target_property(kind ${target} ROVER_KIND)
    if(kind STREQUAL "test")
      continue()  # tests may use anything
    endif()
    _rover_direct_deps(${target} deps)
    foreach(dep IN LISTS deps)
      if(TARGET ${dep})
        get_target_property(dep_layer ${dep} ROVER_LAYER)
        if(dep_layer)
          if(NOT dep_layer IN_LIST ROVER_ALLOWED_${layer})
            string(APPEND errors
              "  layer rule: ${layer} target '${target}' links ${dep_layer} target '${dep}'; "
              "${layer} may use only: ${ROVER_ALLOWED_${layer}} (talk over topics instead)\n")
          endif()
        endif()
      endif()
      if(kind STREQUAL "library" AND layer MATCHES "^(ddl|dl|apl|sim)$"
         AND dep IN_LIST ROVER_DDS_TARGETS)
        string(APPEND errors
          "  layer rule: ${layer} library '${target}' links DDS target '${dep}'; algorithm "
          "libraries stay free of DDS, only their service binds topics\n")
      endif()
    endforeach()
  endforeach()
  if(errors)
    message(FATAL_ERROR "rover: the layer rule is broken:\n${errors}")
  endif()
endfunction()

# Writes ${CMAKE_BINARY_DIR}/rover_executables.txt ("<kind> <name>" per line) and adds the
# `benchmarks` target. Called once at the end of the top-level CMakeLists.txt.
function(rover_write_executable_lists)
  set(text "")
  foreach(kind service tool benchmark)
    get_property(names GLOBAL PROPERTY ROVER_EXECUTABLES_${kind})
    list(SORT names)
    foreach(name IN LISTS names)
      string(APPEND text "${kind} ${name}\n")
    endforeach()
  endforeach()
  file(GENERATE OUTPUT "${CMAKE_BINARY_DIR}/rover_executables.txt" CONTENT "${text}")
  get_property(benchmarks GLOBAL PROPERTY ROVER_EXECUTABLES_benchmark)
  if(benchmarks)
    add_custom_target(benchmarks DEPENDS ${benchmarks})
  endif()
endfunction()

# Adds every sub-folder of the current folder that has a CMakeLists.txt, in sorted order.
# ROVER_MODULE_FILTER (a regex over paths relative to the source root, e.g. "dl/stereo|core/.*")
# limits which component folders are added, for building one module in isolation.
# EXCLUDE names sub-folders the caller adds itself.
set(ROVER_MODULE_FILTER "" CACHE STRING "Regex of component folders to build (empty = all)")
function(rover_add_subdirectories)
  cmake_parse_arguments(A "" "" "EXCLUDE" ${ARGN})
  file(GLOB children RELATIVE "${CMAKE_CURRENT_SOURCE_DIR}" "${CMAKE_CURRENT_SOURCE_DIR}/*/CMakeLists.txt")
  list(SORT children)
  foreach(child IN LISTS children)
    get_filename_component(dir "${child}" DIRECTORY)
    if(dir IN_LIST A_EXCLUDE)
      continue()
    endif()
    file(RELATIVE_PATH rel "${PROJECT_SOURCE_DIR}" "${CMAKE_CURRENT_SOURCE_DIR}/${dir}")
    if(ROVER_MODULE_FILTER AND NOT rel MATCHES "^(${ROVER_MODULE_FILTER})$")
      continue()
    endif()
    add_subdirectory("${dir}")
  endforeach()
endfunction()
