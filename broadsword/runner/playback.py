"""Playing a recording back: its inputs and live toggles, stage by stage, each frame's state
compared with the digests it kept, so a replay that drifts says at which frame it first
differs and in which part of the state."""

from __future__ import annotations

from dataclasses import dataclass

from ..data.recordings import DIGEST_BYTES, Recording, StageRecording
from ..sim import Input, Toggle, ToggleEvent, World
from ..sim.hashing import differing_part
from .recorder import PARTS

#: The part a divergence names when every part's digest matched but a checkpoint's state
#: hash did not (the recording's checkpoint itself was changed).
CHECKPOINT = "checkpoint"


@dataclass(frozen=True)
class Divergence:
    """The first frame of the run (frames played, all stages counted) after which the state
    differed from the recording's, and the part that differed (a
    :class:`~broadsword.sim.hashing.Part` value, or :data:`CHECKPOINT`)."""

    frame: int
    part: str


@dataclass(frozen=True)
class Mismatch:
    """The first checkpoint (or stage's final) state hash that differs from the recorded one;
    ``frame`` counts the run's frames."""

    frame: int
    expected: str
    got: str


class Playback:
    """A recording's inputs and toggles, from stage ``stage``'s frame ``frame`` on (0, 0:
    the start; a seek restores a world there and starts a playback at the same place).

    Per stage: :meth:`next_input` applies the toggles due before the world's next step and
    returns that step's input (``None`` once the stage's inputs run out); :meth:`stepped`
    after the step compares the state's digests, and its checkpoint when one is due.
    :meth:`next_stage` moves on to the next recorded stage. ``divergence`` and ``mismatch``
    hold the first differences, if any; ``played`` counts the run's frames played."""

    def __init__(self, rec: Recording, stage: int = 0, frame: int = 0):
        if tuple(rec.parts) != PARTS:
            raise ValueError(f"recorded with the parts {list(rec.parts)}; this game's are {list(PARTS)}")
        self.rec = rec
        self.index = stage
        self.frame = frame  # inputs of this stage played
        self.played = rec.starts[stage] + frame
        self.divergence: Divergence | None = None
        self.mismatch: Mismatch | None = None
        self._toggle = self._checkpoint = 0
        st = self.stage
        at = st.origin + frame  # the world's frame there
        while self._toggle < len(st.toggles) and st.toggles[self._toggle][0] < at:
            self._toggle += 1
        while self._checkpoint < len(st.checkpoints) and st.checkpoints[self._checkpoint][0] <= at:
            self._checkpoint += 1

    @property
    def stage(self) -> StageRecording:
        return self.rec.stages[self.index]

    @property
    def stage_done(self) -> bool:
        """Every input of the stage in play was played."""
        return self.frame >= self.stage.frames

    @property
    def done(self) -> bool:
        """Every recorded frame was played."""
        return self.played >= self.rec.frames

    @property
    def has_next_stage(self) -> bool:
        return self.index + 1 < len(self.rec.stages)

    def continue_pending(self, world: World) -> bool:
        """A recorded continue is still to come in this stage (so a game over is not its end)."""
        return any(t[1] == Toggle.CONTINUE.value and t[0] >= world.frame for t in self.stage.toggles[self._toggle :])

    def next_input(self, world: World) -> Input | None:
        if self.stage_done:
            return None
        toggles = self.stage.toggles
        while self._toggle < len(toggles) and toggles[self._toggle][0] == world.frame:
            frame, name, value = toggles[self._toggle]
            world.apply(ToggleEvent(frame, Toggle(name), value))
            self._toggle += 1
        inp = Input.from_byte(self.stage.inputs[self.frame])
        self.frame += 1
        self.played += 1
        return inp

    def check(self, digests: bytes) -> None:
        """Compare the state after the stage's last frame played (``digests``: its
        :func:`~broadsword.sim.hashing.part_digests`) with the recording's; the first
        difference is kept in ``divergence``."""
        if self.frame == 0 or self.divergence is not None:
            return
        width = len(PARTS) * DIGEST_BYTES
        k = self.frame - 1
        recorded = self.stage.digests[k * width : (k + 1) * width]
        if recorded != digests:
            part = differing_part(recorded, digests)
            self.divergence = Divergence(self.played, part.value if part is not None else CHECKPOINT)

    def stepped(self, world: World, digests: bytes) -> None:
        """Compare the state after the step just played (``digests``: its
        :func:`~broadsword.sim.hashing.part_digests`) with the recording's, and its
        checkpoint when one is due."""
        self.check(digests)
        cps = self.stage.checkpoints
        if self._checkpoint < len(cps) and cps[self._checkpoint][0] == world.frame:
            frame, expected = cps[self._checkpoint]
            self._checkpoint += 1
            self._compare(expected, world.state_hash())

    def _compare(self, expected: str, got: str) -> None:
        if got != expected and self.mismatch is None:
            self.mismatch = Mismatch(self.played, expected, got)
            if self.divergence is None:  # every part matched: the checkpoint itself differs
                self.divergence = Divergence(self.played, CHECKPOINT)

    def end_stage(self, world: World) -> None:
        """The stage's inputs are all played: compare its final state hash (when kept)."""
        if self.stage_done and self.stage.state_hash:
            self._compare(self.stage.state_hash, world.state_hash())

    def next_stage(self) -> StageRecording:
        """Move on to the next recorded stage (the caller opens its world); returns it."""
        self.index += 1
        self.frame = self._toggle = self._checkpoint = 0
        return self.stage

    @property
    def matches(self) -> bool:
        """Every recorded frame was played and every digest and hash matched."""
        return self.done and self.divergence is None and self.mismatch is None
