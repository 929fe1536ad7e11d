"""Armature kinds: one per sprite and animation frame, packed for the collision pipeline.

A sprite with ``F`` animation frames owns ``F`` consecutive kinds, one hit shape each. An
object stores its sprite's first kind (its *base*); :meth:`Kinds.current` adds the frame it
shows at its age, so the shape collided is always the shape drawn.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ..collision import Armature, ArmatureSet

#: The player's graze shape when its armature file names none: a 40 x 40 px box.
DEFAULT_GRAZE = (40.0, 40.0)
#: Sprites every level has: the player, its shot and the items.
ALWAYS = frozenset({"player", "shot", "item_power", "item_point", "item_star"})
#: Seconds a frame shows when an armature file does not say.
DEFAULT_FRAME_TIME = 0.1


def frame_sets(f) -> list[dict[str, Armature]]:
    """The shape sets of an ArmatureFile (one per animation frame), or of any object with
    ``.armature`` and ``.graze`` (one frame)."""
    frames = getattr(f, "frames", None)
    if frames:
        return list(frames)
    return [{"hit": f.armature} | ({"graze": f.graze} if f.graze is not None else {})]


class Kinds:
    """The armature kinds of a level.

    Parameters
    ----------
    armatures : mapping name -> ArmatureFile
        Every sprite the level names, plus ``player`` and ``shot``.
    names : iterable of str
        The sprites to pack (``player``, ``shot`` and the items are always added). The
        player's graze shape becomes a kind of its own, named ``graze``.
    extra : mapping name -> list of Armature, optional
        Shapes made in code (the bomb's), one kind per entry, as animation frames are.

    Attributes
    ----------
    base : dict name -> int
        First kind of each sprite (and of ``graze``).
    names : list of str
        Sprite name of each kind.
    frame : (K,) int64
        Animation frame of each kind.
    shapes : ArmatureSet
        The hit shape of each kind, for the pipeline.
    """

    def __init__(self, armatures: Mapping, names, extra: Mapping[str, list[Armature]] | None = None):
        shapes: list[Armature] = []
        self.base: dict[str, int] = {}
        self.names: list[str] = []
        frame, count, time = [], [], []

        def add(name: str, frames: list[Armature], frame_time: float) -> None:
            self.base[name] = len(shapes)
            for i, shape in enumerate(frames):
                shapes.append(shape)
                self.names.append(name)
                frame.append(i)
                count.append(len(frames))
                time.append(frame_time)

        for n in sorted(ALWAYS | set(names)):
            add(
                n,
                [fs["hit"] for fs in frame_sets(armatures[n])],
                getattr(armatures[n], "frame_time", DEFAULT_FRAME_TIME),
            )
        add(
            "graze",
            [fs.get("graze") or Armature.box(*DEFAULT_GRAZE, name="graze") for fs in frame_sets(armatures["player"])],
            getattr(armatures["player"], "frame_time", DEFAULT_FRAME_TIME),
        )
        for n, shapes_of in (extra or {}).items():
            add(n, list(shapes_of), DEFAULT_FRAME_TIME)
        self.frame = np.array(frame, dtype=np.int64)
        self._count = np.array(count, dtype=np.int64)
        self._time = np.array(time, dtype=np.float64)
        self.animated = bool((self._count > 1).any())
        self.shapes = ArmatureSet(shapes)

    def current(self, base, age) -> np.ndarray:
        """The kinds shown now: (n,) int64 for objects of first kind ``base`` (n,) aged
        ``age`` seconds (scalar or (n,)): frame ``floor(age / frame_time) mod frames`` of
        their sprite. Still sprites (one frame) keep ``base``."""
        base = np.asarray(base, dtype=np.int64)
        if not self.animated:
            return base
        tick = np.floor(np.asarray(age, dtype=np.float64) / self._time[base]).astype(np.int64)
        return base + tick % self._count[base]
