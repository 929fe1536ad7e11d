"""A package's import graph, read from its source, and one import loop in it.

Every ``import`` statement counts, including those inside functions and under
``TYPE_CHECKING`` (a lazy or type-only import still ties two modules together).
``from .pkg import name`` is an arrow to ``pkg.name`` when that is a module, else to ``pkg``.
"""

from __future__ import annotations

import ast
from pathlib import Path
from types import ModuleType


def import_graph(package: ModuleType) -> dict[str, set[str]]:
    """Module name -> the modules of ``package`` it imports (itself excluded)."""
    root, prefix = Path(package.__file__ or "").parent, package.__name__

    def name(path: Path) -> str:
        parts = [prefix, *path.relative_to(root).with_suffix("").parts]
        return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)

    modules = {name(p): p for p in root.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for mod_name, path in modules.items():
        here = mod_name.split(".") if path.name == "__init__.py" else mod_name.split(".")[:-1]
        out: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = ".".join(here[: len(here) - node.level + 1]) if node.level else ""
                mod = ".".join(p for p in (base, node.module or "") if p)
                targets = [f"{mod}.{a.name}" if f"{mod}.{a.name}" in modules else mod for a in node.names]
            else:
                continue
            out |= {t for t in targets if t in modules and t != mod_name}
        graph[mod_name] = out
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import loop as a list of modules (the first repeated at the end), or None."""
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
