"""Seeking in a recorded run: reach any frame by restoring the nearest snapshot, then stepping.

A :class:`Seeker` replays a run's inputs and live toggles into one world. As it steps it
keeps a snapshot (:mod:`.snapshot`) every ``every`` frames; :meth:`Seeker.seek` to frame
``f`` starts from whichever is latest at or before ``f`` -- the world where it is now, or
the nearest snapshot -- and steps on. A seek costs one restore and fewer than ``every``
steps once the snapshots up to ``f`` exist (:meth:`Seeker.prepare` makes them all), and
reaches exactly the state straight playback reaches (the snapshots are exact).
"""

from __future__ import annotations

import zlib
from collections.abc import Callable, Sequence

from .input import Input
from .settings import Toggle, ToggleEvent
from .snapshot import Snapshots
from .world import World

#: Frames between kept snapshots (a sixth of a second): a seek restores one and steps at most
#: 9 frames; a 5-minute run keeps 1,800, some 14 MB compressed (docs/PERFORMANCE.md).
SNAPSHOT_EVERY = 10


class Seeker:
    """One world moved about a recorded run.

    Parameters
    ----------
    make_world : callable () -> World
        Makes the run's starting world (its level, armatures, seed, settings and carry).
    inputs : sequence of Input
        ``inputs[k]`` is the input of the step from frame ``k`` to ``k + 1``.
    toggles : sequence of ToggleEvent
        The run's live toggles, applied before the step of their frame (frames not
        decreasing).
    every : int
        Keep a snapshot every this many frames. Snapshots are kept zlib-compressed
        (level 1): about a tenth of the memory for a millisecond or two per restore.

    Attributes
    ----------
    world : World
        The world, at the frame the last :meth:`seek` reached. Do not step it yourself:
        the Seeker takes it to be where the run's inputs put it (play on from a copy).
    snapshots : dict frame -> bytes
        The compressed snapshots kept so far.
    """

    def __init__(
        self,
        make_world: Callable[[], World],
        inputs: Sequence[Input],
        toggles: Sequence[ToggleEvent] = (),
        every: int = SNAPSHOT_EVERY,
    ):
        if int(every) < 1:
            raise ValueError(f"every must be at least 1, got {every!r}")
        self.world = make_world()
        self.inputs = list(inputs)
        self.every = int(every)
        self._toggles: dict[int, list[ToggleEvent]] = {}
        for t in toggles:
            self._toggles.setdefault(t.frame, []).append(t)
        self._codec = Snapshots(self.world)
        self.snapshots: dict[int, bytes] = {}
        self._keep()

    @property
    def end(self) -> int:
        """The last frame of the run (after its last input)."""
        return len(self.inputs)

    def _keep(self) -> None:
        f = self.world.frame
        if f % self.every == 0 and f not in self.snapshots:
            self.snapshots[f] = zlib.compress(self._codec.save(self.world), 1)

    def _ended(self) -> bool:
        """Whether the run's game ended where the world is (no continue taken there)."""
        w = self.world
        if w.complete:
            return True
        return w.over and not any(t.toggle is Toggle.CONTINUE for t in self._toggles.get(w.frame, ()))

    def _step(self) -> None:
        """One step of the run: the toggles due at this frame, then its input."""
        w = self.world
        f = w.frame
        if self._ended():
            raise ValueError(f"the run ended at frame {f} ({'game over' if w.over else 'stage complete'})")
        for t in self._toggles.get(f, ()):
            w.apply(t)
        w.step(self.inputs[f])
        self._keep()

    def seek(self, frame: int) -> World:
        """The world after ``frame`` steps (0..``end``); ``ValueError`` for a frame outside the
        run or past where its game ended."""
        if not 0 <= frame <= self.end:
            raise ValueError(f"frame {frame} is outside the run (0..{self.end})")
        w = self.world
        start = max((f for f in self.snapshots if f <= frame), default=0)
        if not start <= w.frame <= frame:  # restoring brings it nearer than stepping on
            self._codec.restore(w, zlib.decompress(self.snapshots[start]))
        while w.frame < frame:
            self._step()
        return w

    def prepare(self) -> None:
        """Play the whole run once, keeping every snapshot (then any seek is quick)."""
        self.seek(max(self.snapshots))
        while self.world.frame < self.end and not self._ended():
            self._step()
