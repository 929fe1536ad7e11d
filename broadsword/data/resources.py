"""Where the shipped levels and assets live, installed or in a source checkout.

A wheel carries the repository's top-level ``levels/`` and ``assets/`` folders as the
packages ``broadsword.levels`` and ``broadsword.assets`` (see pyproject.toml). An
editable install or a plain checkout has no such packages, so the folders beside the
``broadsword`` package are used instead.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from .errors import DataError

_ROOT = Path(__file__).resolve().parents[2]  # the repository, in a source checkout


def data_dir(kind: str) -> Path:
    """The folder of shipped ``"levels"`` or ``"assets"``."""
    if kind not in ("levels", "assets"):
        raise ValueError(f"kind must be 'levels' or 'assets', got {kind!r}")
    try:
        path = Path(str(resources.files(f"broadsword.{kind}")))
        if path.is_dir():
            return path
    except ModuleNotFoundError:
        pass
    path = _ROOT / kind
    if not path.is_dir():
        raise FileNotFoundError(f"shipped {kind} not found (looked in the package and in {path})")
    return path


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
