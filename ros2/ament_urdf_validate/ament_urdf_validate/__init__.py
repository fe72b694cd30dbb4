"""ament linter for robot descriptions: runs urdf_validate and writes an xUnit result file."""
