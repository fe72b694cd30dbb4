# Copyright (c) urdf-validator contributors. MIT License.
#
# ament_lint_auto's hook: adds the urdf_validate test when the package holds robot descriptions
# (*.urdf, *.xacro, *.sdf, *.world; MJCF *.xml files are found by the linter, not by this glob).
# ament_lint_auto_find_test_dependencies() runs it for every <test_depend> that registered one.

file(GLOB_RECURSE _ament_urdf_validate_files FOLLOW_SYMLINKS
  "*.urdf" "*.xacro" "*.sdf" "*.world")
if(_ament_urdf_validate_files)
  message(STATUS "Added test 'urdf_validate' to check robot descriptions with urdf_validate")
  ament_urdf_validate()
endif()
