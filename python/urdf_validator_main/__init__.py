"""Compatibility package: the import paths of the Python tool this one replaces
(``urdf_validator_main.api.task_runner``, ``urdf_validator_main.api.task_schema``)."""
