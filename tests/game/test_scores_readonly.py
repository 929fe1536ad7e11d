"""High scores in a data directory that cannot be written: warn, keep playing, lose nothing.

Rules under test:

* ``load`` works in a read-only directory (no warning for a good file); a corrupt file that
  cannot be moved aside gives a one-line warning and an empty table, never an exception.
* ``save`` raises OSError -- errno kept (EROFS / EACCES / ENOTDIR...), the high-score file
  named -- and changes nothing on disk: no temporary, no lock file, no directory created.
  ``entries`` keeps the new score, and a save once the directory is writable writes it.
* The game catches that OSError, shows ``could not save high scores: ...`` and plays on.

Tests run as root on CI, where chmod does not stop writes, so the main tests use a
read-only *mount* emulated in-process (``read_only`` below: every call that would create,
rename, replace or delete under the directory fails with EROFS, as the kernel does); a
real ``chmod`` test runs when not root, and a data path under a regular file needs no
emulation at all.
"""

from __future__ import annotations

import builtins
import errno
import io
import os
from pathlib import Path

import pygame
import pytest
from score_rows import entry

from broadsword.game.scores import Entry, HighScores

LOCK = "highscores.json.lock"
EROFS = errno.EROFS
_WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_TRUNC | os.O_APPEND


def tree(directory: Path) -> dict[str, bytes | None]:
    """Every path under ``directory`` with its bytes (None for a directory)."""
    return {
        str(p.relative_to(directory)): (None if p.is_dir() else p.read_bytes()) for p in sorted(directory.rglob("*"))
    }


class ReadOnlyMount:
    """Make paths under ``roots`` behave as on a read-only filesystem, for root too.

    ``open``/``io.open`` in a writing mode, ``os.open`` with any write/create flag,
    ``os.mkdir``, ``os.rename``, ``os.replace``, ``os.unlink``/``os.remove`` and
    ``os.rmdir`` raise ``OSError(EROFS)`` for such paths (tempfile.mkstemp and pathlib go
    through these); reading is untouched.
    """

    def __init__(self, monkeypatch):
        self.roots: list[str] = []
        self.refused: list[str] = []
        real = {name: getattr(os, name) for name in ("open", "mkdir", "rename", "replace", "unlink", "remove", "rmdir")}
        real_io_open = io.open

        def guard(name, *paths):
            for p in paths:
                if isinstance(p, (str, bytes, os.PathLike)) and self.covers(p):
                    self.refused.append(f"{name} {os.fspath(p)}")
                    raise OSError(EROFS, os.strerror(EROFS), os.fspath(p))

        def fake_open(path, flags, *args, **kwargs):
            if flags & _WRITE_FLAGS:
                guard("open", path)
            return real["open"](path, flags, *args, **kwargs)

        def one(name):
            def fake(path, *args, **kwargs):
                guard(name, path)
                return real[name](path, *args, **kwargs)

            return fake

        def two(name):
            def fake(src, dst, *args, **kwargs):
                guard(name, src, dst)
                return real[name](src, dst, *args, **kwargs)

            return fake

        def fake_io_open(file, mode="r", *args, **kwargs):
            if any(c in mode for c in "wax+"):
                guard("open", file)
            return real_io_open(file, mode, *args, **kwargs)

        monkeypatch.setattr(os, "open", fake_open)
        monkeypatch.setattr(io, "open", fake_io_open)
        monkeypatch.setattr(builtins, "open", fake_io_open)
        for name in ("mkdir", "unlink", "remove", "rmdir"):
            monkeypatch.setattr(os, name, one(name))
        for name in ("rename", "replace"):
            monkeypatch.setattr(os, name, two(name))

    def covers(self, path) -> bool:
        p = os.path.abspath(os.fsdecode(os.fspath(path)))
        return any(p == r or p.startswith(r + os.sep) for r in self.roots)

    def mount(self, root: Path) -> None:
        self.roots.append(os.path.abspath(root))

    def unmount(self) -> None:
        self.roots.clear()


@pytest.fixture
def read_only(monkeypatch):
    return ReadOnlyMount(monkeypatch)


def test_read_only_mount__refuses_writes_like_the_kernel(tmp_path, read_only):
    """The emulation itself: writes refused with EROFS, reads fine, outside untouched."""
    (tmp_path / "ro").mkdir()
    (tmp_path / "ro" / "f").write_bytes(b"x")
    read_only.mount(tmp_path / "ro")
    assert (tmp_path / "ro" / "f").read_bytes() == b"x"
    for attempt in (
        lambda: (tmp_path / "ro" / "g").write_bytes(b"y"),  # builtin open
        lambda: os.open(tmp_path / "ro" / "g", os.O_RDWR | os.O_CREAT),
        lambda: (tmp_path / "ro" / "d").mkdir(),
        lambda: os.replace(tmp_path / "ro" / "f", tmp_path / "ro" / "h"),
        lambda: (tmp_path / "ro" / "f").unlink(),
    ):
        with pytest.raises(OSError) as info:
            attempt()
        assert info.value.errno == EROFS
    (tmp_path / "rw").write_bytes(b"ok")
    assert tree(tmp_path / "ro") == {"f": b"x"}


# --------------------------------------------------------------------------- load and save


def saved(path: Path, *entries: Entry) -> bytes:
    table = HighScores(path)
    for e in entries:
        table.add(e)
    table.save()
    return path.read_bytes()


@pytest.mark.parametrize("with_lock_file", [True, False])
def test_read_only__load_works_save_fails_cleanly_and_scores_stay_in_memory(tmp_path, read_only, with_lock_file):
    path = tmp_path / "highscores.json"
    before = saved(path, entry("OLD", 50))
    if not with_lock_file:  # e.g. a table copied in by hand, never saved by the game here
        (tmp_path / LOCK).unlink()
    files = tree(tmp_path)
    read_only.mount(tmp_path)

    table = HighScores(path).load()
    assert table.warning is None and table.entries == [entry("OLD", 50)]
    assert table.add(entry("NEW", 70)) == 0
    with pytest.raises(OSError) as info:
        table.save()
    assert info.value.errno == EROFS and info.value.filename == str(path)
    assert "Read-only file system" in str(info.value) and str(path) in str(info.value)
    assert read_only.refused  # the save really tried, and was refused
    assert tree(tmp_path) == files and path.read_bytes() == before
    assert table.entries == [entry("NEW", 70), entry("OLD", 50)]  # still shown this session
    table.add(entry("MORE", 60))
    with pytest.raises(OSError):
        table.save()
    assert tree(tmp_path) == files

    read_only.unmount()  # remounted read-write: the next save writes everything, once
    table.save()
    assert HighScores(path).load().entries == [entry("NEW", 70), entry("MORE", 60), entry("OLD", 50)]


def test_read_only__data_directory_that_does_not_exist_yet(tmp_path, read_only):
    path = tmp_path / "share" / "broadsword" / "highscores.json"
    read_only.mount(tmp_path)
    table = HighScores(path).load()
    assert table.entries == [] and table.warning is None
    table.add(entry())
    with pytest.raises(OSError) as info:
        table.save()
    assert info.value.errno == EROFS and info.value.filename == str(path)
    assert f"(at {tmp_path / 'share'}" in str(info.value)  # which directory could not be made
    assert tree(tmp_path) == {}
    assert table.entries == [entry()]


def test_read_only__corrupt_file_warns_and_is_left_alone(tmp_path, read_only):
    path = tmp_path / "highscores.json"
    path.write_bytes(b"{not json")
    read_only.mount(tmp_path)
    table = HighScores(path).load()
    assert table.entries == []
    assert table.warning is not None and "\n" not in table.warning
    assert str(path) in table.warning and "could not be moved aside" in table.warning
    table.add(entry())
    with pytest.raises(OSError) as info:
        table.save()
    assert info.value.errno == EROFS
    assert tree(tmp_path) == {"highscores.json": b"{not json"}


@pytest.mark.skipif(
    os.name != "posix" or os.geteuid() == 0, reason="needs POSIX permissions and a non-root user (root ignores chmod)"
)
def test_read_only__real_chmod_555_directory(tmp_path):
    data = tmp_path / "data"
    path = data / "highscores.json"
    before = saved(path, entry("OLD", 50))
    files = tree(data)
    data.chmod(0o555)
    try:
        table = HighScores(path).load()
        assert table.warning is None and table.entries == [entry("OLD", 50)]
        table.add(entry("NEW", 70))
        with pytest.raises(PermissionError) as info:
            table.save()
        assert info.value.filename == str(path)
        assert tree(data) == files and path.read_bytes() == before
        assert table.entries == [entry("NEW", 70), entry("OLD", 50)]
    finally:
        data.chmod(0o755)
    table.save()
    assert HighScores(path).load().entries == [entry("NEW", 70), entry("OLD", 50)]


def test_data_path_under_a_regular_file__warns_and_save_fails(tmp_path):
    """Root-proof without any emulation: the data 'directory' is a regular file."""
    blocker = tmp_path / "broadsword"
    blocker.write_bytes(b"not a directory")
    path = blocker / "highscores.json"
    table = HighScores(path).load()
    assert table.entries == []
    assert table.warning is not None and str(path) in table.warning and "\n" not in table.warning
    table.add(entry())
    with pytest.raises(OSError) as info:
        table.save()
    assert info.value.errno in (errno.ENOTDIR, errno.EEXIST) and info.value.filename == str(path)
    assert f"(at {blocker})" in str(info.value)
    assert tree(tmp_path) == {"broadsword": b"not a directory"}
    assert table.entries == [entry()]


# --------------------------------------------------------------------------- the game plays on


@pytest.fixture
def app_factory():
    from broadsword.game.app import App

    made = []

    def make(**kwargs):
        made.append(App(seed=1, audio=False, **kwargs))
        return made[-1]

    yield make
    pygame.quit()


def test_app__read_only_save_shows_a_message_and_the_game_goes_on(tmp_path, read_only, app_factory):
    path = tmp_path / "highscores.json"
    before = saved(path, entry("OLD", 50))
    read_only.mount(tmp_path)
    app = app_factory(scores=HighScores(path))
    assert app.ctx.message is None and app.ctx.scores.entries == [entry("OLD", 50)]

    from broadsword.game.scenes import HighScoresScene, NameEntry, Play, Title

    entry_screen = NameEntry(app.ctx, 5000, "1-picket")
    app.stack.push(entry_screen)
    entry_screen.name = "ME"
    app.apply(entry_screen.save())  # what Enter on the name screen does
    assert isinstance(app.scene, HighScoresScene)
    assert app.ctx.message.startswith("could not save high scores: ")
    assert "Read-only file system" in app.ctx.message and str(path) in app.ctx.message
    assert [(e.name, e.score) for e in app.ctx.scores.entries] == [("ME", 5000), ("OLD", 50)]
    assert path.read_bytes() == before

    app.frame(0.0)  # the scores screen draws
    pygame.event.post(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_RETURN, mod=0, unicode="\r", scancode=0))
    app.frame(0.0)
    assert isinstance(app.scene, Title)  # the title shows the message
    app.start_run()
    assert isinstance(app.scene, Play)
    app.frame(1 / 60)
    assert isinstance(app.scene, Play) and app.running


def test_app__corrupt_table_on_read_only_disk_is_reported_on_the_title(tmp_path, read_only, app_factory):
    path = tmp_path / "highscores.json"
    path.write_bytes(b"\xff\xfe garbage")
    read_only.mount(tmp_path)
    app = app_factory(scores=HighScores(path))
    assert app.ctx.message is not None and str(path) in app.ctx.message
    assert app.ctx.scores.entries == []
    app.frame(0.0)
    from broadsword.game.scenes import Title

    assert isinstance(app.scene, Title)
    assert path.read_bytes() == b"\xff\xfe garbage"
