# heightpack_add_gtest_suites(TARGET [PROPERTIES prop value ...]): one ctest test per test suite of a
# googletest program (run with --gtest_filter=Suite.*), discovered when ctest runs, as
# gtest_discover_tests(DISCOVERY_MODE PRE_TEST) does one per test case. Each test program starts in
# about 0.14 s (the ~260 shared libraries that come with OpenImageIO): a process per suite instead of per
# case saves most of a minute of the tests' time, and a failing suite still names its failing case.
function(heightpack_add_gtest_suites target)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "" "PROPERTIES")
  set(dir "${CMAKE_CURRENT_BINARY_DIR}")
  set(properties "")
  foreach(word IN LISTS ARG_PROPERTIES)
    string(APPEND properties " \"${word}\"")
  endforeach()
  set(template [[
set(exe "$<TARGET_FILE:@target@>")
if(NOT EXISTS "${exe}")
  # With the suites' properties: a program a build leaves out (see tests/CMakeLists.txt) keeps its label,
  # so a run that excludes the label does not fail on it, and one that selects it does.
  add_test(@target@_NOT_BUILT "${exe}")
  set_tests_properties(@target@_NOT_BUILT PROPERTIES WORKING_DIRECTORY "@dir@"@properties@)
  return()
endif()
execute_process(COMMAND "${exe}" --gtest_list_tests OUTPUT_VARIABLE listing RESULT_VARIABLE status
  WORKING_DIRECTORY "@dir@")
if(NOT status EQUAL 0)
  add_test(@target@_CANNOT_LIST "${exe}" --gtest_list_tests)
  return()
endif()
string(REPLACE "\n" ";" lines "${listing}")
foreach(line IN LISTS lines)
  # A suite's line is flush left and ends in a dot, maybe followed by "  # TypeParam = ...".
  if(line MATCHES "^([^ #][^ ]*)\\.( .*)?$")
    set(suite "${CMAKE_MATCH_1}")
    add_test("${suite}" "${exe}" "--gtest_filter=${suite}.*")
    set_tests_properties("${suite}" PROPERTIES WORKING_DIRECTORY "@dir@"@properties@)
  endif()
endforeach()
]])
  string(CONFIGURE "${template}" content @ONLY)
  set(script "${dir}/${target}_suites.cmake")
  file(GENERATE OUTPUT "${script}" CONTENT "${content}")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${script}")
endfunction()
