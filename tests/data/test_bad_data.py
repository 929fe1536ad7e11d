"""The bad-data corpus (issue 6, "Reliability"): every broken file gets one line naming it.

``tests/data/bad/`` holds one small file per fault, for levels, armatures and recordings;
``tests/data/bad/EXPECTED.toml`` says, for each, the field the error must name ("" for the
whole file) and words of what is expected. Files too big to commit (many megabytes, deep
nesting, too many of something) are made at test time by ``GENERATED``. For every one:
the loader raises a one-line :class:`DataError` ``"<file>: <field>: <what is expected>"``,
and the command line ends with status 2 and exactly that line on stderr, no traceback.
"""

from __future__ import annotations

import ast
import inspect
import json
import shutil
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import pytest

from broadsword import cli
from broadsword.data import (
    DataError,
    data_dir,
    list_levels,
    load_armature_file,
    load_armatures,
    load_level,
    recordings,
    resolve_level,
)
from broadsword.data.armatures import FILE_MAX_BYTES, SUFFIX
from broadsword.data.errors import FIELD_MAX_CHARS, MESSAGE_MAX_CHARS
from broadsword.data.levels import LEVEL_MAX_BYTES, check_level_sprites
from broadsword.runner import stages

BAD = Path(__file__).parent / "bad"
EXPECTED = tomllib.loads((BAD / "EXPECTED.toml").read_text(encoding="utf-8"))
SPRITES = data_dir("assets") / "sprites"
RECORDING_MAX_BYTES = 8 << 20  # load_recording's limit, as its docstring states
MB20 = 20 << 20

# ---------------------------------------------------------------------- files made at test time
WAVE = '[[wave]]\nenemy = "scout"\n'
TRI = "[[0.0, -10.0], [9.0, 6.0], [-9.0, 6.0]]"
DEEP = 100_000


def padded(text: str, size: int) -> str:
    """``text`` followed by TOML comment lines up to ``size`` bytes: valid apart from its size."""
    line = "# " + "padding " * 12 + "\n"
    n = max(0, size - len(text)) // len(line) + 1
    return text + line * n


def ring(n: int, r: float = 100.0) -> str:
    """A convex ``n``-gon of radius ``r`` as a TOML array (valid for any n >= 3)."""
    import math

    pts = [f"[{r * math.cos(2 * math.pi * i / n):.6f}, {r * math.sin(2 * math.pi * i / n):.6f}]" for i in range(n)]
    return "[" + ", ".join(pts) + "]"


RECORDING = {
    "version": 3,
    "game_version": "test",
    "parts": ["player"],
    "frames": 4,
    "stages": [],  # the size tests below pad "inputs": only the file's size matters there
    "inputs": "05050505",
}

#: (kind, file name) -> (text maker, field, expected words): faults too big to commit.
#: Each text is made only when its test runs.
GENERATED = {
    ("levels", "huge.toml"): (lambda: padded(WAVE, MB20), "", f"at most {LEVEL_MAX_BYTES:,}"),
    ("levels", "deep-nesting-arrays.toml"): (
        lambda: WAVE + "count = " + "[" * DEEP + "]" * DEEP + "\n",
        "",
        "nested too deeply",
    ),
    ("levels", "deep-nesting-inline-tables.toml"): (
        lambda: WAVE + "path = " + "{a = " * DEEP + "1" + "}" * DEEP + "\n",
        "",
        "nested too deeply",
    ),
    ("levels", "deep-nesting-dotted-table.toml"): (
        lambda: "[wave" + ".a" * DEEP + "]\nx = 1\n",
        "",
        "nested too deeply",
    ),
    ("levels", "deep-nesting-dotted-key.toml"): (lambda: WAVE + "a" + ".a" * DEEP + " = 1\n", "", "nested too deeply"),
    ("levels", "too-many-waves.toml"): (lambda: WAVE * 300, "wave", "at most 256 waves"),
    ("levels", "too-many-ships.toml"): (
        lambda: (WAVE + "count = 1000\nmirror = true\n") * 6,
        "wave[5].count",
        "12,000 ships; a level sends at most 10,000",
    ),
    ("levels", "too-many-boss-parts.toml"): (
        lambda: "[boss]\nhp = 100\n" + '[[boss.part]]\nsprite = "boss_core"\n' * 20,
        "boss.part",
        "at most 16 parts",
    ),
    ("armatures", "huge" + SUFFIX): (
        lambda: padded(f"[shapes]\nhit = {TRI}\n", MB20),
        "",
        f"at most {FILE_MAX_BYTES:,}",
    ),
    ("armatures", "deep-nesting-arrays" + SUFFIX): (
        lambda: "[shapes]\nhit = " + "[" * DEEP + "]" * DEEP + "\n",
        "",
        "nested too deeply",
    ),
    ("armatures", "deep-nesting-dotted-table" + SUFFIX): (
        lambda: "[shapes" + ".a" * DEEP + "]\nx = 1\n",
        "",
        "nested too deeply",
    ),
    ("armatures", "too-many-vertices" + SUFFIX): (
        lambda: f"[shapes]\nhit = {ring(300)}\n",
        "shapes.hit",
        "3 to 256 vertices",
    ),
    ("armatures", "too-many-shapes" + SUFFIX): (
        lambda: "[shapes]\n" + "".join(f"s{i} = {TRI}\n" for i in range(20)) + f"hit = {TRI}\n",
        "shapes",
        "at most 16 shapes",
    ),
    ("recordings", "huge.json"): (
        lambda: json.dumps({**RECORDING, "frames": MB20 // 2, "inputs": "05" * (MB20 // 2)}),
        "",
        f"at most {RECORDING_MAX_BYTES:,}",
    ),
    ("recordings", "deep-nesting.json"): (lambda: "[" * DEEP + "]" * DEEP, "", "nested too deeply"),
    ("recordings", "giant-number.json"): (
        lambda: '{"version": 3, "parts": ["player"], "stages": [{"start": 0, "seed": ' + "9" * 5000 + "}]}",
        "",
        "bad JSON",
    ),
}

CASES = [(kind, name, False) for kind in ("levels", "armatures", "recordings") for name in EXPECTED[kind]]
CASES += [(kind, name, True) for kind, name in GENERATED]


def case_id(case) -> str:
    kind, name, generated = case
    return f"{kind}/{name}" + (" (generated)" if generated else "")


@pytest.fixture(scope="module")
def shipped_armatures(armatures):
    return armatures  # tests/conftest.py: loaded once per process


def materialise(case, tmp_path: Path) -> tuple[Path, str, str]:
    """The case's file (committed, or written into ``tmp_path``), field and expected words."""
    kind, name, generated = case
    if not generated:
        e = EXPECTED[kind][name]
        return BAD / kind / name, e["field"], e["expect"]
    make, field, expect = GENERATED[(kind, name)]
    path = tmp_path / name
    path.write_text(make(), encoding="utf-8")
    return path, field, expect


def load(kind: str, path: Path, armatures) -> object:
    """What the command line does with the file: a level is loaded and its sprite names
    checked against the shipped armatures; an armature file or recording is loaded."""
    if kind == "levels":
        level = load_level(path)
        check_level_sprites(level, armatures)
        return level
    if kind == "armatures":
        return load_armature_file(path)
    return recordings.load_recording(path)


def expected_error(case, tmp_path, armatures) -> tuple[Path, str]:
    kind = case[0]
    path, field, expect = materialise(case, tmp_path)
    with pytest.raises(DataError) as info:
        load(kind, path, armatures)
    message = str(info.value)
    prefix = f"{path}: {field}: " if field else f"{path}: "
    assert message.startswith(prefix), (message, prefix)
    assert expect in message[len(prefix) :], (message, expect)
    assert "\n" not in message and "\r" not in message and message.isprintable()
    assert len(message) <= len(prefix) + MESSAGE_MAX_CHARS
    return path, message


# ---------------------------------------------------------------------- the corpus itself
def test_corpus__manifest_lists_exactly_the_files():
    for kind in ("levels", "armatures", "recordings"):
        on_disk = sorted(p.name for p in (BAD / kind).iterdir())
        assert on_disk == sorted(EXPECTED[kind]), kind
        for name, e in EXPECTED[kind].items():
            assert set(e) == {"field", "expect"} and e["expect"], name
    assert sorted(p.name for p in BAD.iterdir()) == ["EXPECTED.toml", "armatures", "levels", "recordings"]


def test_corpus__small_files_only():
    # Big files are generated at test time, never committed.
    sizes = {p.name: p.stat().st_size for kind in ("levels", "armatures", "recordings") for p in (BAD / kind).iterdir()}
    assert max(sizes.values()) <= 8192


#: Every fault issue 6 lists, as the file-name words that mark it, per kind.
FAULTS = {
    "not TOML or JSON": ("not-toml", "not-json"),
    "empty": ("empty",),
    "binary": ("binary",),
    "truncated": ("truncated",),
    "wrong types": ("wrong-type",),
    "missing fields": ("missing",),
    "unknown fields": ("unknown-field",),
    "negative counts or times": ("negative",),
    "absurd counts or times": ("-huge", "bigint", "too-many"),
    "nan": ("nan",),
    "inf": ("inf",),
    "a file of many megabytes": ("huge.",),
    "deep nesting": ("deep-nesting",),
}
LEVEL_FAULTS = {
    "unknown enemy": ("unknown-enemy",),
    "unknown pattern": ("unknown-pattern",),
    "sprite path with ../": ("sprite-path-dotdot",),
    "absolute sprite path": ("sprite-path-absolute",),
}
ARMATURE_FAULTS = {
    "self-crossing": ("self-crossing",),
    "degenerate": ("degenerate",),
    "fewer than 3 vertices": ("two-vertices",),
    "sprite path with ../": ("sprite-path-dotdot",),
    "absolute sprite path": ("sprite-path-absolute",),
}
RECORDING_FAULTS = (
    "not TOML or JSON",
    "empty",
    "binary",
    "truncated",
    "wrong types",
    "missing fields",
    "a file of many megabytes",
    "deep nesting",
    "negative counts or times",
    "absurd counts or times",
    "nan",
    "inf",
)


@pytest.mark.parametrize("kind", ["levels", "armatures", "recordings"])
def test_corpus__covers_every_fault_the_issue_lists(kind):
    names = [name for k, name, _ in CASES if k == kind]
    wanted = {**FAULTS, **(LEVEL_FAULTS if kind == "levels" else ARMATURE_FAULTS if kind == "armatures" else {})}
    if kind == "recordings":
        wanted = {f: FAULTS[f] for f in RECORDING_FAULTS}
    missing = [fault for fault, marks in wanted.items() if not any(m in n for n in names for m in marks)]
    assert not missing


# ---------------------------------------------------------------------- the loaders
@pytest.mark.parametrize("case", CASES, ids=case_id)
def test_loader__one_line_naming_file_field_and_what_is_expected(case, tmp_path, shipped_armatures):
    expected_error(case, tmp_path, shipped_armatures)


@pytest.mark.parametrize("case", [c for c in CASES if c[0] == "armatures"], ids=case_id)
def test_load_armatures__a_bad_file_in_the_folder_fails_the_folder_with_its_line(case, tmp_path, shipped_armatures):
    made = tmp_path / "made"
    made.mkdir()
    path, message = expected_error(case, made, shipped_armatures)
    folder = tmp_path / "sprites"
    shutil.copytree(SPRITES, folder, ignore=shutil.ignore_patterns("*.png"))
    shutil.copy(path, folder / path.name)
    with pytest.raises(DataError) as info:
        load_armatures(folder)
    assert str(info.value) == message.replace(str(path), str(folder / path.name))


# ---------------------------------------------------------------------- the command line
def one_error_line(err: str) -> str:
    lines = err.splitlines()
    assert len(lines) == 1, err
    return lines[0]


@pytest.mark.parametrize("case", [c for c in CASES if c[0] == "levels"], ids=case_id)
def test_headless_level__exit_2_and_the_loader_line(case, tmp_path, shipped_armatures, capsys):
    path, message = expected_error(case, tmp_path, shipped_armatures)
    code = cli.main(["--headless", "--level", str(path), "--frames", "5"])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert one_error_line(err) == f"broadsword: {message}"


@pytest.mark.parametrize("case", [c for c in CASES if c[0] == "recordings"], ids=case_id)
def test_headless_replay__exit_2_and_the_loader_line(case, tmp_path, shipped_armatures, capsys):
    path, message = expected_error(case, tmp_path, shipped_armatures)
    code = cli.main(["--headless", "--replay", str(path), "--frames", "5"])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert one_error_line(err) == f"broadsword: {message}"


@pytest.mark.parametrize("case", [c for c in CASES if c[0] == "armatures"], ids=case_id)
def test_headless_with_a_bad_armature__exit_2_and_the_loader_line(
    case, tmp_path, shipped_armatures, capsys, monkeypatch
):
    made = tmp_path / "made"
    made.mkdir()
    path, message = expected_error(case, made, shipped_armatures)
    assets = tmp_path / "assets"
    shutil.copytree(SPRITES, assets / "sprites", ignore=shutil.ignore_patterns("*.png"))
    shutil.copy(path, assets / "sprites" / path.name)
    # The headless command loads the armatures of data_dir("assets"); point it at a copy
    # of the shipped ones with the bad file added.
    monkeypatch.setattr(stages, "data_dir", lambda kind: assets if kind == "assets" else data_dir(kind))
    code = cli.main(["--headless", "--level", "1-picket", "--frames", "5"])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert one_error_line(err) == f"broadsword: {message.replace(str(path), str(assets / 'sprites' / path.name))}"


@pytest.mark.parametrize("case", [c for c in CASES if c[0] == "armatures"], ids=case_id)
def test_armature_check__fails_with_one_error_line(case, tmp_path, shipped_armatures, capsys):
    path, message = expected_error(case, tmp_path, shipped_armatures)
    code = cli.main(["armature", "check", str(path)])
    out, err = capsys.readouterr()
    assert code == 1
    errors = [line for line in out.splitlines() if "error:" in line]
    assert len(errors) == 1 and errors[0].endswith(f"error: {message}")
    assert one_error_line(err) == "broadsword armature check: 1 invalid file(s)"


SUBPROCESS_CASES = [
    ("levels", "binary-png.toml", False),
    ("levels", "unknown-enemy.toml", False),
    ("levels", "sprite-path-dotdot.toml", False),
    ("levels", "deep-nesting-arrays.toml", True),
    ("levels", "huge.toml", True),
    ("recordings", "not-json.json", False),
]


@pytest.mark.parametrize("case", SUBPROCESS_CASES, ids=case_id)
def test_headless_in_a_fresh_process__exit_2_one_line_no_traceback(case, tmp_path, shipped_armatures):
    path, message = expected_error(case, tmp_path, shipped_armatures)
    flag = "--level" if case[0] == "levels" else "--replay"
    run = subprocess.run(
        [sys.executable, "-m", "broadsword", "--headless", flag, str(path), "--frames", "5"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 2 and run.stdout == ""
    assert "Traceback" not in run.stderr
    assert one_error_line(run.stderr) == f"broadsword: {message}"


def test_armature_check_in_a_fresh_process__one_error_no_traceback(shipped_armatures):
    path = BAD / "armatures" / "self-crossing.armature.toml"
    run = subprocess.run(
        [sys.executable, "-m", "broadsword", "armature", "check", str(path)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 1 and "Traceback" not in run.stderr
    assert [line for line in run.stdout.splitlines() if "error:" in line][0].endswith(
        f"error: {path}: shapes.hit: armature 'self-crossing': edge 0 [0.0, 0.0]-[4.0, 4.0] meets edge 2 "
        "[4.0, 0.0]-[0.0, 4.0]; an armature must be a simple polygon"
    )


# ---------------------------------------------------------------------- size limits
@pytest.mark.parametrize(
    "kind, limit, valid",
    [("levels", LEVEL_MAX_BYTES, WAVE), ("armatures", FILE_MAX_BYTES, f"[shapes]\nhit = {TRI}\n")],
)
def test_size_limit__refused_by_size_before_parsing_and_a_file_at_the_limit_loads(
    kind, limit, valid, tmp_path, shipped_armatures, monkeypatch
):
    at_limit = padded(valid, limit - 200)
    at_limit += "#" * (limit - len(at_limit.encode()) - 1) + "\n"
    path = tmp_path / ("x" + (SUFFIX if kind == "armatures" else ".toml"))
    path.write_text(at_limit)
    assert path.stat().st_size == limit
    load(kind, path, shipped_armatures)  # exactly the limit: loads
    path.write_text(at_limit + "\n")
    calls = []
    monkeypatch.setattr(tomllib, "loads", lambda *a, **k: calls.append(a) or {})
    with pytest.raises(DataError, match=f"is {limit + 1:,} bytes; .* is at most {limit:,}"):
        load(kind, path, shipped_armatures)
    assert calls == []  # never parsed


def test_size_limit__a_recording_over_8_mib_is_not_parsed(tmp_path, monkeypatch):
    path = tmp_path / "big.json"
    path.write_text(json.dumps({**RECORDING, "inputs": "05" * (RECORDING_MAX_BYTES // 2)}))
    calls = []
    monkeypatch.setattr(json, "loads", lambda *a, **k: calls.append(a) or {})
    with pytest.raises(DataError, match=f"at most {RECORDING_MAX_BYTES:,}"):
        recordings.load_recording(path)
    assert calls == []


def test_not_a_regular_file__refused_without_reading(tmp_path):
    with pytest.raises(DataError, match="not a regular file"):
        load_armature_file(tmp_path)
    with pytest.raises(DataError, match="no such level file"):
        resolve_level(str(tmp_path))


def test_dotted_keys__refused_from_32_parts_before_parsing(tmp_path, monkeypatch):
    path = tmp_path / "keys.toml"
    path.write_text(WAVE + "[x" + ".a" * 30 + "]\n")  # 31 parts: parsed; the loader names the field
    with pytest.raises(DataError) as info:
        load_level(path)
    assert str(info.value).startswith(f"{path}: x: unknown field")
    path.write_text(WAVE + "\n[x" + ".a" * 31 + "]\n")  # 32 parts
    monkeypatch.setattr(tomllib, "loads", lambda *a, **k: pytest.fail("parsed"))
    with pytest.raises(DataError) as info:
        load_level(path)
    assert str(info.value) == f"{path}: not valid TOML: nested too deeply (a key of 32 or more dotted parts, at line 4)"


# ---------------------------------------------------------------------- errors stay one short line
def test_data_error__escapes_unprintable_characters_and_cuts_long_parts():
    err = DataError("dir/a\nb.toml", "wave[0].x\ny" + "z" * 500, "bad\r\nvalue\x00\u2028" + "m" * 1000)
    line = str(err)
    assert line.isprintable() and "\n" not in line
    assert line.startswith("dir/a\\nb.toml: wave[0].x\\ny")
    field, message = line.split(": ", 2)[1:]
    assert len(field) == FIELD_MAX_CHARS and field.endswith("...")
    assert len(message) == MESSAGE_MAX_CHARS and message.startswith("bad\\r\\nvalue\\x00\\u2028mmm")
    assert (err.path, err.field) == ("dir/a\nb.toml", "wave[0].x\ny" + "z" * 500)  # the attributes keep what was given


def test_data_error__a_huge_bad_value_is_described_not_dumped(tmp_path):
    path = tmp_path / "big-value.toml"
    path.write_text(WAVE + 'count = "' + "6" * 100_000 + '"\n')
    with pytest.raises(DataError) as info:
        load_level(path)
    assert str(info.value).startswith(f"{path}: wave[0].count: must be a whole number in [1, 1000], got '666")
    assert len(str(info.value)) < len(str(path)) + 120


# ---------------------------------------------------------------------- sprite names
def test_check_level_sprites__every_shipped_level_passes_and_a_missing_armature_is_named(tmp_path, shipped_armatures):
    for name in list_levels():
        check_level_sprites(load_level(resolve_level(name)), shipped_armatures)
    path = tmp_path / "two.toml"
    path.write_text(WAVE + 'fire = "aimed"\nbullet = "needle"\n[boss]\n[[boss.part]]\nsprite = "boss_turret"\n')
    level = load_level(path)
    check_level_sprites(level, shipped_armatures)
    for gone, field in (
        ("scout", "wave[0].enemy"),
        ("needle", "wave[0].bullet"),
        ("boss_turret", "boss.part[0].sprite"),
    ):
        without = {k: v for k, v in shipped_armatures.items() if k != gone}
        with pytest.raises(DataError) as info:
            check_level_sprites(level, without)
        assert str(info.value) == f"{path}: {field}: unknown sprite {gone!r}; known: {', '.join(sorted(without))}"


def test_resolve_level__a_name_is_never_a_path(tmp_path):
    for name in ("../levels/1-picket", "levels/1-picket", "/1-picket", "a" * 5000):
        with pytest.raises(DataError):
            resolve_level(name)


# ---------------------------------------------------------------------- nothing is executed
def test_nothing_executed__code_in_a_string_is_only_a_string(tmp_path, monkeypatch, shipped_armatures):
    monkeypatch.chdir(tmp_path)
    code = "__import__('os').system('touch PWNED')"
    path = tmp_path / "code.toml"
    path.write_text(f'[level]\ntitle = "{code[:80]}"\n' + WAVE)
    level = load("levels", path, shipped_armatures)
    assert level.title == code
    assert sorted(p.name for p in tmp_path.iterdir()) == ["code.toml"]
    # Where a name is expected, code is refused as not a name.
    path.write_text(f'[[wave]]\nenemy = "{code}"\n')
    with pytest.raises(DataError, match="wave\\[0\\].enemy: must be a sprite name"):
        load_level(path)
    arm = tmp_path / "code.armature.toml"
    arm.write_text(f'sprite = "{code}.png"\n[shapes]\nhit = {TRI}\n')
    assert load_armature_file(arm).sprite == f"{code}.png"  # a file name like any other, never run
    assert sorted(p.name for p in tmp_path.iterdir()) == ["code.armature.toml", "code.toml"]


#: Calls and modules that could run a file's contents (``re.compile`` is not one: only
#: the builtin ``compile`` counts).
EXECUTING_BUILTINS = {"eval", "exec", "compile", "__import__"}
EXECUTING_METHODS = {"eval", "exec", "__import__", "import_module"}
EXECUTING_MODULES = {"pickle", "marshal", "shelve", "runpy", "importlib", "yaml", "code", "codeop"}
#: Submodules of those that only read files, never run them: how shipped data is found.
READING_MODULES = {"importlib.resources"}


def executing_uses(tree: ast.AST) -> list[str]:
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            f = node.func
            if (
                isinstance(f, ast.Name)
                and f.id in EXECUTING_BUILTINS
                or isinstance(f, ast.Attribute)
                and f.attr in EXECUTING_METHODS
            ):
                found.append(f"call {f.id if isinstance(f, ast.Name) else f.attr}")
        elif isinstance(node, ast.Import):
            found += [
                f"import {a.name}"
                for a in node.names
                if a.name.split(".")[0] in EXECUTING_MODULES and a.name not in READING_MODULES
            ]
        elif isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] in EXECUTING_MODULES:
            if node.module in READING_MODULES:
                continue
            names = [a.name for a in node.names]
            if node.module == "importlib" and set(names) <= {m.split(".")[1] for m in READING_MODULES}:
                continue  # from importlib import resources
            found.append(f"from {node.module}")
    return found


def test_nothing_executed__the_loaders_parse_with_tomllib_and_json_only():
    package = Path(cli.__file__).parent / "data"
    sources = {p.relative_to(package).as_posix(): p.read_text(encoding="utf-8") for p in sorted(package.rglob("*.py"))}
    sources["load_recording"] = textwrap.dedent(inspect.getsource(recordings.load_recording))
    assert {"levels/load.py", "armatures.py", "resources.py", "recordings.py", "table.py"} <= set(sources)
    for name, source in sources.items():
        assert executing_uses(ast.parse(source)) == [], name
    # The check itself can fail: it finds each kind of use.
    probe = (
        "import pickle\nfrom importlib import x\neval(s)\nobj.exec(s)\ncompile(s, 'f', 'exec')\nre.compile(s)\n"
        "import importlib\nimport importlib.resources\nfrom importlib import resources\n"
        "from importlib.resources import files\nimport importlib.util\n"
    )
    assert sorted(executing_uses(ast.parse(probe))) == [
        "call compile",
        "call eval",
        "call exec",
        "from importlib",
        "import importlib",
        "import importlib.util",
        "import pickle",
    ]
    # The parsers are the standard ones.
    assert "tomllib.loads(" in sources["resources.py"] and "json.loads(" in sources["load_recording"]
