"""Armature files: the hand-authored hit polygon of each sprite, beside its PNG.

Format (``assets/sprites/<name>.armature.toml``, documented in docs/FORMATS.md)::

    name = "scout"
    sprite = "scout.png"
    vertices = [[0.0, -10.0], [9.0, 6.0], [0.0, 2.0], [-9.0, 6.0]]
    graze = [[...], ...]          # optional: a larger near-miss shape (the player's)

Coordinates are sprite pixels around the sprite's centre, +x right, +y down.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path

from ..collision import Armature
from .errors import DataError

SUFFIX = ".armature.toml"


@dataclass(frozen=True)
class ArmatureFile:
    """A parsed armature file: the validated hit polygon and, optionally, a graze polygon."""

    name: str
    sprite: str
    armature: Armature
    graze: Armature | None
    path: Path


def _read_toml(path: Path) -> dict:
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except OSError as exc:
        raise DataError(path, "", f"cannot read: {exc.strerror or exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise DataError(path, "", f"not valid TOML: {exc}") from None


def _polygon(doc: dict, key: str, path: Path, name: str) -> Armature:
    value = doc.get(key)
    if not isinstance(value, list):
        raise DataError(path, key, "must be a list of [x, y] pairs")
    for i, v in enumerate(value):
        if not (isinstance(v, list) and len(v) == 2 and all(isinstance(c, (int, float)) and not isinstance(c, bool) for c in v)):
            raise DataError(path, f"{key}[{i}]", f"must be an [x, y] pair of numbers, got {v!r}")
    try:
        return Armature(value, name=f"{name}.{key}" if key != "vertices" else name)
    except ValueError as exc:
        raise DataError(path, key, str(exc)) from None


def load_armature_file(path: str | Path) -> ArmatureFile:
    """Parse and validate one armature file; :class:`DataError` names the file and field."""
    path = Path(path)
    doc = _read_toml(path)
    name = doc.get("name", path.name.removesuffix(SUFFIX))
    if not isinstance(name, str) or not name:
        raise DataError(path, "name", "must be a non-empty string")
    sprite = doc.get("sprite", f"{name}.png")
    if not isinstance(sprite, str):
        raise DataError(path, "sprite", "must be a file name")
    unknown = set(doc) - {"name", "sprite", "vertices", "graze"}
    if unknown:
        raise DataError(path, sorted(unknown)[0], "unknown field")
    armature = _polygon(doc, "vertices", path, name)
    graze = _polygon(doc, "graze", path, name) if "graze" in doc else None
    return ArmatureFile(name, sprite, armature, graze, path)


def load_armatures(folder: str | Path) -> dict[str, ArmatureFile]:
    """Every ``*.armature.toml`` in ``folder``, by name."""
    out = {}
    for path in sorted(Path(folder).glob(f"*{SUFFIX}")):
        f = load_armature_file(path)
        if f.name in out:
            raise DataError(path, "name", f"{f.name!r} is also the name of {out[f.name].path.name}")
        out[f.name] = f
    return out
