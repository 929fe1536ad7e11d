"""Recording a run as it is played: every stage's start, inputs, live toggles, each frame's
state digests by part, and a checkpoint hash every ``CHECKPOINT_EVERY`` frames.

A stage whose world does not start at frame 0 (restored from a snapshot: a practice start,
a take-over) is recorded with that start state, a snapshot taken when it begins, so its
replay starts there."""

from __future__ import annotations

import dataclasses

from ..data.recordings import CHECKPOINT_EVERY, PLAIN_RUN, Recording, RecordingInfo, StageRecording
from ..sim import Input
from ..sim.hashing import Part
from ..sim.snapshot import save as save_snapshot
from .stages import Stage

#: The names of the state's parts, in the order of each frame's digests.
PARTS = tuple(p.value for p in Part)


class _StageTape:
    """One stage being recorded."""

    def __init__(self, stage: Stage):
        world = stage.world
        self.world, self.level_ref, self.level_sha256 = world, stage.level_ref, stage.digest
        self.settings = {"rotation": world.rotation, "difficulty": world.settings.difficulty.value}
        self.inputs = bytearray()
        self.digests = bytearray()
        self.checkpoints: list[tuple[int, str]] = []
        self.origin = world.frame
        self.snapshot = save_snapshot(world) if world.frame else b""
        self.toggles_before = len(world.toggles)  # a restored world's toggles so far are in its snapshot

    def stepped(self, inp: Input, digests: bytes) -> None:
        self.inputs.append(inp.to_byte())
        self.digests += digests
        if self.world.frame % CHECKPOINT_EVERY == 0:
            self.checkpoints.append((self.world.frame, self.world.state_hash()))

    def recording(self) -> StageRecording:
        w = self.world
        toggles = tuple((t.frame, t.toggle.value, t.value) for t in w.toggles[self.toggles_before :])
        c = w.carry
        return StageRecording(
            self.level_ref,
            w.seed,
            dict(self.settings),
            bytes(self.inputs),
            toggles,
            tuple(self.checkpoints),
            w.state_hash(),
            self.level_sha256,
            carry={"score": c.score, "lives": c.lives, "continues": c.continues, "power": c.power},
            digests=bytes(self.digests),
            snapshot=self.snapshot,
            origin=self.origin,
        )


class Recorder:
    """Keeps a run's stages: :meth:`begin` when a stage starts (its settings are read then),
    :meth:`stepped` after every step of it with the step's input and the state's
    :func:`~broadsword.sim.hashing.part_digests`; :meth:`recording` at any time, its
    ``info`` being ``info`` with the final score."""

    def __init__(self, info: RecordingInfo = PLAIN_RUN):
        self.info = info
        self._tapes: list[_StageTape] = []

    def begin(self, stage: Stage) -> None:
        self._tapes.append(_StageTape(stage))

    def stepped(self, inp: Input, digests: bytes) -> None:
        self._tapes[-1].stepped(inp, digests)

    @property
    def stages(self) -> int:
        return len(self._tapes)

    @property
    def last_input(self) -> Input | None:
        """The input of the last step recorded in the stage in play (None before its first)."""
        if not self._tapes or not self._tapes[-1].inputs:
            return None
        return Input.from_byte(self._tapes[-1].inputs[-1])

    def recording(self) -> Recording:
        """The run so far: every stage begun, in order."""
        info = self.info
        if self._tapes:
            info = dataclasses.replace(info, score=int(self._tapes[-1].world.score.points))
        return Recording(tuple(t.recording() for t in self._tapes), PARTS, info=info)
