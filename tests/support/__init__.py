"""Helpers shared by tests (importable as ``support`` from the tests directory)."""
