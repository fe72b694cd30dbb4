"""The task-query API, at the import path the spec documents."""
