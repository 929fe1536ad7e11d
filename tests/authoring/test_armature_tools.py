"""``armature generate|check`` logic, driven with alpha channels from numpy (no image library)."""

from __future__ import annotations

import io
import subprocess
import sys

import numpy as np

from broadsword.authoring.armature_tools import check, generate, strip_warning
from broadsword.data import DataError, data_dir, load_armature_file
from broadsword.data.armatures import save_armature_file


def reader(images: dict[str, np.ndarray]):
    """A ``read_alpha`` over in-memory images, by file name; a missing one is a DataError."""

    def read(path):
        if path.name not in images:
            raise DataError(path, "", "cannot load image: no such file")
        return images[path.name]

    return read


def ship(h=20, w=16):
    a = np.zeros((h, w), dtype=np.uint8)
    a[3:17, 4:12] = 255
    a[8:14, 1:15] = 255  # wings
    return a


def test_generate__one_frame_writes_the_file_and_its_fit(tmp_path):
    sprite = tmp_path / "ship.png"
    made = generate(sprite, reader({"ship.png": ship()}), max_vertices=12)
    f = load_armature_file(tmp_path / "ship.armature.toml")
    assert made.file.drawn == f.drawn and f.sprite == "ship.png" and len(f.frames) == 1
    assert made.fits[0].iou == 1.0 and made.strip is None  # 12 corners trace the cross exactly


def test_generate__a_strip_without_frames_is_traced_whole_with_a_warning(tmp_path):
    sprite = tmp_path / "anim.png"
    strip = np.concatenate([ship(), ship()], axis=1)
    made = generate(sprite, reader({"anim.png": strip}))
    assert len(made.file.frames) == 1 and made.strip is not None and made.strip.frames == 2
    line = strip_warning(sprite, made.strip)
    assert "anim.png" in line and "strip of 2 frames" in line and "--frames 2" in line
    # Told the frame count, it traces each frame and says nothing.
    (tmp_path / "anim.armature.toml").unlink()
    made = generate(sprite, reader({"anim.png": strip}), frames=2)
    assert len(made.file.frames) == 2 and made.strip is None
    # Told it is one frame, it believes it.
    made = generate(sprite, reader({"anim.png": strip}), out=tmp_path / "one.armature.toml", frames=1)
    assert made.strip is None
    # Without --frames, an existing file's frame count is used.
    made = generate(sprite, reader({"anim.png": strip}), shape="graze", max_vertices=6)
    assert len(made.file.frames) == 2 and made.file.shape_names == ("hit", "graze") and made.strip is None


def test_check__a_one_frame_file_over_a_strip_is_invalid_naming_file_and_why(tmp_path):
    strip = np.concatenate([ship(), ship()], axis=1)
    save_armature_file(tmp_path / "anim.armature.toml", "anim", "anim.png", [{"hit": [(-8, -8), (8, -8), (0, 8)]}])
    save_armature_file(tmp_path / "ok.armature.toml", "ok", "ok.png", [{"hit": [(-4, -4), (4, -4), (0, 4)]}])
    for name in ("anim.png", "ok.png"):
        (tmp_path / name).write_bytes(b"")  # there: the reader supplies the pixels
    out = io.StringIO()
    assert check([str(tmp_path)], reader({"anim.png": strip, "ok.png": ship()}), out) == 1
    text = out.getvalue()
    line = next(x for x in text.splitlines() if x.startswith("anim.armature.toml"))
    assert (
        "error:" in line
        and "anim.armature.toml: frames: one frame, but anim.png looks like a strip of 2 frames" in line
    )
    assert "give frames = 2" in line and "2 file(s), 1 invalid" in text


def test_check__the_shipped_files_pass_with_any_reader():
    """The shipped two-frame wasp declares its frames, so it is not flagged."""
    folder = data_dir("assets") / "sprites"
    wasp = load_armature_file(folder / "wasp.armature.toml")
    assert len(wasp.frames) == 2
    from broadsword.authoring.png import read_png_header

    def blank_reader(path):  # every sprite a solid block of its real size: only the frames rule can fail
        h = read_png_header(path)
        return np.full((h.height, h.width), 255, dtype=np.uint8)

    out = io.StringIO()
    assert check([], blank_reader, out) == 0, out.getvalue()


def test_authoring_never_imports_pygame():
    code = (
        "import sys; sys.modules['pygame'] = None\n"
        "import pkgutil, importlib, broadsword.authoring as a\n"
        "for m in pkgutil.walk_packages(a.__path__, 'broadsword.authoring.'):\n"
        "    importlib.import_module(m.name)\n"
        "print('ok')"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr
