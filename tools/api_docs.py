"""Build the API reference of broadsword.collision and broadsword.patterns from their docstrings.

    python3 tools/api_docs.py [OUT]        # HTML into OUT (default build/api); needs pdoc (the dev extra)

Every public submodule is documented, not only what a package's ``__all__`` re-exports. A
package that is not there yet is skipped with a note. Exit status 1 if pdoc is missing or
documents nothing.
"""

from __future__ import annotations

import importlib
import pkgutil
import sys
import warnings
from pathlib import Path

PACKAGES = ("broadsword.collision", "broadsword.patterns")


def modules() -> list[str]:
    """The packages of :data:`PACKAGES` that exist and their public submodules."""
    out = []
    for name in PACKAGES:
        try:
            package = importlib.import_module(name)
        except ModuleNotFoundError:
            print(f"api_docs: {name} not found; skipped", file=sys.stderr)
            continue
        out.append(name)
        out += [f"{name}.{m.name}" for m in pkgutil.walk_packages(package.__path__) if not m.name.startswith("_")]
    return out


def main(argv: list[str]) -> int:
    out = Path(argv[0] if argv else "build/api")
    try:
        import pdoc
    except ImportError:
        print("api_docs: pdoc is not installed (pip install -e '.[dev]')", file=sys.stderr)
        return 1
    names = modules()
    if not names:
        return 1
    with warnings.catch_warnings():
        # Every public submodule is listed (a package's __all__ may not name them), and pdoc
        # also walks a package without __all__ itself: it then says each such module was
        # added twice, and documents it once. Nothing is lost; the note is noise.
        warnings.filterwarnings("ignore", message=r"The module specification .* has already been added")
        pdoc.pdoc(*names, output_directory=out)
    pages = sorted(out.rglob("*.html"))
    print(f"api_docs: {len(names)} modules, {len(pages)} pages in {out}")
    return 0 if pages else 1


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
