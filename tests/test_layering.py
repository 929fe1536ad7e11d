"""The house's layering (DESIGN.md, Layers), checked from the code so it cannot rot.

``collision`` <- ``patterns``, ``authoring`` <- ``sim`` <- ``runner`` <- ``game``; ``data`` feeds
``authoring``, ``sim``, ``runner`` and ``game``; ``bench`` may use all, and nothing imports ``bench``. Two checks: every module
below ``game`` imports with pygame blocked, and no module imports a layer above its own
(read from the source, every ``import`` statement, including those inside functions).
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import broadsword

ROOT = Path(broadsword.__file__).parent

#: What each package may import (besides itself). ``fileio`` is a leaf utility module
#: any layer may use; the command-line modules (``cli``, ``headless``, ...) sit on top.
LEAVES = {"fileio"}
ALLOWED = {
    "collision": set(),
    "patterns": {"collision"},
    "authoring": {"collision", "data"},  # the editor's document reads and writes armature files through data
    "data": {"collision", "patterns"},
    "sim": {"collision", "patterns", "authoring", "data"},
    "runner": {"collision", "patterns", "authoring", "data", "sim"},  # the game runner: no pygame
    "game": {"collision", "patterns", "authoring", "data", "sim", "runner"},
}
BELOW_GAME = ("collision", "patterns", "authoring", "data", "sim", "runner")


def _modules(package: str) -> list[Path]:
    folder = ROOT / package
    return sorted(folder.rglob("*.py")) if folder.is_dir() else []


def _module_name(path: Path) -> str:
    rel = path.relative_to(ROOT.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _is_layer(name: str) -> bool:
    return (ROOT / name).is_dir() or (ROOT / f"{name}.py").is_file()


def _imported_layers(path: Path) -> set[tuple[str, int]]:
    """``(top-level part of broadsword imported, line)`` for every import in ``path``."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    here = _module_name(path).split(".")
    package = here if path.name == "__init__.py" else here[:-1]
    out = set()
    for node in ast.walk(tree):
        targets = []
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
                targets = [mod] if node.module else [f"{mod}.{a.name}" for a in node.names]
            else:
                targets = [node.module or ""]
        for t in targets:
            parts = t.split(".")
            # ``from .. import __version__``: an attribute of the root package, not a layer
            if parts[0] == "broadsword" and len(parts) > 1 and _is_layer(parts[1]):
                out.add((parts[1], node.lineno))
    return out


def test_layering__every_package_imports_only_layers_below():
    bad = []
    for package, allowed in ALLOWED.items():
        for path in _modules(package):
            for layer, line in _imported_layers(path):
                if layer != package and layer not in allowed and layer not in LEAVES:
                    bad.append(f"{path.relative_to(ROOT.parent)}:{line} imports broadsword.{layer}")
    assert not bad, "imports against the layering:\n" + "\n".join(sorted(bad))


def test_layering__nothing_imports_bench():
    bad = [
        f"{path.relative_to(ROOT.parent)}:{line}"
        for path in ROOT.rglob("*.py")
        if "bench" not in path.relative_to(ROOT).parts
        for layer, line in _imported_layers(path)
        if layer == "bench"
    ]
    assert not bad, "bench is imported by: " + ", ".join(bad)


def test_layering__the_checker_sees_relative_and_nested_imports():
    """The checker itself: relative imports two levels up, and an import inside a function."""
    assert {layer for layer, _ in _imported_layers(ROOT / "collision" / "broadphase" / "grid.py")} == {"collision"}
    assert {layer for layer, _ in _imported_layers(ROOT / "data" / "levels" / "load.py")} >= {"collision", "data"}
    assert "game" in {layer for layer, _ in _imported_layers(ROOT / "bench" / "truth.py")}  # inside a function


def test_layering__below_game_imports_without_pygame():
    names = [_module_name(p) for pkg in BELOW_GAME for p in _modules(pkg)]
    assert len(names) > 40, names
    code = (
        "import importlib, sys\n"
        "sys.modules['pygame'] = None\n"
        f"for name in {names!r}:\n"
        "    importlib.import_module(name)\n"
        "assert 'pygame' not in [m.split('.')[0] for m in sys.modules if sys.modules[m] is not None]\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT.parent)
