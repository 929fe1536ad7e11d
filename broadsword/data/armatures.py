"""Armature files: the hand-authored hit shapes of each sprite, beside its PNG.

Format (``assets/sprites/<name>.armature.toml``, documented in docs/FORMATS.md)::

    name = "scout"
    sprite = "scout.png"
    [shapes]
    hit = [[0.0, -10.0], [9.0, 6.0], [0.0, 2.0], [-9.0, 6.0]]   # required: takes damage
    graze = [[...], ...]                                       # optional: near misses

A sprite drawn as a horizontal strip of equal frames says ``frames = N`` (and, optionally,
``frame_time`` in seconds) and gives one shape set per frame as ``[[frame]]`` tables in
place of ``[shapes]``; every frame names the same shapes. Coordinates are pixels of one
frame around its centre, +x right, +y down. The shapes are validated
(:class:`broadsword.collision.Armature`) but kept in the order the designer drew them, so a
file that is loaded and saved again is unchanged.

Limits: a file of at most ``FILE_MAX_BYTES`` (1 MiB, refused by its size before it is
parsed), UTF-8 TOML; at most ``FRAMES_MAX`` frames of at most ``SHAPES_MAX`` shapes of 3 to
``VERTICES_MAX`` vertices, each finite and within ``COORD_MAX`` px of the centre; the
sprite is a file name beside the armature file, never a path (``../x.png``, ``/x.png``).
"""

from __future__ import annotations

import json
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from ..collision import Armature
from ..fileio import write_atomic
from .errors import DataError, shown
from .resources import read_text, read_toml

SUFFIX = ".armature.toml"
#: Shape names: lower-case identifiers. ``hit`` is required in every frame.
SHAPE_NAME = re.compile(r"[a-z][a-z0-9_]{0,31}\Z")
FRAMES_MAX = 64
VERTICES_MAX = 256
SHAPES_MAX = 16  # shapes in one frame, hit among them
COORD_MAX = 4096.0
FILE_MAX_BYTES = 1 << 20
FIELDS = {"name", "sprite", "frames", "frame_time", "shapes", "frame"}


@dataclass(frozen=True)
class ArmatureFile:
    """A parsed armature file.

    Attributes
    ----------
    name, sprite : str
        The object's name and its image file, relative to the file's folder.
    frames : tuple of dict[str, Armature]
        ``frames[i][shape]``: the validated shapes of animation frame ``i`` (one frame for a
        still sprite). Every frame has the same shape names, ``hit`` among them.
    drawn : tuple of dict[str, tuple[tuple[float, float], ...]]
        The same shapes exactly as written in the file (the designer's vertex order and
        winding), which :func:`save_armature_file` writes back.
    frame_time : float
        Seconds each frame shows, for animated sprites.
    path : Path
    header : str
        The file's leading comment lines, kept when it is saved.
    """

    name: str
    sprite: str
    frames: tuple[dict[str, Armature], ...]
    path: Path
    frame_time: float = 0.1
    drawn: tuple[dict[str, tuple[tuple[float, float], ...]], ...] = field(default=(), repr=False)
    header: str = ""

    @property
    def armature(self) -> Armature:
        """The ``hit`` shape of frame 0: what takes damage."""
        return self.frames[0]["hit"]

    @property
    def graze(self) -> Armature | None:
        """The ``graze`` shape of frame 0, if the file has one."""
        return self.frames[0].get("graze")

    @property
    def shape_names(self) -> tuple[str, ...]:
        """The shape names, ``hit`` first, then in file order."""
        return tuple(self.frames[0])


def _read_toml(path: Path) -> dict:
    """The file's TOML table: at most ``FILE_MAX_BYTES`` (refused by size, unparsed), UTF-8."""
    return read_toml(path, FILE_MAX_BYTES, "an armature file")


def _is_number(c) -> bool:
    return isinstance(c, (int, float)) and not isinstance(c, bool)


def parse_polygon(value, path: Path, where: str, label: str) -> tuple[Armature, tuple[tuple[float, float], ...]]:
    """Validate one shape: a list of 3 to ``VERTICES_MAX`` ``[x, y]`` pairs of finite numbers
    within ``COORD_MAX`` of the origin, forming a simple polygon of non-zero area."""
    if not isinstance(value, list):
        raise DataError(path, where, f"must be a list of [x, y] pairs, got {shown(value)}")
    if not 3 <= len(value) <= VERTICES_MAX:
        raise DataError(path, where, f"must have 3 to {VERTICES_MAX} vertices, got {len(value)}")
    for i, v in enumerate(value):
        if not (isinstance(v, list) and len(v) == 2 and all(_is_number(c) for c in v)):
            got = shown(v)
            if isinstance(v, list):
                got = f"[{', '.join(shown(c) for c in v[:3])}{', ...' if len(v) > 3 else ''}]"
            raise DataError(path, f"{where}[{i}]", f"must be an [x, y] pair of numbers, got {got}")
        if not all(-COORD_MAX <= c <= COORD_MAX for c in v):  # nan and inf fail the range
            raise DataError(
                path,
                f"{where}[{i}]",
                f"must be finite and within {COORD_MAX:g} px of the centre, got [{shown(v[0])}, {shown(v[1])}]",
            )
    drawn = tuple((float(x), float(y)) for x, y in value)
    try:
        return Armature(drawn, name=label), drawn
    except ValueError as exc:
        raise DataError(path, where, str(exc)) from None


def _shape_set(table, path: Path, where: str, name: str) -> tuple[dict[str, Armature], dict]:
    if not isinstance(table, dict):
        raise DataError(path, where, f"must be a table of shape = [[x, y], ...], got {shown(table)}")
    if "hit" not in table:
        raise DataError(path, f"{where}.hit", "missing: every frame needs a hit shape")
    if len(table) > SHAPES_MAX:
        raise DataError(path, where, f"must have at most {SHAPES_MAX} shapes, got {len(table)}")
    shapes, drawn = {}, {}
    for key in ["hit"] + [k for k in table if k != "hit"]:
        if not SHAPE_NAME.match(key):
            raise DataError(path, f"{where}.{key}"[:120], "shape names are lower-case identifiers (a-z, 0-9, _)")
        label = name if key == "hit" else f"{name}.{key}"
        shapes[key], drawn[key] = parse_polygon(table[key], path, f"{where}.{key}", label)
    return shapes, drawn


def _header(path: Path) -> str:
    try:
        lines = read_text(path, FILE_MAX_BYTES, "an armature file").splitlines()
    except DataError:
        return ""
    head = []
    for line in lines:
        if not line.startswith("#"):
            break
        head.append(line)
    return "\n".join(head)


def load_armature_file(path: str | Path) -> ArmatureFile:
    """Parse and validate one armature file; :class:`DataError` names the file and field."""
    path = Path(path)
    return _parse(_read_toml(path), path, _header(path))


def _parse(doc: dict, path: Path, header: str) -> ArmatureFile:
    """Validate the parsed TOML table ``doc`` of the armature file ``path``."""
    if "vertices" in doc or "graze" in doc:
        key = "vertices" if "vertices" in doc else "graze"
        raise DataError(path, key, "is the old format: put the shapes under [shapes] as hit = [...] and graze = [...]")
    unknown = sorted(set(doc) - FIELDS)
    if unknown:
        raise DataError(path, unknown[0], f"unknown field (expected some of {', '.join(sorted(FIELDS))})")
    name = doc.get("name", path.name.removesuffix(SUFFIX))
    if not isinstance(name, str) or not SHAPE_NAME.match(name.replace("-", "_")):
        raise DataError(path, "name", f"must be a short lower-case name (a-z, 0-9, _ or -), got {shown(name)}")
    sprite = doc.get("sprite", f"{name}.png")
    if not isinstance(sprite, str) or not sprite.endswith(".png"):
        raise DataError(path, "sprite", f"must be the file name of a .png beside this file, got {shown(sprite)}")
    if (
        "/" in sprite
        or "\\" in sprite
        or sprite.startswith(".")
        or Path(sprite).is_absolute()
        or not sprite.isprintable()
        or len(sprite) > 64
    ):
        raise DataError(path, "sprite", f"must be a file name in the same folder, not a path; got {shown(sprite)}")
    frames_n = doc.get("frames", 1)
    if not isinstance(frames_n, int) or isinstance(frames_n, bool) or not 1 <= frames_n <= FRAMES_MAX:
        raise DataError(path, "frames", f"must be a whole number from 1 to {FRAMES_MAX}, got {shown(frames_n)}")
    frame_time = doc.get("frame_time", 0.1)
    if not _is_number(frame_time) or not (1 / 120 <= frame_time <= 10):  # nan and inf fail the range
        finite = "finite, " if isinstance(frame_time, float) and not math.isfinite(frame_time) else ""
        raise DataError(
            path, "frame_time", f"must be {finite}a number of seconds from 1/120 to 10, got {shown(frame_time)}"
        )
    if frames_n == 1:
        if "frame" in doc:
            raise DataError(path, "frame", "only for animated sprites (frames > 1); use [shapes]")
        if "shapes" not in doc:
            raise DataError(path, "shapes", "missing: give [shapes] with at least hit = [[x, y], ...]")
        sets = [_shape_set(doc["shapes"], path, "shapes", name)]
    else:
        if "shapes" in doc:
            raise DataError(path, "shapes", "an animated sprite gives one [[frame]] table per frame instead")
        tables = doc.get("frame")
        if not isinstance(tables, list) or len(tables) != frames_n:
            got = len(tables) if isinstance(tables, list) else "none"
            raise DataError(path, "frame", f"must be {frames_n} [[frame]] tables (frames = {frames_n}); got {got}")
        sets = [_shape_set(t, path, f"frame[{i}]", name) for i, t in enumerate(tables)]
        names = list(sets[0][0])
        for i, (shapes, _) in enumerate(sets):
            if sorted(shapes) != sorted(names):
                raise DataError(path, f"frame[{i}]", f"must name the same shapes as frame[0]: {', '.join(names)}")
    return ArmatureFile(
        name, sprite, tuple(s for s, _ in sets), path, float(frame_time), tuple(d for _, d in sets), header
    )


def load_armatures(folder: str | Path) -> dict[str, ArmatureFile]:
    """Every ``*.armature.toml`` in ``folder``, by name."""
    out: dict[str, ArmatureFile] = {}
    for path in sorted(Path(folder).glob(f"*{SUFFIX}")):
        f = load_armature_file(path)
        if f.name in out:
            raise DataError(path, "name", f"{f.name!r} is also the name of {out[f.name].path.name}")
        out[f.name] = f
    return out


# ---------------------------------------------------------------------- writing
def _number(x: float) -> str:
    """Shortest TOML float that reads back as exactly ``x`` (``3.0``, ``0.5``, ``1e-05``)."""
    return repr(float(x))


def _polygon_toml(points, indent: str = "    ", per_line: int = 4) -> str:
    pairs = [f"[{_number(x)}, {_number(y)}]" for x, y in points]
    if len(pairs) <= per_line:
        return "[" + ", ".join(pairs) + "]"
    rows = [indent + ", ".join(pairs[i : i + per_line]) + "," for i in range(0, len(pairs), per_line)]
    return "[\n" + "\n".join(rows) + "\n]"


def format_armature_file(name: str, sprite: str, frames, frame_time: float = 0.1, header: str = "") -> str:
    """The text of an armature file: ``frames`` is a list of ``{shape: [(x, y), ...]}``
    (``hit`` first), one per animation frame. Four vertices to a line, shortest exact floats."""
    lines = (
        [header] if header else [f"# Armatures of {sprite}: sprite pixels, origin at the centre, +x right, +y down."]
    )
    lines += [f"name = {json.dumps(name)}", f"sprite = {json.dumps(sprite)}"]  # a JSON string is a TOML basic string
    if len(frames) > 1:
        lines += [f"frames = {len(frames)}", f"frame_time = {_number(frame_time)}"]
    for i, shapes in enumerate(frames):
        lines.append("")
        lines.append("[shapes]" if len(frames) == 1 else f"[[frame]]  # frame {i}")
        for key in ["hit"] + [k for k in shapes if k != "hit"]:
            lines.append(f"{key} = {_polygon_toml(shapes[key])}")
    return "\n".join(lines) + "\n"


def save_armature_file(
    path: str | Path, name: str, sprite: str, frames, frame_time: float = 0.1, header: str = ""
) -> ArmatureFile:
    """Validate ``frames`` (as :func:`format_armature_file` takes them), write the file
    atomically and return it as loaded back. Nothing is written if anything is invalid (a
    shape, the name, the sprite: :class:`DataError` naming the field)."""
    path = Path(path)
    text = format_armature_file(name, sprite, frames, frame_time, header)
    _parse(tomllib.loads(text), path, header)  # validate exactly what would be written, before touching the disk
    write_atomic(path, text.encode("utf-8"))
    return load_armature_file(path)
