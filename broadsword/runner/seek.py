"""Seeking in a recorded run: reach any frame of it by restoring the nearest snapshot, then
stepping with the recording's inputs through a :class:`~broadsword.runner.Runner`.

A :class:`Seeker` holds two runs of one recording. The *preparer* plays it straight through,
stage after stage, continues included (as headless playback does), a few frames at a time
(:meth:`Seeker.prepare`): it keeps a zlib-compressed exact snapshot every ``every`` frames
and at each stage's start, notes the **marks** (each miss, bomb, boss phase start and stage
start) and finds where the replay first differs from its recording, if it does. The
*viewer* (``seeker.runner``) is the run a caller watches: :meth:`Seeker.seek` puts it at any
frame the preparer reached by restoring the latest snapshot at or before that frame and
stepping on; :meth:`Seeker.step` plays it one frame forward. Both step only through
:meth:`Runner.step`, each with a :class:`~broadsword.runner.Playback` placed where its world
is, so a seek reaches the very state straight playback reaches (the snapshots are exact) and
checks every frame it steps against the recording's digests.

Frames are the run's frames as :attr:`Runner.frame` counts them (every stage, continues
included): frame ``F`` is the state after ``F`` steps of the run; at a stage's end, frame
``F`` is the stage left, not the next one's start (as ``--hashes`` reports it).
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass
from enum import Enum
from pathlib import Path

from ..data import DataError
from ..data.recordings import Recording
from ..sim import Events, Snapshots, World
from .playback import Divergence, Playback
from .runner import Runner
from .stages import Stage, open_recorded

#: Frames between kept snapshots (half a second of play). A seek restores one snapshot and
#: steps at most ``SNAPSHOT_EVERY - 1`` frames; docs/PERFORMANCE.md ("Snapshots and seeking")
#: has the figures this spacing was chosen from (a 5-minute run keeps about 600, some 4 MB).
SNAPSHOT_EVERY = 30


class MarkKind(Enum):
    """What a mark on the seek bar stands for."""

    STAGE = "stage"  # a stage starts (frame: the run's frame before its first step)
    PHASE = "phase"  # a boss phase starts (the boss arrived, or a phase ended and the next began)
    BOMB = "bomb"  # a bomb went off
    MISS = "miss"  # a life was lost


@dataclass(frozen=True)
class Mark:
    """A moment of the run: ``frame`` (the run's frame after the step it happened in; a
    stage's start: the frame before its first step) and its ``kind``."""

    frame: int
    kind: MarkKind


def marks_of(ev: Events, frame: int) -> list[Mark]:
    """The marks one step's events make (``frame``: the run's frame after the step)."""
    out = []
    if ev.boss_arrived or (ev.phase_ended and not ev.boss_killed):
        out.append(Mark(frame, MarkKind.PHASE))
    if ev.bomb:
        out.append(Mark(frame, MarkKind.BOMB))
    if ev.player_hit:
        out.append(Mark(frame, MarkKind.MISS))
    return out


@dataclass(frozen=True)
class _Kept:
    """A snapshot: the stage it is of, the inputs of that stage played, the zlib bytes."""

    stage: int
    local: int
    data: bytes


class Seeker:
    """Any frame of a recorded run, reached by snapshots and the runner.

    Parameters
    ----------
    rec : Recording
        The run (every stage, continues included).
    rec_path : str or Path
        Where it was read from (its levels are checked against the digests it kept, and
        errors name it).
    armatures : dict, optional
        The sprites' armatures (default: the shipped ones).
    every : int
        Keep a snapshot every this many frames of the run (and at each stage's start).

    Attributes
    ----------
    runner : Runner
        The viewer: the run at the frame the last :meth:`seek` or :meth:`step` reached. Do
        not step it yourself (play on from a world restored from :meth:`snapshot`).
    marks : list of Mark
        The marks of the frames prepared so far, in frame order.
    reached : int
        The frames prepared: any frame in ``0..reached`` can be sought at once.
    end : int
        The last frame of the run: the recording's frames, or the first frame that differs
        once the preparer found one (:attr:`divergence`).

    error : DataError or None
        Why the run stops before its end when a later stage cannot be opened (its level
        changed or missing: naming the file and field); the frames before it play.

    DataError (naming the file and field) if the first stage's level cannot load or has
    changed, or the recording hashes other parts of the state.
    """

    def __init__(
        self, rec: Recording, rec_path: str | Path, armatures: dict | None = None, every: int = SNAPSHOT_EVERY
    ):
        if int(every) < 1:
            raise ValueError(f"every must be at least 1, got {every!r}")
        self.rec, self.path, self.armatures, self.every = rec, rec_path, armatures, int(every)
        self._prep = Runner.replaying(rec, rec_path, armatures)  # plays straight through, a few frames a call
        self._stages: dict[int, Stage] = {}  # the viewer's world of each stage, opened once
        self._runners: dict[int, Runner] = {}  # the viewer's runner of each stage
        self._codecs: dict[int, Snapshots] = {}  # one per stage: its level's numbering, worked out once
        self._kept: dict[int, _Kept] = {}  # run frame -> its snapshot (a stage's last frame: that stage's)
        self._starts: dict[int, bytes] = {}  # stage -> its start's snapshot
        self._path: dict[int, _Kept] = {}  # the last seek's frames on the way (seek's keep_path)
        self.marks: list[Mark] = [Mark(0, MarkKind.STAGE)]
        self._finished = False
        self.error: DataError | None = None
        self._keep_start(0, self._prep.world)
        self._keep()
        self._place(0, 0)

    # ------------------------------------------------------------------ what is known
    @property
    def frames(self) -> int:
        """The recording's frames (all stages)."""
        return self.rec.frames

    @property
    def reached(self) -> int:
        return self._prep.frame

    @property
    def prepared(self) -> bool:
        """The whole run was played through (every snapshot and mark is known)."""
        return self._finished

    @property
    def divergence(self) -> Divergence | None:
        """Where the replay first differs from its recording, once the preparer got there."""
        return self._prep.playback.divergence if self._prep.playback is not None else None

    @property
    def end(self) -> int:
        return self._prep.frame if self._finished else self.frames

    @property
    def frame(self) -> int:
        """The viewer's frame."""
        return self.runner.frame

    @property
    def world(self) -> World:
        """The viewer's world."""
        return self.runner.world

    @property
    def snapshot_bytes(self) -> int:
        """The memory the kept snapshots take (compressed)."""
        return sum(len(k.data) for k in self._kept.values()) + sum(len(b) for b in self._starts.values())

    @property
    def snapshots(self) -> int:
        return len(self._kept) + len(self._starts)

    def stage_of(self, frame: int) -> int:
        """The recorded stage frame ``frame`` is in (a stage's last frame is its own)."""
        starts = self.rec.starts
        i = 0
        while i + 1 < len(starts) and starts[i + 1] < frame:
            i += 1
        return i

    # ------------------------------------------------------------------ preparing
    def prepare(self, frames: int | None = None) -> int:
        """Play the preparer on by at most ``frames`` frames (None: to the run's end),
        keeping snapshots and marks; returns the frames played. Once the run's end (or its
        first difference) is reached, :attr:`prepared` is true and this does nothing."""
        played = 0
        prep = self._prep
        while not self._finished and (frames is None or played < frames):
            inp = prep.replay_input()
            if inp is None:
                if not self._next_stage(prep):
                    self._finished = True
                continue
            ev = prep.step(inp)
            played += 1
            self.marks.extend(marks_of(ev, prep.frame))
            self._keep()
        return played

    def _next_stage(self, prep: Runner) -> bool:
        pb = prep.playback
        assert pb is not None
        pb.end_stage(prep.world)
        if not (pb.stage_done and pb.has_next_stage and pb.divergence is None and pb.mismatch is None):
            return False
        pb.next_stage()
        try:
            stage = open_recorded(pb.stage, pb.index, self.path, self.armatures)
        except DataError as exc:  # a later stage's level changed or went missing: the run stops here
            self.error = exc
            return False
        prep.begin_stage(stage)
        self._keep_start(pb.index, stage.world)
        self.marks.append(Mark(prep.frame, MarkKind.STAGE))
        return True

    def _codec(self, index: int, world: World) -> Snapshots:
        if index not in self._codecs:
            self._codecs[index] = Snapshots(world)
        return self._codecs[index]

    def _keep_start(self, index: int, world: World) -> None:
        self._starts[index] = zlib.compress(self._codec(index, world).save(world), 1)

    def _keep(self) -> None:
        prep = self._prep
        f = prep.frame
        if f % self.every == 0 and f not in self._kept:
            pb = prep.playback
            assert pb is not None
            data = zlib.compress(self._codec(pb.index, prep.world).save(prep.world), 1)
            self._kept[f] = _Kept(pb.index, pb.frame, data)

    def _open(self, index: int) -> Stage:
        """The viewer's world of recorded stage ``index`` (opened once, then restored into)."""
        if index not in self._stages:
            self._stages[index] = open_recorded(self.rec.stages[index], index, self.path, self.armatures)
        return self._stages[index]

    def _restore(self, index: int, frame: int, data: bytes) -> None:
        """Put the viewer at the run's ``frame`` of stage ``index``, restored from ``data``."""
        stage = self._open(index)
        self._codec(index, stage.world).restore(stage.world, zlib.decompress(data))
        self._place(index, frame)

    def _place(self, index: int, frame: int) -> None:
        """The viewer is stage ``index``'s runner, at the run's ``frame`` (its world already
        there), with a playback placed at the same frame. One runner a stage, made once:
        a runner begun on a restored world keeps its start snapshot, which costs a save."""
        playback = Playback(self.rec, index, frame - self.rec.starts[index])
        runner = self._runners.get(index)
        if runner is None:
            runner = self._runners[index] = Runner(self._open(index), (), playback, frame)
        else:
            runner.playback, runner.frame = playback, frame
        self.runner = runner

    # ------------------------------------------------------------------ the viewer
    def seek(self, frame: int, keep_path: bool = False) -> World:
        """Put the viewer at ``frame`` (0..:attr:`end`; a frame not yet prepared is prepared
        first) and return its world. ``ValueError`` for a frame outside the run.

        ``keep_path``: keep a snapshot of every frame stepped through on the way (a frame by
        frame walk back, as a held Left key makes, then costs one restore a frame until it
        passes the snapshot the walk started from). Only the last such path is kept."""
        if not 0 <= frame <= self.end:
            raise ValueError(f"frame {frame} is outside the run (0..{self.end})")
        if frame > self.reached:
            self.prepare(frame - self.reached)
            if frame > self.end:
                raise ValueError(f"frame {frame} is outside the run (0..{self.end})")
        index = self.stage_of(frame)
        if frame != self.runner.frame and frame in self._path and self._path[frame].stage == index:
            self._restore(index, frame, self._path[frame].data)
            return self.world
        kept = [f for f, k in self._kept.items() if f <= frame and k.stage == index]
        base = max(kept) if kept else self.rec.starts[index]
        here = self.runner
        here_index = here.playback.index if here.playback is not None else 0
        if not (here_index == index and base <= here.frame <= frame):  # restoring is nearer than stepping on
            self._restore(index, base, self._kept[base].data if kept else self._starts[index])
        if keep_path:
            self._path = {}
        while self.runner.frame < frame:
            if keep_path:
                world = self.world
                self._path[self.runner.frame] = _Kept(index, 0, zlib.compress(self._codec(index, world).save(world), 1))
            if self.step() is None:
                raise ValueError(f"frame {frame} is past where the replay ended ({self.runner.frame})")
        return self.world

    def step(self) -> Events | None:
        """Play the viewer one frame on (into the next stage at a stage's end); its events,
        or None at the run's end (or the first frame that differs). The preparer is kept at
        least as far on (it steps first when the viewer is where it is), so every frame the
        viewer played can be sought back to."""
        r = self.runner
        if r.frame >= self.reached:
            self.prepare(1)
        inp = r.replay_input()
        if inp is None:
            pb = r.playback
            assert pb is not None
            pb.end_stage(r.world)
            index = pb.index + 1
            if not (pb.stage_done and pb.has_next_stage and pb.divergence is None and index in self._starts):
                return None
            self._restore(index, r.frame, self._starts[index])  # the preparer opened it: its start is kept
            return self.step()
        return r.step(inp)

    def snapshot(self) -> bytes:
        """The viewer's state as snapshot bytes (uncompressed): a take-over restores it into
        a fresh world of the viewer's stage."""
        index = self.runner.playback.index if self.runner.playback is not None else 0
        return self._codec(index, self.world).save(self.world)
