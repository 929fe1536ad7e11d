"""The one error type of the data layer."""

from __future__ import annotations

from pathlib import Path


class DataError(ValueError):
    """A data file failed to load. ``str(err)`` is one line: ``file: field: what is wrong``."""

    def __init__(self, path: str | Path, field: str, message: str):
        self.path, self.field, self.message = str(path), field, message
        super().__init__(f"{self.path}: {field}: {message}" if field else f"{self.path}: {message}")
