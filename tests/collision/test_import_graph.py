"""No import loop inside ``broadsword.collision`` (issue 24.1), read from the source
(``tests/support/imports.py``: every import counts, lazy and type-only ones too)."""

from __future__ import annotations

from support.imports import find_cycle as _cycle
from support.imports import import_graph

import broadsword.collision

PACKAGE = "broadsword.collision"


def _graph() -> dict[str, set[str]]:
    return import_graph(broadsword.collision)


def test_import_graph__collision_has_no_import_loop():
    graph = _graph()
    assert len(graph) > 25 and f"{PACKAGE}._kernel" in graph[f"{PACKAGE}._narrow_kernel"]
    assert _cycle(graph) is None, " -> ".join(_cycle(graph) or [])


def test_import_graph__the_checker_finds_a_loop():
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": set()}) is None


def test_import_graph__no_loop_between_collision_and_its_subpackages():
    """Seen a folder at a time (``broadphase/`` as one node), the arrows still point one way:
    the backend sits below the bin grid, and the compiled grid kernel below both."""
    folder = f"{PACKAGE}.broadphase"

    def node(m: str) -> str:
        return folder if m.startswith(folder + ".") else m

    coarse: dict[str, set[str]] = {}
    for m, targets in _graph().items():
        coarse.setdefault(node(m), set()).update(node(t) for t in targets if node(t) != node(m))
    assert f"{PACKAGE}.backend" in coarse[folder]  # the grid takes a backend
    assert _cycle(coarse) is None, " -> ".join(_cycle(coarse) or [])
