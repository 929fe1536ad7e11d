"""Fuzzing the loaders (issue 6, "Reliability").

Whatever the bytes, :func:`load_level`, :func:`load_armature_file` and
:func:`broadsword.data.recordings.load_recording` return a valid object or raise :class:`DataError`
(one line, naming the file), never any other exception. Inputs: random bytes, random
TOML-ish text, and random mutations of the shipped files (a key deleted or added, a value
of another type, nan, inf, huge or negative numbers, deep nesting, a list grown long).
"Valid" is checked, not assumed: a level that loads and names known sprites builds a
:class:`World` that plays some frames with the autopilot; a loaded armature's shapes are
finite, in range and simple; a loaded recording decodes to one input per byte.
"""

from __future__ import annotations

import base64
import copy
import dataclasses
import datetime
import json
import math
import tomllib
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from broadsword import __version__
from broadsword.data import (
    DataError,
    data_dir,
    list_levels,
    load_armature_file,
    load_level,
    resolve_level,
)
from broadsword.data.armatures import COORD_MAX, FRAMES_MAX, SUFFIX, VERTICES_MAX
from broadsword.data.levels import check_level_sprites
from broadsword.data.recordings import load_recording
from broadsword.sim import Input, Pilot, World

SPRITES = data_dir("assets") / "sprites"
LEVEL_PATHS = [resolve_level(name) for name in list_levels()]
ARMATURE_PATHS = sorted(SPRITES.glob(f"*{SUFFIX}"))
RECORDING = {
    "version": 3,
    "game_version": __version__,
    "parts": ["player", "bullets", "enemies", "boss", "items", "score", "modes", "rng"],
    "frames": 6,
    "stages": [
        {
            "start": 0,
            "level": "1-picket",
            "seed": 9,
            "settings": {"rotation": "lut", "difficulty": "normal"},
            "carry": {"score": 10, "lives": 2, "continues": 0, "power": None},
            "toggles": [[2, "rotation", "exact"]],
            "frames": 6,
            "inputs": "051525053505",
            "digests": base64.b64encode(bytes(range(192))).decode(),  # 4 bytes a part a frame
            "checkpoints": [],
            "state_hash": "0f" * 32,
        }
    ],
}
FRAMES_PLAYED = 20
SETTINGS = dict(deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("fuzz")


# ---------------------------------------------------------------------- what "valid" means
def finite_numbers(obj) -> bool:
    """Every float in a (nested) dataclass, tuple or dict is finite."""
    if isinstance(obj, float):
        return math.isfinite(obj)
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return all(finite_numbers(getattr(obj, f.name)) for f in dataclasses.fields(obj))
    if isinstance(obj, (tuple, list)):
        return all(finite_numbers(x) for x in obj)
    if isinstance(obj, dict):
        return all(finite_numbers(x) for x in obj.values())
    return True


def try_level(path: Path, armatures):
    """Load the level; if it loads and names known sprites, play it a little."""
    try:
        level = load_level(path)
        check_level_sprites(level, armatures)
    except DataError as exc:
        assert_error_line(exc, path)
        return None
    assert finite_numbers(level)
    world = World(level, armatures, seed=1)
    pilot = Pilot()
    for _ in range(FRAMES_PLAYED):
        world.step(pilot(world))
    assert len(world.state_hash()) > 0
    if not level.waves and level.boss is None:
        assert world.complete and world.frame == 1  # nothing to fight: complete at once
    return level


def try_armature(path: Path):
    try:
        f = load_armature_file(path)
    except DataError as exc:
        assert_error_line(exc, path)
        return None
    assert 1 <= len(f.frames) <= FRAMES_MAX and math.isfinite(f.frame_time)
    for shapes in f.frames:
        assert list(shapes) and "hit" in shapes and sorted(shapes) == sorted(f.frames[0])
        for arm in shapes.values():
            v = arm.vertices  # (N, 2)
            assert 3 <= len(v) <= VERTICES_MAX and all(math.isfinite(c) and abs(c) <= COORD_MAX for c in v.ravel())
            assert arm.area > 0
    return f


def try_recording(path: Path):
    try:
        rec = load_recording(path)
    except DataError as exc:
        assert_error_line(exc, path)
        return None
    assert rec.frames == sum(stage.frames for stage in rec.stages)
    for stage in rec.stages:
        decoded = [Input.from_byte(b) for b in stage.inputs]  # every byte is a valid input
        assert len(decoded) == stage.frames and len(stage.digests) == 4 * len(rec.parts) * stage.frames
        assert isinstance(stage.seed, int) and 0 <= stage.seed < 2**63 and isinstance(stage.level, str) and stage.level
        assert stage.settings["rotation"] in ("lut", "exact")
        assert all(0 <= t[0] <= stage.frames for t in stage.toggles)
    return rec


def assert_error_line(exc: DataError, path: Path) -> None:
    line = str(exc)
    assert line.startswith(f"{path}: ") and line.isprintable()


# ---------------------------------------------------------------------- TOML and JSON writers
@dataclasses.dataclass
class Deep:
    """``value`` inside ``depth`` arrays, written without recursion (depth may be 100,000)."""

    value: object
    depth: int


def toml_string(s: str) -> str:
    # JSON's escapes are TOML's; TOML also wants DEL escaped.
    return json.dumps(s, ensure_ascii=False).replace("\x7f", "\\u007f")


def toml_value(v) -> str:
    if isinstance(v, Deep):
        return "[" * v.depth + toml_value(v.value) + "]" * v.depth
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, str):
        return toml_string(v)
    if isinstance(v, datetime.date):
        return v.isoformat()
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{toml_string(k)} = {toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(type(v))


def toml_doc(doc: dict) -> str:
    """A TOML document of ``doc``: one ``key = value`` line per top-level key (inline tables)."""
    return "".join(f"{toml_string(k)} = {toml_value(v)}\n" for k, v in doc.items())


def json_value(v) -> str:
    if isinstance(v, Deep):
        return "[" * v.depth + json_value(v.value) + "]" * v.depth
    if isinstance(v, datetime.date):
        return json.dumps(v.isoformat())
    if isinstance(v, list):
        return "[" + ", ".join(json_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)}: {json_value(x)}" for k, x in v.items()) + "}"
    return json.dumps(v)  # nan and inf as NaN and Infinity, which Python's json reads


# ---------------------------------------------------------------------- strategies
KNOWN_KEYS = sorted(
    {
        "level",
        "title",
        "name",
        "scene",
        "tiers",
        "rotation",
        "bin_size",
        "graze",
        "player",
        "speed",
        "slow_speed",
        "fire_every",
        "shot_speed",
        "lives",
        "wave",
        "at",
        "enemy",
        "count",
        "every",
        "hp",
        "score",
        "mirror",
        "path",
        "x",
        "amplitude",
        "period",
        "radius",
        "turn",
        "dive_at",
        "hold_y",
        "hold_for",
        "fire",
        "bullet",
        "bullet_speed",
        "shots",
        "spread",
        "volley_turn",
        "fire_delay",
        "boss",
        "y",
        "sway",
        "part",
        "sprite",
        "offset",
        "spin",
        "shapes",
        "hit",
        "frames",
        "frame_time",
        "frame",
        "vertices",
        "version",
        "seed",
        "inputs",
        "state_hash",
        "pattern",
        "pattern_params",
    }
)
keys = st.one_of(st.sampled_from(KNOWN_KEYS), st.text(max_size=8))
SPECIAL_NUMBERS = [
    math.nan,
    math.inf,
    -math.inf,
    1e300,
    -1e300,
    5e-324,
    -0.0,
    0,
    -1,
    -1000,
    10**6,
    2**63,
    -(2**63),
    10**40,
    1e9,
    -1e9,
    4096.5,
    3.0e-3,
]
numbers = st.one_of(
    st.sampled_from(SPECIAL_NUMBERS), st.integers(-(2**70), 2**70), st.floats(allow_nan=True, allow_infinity=True)
)
NAMES = [
    "",
    "scout",
    "pellet",
    "boss_core",
    "player",
    "aimed",
    "ring",
    "sine",
    "hold",
    "auto",
    "bins",
    "armature",
    "lut",
    "../x",
    "/abs/x",
    "..\\x",
    "x.png",
    "../x.png",
    "/etc/passwd.png",
    "a\nb",
    "\x00",
    "hit",
    "graze",
    "__import__('os')",
    "1-picket",
    "zz",
    "0505",
    "ff",
    "flower.xml",
    "../aimed.xml",
    "/etc/passwd.xml",
    "ring",
]
strings = st.one_of(st.sampled_from(NAMES), st.text(max_size=20))
scalars = st.one_of(numbers, strings, st.booleans(), st.dates())
values = st.recursive(
    scalars, lambda inner: st.lists(inner, max_size=5) | st.dictionaries(keys, inner, max_size=4), max_leaves=12
)
depths = st.one_of(st.integers(1, 300), st.sampled_from([1000, 5000, 100_000]))


def node_paths(node, prefix=()):
    """Every path (tuple of keys and indices) into ``node``, the root ``()`` first."""
    yield prefix
    if isinstance(node, dict):
        for k, v in node.items():
            yield from node_paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from node_paths(v, prefix + (i,))


def at(node, path):
    for k in path:
        node = node[k]
    return node


def mutate(doc, data) -> dict:
    """``doc`` after one to three random edits drawn from ``data``."""
    doc = copy.deepcopy(doc)
    for _ in range(data.draw(st.integers(1, 3), label="edits")):
        paths = list(node_paths(doc))
        inner = [p for p in paths if p]
        op = data.draw(st.sampled_from(["delete", "replace", "number", "add", "deepen", "grow"]), label="op")
        if op == "add":
            tables = [p for p in paths if isinstance(at(doc, p), dict)]
            p = data.draw(st.sampled_from(tables), label="table")
            at(doc, p)[data.draw(keys, label="key")] = data.draw(values, label="value")
            continue
        if op == "grow":
            lists = [p for p in paths if isinstance(at(doc, p), list) and at(doc, p)]
            if lists:
                target = at(doc, data.draw(st.sampled_from(lists), label="list"))
                target *= data.draw(st.sampled_from([2, 17, 300]), label="times")
            continue
        if op == "number":
            inner = [p for p in inner if isinstance(at(doc, p), (int, float)) and not isinstance(at(doc, p), bool)]
        if not inner:
            continue
        p = data.draw(st.sampled_from(inner), label="path")
        parent, key = at(doc, p[:-1]), p[-1]
        if op == "delete":
            del parent[key]
        elif op == "replace":
            parent[key] = data.draw(values, label="value")
        elif op == "number":
            parent[key] = data.draw(numbers, label="number")
        else:
            parent[key] = Deep(parent[key], data.draw(depths, label="depth"))
    return doc


def toml_ish_line():
    header = st.sampled_from(
        [
            "[scene]",
            "[player]",
            "[[wave]]",
            "[boss]",
            "[[boss.part]]",
            "[level]",
            "[shapes]",
            "[[frame]]",
            "[",
            "[[",
            "]]",
            "[wave]",
            "[[shapes]]",
            "[a.b.c]",
        ]
    )
    raw = st.sampled_from(
        [
            "nan",
            "inf",
            "-inf",
            "+nan",
            "1e999",
            "-0",
            "0x10",
            "0o7",
            "0b1",
            "1979-05-27",
            "07:32:00",
            "1979-05-27T07:32:00Z",
            "true",
            "false",
            '""',
            "[]",
            "{}",
            "[[",
            '"unterminated',
            "'''",
            "1_000",
            "1__0",
            "[1, [2, [3]]]",
            "{a = {b = 1}}",
            '"../x"',
            "-1",
            "9" * 30,
        ]
    )
    literal = st.one_of(raw, values.map(toml_value))
    pair = st.builds(lambda k, v: f"{k} = {v}", st.one_of(st.sampled_from(KNOWN_KEYS), st.text(max_size=6)), literal)
    return st.one_of(header, pair, pair, st.text(max_size=30))


# ---------------------------------------------------------------------- the writers are right
@pytest.mark.parametrize("path", LEVEL_PATHS + ARMATURE_PATHS, ids=lambda p: p.name)
def test_writer__shipped_files_round_trip(path):
    doc = tomllib.loads(path.read_text(encoding="utf-8"))
    assert tomllib.loads(toml_doc(doc)) == doc
    assert json.loads(json_value(doc)) == doc


@given(st.dictionaries(keys, values.filter(lambda v: "nan" not in toml_value(v)), max_size=4))
@settings(max_examples=50, deadline=None)
def test_writer__random_documents_round_trip(doc):
    assert tomllib.loads(toml_doc(doc)) == doc


def test_writer__shipped_levels_load_the_same_from_the_written_form(folder):
    for path in LEVEL_PATHS:
        out = folder / path.name
        out.write_text(toml_doc(tomllib.loads(path.read_text(encoding="utf-8"))), encoding="utf-8")
        assert dataclasses.replace(load_level(out), path=path) == load_level(path)


def test_try_level__a_shipped_level_plays_and_a_broken_one_is_refused(folder, armatures):
    # The checks the fuzzing relies on can fail both ways.
    out = folder / "check.toml"
    out.write_text(LEVEL_PATHS[0].read_text(encoding="utf-8"), encoding="utf-8")
    assert try_level(out, armatures) is not None
    out.write_text("[[wave]]\nenemy = 3\n")
    assert try_level(out, armatures) is None


# ---------------------------------------------------------------------- fuzzing
@given(st.binary(max_size=3000))
@settings(max_examples=100, **SETTINGS)
def test_fuzz__random_bytes(folder, armatures, blob):
    for name, load in (
        ("bytes.toml", lambda p: try_level(p, armatures)),
        ("bytes" + SUFFIX, try_armature),
        ("bytes.json", try_recording),
    ):
        path = folder / name
        path.write_bytes(blob)
        load(path)


@given(st.lists(toml_ish_line(), max_size=25))
@settings(max_examples=150, **SETTINGS)
def test_fuzz__toml_ish_text(folder, armatures, lines):
    text = "\n".join(lines) + "\n"
    level, arm = folder / "text.toml", folder / ("text" + SUFFIX)
    level.write_text(text, encoding="utf-8")
    arm.write_text(text, encoding="utf-8")
    try_level(level, armatures)
    try_armature(arm)


@given(st.sampled_from(LEVEL_PATHS), st.data())
@settings(max_examples=120, **SETTINGS)
def test_fuzz__mutated_shipped_levels(folder, armatures, source, data):
    doc = mutate(tomllib.loads(source.read_text(encoding="utf-8")), data)
    path = folder / source.name
    path.write_text(toml_doc(doc), encoding="utf-8")
    try_level(path, armatures)


@given(st.sampled_from(ARMATURE_PATHS), st.data())
@settings(max_examples=120, **SETTINGS)
def test_fuzz__mutated_shipped_armatures(folder, source, data):
    doc = mutate(tomllib.loads(source.read_text(encoding="utf-8")), data)
    path = folder / source.name
    path.write_text(toml_doc(doc), encoding="utf-8")
    try_armature(path)


@given(st.data())
@settings(max_examples=120, **SETTINGS)
def test_fuzz__mutated_recordings(folder, data):
    doc = mutate(RECORDING, data)
    path = folder / "run.json"
    path.write_text(json_value(doc), encoding="utf-8")
    try_recording(path)


def test_fuzz__the_unmutated_sources_are_valid(folder, armatures):
    # Mutations start from valid files, so a refusal is the mutation's doing.
    for path in LEVEL_PATHS:
        assert try_level(path, armatures) is not None
    for path in ARMATURE_PATHS:
        assert try_armature(path) is not None
    rec = folder / "valid.json"
    rec.write_text(json.dumps(RECORDING))
    assert Input.from_byte(try_recording(rec).first.inputs[1]).fire
