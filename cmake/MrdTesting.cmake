# The one way tests are registered (tests/*/CMakeLists.txt).
#
# mrd_gtest(<target> LABEL <label> SOURCES <file>...
#           [LIBS <target>...] [DEFINES <NAME=value>...] [INCLUDES <dir>...]
#           [DEPENDS <target>...] [TIMEOUT <s>])
#   A GoogleTest program linked with gtest_main; each TEST becomes one CTest
#   test carrying LABEL. Its files are compiled in unity batches of six: much
#   of a test file's compile time is GoogleTest's code generation, done once
#   per batch (CI's two builds went from about 1200-1340 s to 990 s), so
#   helpers in a test file's anonymous namespace need names unique within
#   its program. DEPENDS names programs the tests run (they are built
#   first). A test whose name begins with LongStudy (TEST(Suite,
#   LongStudyWhatever)) is a study of minutes that a developer runs by hand
#   (`<program> --gtest_filter=*LongStudy*`); it is not registered with
#   CTest, so CI neither runs nor skips it.
#
# mrd_script_test(<name> LABEL <label> COMMAND <arg>...
#                 [TIMEOUT <s>] [SKIP_RETURN_CODE <n>])
#   A test run by a script (bash) or a program, one CTest test.
#
# Labels: unit (fast, in-process), cli (the programs run as a user runs them),
# integration (several programs or nodes together), cross (bare-metal
# Cortex-M4F compiles), layering, fuzz, discrepancy_study, emulated-board.

function(mrd_gtest target)
  cmake_parse_arguments(T "" "LABEL;TIMEOUT" "SOURCES;LIBS;DEFINES;INCLUDES;DEPENDS" ${ARGN})
  if(NOT T_LABEL OR NOT T_SOURCES)
    message(FATAL_ERROR "mrd_gtest(${target}): LABEL and SOURCES are required")
  endif()
  add_executable(${target} ${T_SOURCES})
  target_link_libraries(${target} PRIVATE ${T_LIBS} GTest::gtest_main)
  set_target_properties(${target} PROPERTIES UNITY_BUILD_BATCH_SIZE 6)
  if(T_DEFINES)
    target_compile_definitions(${target} PRIVATE ${T_DEFINES})
  endif()
  if(T_INCLUDES)
    target_include_directories(${target} PRIVATE ${T_INCLUDES})
  endif()
  if(T_DEPENDS)
    add_dependencies(${target} ${T_DEPENDS})
  endif()
  set(properties LABELS ${T_LABEL})
  if(T_TIMEOUT)
    list(APPEND properties TIMEOUT ${T_TIMEOUT})
  endif()
  gtest_discover_tests(${target} DISCOVERY_MODE PRE_TEST TEST_FILTER "-*.LongStudy*" PROPERTIES ${properties})
endfunction()

function(mrd_script_test name)
  cmake_parse_arguments(T "" "LABEL;TIMEOUT;SKIP_RETURN_CODE" "COMMAND" ${ARGN})
  if(NOT T_LABEL OR NOT T_COMMAND)
    message(FATAL_ERROR "mrd_script_test(${name}): LABEL and COMMAND are required")
  endif()
  add_test(NAME ${name} COMMAND ${T_COMMAND})
  set_tests_properties(${name} PROPERTIES LABELS ${T_LABEL})
  if(T_TIMEOUT)
    set_tests_properties(${name} PROPERTIES TIMEOUT ${T_TIMEOUT})
  endif()
  if(T_SKIP_RETURN_CODE)
    set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE ${T_SKIP_RETURN_CODE})
  endif()
endfunction()
