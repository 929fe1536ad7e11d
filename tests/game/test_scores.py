"""The high-score table: file round trips, ranking, atomic saves, corrupt-file handling.

Rules under test:

* ``entries`` is sorted by score, best first, at most ``MAX`` (10); on equal scores the
  entry that was there first stays ahead, and a full table only admits a score strictly
  above its last one. ``add`` returns the 0-based rank or None.
* Names are sanitised on ``add``: printable only, whitespace collapsed and trimmed, at most
  12 characters, ``"???"`` if nothing is left. A file holding a name that sanitising would
  change is corrupt.
* ``load``: a missing file is an empty table; a corrupt one is renamed to
  ``<name>.corrupt-<YYYYmmddTHHMMSSZ>`` with its bytes preserved, ``warning`` names the file
  on one line, and the table is empty -- never an exception. An unreadable file is left in
  place (warning, empty table) and ``save`` refuses to replace it.
* ``save`` writes ``{"version": 1, "scores": [...]}`` atomically: after any failure the old
  file is byte-for-byte intact and no temporary file remains. It (and a load that sets a
  corrupt file aside) leaves the sidecar lock file ``highscores.json.lock``. Merging with
  other instances, the lock, kills and read-only directories: test_scores_merge.py,
  test_scores_processes.py, test_scores_readonly.py.
* the default path is ``data_home() / "highscores.json"``; where ``data_home`` points on
  each platform is tested in tests/game/test_userdata.py.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

import pytest
from score_rows import DAY, entry

from broadsword.data.difficulty import Difficulty
from broadsword.game import scores as scores_mod
from broadsword.game.scores import Entry, HighScores, sanitise_name

CORRUPT_RE = re.compile(r"^highscores\.json\.corrupt-\d{8}T\d{6}Z(-\d+)?$")
LOCK = "highscores.json.lock"  # the sidecar save() (and a corrupt-file load) locks


def write_doc(path: Path, scores: list, version=1) -> None:
    path.write_text(json.dumps({"version": version, "scores": scores}), encoding="utf-8")


def row(name="ACE", score=100, level="1-picket", date=DAY) -> dict:
    return {"name": name, "score": score, "level": level, "date": date}


def listing(directory: Path) -> list[str]:
    return sorted(p.name for p in directory.iterdir())


# --------------------------------------------------------------------------- round trip


def test_roundtrip__save_then_load_gives_equal_entries(tmp_path):
    path = tmp_path / "highscores.json"
    table = HighScores(path)
    for i, score in enumerate([500, 1200, 90, 1200, 7]):
        table.add(entry(name=f"P{i}", score=score, level=f"{i % 3 + 1}-lvl"))
    table.save()
    again = HighScores(path).load()
    assert again.entries == table.entries
    assert again.warning is None
    assert [e.score for e in again.entries] == [1200, 1200, 500, 90, 7]
    assert [e.name for e in again.entries[:2]] == ["P1", "P3"]  # tie: first one stays ahead


def test_roundtrip__file_format_is_versioned_json(tmp_path):
    path = tmp_path / "highscores.json"
    table = HighScores(path)
    table.add(entry(name="Zoë", score=42, level="2-gauntlet", date="2023-12-31"))
    table.save()
    doc = json.loads(path.read_text(encoding="utf-8"))
    want = dict(row("Zoë", 42, "2-gauntlet", "2023-12-31"), difficulty="normal", speed=100)
    assert doc == {"version": 3, "scores": [want]}


def test_difficulties__each_keeps_its_own_table(tmp_path):
    """Easy's scores never push Lunatic's out, and each ranks on its own (issue 22)."""
    path = tmp_path / "highscores.json"
    table = HighScores(path)
    for i in range(HighScores.MAX + 3):
        assert table.add(Entry(f"E{i}", 10_000 + i, "I. Outer Picket", DAY, Difficulty.EASY)) is not None
    assert table.add(Entry("L", 50, "V. The Citadel", DAY, Difficulty.LUNATIC)) == 0  # first of its table
    assert not table.qualifies(10_000, Difficulty.EASY) and table.qualifies(1, Difficulty.LUNATIC)
    assert table.qualifies(1)  # Normal's table is empty
    table.save()
    again = HighScores(path).load()
    assert [e.name for e in again.of(Difficulty.LUNATIC)] == ["L"]
    easy = again.of(Difficulty.EASY)
    assert len(easy) == HighScores.MAX and easy[0].score == 10_000 + HighScores.MAX + 2
    assert again.of(Difficulty.NORMAL) == [] and len(again.entries) == HighScores.MAX + 1


def test_difficulties__a_version_1_table_is_normals(tmp_path):
    path = tmp_path / "highscores.json"
    path.write_text(json.dumps({"version": 1, "scores": [row("OLD", 900)]}))
    table = HighScores(path).load()
    assert table.warning is None and [(e.name, e.difficulty) for e in table.entries] == [("OLD", Difficulty.NORMAL)]
    table.add(Entry("NEW", 5, "II. The Gauntlet", DAY, Difficulty.HARD))
    table.save()
    doc = json.loads(path.read_text())
    assert doc["version"] == 3 and [r["difficulty"] for r in doc["scores"]] == ["normal", "hard"]


def test_speed__kept_with_a_score_and_a_version_2_table_is_at_full_speed(tmp_path):
    """The game speed a score was made at is saved with it (issue 22); older tables' were 100 %."""
    path = tmp_path / "highscores.json"
    path.write_text(json.dumps({"version": 2, "scores": [dict(row("OLD", 900), difficulty="easy")]}))
    table = HighScores(path).load()
    assert table.warning is None and [(e.name, e.speed) for e in table.entries] == [("OLD", 100)]
    table.add(Entry("SLOW", 5, "II. The Gauntlet", DAY, Difficulty.EASY, 70))
    table.save()
    doc = json.loads(path.read_text())
    assert doc["version"] == 3 and [r["speed"] for r in doc["scores"]] == [100, 70]
    assert [(e.name, e.speed) for e in HighScores(path).load().entries] == [("OLD", 100), ("SLOW", 70)]


@pytest.mark.parametrize("speed", [0, 101, 70.0, True, "70", None])
def test_speed__a_bad_one_is_a_corrupt_file_or_refused(tmp_path, speed):
    path = tmp_path / "highscores.json"
    path.write_text(json.dumps({"version": 3, "scores": [dict(row(), difficulty="hard", speed=speed)]}))
    table = HighScores(path).load()
    assert table.entries == [] and "speed" in table.warning
    with pytest.raises(ValueError, match="speed"):
        table.add(Entry("X", 5, "II. The Gauntlet", DAY, Difficulty.HARD, speed))


def test_difficulties__an_unknown_one_is_a_corrupt_file(tmp_path):
    path = tmp_path / "highscores.json"
    path.write_text(json.dumps({"version": 2, "scores": [dict(row(), difficulty="nightmare")]}))
    table = HighScores(path).load()
    assert table.entries == [] and "difficulty" in table.warning and "nightmare" in table.warning


def test_roundtrip__empty_table_saves_and_loads(tmp_path):
    path = tmp_path / "highscores.json"
    HighScores(path).save()
    again = HighScores(path).load()
    assert again.entries == [] and again.warning is None


def test_roundtrip__save_creates_missing_directories(tmp_path):
    path = tmp_path / "a" / "b" / "highscores.json"
    table = HighScores(path)
    table.add(entry())
    table.save()
    assert HighScores(path).load().entries == [entry()]


def test_load__missing_file_is_empty_without_warning(tmp_path):
    table = HighScores(tmp_path / "nope" / "highscores.json").load()
    assert table.entries == [] and table.warning is None


def test_load__returns_self_and_replaces_entries(tmp_path):
    path = tmp_path / "highscores.json"
    write_doc(path, [row("A", 5)])
    table = HighScores(path)
    table.add(entry("Z", 999))
    assert table.load() is table
    assert table.entries == [Entry("A", 5, "1-picket", DAY)]


def test_load__unsorted_file_is_sorted_and_trimmed_to_max(tmp_path):
    """Valid but unsorted or longer than MAX (e.g. from an older, bigger MAX): kept, ranked."""
    path = tmp_path / "highscores.json"
    raw = [3, 50, 7, 1, 99, 4, 8, 2, 60, 5, 6, 70]
    write_doc(path, [row(f"P{i}", s) for i, s in enumerate(raw)])
    table = HighScores(path).load()
    assert table.warning is None
    assert [e.score for e in table.entries] == [99, 70, 60, 50, 8, 7, 6, 5, 4, 3]
    assert listing(tmp_path) == ["highscores.json"]


def test_load__tolerates_utf8_bom(tmp_path):
    path = tmp_path / "highscores.json"
    path.write_bytes(b"\xef\xbb\xbf" + json.dumps({"version": 1, "scores": [row()]}).encode())
    assert HighScores(path).load().entries == [entry()]


# --------------------------------------------------------------------------- ranking


def test_add__ranks_best_first_and_caps_at_max(tmp_path):
    table = HighScores(tmp_path / "h.json")
    ranks = [table.add(entry(name=f"P{s}", score=s)) for s in range(10, 0, -1)]
    assert ranks == list(range(10))
    assert len(table.entries) == HighScores.MAX == 10
    assert table.add(entry(score=0)) is None  # below the lowest
    assert table.add(entry(score=1)) is None  # equal to the lowest: the holder keeps it
    assert table.add(entry(name="TOP", score=11)) == 0
    assert table.add(entry(name="MID", score=5)) == 7  # just below the existing 5 (tie rule)
    assert [e.name for e in table.entries[6:8]] == ["P5", "MID"]
    assert len(table.entries) == 10
    scores = [e.score for e in table.entries]
    assert scores == sorted(scores, reverse=True)
    assert scores == [11, 10, 9, 8, 7, 6, 5, 5, 4, 3]


def test_qualifies__boundaries(tmp_path):
    table = HighScores(tmp_path / "h.json")
    assert table.qualifies(0)  # empty table: anything non-negative
    for s in range(100, 1100, 100):
        table.add(entry(score=s))
    assert not table.qualifies(99)
    assert not table.qualifies(100)  # tie with the last: no
    assert table.qualifies(101)
    for bad, exc in [(-1, ValueError), (1.5, TypeError), (True, TypeError), ("9", TypeError)]:
        with pytest.raises(exc):
            table.qualifies(bad)


def test_qualifies__agrees_with_add(tmp_path):
    table = HighScores(tmp_path / "h.json")
    for s in [5, 3, 9, 3, 1, 7, 3, 8, 2, 6, 3, 3, 4, 10, 0, 3]:
        q = table.qualifies(s)
        assert (table.add(entry(score=s)) is not None) == q


def test_add__numpy_integer_score_is_stored_as_int(tmp_path):
    """Scores computed with numpy (np.int64) are accepted and saved as plain JSON ints."""
    np = pytest.importorskip("numpy")
    path = tmp_path / "highscores.json"
    table = HighScores(path)
    assert table.qualifies(np.int64(5))
    assert table.add(entry(score=np.int64(1234))) == 0
    assert type(table.entries[0].score) is int
    table.save()
    assert json.loads(path.read_text())["scores"][0]["score"] == 1234


@pytest.mark.parametrize(
    "raw,clean",
    [
        ("ACE", "ACE"),
        ("  spaced   out  ", "spaced out"),
        ("tab\there\nnl", "tab here nl"),
        ("bell\x07\x1b[31m", "bell [31m"),
        ("zero\u200bwidth", "zero width"),  # format characters are not printable
        ("ABCDEFGHIJKLMNOP", "ABCDEFGHIJKL"),
        ("ABCDEFGHIJK LMN", "ABCDEFGHIJK"),  # cut at 12 then trimmed: no trailing space
        ("", "???"),
        ("\x00\x01 \t", "???"),
        ("Zoë 東京", "Zoë 東京"),
    ],
)
def test_sanitise_name__printable_trimmed_max_12(raw, clean):
    assert sanitise_name(raw) == clean
    assert len(clean) <= 12 and clean.isprintable()
    assert sanitise_name(clean) == clean  # idempotent


def test_add__sanitises_name_and_roundtrips(tmp_path):
    path = tmp_path / "highscores.json"
    table = HighScores(path)
    rank = table.add(entry(name="\tA very long name indeed\n", score=10))
    assert table.entries[rank].name == "A very long"
    table.save()
    assert HighScores(path).load().entries == table.entries


@pytest.mark.parametrize(
    "bad,exc",
    [
        (dict(score=-1), ValueError),
        (dict(score=3.0), TypeError),
        (dict(score=False), TypeError),
        (dict(date="17/05/2024"), ValueError),
        (dict(date="2024-02-30"), ValueError),
        (dict(date="20240517"), ValueError),
        (dict(level=3), TypeError),
    ],
)
def test_add__rejects_invalid_entries(tmp_path, bad, exc):
    table = HighScores(tmp_path / "h.json")
    with pytest.raises(exc):
        table.add(entry(**bad))
    assert table.entries == []


# --------------------------------------------------------------------------- atomic save


def make_saved(tmp_path: Path) -> tuple[HighScores, Path, bytes]:
    path = tmp_path / "highscores.json"
    table = HighScores(path)
    table.add(entry("OLD", 10))
    table.save()
    return table, path, path.read_bytes()


def test_save__leaves_no_temp_files(tmp_path):
    table, path, _ = make_saved(tmp_path)
    for s in range(5):
        table.add(entry(score=s * 100))
        table.save()
    assert listing(tmp_path) == ["highscores.json", LOCK]


def test_save__replace_failure_keeps_old_file_and_cleans_up(tmp_path, monkeypatch):
    table, path, before = make_saved(tmp_path)
    table.add(entry("NEW", 999))

    def broken_replace(src, dst):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(scores_mod.os, "replace", broken_replace)
    with pytest.raises(OSError, match="No space"):
        table.save()
    assert path.read_bytes() == before
    assert listing(tmp_path) == ["highscores.json", LOCK]


def test_save__fsync_failure_keeps_old_file_and_cleans_up(tmp_path, monkeypatch):
    """A failure mid-write (before the rename) never exposes a half-written file."""
    table, path, before = make_saved(tmp_path)
    table.add(entry("NEW", 999))
    seen = {}

    def broken_fsync(fd):
        seen["partial"] = True
        raise OSError(5, "Input/output error")

    monkeypatch.setattr(scores_mod.os, "fsync", broken_fsync)
    with pytest.raises(OSError):
        table.save()
    assert seen and path.read_bytes() == before
    assert listing(tmp_path) == ["highscores.json", LOCK]


def test_save__writes_temp_in_same_directory_then_replaces(tmp_path, monkeypatch):
    """The temp file lives beside the target (same filesystem: os.replace is atomic) and
    is fsynced before the replace."""
    table, path, _ = make_saved(tmp_path)
    calls = []
    real_replace, real_fsync = os.replace, os.fsync

    def spy_fsync(fd):
        calls.append(("fsync", fd))
        return real_fsync(fd)

    def spy_replace(src, dst):
        calls.append(("replace", Path(src), Path(dst)))
        return real_replace(src, dst)

    monkeypatch.setattr(scores_mod.os, "fsync", spy_fsync)
    monkeypatch.setattr(scores_mod.os, "replace", spy_replace)
    table.add(entry("NEW", 999))
    table.save()
    kinds = [c[0] for c in calls]
    assert kinds.index("fsync") < kinds.index("replace")
    _, src, dst = calls[kinds.index("replace")]
    assert src.parent == path.parent and dst == path
    assert HighScores(path).load().entries[0].name == "NEW"


def test_save__unwritable_location_raises_oserror(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    table = HighScores(blocker / "highscores.json")
    table.add(entry())
    with pytest.raises(OSError):
        table.save()


# --------------------------------------------------------------------------- corrupt files


CORRUPT = {
    "empty": b"",
    "truncated_json": b'{"version": 1, "scores": [{"name": "A',
    "not_utf8": b'{"version": 1, "scores": [{"name": "\xff\xfe"}]}',
    "top_level_list": b"[1, 2, 3]",
    "wrong_version": b'{"version": 4, "scores": []}',
    "version_as_bool": b'{"version": true, "scores": []}',
    "missing_scores": b'{"version": 1}',
    "extra_top_key": b'{"version": 1, "scores": [], "cheat": 1}',
    "scores_not_list": b'{"version": 1, "scores": {"a": 1}}',
    "entry_not_object": b'{"version": 1, "scores": [[1, 2]]}',
    "missing_field": b'{"version": 1, "scores": [{"name": "A", "score": 1, "level": "x"}]}',
    "extra_field": json.dumps({"version": 1, "scores": [dict(row(), x=1)]}).encode(),
    "negative_score": json.dumps({"version": 1, "scores": [row(score=-5)]}).encode(),
    "float_score": json.dumps({"version": 1, "scores": [row(score=10.0)]}).encode(),
    "bool_score": json.dumps({"version": 1, "scores": [row(score=True)]}).encode(),
    "string_score": json.dumps({"version": 1, "scores": [row(score="10")]}).encode(),
    "nan_score": b'{"version": 1, "scores": [{"name": "A", "score": NaN, "level": "x", "date": "2024-01-01"}]}',
    "huge_int": b'{"version": 1, "scores": [{"name": "A", "score": 1' + b"0" * 5000 + b"}]}",
    "long_name": json.dumps({"version": 1, "scores": [row(name="N" * 13)]}).encode(),
    "control_in_name": json.dumps({"version": 1, "scores": [row(name="A\nB")]}).encode(),
    "empty_name": json.dumps({"version": 1, "scores": [row(name="")]}).encode(),
    "name_not_string": json.dumps({"version": 1, "scores": [row(name=7)]}).encode(),
    "level_not_string": json.dumps({"version": 1, "scores": [row(level=None)]}).encode(),
    "bad_date_format": json.dumps({"version": 1, "scores": [row(date="05/17/2024")]}).encode(),
    "impossible_date": json.dumps({"version": 1, "scores": [row(date="2023-02-29")]}).encode(),
    "deep_nesting": b"[" * 100_000 + b"]" * 100_000,
    "too_big": b'{"version": 1, "scores": []}' + b" " * (1 << 20),
}


@pytest.mark.parametrize("kind", sorted(CORRUPT))
def test_load__corrupt_file_is_set_aside(tmp_path, kind):
    """Renamed beside itself with its bytes intact; one-line warning naming the file;
    empty table; no exception; a later save writes a fresh valid file."""
    path = tmp_path / "highscores.json"
    content = CORRUPT[kind]
    path.write_bytes(content)
    table = HighScores(path).load()
    assert table.entries == []
    assert table.warning is not None
    assert str(path) in table.warning and "\n" not in table.warning
    assert not path.exists()
    (aside,) = [p for p in tmp_path.iterdir() if p.name != LOCK]
    assert listing(tmp_path) == sorted([aside.name, LOCK])
    assert CORRUPT_RE.match(aside.name), aside.name
    assert aside.name in table.warning
    assert aside.read_bytes() == content
    table.add(entry())
    table.save()
    assert HighScores(path).load().entries == [entry()]


def test_load__warning_says_why(tmp_path):
    path = tmp_path / "highscores.json"
    write_doc(path, [row(), row(name="X", score=-3)])
    table = HighScores(path).load()
    assert "scores[1]" in table.warning and "negative" in table.warning


def test_load__one_bad_entry_discards_the_whole_file(tmp_path):
    """Not partially trusted: a file with one bad row is set aside whole."""
    path = tmp_path / "highscores.json"
    write_doc(path, [row("GOOD", 50), row("N" * 20, 40)])
    assert HighScores(path).load().entries == []


def test_load__repeated_corruption_gets_distinct_names(tmp_path):
    """Two corrupt files within the same second do not overwrite each other."""
    path = tmp_path / "highscores.json"
    for content in (b"one", b"two", b"three"):
        path.write_bytes(content)
        HighScores(path).load()
    asides = sorted(p for p in tmp_path.iterdir() if p.name != LOCK)
    assert listing(tmp_path) == sorted([p.name for p in asides] + [LOCK])
    assert len(asides) == 3
    assert all(CORRUPT_RE.match(p.name) for p in asides)
    assert sorted(p.read_bytes() for p in asides) == [b"one", b"three", b"two"]


# --------------------------------------------------------------------------- unreadable files


def test_load__permission_denied_warns_without_renaming(tmp_path, monkeypatch):
    path = tmp_path / "highscores.json"
    write_doc(path, [row()])
    before = path.read_bytes()

    def denied(*args, **kwargs):
        raise PermissionError(13, "Permission denied", str(path))

    monkeypatch.setattr(scores_mod, "read_capped", denied)
    table = HighScores(path).load()
    assert table.entries == []
    assert table.warning is not None and str(path) in table.warning
    assert "permission" in table.warning.lower() and "\n" not in table.warning
    assert listing(tmp_path) == ["highscores.json"]
    # the scores we could not read must not be clobbered by an empty/new table
    table.add(entry("NEW", 1))
    with pytest.raises(PermissionError):
        table.save()
    monkeypatch.undo()
    assert path.read_bytes() == before


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="needs POSIX permissions and a non-root user")
def test_load__real_chmod_000_file(tmp_path):
    path = tmp_path / "highscores.json"
    write_doc(path, [row()])
    path.chmod(0)
    try:
        table = HighScores(path).load()
        assert table.entries == [] and "permission" in table.warning.lower()
        assert listing(tmp_path) == ["highscores.json"]
    finally:
        path.chmod(0o600)


def test_load__directory_in_the_way_warns_without_renaming(tmp_path):
    path = tmp_path / "highscores.json"
    path.mkdir()
    table = HighScores(path).load()
    assert table.entries == [] and str(path) in table.warning
    assert path.is_dir()


def test_load__clean_load_clears_previous_warning(tmp_path):
    path = tmp_path / "highscores.json"
    path.write_bytes(b"garbage")
    table = HighScores(path).load()
    assert table.warning is not None
    write_doc(path, [row()])
    assert table.load().warning is None
    assert table.entries == [entry()]


# --------------------------------------------------------------------------- data_home
# The rules themselves, on every platform: tests/game/test_userdata.py.


@pytest.fixture
def clean_env(monkeypatch):
    for var in ("BROADSWORD_DATA_DIR", "XDG_DATA_HOME", "APPDATA"):
        monkeypatch.delenv(var, raising=False)
    return monkeypatch


def test_highscores__default_path_follows_data_home(clean_env, tmp_path):
    clean_env.setenv("BROADSWORD_DATA_DIR", str(tmp_path / "d"))
    assert HighScores().path == tmp_path / "d" / "highscores.json"
