"""No import loop inside ``broadsword.collision`` (issue 24.1), read from the source.

Every ``import`` statement counts, including those inside functions (a lazy import still
ties two modules together). ``from .pkg import name`` is an arrow to ``pkg.name`` when that
is a module, else to ``pkg``.
"""

from __future__ import annotations

import ast
from pathlib import Path

import broadsword.collision

ROOT = Path(broadsword.collision.__file__).parent
PACKAGE = "broadsword.collision"


def _name(path: Path) -> str:
    parts = [PACKAGE, *path.relative_to(ROOT).with_suffix("").parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _graph() -> dict[str, set[str]]:
    modules = {_name(p): p for p in ROOT.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
        out = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = ".".join(package[: len(package) - node.level + 1]) if node.level else ""
                mod = ".".join(p for p in (base, node.module or "") if p)
                targets = [f"{mod}.{a.name}" if f"{mod}.{a.name}" in modules else mod for a in node.names]
            else:
                continue
            out |= {t for t in targets if t in modules and t != name}
        graph[name] = out
    return graph


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import loop as a list of modules, or None (depth-first search)."""
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(m: str) -> list[str] | None:
        state[m] = 1
        stack.append(m)
        for n in sorted(graph[m]):
            if state.get(n) == 1:
                return [*stack[stack.index(n) :], n]
            if n not in state and (found := visit(n)):
                return found
        stack.pop()
        state[m] = 2
        return None

    for m in sorted(graph):
        if m not in state and (found := visit(m)):
            return found
    return None


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
