"""High scores saved by more than one instance: merge on save, the lock, stale temporaries.

Rules under test:

* ``save`` re-reads the file and writes the best ``MAX`` of the file's entries followed by
  the entries this instance added since its last load or save: nobody's scores are lost,
  the entries an instance loaded (or already saved) are not written twice, and on equal
  scores the file's entries stay ahead. After a successful save ``entries`` is the merged
  table; after a failed one it still holds the new scores, and a later save writes them
  once. A file that vanished since counts as empty; one that turned corrupt is set aside
  (warning returned and stored) and the merge starts from the table last read or written.
* ``save`` holds ``fileio.locked(<name>.lock)`` while it reads and writes.
* ``fileio.locked`` is an exclusive flock (POSIX); without fcntl, or when the lock file
  cannot be opened, the block runs unlocked and is told so.
* ``fileio.remove_stale_temps`` removes exactly write_atomic's ``.<name>.<random>.tmp``
  regular files; ``save`` calls it only while holding the lock.
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from score_rows import entry

from broadsword import fileio
from broadsword.fileio import locked, remove_stale_temps, write_atomic
from broadsword.game import scores as scores_mod
from broadsword.game.scores import Entry, HighScores

LOCK = "highscores.json.lock"
try:
    import fcntl
except ImportError:  # not POSIX: the lock tests that need flock skip
    fcntl = None


def listing(directory: Path) -> list[str]:
    return sorted(p.name for p in directory.iterdir())


def on_disk(path: Path) -> list[Entry]:
    table = HighScores(path).load()
    assert table.warning is None
    return table.entries


def saved_table(path: Path, *entries: Entry) -> HighScores:
    table = HighScores(path)
    for e in entries:
        table.add(e)
    table.save()
    return table


# --------------------------------------------------------------------------- merging


def test_merge__two_instances_lose_nothing(tmp_path):
    """The lost update: both load, both add, both save -- the second save keeps the first's."""
    path = tmp_path / "highscores.json"
    saved_table(path, entry("OLD", 45))
    a, b = HighScores(path).load(), HighScores(path).load()
    a.add(entry("A1", 50))
    a.add(entry("A2", 30))
    b.add(entry("B1", 40))
    b.add(entry("B2", 20))
    assert a.save() is None
    assert b.save() is None
    expected = [entry("A1", 50), entry("OLD", 45), entry("B1", 40), entry("A2", 30), entry("B2", 20)]
    assert on_disk(path) == expected
    assert b.entries == expected  # the saver now shows the merged table
    assert a.entries == [entry("A1", 50), entry("OLD", 45), entry("A2", 30)]  # not yet re-read
    assert a.save() is None  # nothing new: rewrites the file's table, duplicates nothing
    assert on_disk(path) == expected and a.entries == expected


def test_merge__loaded_and_already_saved_entries_are_not_written_twice(tmp_path):
    path = tmp_path / "highscores.json"
    saved_table(path, entry("X", 70))
    table = HighScores(path).load()
    table.add(entry("Y", 60))
    table.save()
    table.save()
    table.add(entry("Z", 80))
    table.save()
    assert on_disk(path) == [entry("Z", 80), entry("X", 70), entry("Y", 60)]


def test_merge__identical_new_entries_are_both_kept(tmp_path):
    """Two equal rows are two results (same pilot, same score, same day), not a duplicate."""
    path = tmp_path / "highscores.json"
    saved_table(path, entry("ACE", 100))
    table = HighScores(path).load()
    table.add(entry("ACE", 100))
    table.add(entry("ACE", 100))
    table.save()
    assert on_disk(path) == [entry("ACE", 100)] * 3


def test_merge__file_entries_win_ties(tmp_path):
    """On equal scores the entry already in the file ranks ahead of this instance's new
    one, even though this instance added its entry first; at a full table it keeps its place."""
    path = tmp_path / "highscores.json"
    mine = HighScores(path).load()
    mine.add(entry("MINE", 50))
    other = HighScores(path).load()
    for s in range(100, 1000, 100):  # 9 entries
        other.add(entry(f"O{s}", s))
    other.add(entry("THEIRS", 50))
    other.save()
    mine.save()
    names = [e.name for e in on_disk(path)]
    assert names == [f"O{s}" for s in range(900, 0, -100)] + ["THEIRS"]  # MINE did not fit


def test_merge__keeps_the_best_max_of_the_union(tmp_path):
    path = tmp_path / "highscores.json"
    mine = HighScores(path).load()
    for s in (1050, 550, 50):
        mine.add(entry(f"M{s}", s))
    saved_table(path, *[entry(f"O{s}", s) for s in range(100, 1100, 100)])  # another instance: 10
    mine.save()
    assert [(e.name, e.score) for e in on_disk(path)] == (
        [("M1050", 1050)]
        + [(f"O{s}", s) for s in range(1000, 500, -100)]
        + [("M550", 550)]
        + [(f"O{s}", s) for s in range(500, 200, -100)]
    )


def test_merge__adds_beyond_max_before_one_save(tmp_path):
    """More than MAX adds between saves: the file gets the best MAX, in order."""
    path = tmp_path / "highscores.json"
    table = HighScores(path).load()
    for s in [5, 25, 1, 17, 9, 30, 2, 22, 13, 8, 28, 3, 19, 11, 26, 6, 14, 20, 4, 24, 7]:
        table.add(entry(f"S{s}", s))
    table.save()
    assert [e.score for e in on_disk(path)] == [30, 28, 26, 25, 24, 22, 20, 19, 17, 14]


def test_merge__vanished_file_counts_as_empty(tmp_path):
    """Someone deleted the file (a reset) after this instance loaded it: the save writes
    only what this instance added since, and does not resurrect the deleted table."""
    path = tmp_path / "highscores.json"
    saved_table(path, entry("GONE", 90))
    table = HighScores(path).load()
    table.add(entry("NEW", 10))
    path.unlink()
    table.save()
    assert on_disk(path) == [entry("NEW", 10)]


def test_merge__file_turned_corrupt_is_set_aside_and_session_table_saved(tmp_path):
    path = tmp_path / "highscores.json"
    saved_table(path, entry("KEPT", 90))
    table = HighScores(path).load()
    table.add(entry("NEW", 10))
    path.write_bytes(b'{"version": 1, "scores": [')  # a hand edit gone wrong
    warning = table.save()
    assert warning is not None and warning == table.warning
    assert str(path) in warning and "corrupt" in warning and "\n" not in warning
    (aside,) = [n for n in listing(tmp_path) if n not in ("highscores.json", LOCK)]
    assert aside.startswith("highscores.json.corrupt-") and aside in warning
    assert (tmp_path / aside).read_bytes() == b'{"version": 1, "scores": ['
    assert on_disk(path) == [entry("KEPT", 90), entry("NEW", 10)]
    assert table.entries == [entry("KEPT", 90), entry("NEW", 10)]


def test_merge__corrupt_file_set_aside_then_write_fails_retry_keeps_everything(tmp_path, monkeypatch):
    """The file turned corrupt and the write after setting it aside fails: the warning
    still says where the file went, and the retry writes the table this instance knew
    (now only in the set-aside file) plus the new entry."""
    path = tmp_path / "highscores.json"
    saved_table(path, entry("KEPT", 90))
    table = HighScores(path).load()
    table.add(entry("NEW", 10))
    path.write_bytes(b"garbage")

    def full(src, dst):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(fileio.os, "replace", full)
    with pytest.raises(OSError, match="No space"):
        table.save()
    monkeypatch.undo()
    (aside,) = [n for n in listing(tmp_path) if n not in ("highscores.json", LOCK)]
    assert table.warning is not None and aside in table.warning
    assert (tmp_path / aside).read_bytes() == b"garbage"
    assert not path.exists()
    assert table.save() is None
    assert on_disk(path) == [entry("KEPT", 90), entry("NEW", 10)]


def test_merge__file_turned_unreadable_is_not_replaced(tmp_path, monkeypatch):
    """The file cannot be read at save time: OSError, file untouched, the new score kept in
    memory; once readable again a save merges and writes it exactly once."""
    path = tmp_path / "highscores.json"
    saved_table(path, entry("OTHER", 90))
    table = HighScores(path).load()
    table.add(entry("NEW", 10))
    before = path.read_bytes()

    def denied(*args, **kwargs):
        raise PermissionError(13, "Permission denied", str(path))

    monkeypatch.setattr(scores_mod, "read_capped", denied)
    with pytest.raises(PermissionError) as info:
        table.save()
    assert info.value.filename == str(path)
    assert table.entries == [entry("OTHER", 90), entry("NEW", 10)]
    monkeypatch.undo()
    assert path.read_bytes() == before
    table.save()
    assert on_disk(path) == [entry("OTHER", 90), entry("NEW", 10)]


def test_merge__failed_write_keeps_new_scores_for_the_next_save(tmp_path, monkeypatch):
    path = tmp_path / "highscores.json"
    table = saved_table(path, entry("OLD", 50))
    table.add(entry("NEW", 60))

    def full(src, dst):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(fileio.os, "replace", full)
    with pytest.raises(OSError, match="No space left on device") as info:
        table.save()
    assert info.value.errno == 28 and info.value.filename == str(path)
    monkeypatch.undo()
    assert on_disk(path) == [entry("OLD", 50)]
    assert listing(tmp_path) == ["highscores.json", LOCK]
    table.save()
    assert on_disk(path) == [entry("NEW", 60), entry("OLD", 50)]


def test_merge__load_forgets_unsaved_adds(tmp_path):
    path = tmp_path / "highscores.json"
    saved_table(path, entry("OLD", 50))
    table = HighScores(path).load()
    table.add(entry("DROPPED", 70))
    table.load()
    table.save()
    assert on_disk(path) == [entry("OLD", 50)]


OP = st.tuples(st.integers(0, 2), st.sampled_from(["add", "add", "save", "load"]))


@settings(max_examples=60, deadline=None)
@given(ops=st.lists(OP, max_size=60), scores=st.lists(st.integers(0, 10_000), min_size=60, max_size=60, unique=True))
def test_merge__any_interleaving_of_three_instances(ops, scores):
    """Three instances on one file, any sequence of add/save/load (distinct scores). After
    each save the file and the saver's table are exactly the best MAX of every entry that
    was pending at some save so far; a load drops that instance's pending entries."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "highscores.json"
        tables = [HighScores(path).load() for _ in range(3)]
        pending: list[list[Entry]] = [[], [], []]
        committed: list[Entry] = []
        fresh = iter(scores)
        for who, op in ops:
            t = tables[who]
            if op == "add":
                e = entry(f"I{who}-{len(committed) + len(pending[who])}", next(fresh))
                if t.add(e) is not None:
                    pending[who].append(e)
            elif op == "save":
                t.save()
                committed += pending[who]
                pending[who] = []
                best = sorted(committed, key=lambda e: -e.score)[: HighScores.MAX]
                assert t.entries == best
                assert on_disk(path) == best
            else:
                t.load()
                pending[who] = []
                assert t.entries == sorted(committed, key=lambda e: -e.score)[: HighScores.MAX]


# --------------------------------------------------------------------------- the lock


needs_flock = pytest.mark.skipif(fcntl is None, reason="needs fcntl.flock (POSIX)")


def try_lock(lock_path: Path) -> bool:
    """Could a second, independent holder take the lock right now? (flock locks belong to
    an open file description, so a fresh open conflicts even within this process.)"""
    fd = os.open(lock_path, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        return False
    finally:
        os.close(fd)
    return True


@needs_flock
def test_locked__excludes_a_second_holder_until_released(tmp_path):
    lock = tmp_path / "x.lock"
    with locked(lock) as held:
        assert held is True
        assert lock.is_file()
        assert not try_lock(lock)
    assert try_lock(lock)
    assert lock.is_file()  # left in place for the next user


def test_locked__unopenable_lock_file_runs_unlocked(tmp_path):
    ran = []
    with locked(tmp_path / "missing-dir" / "x.lock") as held:
        ran.append(held)
    assert ran == [False]
    assert not (tmp_path / "missing-dir").exists()


def test_locked__without_fcntl_runs_unlocked(tmp_path, monkeypatch):
    monkeypatch.setattr(fileio, "fcntl", None)
    with locked(tmp_path / "x.lock") as held:
        assert held is False
    assert listing(tmp_path) == ["x.lock"]  # the same files on every platform


@needs_flock
def test_save__reads_and_writes_while_holding_the_lock(tmp_path, monkeypatch):
    path = tmp_path / "highscores.json"
    table = saved_table(path, entry("OLD", 5))
    table.add(entry("NEW", 9))
    seen = []
    real_read, real_write, real_sweep = HighScores._read, scores_mod.write_atomic, scores_mod.remove_stale_temps

    def spy_read(self):
        seen.append(("read", try_lock(self.lock_path)))
        return real_read(self)

    def spy_write(p, data):
        seen.append(("write", try_lock(table.lock_path)))
        return real_write(p, data)

    def spy_sweep(p):
        seen.append(("sweep", try_lock(table.lock_path)))
        return real_sweep(p)

    monkeypatch.setattr(HighScores, "_read", spy_read)
    monkeypatch.setattr(scores_mod, "write_atomic", spy_write)
    monkeypatch.setattr(scores_mod, "remove_stale_temps", spy_sweep)
    table.save()
    assert seen == [("read", False), ("write", False), ("sweep", False)]
    assert try_lock(table.lock_path)  # released afterwards
    assert on_disk(path) == [entry("NEW", 9), entry("OLD", 5)]


# --------------------------------------------------------------------------- stale temporaries


def test_remove_stale_temps__only_write_atomics_temporaries(tmp_path):
    target = tmp_path / "highscores.json"
    target.write_text("{}")
    stale = [".highscores.json.abc123_x.tmp", ".highscores.json.k9q2w8e7.tmp"]
    keep = [
        "highscores.json.corrupt-20240101T000000Z",
        ".highscores.json.tmp",
        "highscores.json.abc.tmp",
        ".other.json.abc123.tmp",
        ".highscores.json.abc.tmp.bak",
        LOCK,
    ]
    for name in stale + keep:
        (tmp_path / name).write_text("x")
    (tmp_path / ".highscores.json.dir12345.tmp").mkdir()  # not a regular file: kept
    if hasattr(os, "symlink"):
        os.symlink(target, tmp_path / ".highscores.json.link1234.tmp")  # a link: kept
        keep.append(".highscores.json.link1234.tmp")
    assert remove_stale_temps(target) == len(stale)
    assert listing(tmp_path) == sorted(keep + ["highscores.json", ".highscores.json.dir12345.tmp"])
    assert target.read_text() == "{}"


def test_remove_stale_temps__matches_what_write_atomic_names(tmp_path, monkeypatch):
    """The pattern follows write_atomic's real naming: a temporary it leaves is found."""
    target = tmp_path / "highscores.json"
    made = []
    real_mkstemp = tempfile.mkstemp

    def spy(*args, **kwargs):
        fd, name = real_mkstemp(*args, **kwargs)
        made.append(Path(name).name)
        return fd, name

    class Killed(BaseException):
        pass

    def killed(src, dst):  # leave the temporary behind, as a kill would
        raise Killed

    monkeypatch.setattr(fileio.tempfile, "mkstemp", spy)
    monkeypatch.setattr(fileio.os, "unlink", lambda p: None)  # a kill runs no clean-up
    monkeypatch.setattr(fileio.os, "replace", killed)
    with pytest.raises(Killed):
        write_atomic(target, b"data")
    monkeypatch.undo()
    assert listing(tmp_path) == made and len(made) == 1
    assert remove_stale_temps(target) == 1
    assert listing(tmp_path) == []


def test_save__sweeps_stale_temporaries_while_locked(tmp_path):
    path = tmp_path / "highscores.json"
    table = saved_table(path, entry("OLD", 5))
    (tmp_path / ".highscores.json.dead0001.tmp").write_bytes(b'{"version": 1, "sco')
    assert HighScores(path).load().entries == [entry("OLD", 5)]  # load never reads temps
    table.add(entry("NEW", 9))
    table.save()
    assert listing(tmp_path) == ["highscores.json", LOCK]
    assert on_disk(path) == [entry("NEW", 9), entry("OLD", 5)]


def test_save__leaves_temporaries_alone_when_not_locked(tmp_path, monkeypatch):
    """Unlocked (no fcntl), another writer's temporary may be live: it is not touched."""
    monkeypatch.setattr(fileio, "fcntl", None)
    path = tmp_path / "highscores.json"
    table = saved_table(path, entry("OLD", 5))
    (tmp_path / ".highscores.json.live0001.tmp").write_bytes(b"{")
    table.add(entry("NEW", 9))
    table.save()
    assert listing(tmp_path) == [".highscores.json.live0001.tmp", "highscores.json", LOCK]
    assert json.loads(path.read_text())["scores"][0]["name"] == "NEW"
