"""broadsword.fileio: bounded reads of regular files only, destinations checked before a
long run, and atomic writes that never replace anything but a regular file (issue 25)."""

from __future__ import annotations

import os

import pytest

from broadsword.fileio import (
    FileTooLarge,
    NotRegularFile,
    check_writable,
    read_capped,
    read_head,
    write_atomic,
)


def test_read_capped__a_regular_file_up_to_the_cap(tmp_path):
    path = tmp_path / "f"
    path.write_bytes(b"x" * 10)
    assert read_capped(path, 10) == b"x" * 10
    assert read_head(path, 3) == b"xxx"
    with pytest.raises(FileTooLarge) as info:
        read_capped(path, 9)
    assert info.value.size == 10 and info.value.exact


def test_read_capped__a_size_that_lies_is_caught_by_the_read():
    with pytest.raises(FileTooLarge) as info:  # /proc files say 0 bytes
        read_capped("/proc/self/maps", 16)
    assert info.value.size == 17 and not info.value.exact


@pytest.mark.parametrize("kind, words", [("fifo", "a FIFO"), ("zero", "a character device"), ("dir", "a directory")])
def test_read_capped__refuses_what_is_not_a_regular_file_without_blocking(tmp_path, kind, words):
    path = tmp_path / "f"
    if kind == "fifo":
        os.mkfifo(path)  # no writer: a plain open would block forever
    elif kind == "zero":
        path.symlink_to("/dev/zero")  # a plain read would never end
    else:
        path.mkdir()
    for read in (lambda: read_capped(path, 1 << 20), lambda: read_head(path, 33)):
        with pytest.raises(NotRegularFile, match=f"{words}, not a regular file"):
            read()


def test_read_capped__a_symlink_loop_is_an_oserror(tmp_path):
    loop = tmp_path / "loop"
    loop.symlink_to(loop)
    with pytest.raises(OSError):
        read_capped(loop, 100)


def test_check_writable__says_why_not_before_the_run(tmp_path):
    (tmp_path / "file").write_text("x")
    os.mkfifo(tmp_path / "fifo")
    (tmp_path / "null").symlink_to("/dev/null")
    assert check_writable(tmp_path / "new" / "run.json") is None  # a directory it can make
    assert check_writable(tmp_path / "file") is None  # a regular file: replaced
    assert check_writable("") == "an empty path"
    assert "a directory" in (check_writable(tmp_path) or "")
    assert "a FIFO" in (check_writable(tmp_path / "fifo") or "")
    assert "a character device" in (check_writable(tmp_path / "null") or "")
    assert check_writable(tmp_path / "file" / "d" / "run.json") == f"{tmp_path / 'file'} is a file, not a folder"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fifo", "file", "new", "null"]  # nothing left over


def test_check_writable__a_read_only_directory(tmp_path, monkeypatch):
    import tempfile

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(tempfile, "mkstemp", refuse)  # root writes anywhere: emulate read-only
    assert check_writable(tmp_path / "run.json") == "cannot write there (Permission denied)"


def test_write_atomic__never_replaces_a_device_node_or_fifo(tmp_path):
    null = tmp_path / "null"
    null.symlink_to("/dev/null")
    os.mkfifo(tmp_path / "fifo")
    for path in (null, tmp_path / "fifo"):
        with pytest.raises(NotRegularFile, match="only a regular file is ever replaced"):
            write_atomic(path, b"data")
    assert null.is_symlink() and os.readlink(null) == "/dev/null"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fifo", "null"]
