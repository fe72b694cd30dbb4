# Copyright (c) urdf-validator contributors. MIT License.

#
# Add a test checking the package's robot descriptions with urdf_validate.
#
# The test runs ament_urdf_validate in the package's source folder and writes
# ${AMENT_TEST_RESULTS_DIR}/${PROJECT_NAME}/<TESTNAME>.xunit.xml, where colcon test-result finds it.
# Options also come from package.xml (<export><urdf_validate args=".." exclude=".." fail-on=".."
# config=".."/>) and urdf-validate.toml (read by urdf_validate itself).
#
# :param TESTNAME: the name of the test, default: "urdf_validate"
# :type TESTNAME: string
# :param FAIL_ON: "warn" (default: a WARN fails the test) or "fail"
# :type FAIL_ON: string
# :param CONFIG: an urdf-validate.toml for every input (default: the nearest one of each file)
# :type CONFIG: string
# :param EXCLUDE: file and folder names to leave out
# :type EXCLUDE: list
# :param URDF_VALIDATE_ARGS: more arguments for urdf_validate (after --)
# :type URDF_VALIDATE_ARGS: list
# :param ARGN: the files or directories to check (default: the package's source folder)
# :type ARGN: list of strings
#
# @public
#
function(ament_urdf_validate)
  cmake_parse_arguments(ARG "" "TESTNAME;FAIL_ON;CONFIG" "EXCLUDE;URDF_VALIDATE_ARGS" ${ARGN})
  if(NOT ARG_TESTNAME)
    set(ARG_TESTNAME "urdf_validate")
  endif()

  find_program(ament_urdf_validate_BIN NAMES "ament_urdf_validate")
  if(NOT ament_urdf_validate_BIN)
    message(FATAL_ERROR "ament_urdf_validate() could not find program 'ament_urdf_validate'")
  endif()

  set(result_file "${AMENT_TEST_RESULTS_DIR}/${PROJECT_NAME}/${ARG_TESTNAME}.xunit.xml")
  # The paths first: --exclude takes every word up to the next option.
  set(cmd "${ament_urdf_validate_BIN}" ${ARG_UNPARSED_ARGUMENTS} "--xunit-file" "${result_file}")
  if(ARG_FAIL_ON)
    list(APPEND cmd "--fail-on" "${ARG_FAIL_ON}")
  endif()
  if(ARG_CONFIG)
    list(APPEND cmd "--config" "${ARG_CONFIG}")
  endif()
  if(ARG_EXCLUDE)
    list(APPEND cmd "--exclude" ${ARG_EXCLUDE})
  endif()
  if(ARG_URDF_VALIDATE_ARGS)
    list(APPEND cmd "--" ${ARG_URDF_VALIDATE_ARGS})
  endif()

  file(MAKE_DIRECTORY "${CMAKE_BINARY_DIR}/ament_urdf_validate")
  ament_add_test(
    "${ARG_TESTNAME}"
    COMMAND ${cmd}
    OUTPUT_FILE "${CMAKE_BINARY_DIR}/ament_urdf_validate/${ARG_TESTNAME}.txt"
    RESULT_FILE "${result_file}"
    WORKING_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}"
  )
  set_tests_properties(
    "${ARG_TESTNAME}"
    PROPERTIES
    LABELS "urdf_validate;linter"
  )
endfunction()
