"""Where the shipped levels and assets live, installed or in a source checkout.

A wheel carries the repository's top-level ``levels/`` and ``assets/`` folders as the
packages ``broadsword.levels`` and ``broadsword.assets`` (see pyproject.toml). An
editable install or a plain checkout has no such packages, so the folders beside the
``broadsword`` package are used instead.
"""

from __future__ import annotations

from pathlib import Path

from .errors import DataError

_PACKAGE = Path(__file__).resolve().parents[1]  # .../broadsword
_ROOT = _PACKAGE.parent  # the repository, in a source checkout


def data_dir(kind: str) -> Path:
    """The folder of shipped ``"levels"`` or ``"assets"``: inside the installed package,
    else beside it in a source checkout (an editable install)."""
    if kind not in ("levels", "assets"):
        raise ValueError(f"kind must be 'levels' or 'assets', got {kind!r}")
    for path in (_PACKAGE / kind, _ROOT / kind):
        if path.is_dir():
            return path
    raise FileNotFoundError(f"shipped {kind} not found in {_PACKAGE / kind} or {_ROOT / kind}")


def list_levels() -> list[str]:
    """Names of the shipped levels, in play order (file names sort by their number prefix)."""
    return [p.stem for p in sorted(data_dir("levels").glob("*.toml"))]


def resolve_level(name_or_path: str) -> Path:
    """A shipped level's name (as :func:`list_levels` gives) or a path to a level file."""
    path = Path(name_or_path)
    if path.suffix == ".toml" or path.exists():
        if not path.is_file():
            raise DataError(path, "", "no such level file")
        return path
    shipped = data_dir("levels") / f"{name_or_path}.toml"
    if not shipped.is_file():
        raise DataError(name_or_path, "", f"no such level; shipped levels are {', '.join(list_levels())}")
    return shipped
