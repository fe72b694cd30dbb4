# Copyright (c) urdf-validator contributors. MIT License.
#
# Loaded by find_package(ament_cmake_urdf_validate): defines ament_urdf_validate() and registers the
# ament_lint_auto hook, as ament_cmake_xmllint does.

find_package(ament_cmake_test QUIET REQUIRED)

include("${ament_cmake_urdf_validate_DIR}/ament_urdf_validate.cmake")

ament_register_extension("ament_lint_auto" "ament_cmake_urdf_validate"
  "ament_cmake_urdf_validate_lint_hook.cmake")
