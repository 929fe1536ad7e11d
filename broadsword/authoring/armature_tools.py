"""``broadsword armature generate|check`` without the window: make armature files from
sprites, and report on them. The image is read by a function the caller passes
(``read_alpha(path) -> (H, W) uint8``, the whole image's alpha channel, raising
:class:`~broadsword.data.DataError`), so this module never imports an image library.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TextIO

import numpy as np

from ..data import ArmatureFile, DataError, data_dir, load_armature_file
from ..data.armatures import SUFFIX, save_armature_file
from .fit import ShapeFit, fit_of
from .frames import StripGuess, detect_frames, split_frames
from .masks import opaque_mask
from .outline import generate_armature

__all__ = ["AlphaReader", "Generated", "check", "generate", "strip_warning"]

#: Reads an image file: ``read_alpha(path) -> (H, W) uint8`` alpha, or :class:`DataError`.
AlphaReader = Callable[[Path], np.ndarray]


@dataclass(frozen=True)
class Generated:
    """What :func:`generate` wrote: the file as loaded back, each frame's fit of the shape,
    and ``strip``: the image looks like a strip of several frames though it was traced as one
    (None otherwise)."""

    file: ArmatureFile
    fits: tuple[ShapeFit, ...]
    strip: StripGuess | None


def strip_warning(sprite: Path, guess: StripGuess) -> str:
    """One line: ``sprite`` was traced as one frame but looks like ``guess``."""
    return (
        f"{sprite}: traced as one frame, but it looks like a strip of {guess.frames} frames "
        f"({guess.reason}); if it is, give --frames {guess.frames}"
    )


def generate(
    sprite: str | Path,
    read_alpha: AlphaReader,
    max_vertices: int = 8,
    inset: int = 0,
    shape: str = "hit",
    out: str | Path | None = None,
    frames: int | None = None,
) -> Generated:
    """Trace the ``shape`` of ``sprite`` (every frame) and write it into its armature file
    (``out``, default ``<stem>.armature.toml`` beside the sprite), keeping the file's other
    shapes and its header. A new file gets the shape as its ``hit`` too if ``shape`` is not
    ``hit``. ``frames``: the sprite is a strip of that many frames; None: as many as the
    existing file has, else 1, and then :func:`detect_frames` may find it looks like a strip
    (``Generated.strip``)."""
    sprite = Path(sprite)
    out = Path(out) if out else sprite.with_name(sprite.stem + SUFFIX)
    alpha = read_alpha(sprite)
    old = load_armature_file(out) if out.exists() else None
    given = frames is not None
    count: int = frames if frames is not None else len(old.drawn) if old is not None else 1
    alphas = split_frames(alpha, count, sprite)
    made: list[tuple[tuple[float, float], ...]] = []
    for i, a in enumerate(alphas):
        try:
            arm = generate_armature(opaque_mask(a), max_vertices, inset, name=f"{sprite.stem}.{shape}")
        except ValueError as exc:
            raise DataError(sprite, f"frame[{i}]" if count > 1 else "", str(exc)) from None
        made.append(tuple((x, y) for x, y in arm.vertices.tolist()))  # clockwise on screen, as the shipped files
    if old is not None:
        if len(old.drawn) != count:
            raise DataError(out, "frames", f"has {len(old.drawn)} frames; --frames {count} was asked for")
        sets = [dict(d) for d in old.drawn]
        name, header, frame_time, sprite_name = old.name, old.header, old.frame_time, old.sprite
    else:
        sets = [{} for _ in range(count)]
        name, header, frame_time, sprite_name = sprite.stem, "", 0.1, sprite.name
    for s, pts in zip(sets, made, strict=True):
        s[shape] = pts
        s.setdefault("hit", pts)
    f = save_armature_file(out, name, sprite_name, sets, frame_time, header)
    fits = tuple(fit_of(shapes[shape].vertices, a) for shapes, a in zip(f.frames, alphas, strict=True))
    strip = detect_frames(alpha) if count == 1 and not given else None
    return Generated(f, fits, strip)


# ---------------------------------------------------------------------- check
def _armature_files(paths: list[str]) -> list[Path]:
    if not paths:
        paths = [str(data_dir("assets") / "sprites")]
    files: list[Path] = []
    for p in map(Path, paths):
        if p.is_dir():
            files += sorted(p.rglob(f"*{SUFFIX}"))
        else:
            files.append(p)
    return files


def _load_checked(path: Path, read_alpha: AlphaReader) -> tuple[ArmatureFile, list[np.ndarray]]:
    """The file and its frames' alpha, or :class:`DataError` naming what is wrong, a
    one-frame file over an image that looks like a strip of separated frames included."""
    f = load_armature_file(path)
    image = path.parent / f.sprite
    if not image.is_file():
        raise DataError(path, "sprite", f"no image {f.sprite} beside it")
    alpha = read_alpha(image)
    alphas = split_frames(alpha, len(f.frames), path)
    if len(f.frames) == 1:
        guess = detect_frames(alpha)
        if guess is not None and guess.separated:
            raise DataError(
                path,
                "frames",
                f"one frame, but {f.sprite} looks like a strip of {guess.frames} frames "
                f"({guess.reason}): give frames = {guess.frames} and a [[frame]] each",
            )
    return f, alphas


def check(paths: list[str], read_alpha: AlphaReader, out: TextIO | None = None) -> int:
    """Print (to ``out``, default stdout) a report line per shape and frame of every
    armature file under ``paths`` (default: the shipped sprites); return the number of
    invalid files (each gets one ``error:`` line naming the file, the field and why)."""
    out = out or sys.stdout
    files = _armature_files(paths)
    bad = 0
    print(
        f"{'file':34s} {'shape':14s} {'verts':>5s} {'valid':>5s} {'area':>8s} {'on_opaque':>9s} "
        f"{'coverage':>8s} {'iou':>6s}",
        file=out,
    )
    for path in files:
        try:
            f, alphas = _load_checked(path, read_alpha)
        except DataError as exc:
            bad += 1
            print(f"{path.name:34s} {'-':14s} {'-':>5s} {'no':>5s}   error: {exc}", file=out)
            continue
        for i, shapes in enumerate(f.frames):
            for key, arm in shapes.items():
                fit = fit_of(arm.vertices, alphas[i])
                label = key if len(f.frames) == 1 else f"{key}[{i}]"
                print(
                    f"{path.name:34s} {label:14s} {len(arm):5d} {'yes':>5s} {arm.area:8.1f} {fit.on_opaque:9.3f} "
                    f"{fit.coverage:8.3f} {fit.iou:6.3f}",
                    file=out,
                )
    print(f"{len(files)} file(s), {bad} invalid", file=out)
    return bad
