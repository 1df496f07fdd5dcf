# Shared build settings for project targets. Third-party headers come in through imported targets,
# whose include directories CMake treats as SYSTEM, so -Werror applies to project code only.

# pushpull_project_target(<target>): warnings as errors and the configured sanitizers.
function(pushpull_project_target target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror)
  if(PUSHPULL_SANITIZE)
    list(JOIN PUSHPULL_SANITIZE "," sanitizers)
    target_compile_options(${target} PRIVATE -fsanitize=${sanitizers} -fno-sanitize-recover=all
                                             -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=${sanitizers})
  endif()
endfunction()

# pushpull_add_gtest(<name> SOURCES ... LIBS ... LABELS ... [TIMEOUT s])
# One GoogleTest executable; every TEST in it becomes a ctest test carrying LABELS
# (unit, integration, gpu, xr). Tests run with the repository root as working directory
# and PUSHPULL_SHARED_DATA / PUSHPULL_SOURCE_DIR in the environment.
function(pushpull_add_gtest name)
  cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  pushpull_project_target(${name})
  target_compile_definitions(${name} PRIVATE
    PUSHPULL_SHARED_DATA="${PUSHPULL_SHARED_DATA_DIR}"
    PUSHPULL_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    PUSHPULL_BINARY_DIR="${CMAKE_BINARY_DIR}")
  gtest_discover_tests(${name}
    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
    TEST_LIST ${name}_TESTS
    PROPERTIES TIMEOUT ${ARG_TIMEOUT}
    DISCOVERY_TIMEOUT 60)
  pushpull_label_discovered_tests(${name} ${ARG_LABELS})
endfunction()

# pushpull_label_discovered_tests(<gtest target> LABEL...): gives every test discovered from the target
# all the labels. gtest_discover_tests splits its PROPERTIES on ';', so LABELS "unit;service" there would
# set only "unit" (and `ctest -L service` would find nothing); a ctest include file that runs after the
# discovered tests are defined sets them instead. Needs TEST_LIST <target>_TESTS in gtest_discover_tests.
function(pushpull_label_discovered_tests name)
  set(labels_file ${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake)
  file(WRITE ${labels_file}
    "if(${name}_TESTS)\n  set_tests_properties(\${${name}_TESTS} PROPERTIES LABELS \"${ARGN}\")\nendif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${labels_file})
endfunction()
