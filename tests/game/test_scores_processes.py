"""High scores against real processes: killed mid-save, and several saving at once.

Rules under test:

* A save killed (SIGKILL) at any point leaves ``highscores.json`` holding some complete
  save -- the one before, or the new one -- never a half-written or empty file; a
  temporary it leaves behind is never read, and the next successful save removes it.
  A kill while the lock is held does not block later saves (the kernel drops the lock).
* Several processes adding and saving scores at the same time lose nothing: afterwards
  the file holds exactly the best ``MAX`` of everything they all added.

The child processes run ``tests/game/scores_child.py``. Nothing here is timed: the only
time limits are generous guards against a hang (a stuck lock would otherwise hang pytest).
"""

from __future__ import annotations

import importlib.util
import json
import os
import random
import re
import selectors
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from broadsword.game.scores import Entry, HighScores

pytestmark = pytest.mark.skipif(
    os.name != "posix" or not hasattr(signal, "SIGKILL"), reason="needs POSIX processes and SIGKILL"
)

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
CHILD = HERE / "scores_child.py"
_spec = importlib.util.spec_from_file_location("scores_child", CHILD)
child_mod = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(child_mod)

DAY, LEVEL = child_mod.DAY, child_mod.LEVEL
LOCK = "highscores.json.lock"
TEMP_RE = re.compile(r"^\.highscores\.json\..+\.tmp$")
HANG_GUARD = 120.0  # seconds: only ever reached if something is stuck


def spawn(*args: str, stdin=subprocess.DEVNULL) -> subprocess.Popen:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT)] + [p for p in [env.get("PYTHONPATH")] if p])
    return subprocess.Popen(
        [sys.executable, str(CHILD), *args],
        env=env,
        stdin=stdin,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def read_line(proc: subprocess.Popen) -> str:
    """The child's next stdout line ('' at EOF); fails instead of hanging forever."""
    with selectors.DefaultSelector() as sel:
        sel.register(proc.stdout, selectors.EVENT_READ)
        if not sel.select(HANG_GUARD):
            proc.kill()
            pytest.fail(f"child printed nothing for {HANG_GUARD} s: {proc.args}")
    return proc.stdout.readline()


def finish(proc: subprocess.Popen) -> tuple[int, str, str]:
    out, err = proc.communicate(timeout=HANG_GUARD)
    return proc.returncode, out, err


def temps(directory: Path) -> list[str]:
    return sorted(p.name for p in directory.iterdir() if TEMP_RE.match(p.name))


def others(directory: Path) -> list[str]:
    """Everything but the table, its lock and write_atomic temporaries (e.g. corrupt-*)."""
    return sorted(
        p.name for p in directory.iterdir() if p.name not in ("highscores.json", LOCK) and not TEMP_RE.match(p.name)
    )


def grown(k: int) -> list[Entry]:
    """The table ``grow`` writes on reaching best score ``k``: P<k> ... down to k-9 (>= 1)."""
    return [Entry(f"P{s}", s, LEVEL, DAY) for s in range(k, max(k - HighScores.MAX, 0), -1)]


# --------------------------------------------------------------------------- kills


def test_kill__at_random_moments_file_is_always_a_complete_save(tmp_path):
    """30 children each continue the table, saving in a tight loop, and are SIGKILLed at a
    varied moment after their first save. After every kill the file loads without a
    warning and is exactly some save's table, further on than before the child started
    (so it is never empty, never rolled back). Leftover temporaries are ignored by load
    and removed by the next save."""
    path = tmp_path / "highscores.json"
    rng = random.Random(6)
    k = 0
    leftovers = 0
    for i in range(30):
        proc = spawn("grow", str(path))
        line = read_line(proc)
        if line != "saved\n":
            rc, out, err = finish(proc)
            pytest.fail(f"child {i} did not save (rc={rc}): {line!r}{out!r}\n{err}")
        time.sleep(rng.choice([0.0, rng.uniform(0.0, 0.002), rng.uniform(0.0, 0.02)]))
        proc.kill()
        rc, _, err = finish(proc)
        assert rc == -signal.SIGKILL, err  # killed, not crashed
        table = HighScores(path).load()
        assert table.warning is None, table.warning
        assert table.entries, "file empty or missing after a completed save"
        new_k = table.entries[0].score
        assert table.entries == grown(new_k)
        assert new_k > k  # the child saved at least once and nothing was rolled back
        k = new_k
        assert others(tmp_path) == []  # nothing was set aside as corrupt
        leftovers = max(leftovers, len(temps(tmp_path)))
    # the next save (by anyone) keeps the table and sweeps up whatever temporaries remain
    table = HighScores(path).load()
    table.save()
    assert HighScores(path).load().entries == grown(k)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["highscores.json", LOCK]


OLD = [Entry(f"O{s}", s, LEVEL, DAY) for s in (30, 20, 10)]
NEW = Entry("NEW", 999, LEVEL, DAY)
BEFORE_REPLACE = ["locked", "read", "mkstemp", "partial-write", "fsync", "replace"]
AFTER_REPLACE = ["replaced", "cleanup"]
LEAVES_TEMP = {"mkstemp", "partial-write", "fsync", "replace"}


def test_kill_points__cover_every_point_the_child_knows():
    assert sorted(BEFORE_REPLACE + AFTER_REPLACE) == sorted(child_mod.POINTS)


@pytest.mark.parametrize("point", BEFORE_REPLACE + AFTER_REPLACE)
def test_kill_at_each_point_of_a_save(tmp_path, point):
    """A child adds NEW and SIGKILLs itself at ``point`` of its save. Before the rename
    the file is byte-for-byte the old save; from the rename on it is the new one. A
    temporary is left exactly when the kill fell between creating and renaming it; it
    never affects loading, and the next save removes it (and is not blocked by a lock the
    dead child held)."""
    path = tmp_path / "highscores.json"
    table = HighScores(path)
    for e in OLD:
        table.add(e)
    table.save()
    before = path.read_bytes()

    rc, out, err = finish(spawn("die-at", point, str(path), str(NEW.score)))
    assert rc == -signal.SIGKILL, f"rc={rc} (3: {point!r} never reached)\n{err}"

    loaded = HighScores(path).load()
    assert loaded.warning is None
    if point in BEFORE_REPLACE:
        assert path.read_bytes() == before
        assert loaded.entries == OLD
    else:
        assert loaded.entries == [NEW] + OLD
    left = temps(tmp_path)
    assert len(left) == (1 if point in LEAVES_TEMP else 0), left
    if point == "partial-write":
        elsewhere = HighScores(tmp_path / "elsewhere" / "highscores.json")
        for e in OLD + [NEW]:
            elsewhere.add(e)
        elsewhere.save()
        full = elsewhere.path.read_bytes()
        (tmp_path / "elsewhere" / LOCK).unlink()
        (tmp_path / "elsewhere" / "highscores.json").unlink()
        (tmp_path / "elsewhere").rmdir()
        half = (tmp_path / left[0]).read_bytes()
        assert len(half) == len(full) // 2 > 0 and full.startswith(half)
        with pytest.raises(json.JSONDecodeError):
            json.loads(half)  # genuinely half a file, and load() above never looked at it
    assert others(tmp_path) == []

    later = Entry("LATER", 5, LEVEL, DAY)
    loaded.add(later)
    loaded.save()
    expected = ([NEW] if point in AFTER_REPLACE else []) + OLD + [later]
    assert HighScores(path).load().entries == expected
    assert sorted(p.name for p in tmp_path.iterdir()) == ["highscores.json", LOCK]


# --------------------------------------------------------------------------- concurrency


@pytest.mark.parametrize("workers,per_worker", [(2, 40), (4, 20)])
def test_concurrent_writers__no_lost_update(tmp_path, workers, per_worker):
    """``workers`` processes start together (each loaded the same table first) and each adds
    and saves ``per_worker`` distinct scores in a shuffled order. Afterwards the file holds
    exactly the best MAX of all of them and the seed entry they all loaded, in order, each
    once."""
    path = tmp_path / "highscores.json"
    seed = Entry("SEED", workers * per_worker + 5, LEVEL, DAY)  # loaded by all: kept once
    seed_table = HighScores(path)
    seed_table.add(seed)
    seed_table.save()
    everything = [seed]
    procs = []
    for w in range(workers):
        mine = [w + workers * i for i in range(per_worker)]
        everything += [Entry(f"W{w}-{s}", s, LEVEL, DAY) for s in mine]
        procs.append(spawn("writer", str(path), str(w), str(100 + w), *map(str, mine), stdin=subprocess.PIPE))
    for p in procs:
        assert read_line(p) == "ready\n", p.stderr.read()
    for p in procs:  # release them as close together as we can
        p.stdin.write("go\n")
        p.stdin.flush()
    for p in procs:
        rc, out, err = finish(p)
        assert (rc, out) == (0, "done\n"), err

    # the oracle: all scores are distinct, so "best MAX" is unambiguous
    expected = sorted(everything, key=lambda e: -e.score)[: HighScores.MAX]
    table = HighScores(path).load()
    assert table.warning is None
    assert table.entries == expected
    assert sorted(p.name for p in tmp_path.iterdir()) == ["highscores.json", LOCK]
