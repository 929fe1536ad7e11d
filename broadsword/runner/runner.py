"""The game runner: one run of the game, stage after stage, between ``sim`` and ``game``.

A :class:`Runner` holds the stage in play (a :class:`~broadsword.runner.stages.Stage`), steps
its world with inputs (:meth:`Runner.step`: the one place a game's world is stepped; the
play scene, headless play, the soak, balance, the benchmark and the tools all step through
it), records the run (every stage, each frame's input and state digests), checks a playback
when it plays a recording, and calls the observers its caller chose after every step.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

from ..data import DataError
from ..data.recordings import PLAIN_RUN, Recording, RecordingInfo
from ..sim import Events, Input, World
from ..sim.hashing import part_digests
from .observers import Observer
from .playback import Playback
from .recorder import Recorder
from .stages import Stage, StageStart, open_recorded, open_stage


class Runner:
    """A run in play: ``stage`` (its ``world``), ``frame`` (the run's frames played, every
    stage counted), ``recorder`` (the run so far, with ``info``: what kind of run it is),
    ``playback`` (the recording being played, if one is) and ``observers``.

    A runner can start anywhere: ``stage`` may hold a world restored at its ``frame``
    (a seek), with a ``playback`` placed at the same frame."""

    def __init__(
        self,
        stage: Stage,
        observers: Sequence[Observer] = (),
        playback: Playback | None = None,
        frame: int = 0,
        info: RecordingInfo = PLAIN_RUN,
    ):
        self.stage = stage
        self.observers = list(observers)
        self.playback = playback
        self.frame = frame
        self.recorder = Recorder(info)
        self.recorder.begin(stage)
        self._began()

    @classmethod
    def open(cls, start: StageStart, armatures: dict | None = None, observers: Sequence[Observer] = ()) -> Runner:
        """A run from the start of the stage ``start`` names. DataError if it cannot load."""
        return cls(open_stage(start, armatures), observers)

    @classmethod
    def replaying(
        cls, rec: Recording, rec_path: str | Path, armatures: dict | None = None, observers: Sequence[Observer] = ()
    ) -> Runner:
        """A run that plays recording ``rec`` (read from ``rec_path``) from its start.
        DataError if its first level cannot load or has changed, or it hashes other parts."""
        try:
            playback = Playback(rec)
        except ValueError as exc:
            raise DataError(rec_path, "parts", str(exc)) from None
        return cls(open_recorded(rec.first, 0, rec_path, armatures), observers, playback)

    @property
    def world(self) -> World:
        return self.stage.world

    def _began(self) -> None:
        for o in self.observers:
            began = getattr(o, "began", None)
            if began is not None:
                began(self)

    # ------------------------------------------------------------------ stepping
    def step(self, inp: Input) -> Events:
        """One step of the stage in play with ``inp``: the world steps, the run records it,
        a playback compares it, the observers see it. Returns the step's events."""
        world = self.stage.world
        ev = world.step(inp)
        self.frame += 1
        digests = part_digests(world)
        self.recorder.stepped(inp, digests)
        if self.playback is not None:
            self.playback.stepped(world, digests)
        for o in self.observers:
            o.stepped(self, inp, ev)
        return ev

    def begin_stage(self, stage: Stage) -> None:
        """Go on to ``stage`` (the run's next stage, already opened)."""
        self.stage = stage
        self.recorder.begin(stage)
        self._began()

    def recording(self) -> Recording:
        """The run so far, every stage."""
        return self.recorder.recording()

    @property
    def ended(self) -> bool:
        """The stage in play is over: cleared, or a game over."""
        return self.world.over or self.world.complete

    def play(self, source: Callable[[World], Input], frames: int) -> None:
        """Step with ``source``'s inputs (the autopilot, idle hands...) until ``frames``
        frames of the run were played or the stage ends (cleared or a game over)."""
        while self.frame < frames and not self.ended:
            self.step(source(self.world))

    # ------------------------------------------------------------------ playing a recording
    def replay_input(self) -> Input | None:
        """The recording's input for the next step of the stage in play (its due toggles
        applied), or None when this stage cannot go on: its inputs ran out, the state
        already differs, or the world has ended (cleared, or a game over with no recorded
        continue to come). The state is compared with the recording's again first, so a
        change made between two steps is named at the frame it was made after."""
        pb = self.playback
        assert pb is not None, "replay_input needs a runner made by Runner.replaying"
        world = self.world
        pb.check(part_digests(world))  # the state is still the one recorded (nothing changed it between steps)
        if pb.divergence is not None or pb.stage_done:
            return None
        if world.complete or (world.over and not pb.continue_pending(world)):
            return None
        return pb.next_input(world)

    def replay_next_stage(self, rec_path: str | Path, armatures: dict | None = None) -> bool:
        """When every input of the stage in play was played, with no difference, and the
        recording has another stage, open that one and go on to it (the recording says where
        each stage ended; its digests, that it ended in the same state). DataError if its
        level cannot load or has changed."""
        pb = self.playback
        assert pb is not None, "replay_next_stage needs a runner made by Runner.replaying"
        pb.end_stage(self.world)
        if not (pb.stage_done and pb.has_next_stage and pb.divergence is None and pb.mismatch is None):
            return False
        nxt = pb.next_stage()
        self.begin_stage(open_recorded(nxt, pb.index, rec_path, armatures))
        return True

    def play_back(self, rec_path: str | Path, armatures: dict | None = None, frames: int | None = None) -> None:
        """Play the recording to its end, every stage (or until ``frames`` frames of the
        run, or the first frame that differs)."""
        while frames is None or self.frame < frames:
            inp = self.replay_input()
            if inp is None:
                if self.replay_next_stage(rec_path, armatures):
                    continue
                return
            self.step(inp)
