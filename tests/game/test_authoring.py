"""``broadsword armature generate|check`` as a designer runs them."""

from __future__ import annotations

import shutil

import numpy as np
import pygame
import pytest

from broadsword.cli import main
from broadsword.data import data_dir, load_armature_file
from broadsword.game.authoring import check, sprite_alpha

SPRITES = data_dir("assets") / "sprites"


def copy_sprite(tmp_path, name):
    shutil.copy(SPRITES / f"{name}.png", tmp_path / f"{name}.png")
    return tmp_path / f"{name}.png"


def test_generate__writes_a_valid_file_beside_the_sprite(tmp_path, capsys):
    png = copy_sprite(tmp_path, "gunship")
    assert main(["armature", "generate", str(png), "--max-vertices", "8", "--inset", "2"]) == 0
    out = capsys.readouterr().out
    f = load_armature_file(tmp_path / "gunship.armature.toml")
    assert f.sprite == "gunship.png" and f.shape_names == ("hit",)
    assert 3 <= len(f.armature) <= 8 and "8 vertices" in out and "IoU" in out
    assert list(f.drawn[0]["hit"]) == [tuple(v) for v in f.armature.vertices.tolist()]  # drawn as stored


def test_generate__adds_a_graze_shape_and_keeps_the_hit_shape(tmp_path, capsys):
    png = copy_sprite(tmp_path, "player")
    target = tmp_path / "player.armature.toml"
    shutil.copy(SPRITES / "player.armature.toml", target)
    before = load_armature_file(target)
    assert main(["armature", "generate", str(png), "--shape", "graze", "--inset", "-4", "--max-vertices", "10"]) == 0
    after = load_armature_file(target)
    assert after.drawn[0]["hit"] == before.drawn[0]["hit"] and after.header == before.header
    assert after.graze.area > before.graze.area * 0.5 and len(after.graze) <= 10
    assert target.read_text().startswith("# Armatures of player.png")


def test_generate__a_strip_gets_one_shape_per_frame(tmp_path, capsys):
    a = pygame.image.load(str(SPRITES / "scout.png"))
    b = pygame.image.load(str(SPRITES / "wasp.png"))
    strip = pygame.Surface((48, 28), pygame.SRCALPHA)
    strip.blit(a, (0, 2))
    strip.blit(b, (24, 0), pygame.Rect(2, 0, 24, 28))
    pygame.image.save(strip, str(tmp_path / "anim.png"))
    assert main(["armature", "generate", str(tmp_path / "anim.png"), "--frames", "2", "--max-vertices", "12"]) == 0
    f = load_armature_file(tmp_path / "anim.armature.toml")
    assert len(f.frames) == 2 and f.frames[0]["hit"].vertices.tolist() != f.frames[1]["hit"].vertices.tolist()
    assert [a.shape for a in sprite_alpha(tmp_path / "anim.png", 2)] == [(28, 24), (28, 24)]
    assert main(["armature", "generate", str(tmp_path / "anim.png"), "--frames", "5"]) == 2
    assert "equal frames" in capsys.readouterr().err


def test_generate__errors_are_one_line_exit_2(tmp_path, capsys):
    blank = pygame.Surface((8, 8), pygame.SRCALPHA)
    pygame.image.save(blank, str(tmp_path / "blank.png"))
    assert main(["armature", "generate", str(tmp_path / "blank.png")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "blank.png" in err and "no opaque pixels" in err
    assert main(["armature", "generate", str(tmp_path / "missing.png")]) == 2
    assert "cannot load image" in capsys.readouterr().err
    assert not list(tmp_path.glob("*.toml"))


def test_check__the_shipped_armatures_are_valid(capsys):
    assert main(["armature", "check"]) == 0
    out = capsys.readouterr().out
    rows = [line.split() for line in out.splitlines()[1:-1]]
    assert {r[0] for r in rows} == {p.name for p in SPRITES.glob("*.armature.toml")}
    player_hit = next(r for r in rows if r[0] == "player.armature.toml" and r[1] == "hit")
    verts, valid, area, on_opaque, coverage, iou = player_hit[2:]
    assert valid == "yes" and int(verts) == 9 and float(on_opaque) == 1.0 and float(coverage) < 0.2


def test_check__an_invalid_file_is_named_and_fails(tmp_path, capsys):
    copy_sprite(tmp_path, "scout")
    shutil.copy(SPRITES / "scout.armature.toml", tmp_path / "scout.armature.toml")
    (tmp_path / "bad.armature.toml").write_text(
        'sprite = "scout.png"\n[shapes]\nhit = [[0, 0], [4, 4], [4, 0], [0, 4]]\n'
    )
    (tmp_path / "orphan.armature.toml").write_text("[shapes]\nhit = [[0, 0], [4, 0], [0, 4]]\n")
    assert main(["armature", "check", str(tmp_path)]) == 1
    out, err = capsys.readouterr()
    assert "bad.armature.toml: shapes.hit:" in out and "meets edge" in out
    assert "orphan.armature.toml: sprite: no image orphan.png" in out
    assert "3 file(s), 2 invalid" in out and "2 invalid file(s)" in err


def test_check__coverage_and_iou_are_the_pixel_counts():
    """A shape that is exactly the sprite's opaque square has coverage and IoU 1."""
    import io
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as d:
        surf = pygame.Surface((10, 10), pygame.SRCALPHA)
        surf.fill((255, 255, 255, 255), pygame.Rect(2, 2, 6, 6))
        pygame.image.save(surf, str(Path(d) / "sq.png"))
        (Path(d) / "sq.armature.toml").write_text(
            "[shapes]\nhit = [[-3, -3], [3, -3], [3, 3], [-3, 3]]\nhalf = [[-3, -3], [0, -3], [0, 3], [-3, 3]]\n"
        )
        buf = io.StringIO()
        assert check([d], out=buf) == 0
        rows = {r.split()[1]: r.split()[2:] for r in buf.getvalue().splitlines()[1:-1]}
        assert rows["hit"] == ["4", "yes", "36.0", "1.000", "1.000", "1.000"]
        assert rows["half"] == ["4", "yes", "18.0", "1.000", "0.500", "0.500"]


@pytest.mark.parametrize("name", ["scout", "boss_wing", "lancer"])
def test_generate__shipped_sprites_fit_well(tmp_path, name, capsys):
    """Generation is a good start: 12 vertices with no inset cover most of a ship."""
    png = copy_sprite(tmp_path, name)
    assert main(["armature", "generate", str(png), "--max-vertices", "12"]) == 0
    f = load_armature_file(tmp_path / f"{name}.armature.toml")
    from broadsword.game.authoring import fit_of

    fit = fit_of(f.armature.vertices, sprite_alpha(png)[0])
    assert fit.iou > 0.8, fit
    assert np.isfinite(f.armature.area)


def test_generate__a_strip_without_frames_warns_and_check_flags_the_file(tmp_path, capsys):
    """The shipped wasp is a strip of 2 frames: traced as one, the tool says so, and check fails."""
    png = copy_sprite(tmp_path, "wasp")
    assert main(["armature", "generate", str(png)]) == 0
    out, err = capsys.readouterr()
    assert err.count("\n") == 1 and err.startswith("broadsword: warning: ") and "wasp.png" in err
    assert "strip of 2 frames" in err and "--frames 2" in err
    assert len(load_armature_file(tmp_path / "wasp.armature.toml").frames) == 1
    assert main(["armature", "check", str(tmp_path)]) == 1
    out, err = capsys.readouterr()
    assert "wasp.armature.toml: frames: one frame, but wasp.png looks like a strip of 2 frames" in out
    assert "1 invalid file(s)" in err
    # With --frames 2 (the file is replaced), no warning and check passes.
    (tmp_path / "wasp.armature.toml").unlink()
    assert main(["armature", "generate", str(png), "--frames", "2"]) == 0
    assert capsys.readouterr().err == ""
    assert main(["armature", "check", str(tmp_path)]) == 0


def write_png_bytes(path, data: bytes):
    path.write_bytes(data)
    return path


def zero_png(path):
    import struct
    import zlib

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    return write_png_bytes(
        path,
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", struct.pack(">IIBBBBB", 0, 0, 8, 6, 0, 0, 0))
        + chunk(b"IDAT", zlib.compress(b""))
        + chunk(b"IEND", b""),
    )


@pytest.mark.parametrize("kind", ["zero", "garbage", "truncated"])
def test_generate__a_broken_png_prints_only_our_line(tmp_path, capfd, kind):
    """Checked at the file descriptor: libpng's own lines never reach standard error."""
    path = tmp_path / "bad.png"
    if kind == "zero":
        zero_png(path)
    elif kind == "garbage":
        write_png_bytes(path, b"\x89PNG\r\n\x1a\n" + b"garbage" * 10)
    else:  # a real sprite cut short: the header is fine, the image data is not
        write_png_bytes(path, (SPRITES / "scout.png").read_bytes()[:80])
    assert main(["armature", "generate", str(path)]) == 2
    out, err = capfd.readouterr()
    assert err.count("\n") == 1 and err.startswith(f"broadsword: {path}: cannot load image: "), err
    assert "libpng" not in err.split("cannot load image")[0]
