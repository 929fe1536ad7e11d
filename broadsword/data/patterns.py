"""BulletML pattern files for levels: where a level's ``pattern`` may point, and loading.

A level names a pattern file by a relative path (``pattern = "stop-and-aim.xml"``). It
resolves beside the level file first, then among the shipped patterns
(``assets/patterns/``), and never anywhere else: an absolute path, a drive, a backslash or a
``..`` part is refused, and so is a name that leads outside its folder through a link.
The file is read by :func:`broadsword.patterns.bulletml.load` (safe XML, validated).
"""

from __future__ import annotations

from pathlib import Path, PurePosixPath

from ..patterns import bulletml
from .resources import data_dir

#: Longest ``pattern`` value accepted, characters.
PATTERN_NAME_MAX = 200
#: The shipped patterns' folder, inside the assets.
SHIPPED = "patterns"


def shipped_patterns() -> Path:
    """The folder of the shipped BulletML patterns."""
    return data_dir("assets") / SHIPPED


def resolve_pattern(name: str, level_path: Path) -> Path:
    """The pattern file ``name`` (a relative path; ``.xml`` is added when it has no
    suffix) beside ``level_path`` or among the shipped patterns. Raises ``ValueError`` with
    the reason (the caller adds the level file and field)."""
    if not isinstance(name, str) or not name.strip():
        raise ValueError('must name a pattern file, e.g. "aimed.xml"')
    if len(name) > PATTERN_NAME_MAX or not name.isprintable():
        raise ValueError(f"must be a printable relative path of at most {PATTERN_NAME_MAX} characters")
    rel = PurePosixPath(name)
    if "\\" in name or ":" in name or rel.is_absolute() or ".." in rel.parts or name.startswith("~"):
        raise ValueError(
            f"{name!r} must be a relative path inside the level's folder or the shipped patterns "
            "(no absolute paths, drives, backslashes or '..')"
        )
    if not rel.suffix:
        rel = rel.with_suffix(".xml")
    roots = [Path(level_path).resolve().parent, shipped_patterns().resolve()]
    for root in roots:
        try:
            candidate = (root / rel).resolve()
        except (RuntimeError, OSError) as exc:  # a symlink loop (RuntimeError in Python 3.11, OSError later)
            raise ValueError(f"{name!r} cannot be resolved ({exc})") from None
        if candidate.is_file():
            if not candidate.is_relative_to(root):
                raise ValueError(f"{name!r} leads outside {root} (through a link)")
            return candidate
    raise ValueError(
        f"no pattern file {str(rel)!r} beside the level ({roots[0]}) or among the shipped patterns "
        f"({roots[1]}); shipped: {', '.join(sorted(p.stem for p in roots[1].glob('*.xml')))}"
    )


def load_pattern(path: Path) -> bulletml.Pattern:
    """Load a BulletML file (``ValueError`` starting with the file name if it is bad)."""
    return bulletml.load(path)


def shipped_kind(kind: str) -> bulletml.Pattern:
    """The shipped BulletML file of one of the game's original kinds (``aimed``...)."""
    return bulletml.load(shipped_patterns() / f"{kind}.xml")
