"""Recording a run and playing one back, frame by frame, with state-hash checkpoints.

:class:`Recorder` watches a :class:`~broadsword.sim.World` as it steps and makes a
:class:`~broadsword.data.recordings.Recording`; :class:`Playback` feeds a recording's inputs
and live toggles back into a fresh world and checks its hash at every checkpoint, so a
replay that drifts says at which frame it first differs.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..data.recordings import CHECKPOINT_EVERY, Recording
from .input import Input
from .settings import Toggle, ToggleEvent


class Recorder:
    """Keeps each step's input and a checkpoint hash every ``CHECKPOINT_EVERY`` steps.

    Call :meth:`stepped` after every ``world.step(inp)``; :meth:`recording` at the end.
    The starting settings are read when recording starts.
    """

    def __init__(self, world, level_ref: str, level_sha256: str = ""):
        self.world, self.level_ref, self.level_sha256 = world, level_ref, level_sha256
        self.settings = {"rotation": world.rotation, "difficulty": world.settings.difficulty.value}
        self.inputs = bytearray()
        self.checkpoints: list[tuple[int, str]] = []

    def stepped(self, inp: Input) -> None:
        self.inputs.append(inp.to_byte())
        if self.world.frame % CHECKPOINT_EVERY == 0:
            self.checkpoints.append((self.world.frame, self.world.state_hash()))

    def recording(self) -> Recording:
        toggles = tuple((t.frame, t.toggle.value, t.value) for t in self.world.toggles)
        carry = self.world.carry
        return Recording(
            self.level_ref,
            self.world.seed,
            dict(self.settings),
            bytes(self.inputs),
            toggles,
            tuple(self.checkpoints),
            self.world.state_hash(),
            self.level_sha256,
            carry={"score": carry.score, "lives": carry.lives, "continues": carry.continues, "power": carry.power},
        )


@dataclass(frozen=True)
class Mismatch:
    """The first checkpoint whose state hash differs from the recorded one."""

    frame: int
    expected: str
    got: str


class Playback:
    """Plays a recording into a world made with its level, seed and settings.

    ``next_input()`` applies the toggles due before this frame's step and returns its
    input (``None`` once the inputs run out); ``stepped()`` after the step compares a
    checkpoint when one is due. ``mismatch`` holds the first difference, if any.
    """

    def __init__(self, rec: Recording, world):
        self.rec, self.world = rec, world
        self.frame = 0
        self._toggle = 0
        self._checkpoint = 0
        self.mismatch: Mismatch | None = None

    @property
    def done(self) -> bool:
        return self.frame >= self.rec.frames

    def next_input(self) -> Input | None:
        if self.done:
            return None
        toggles = self.rec.toggles
        while self._toggle < len(toggles) and toggles[self._toggle][0] == self.world.frame:
            frame, name, value = toggles[self._toggle]
            self.world.apply(ToggleEvent(frame, Toggle(name), value))
            self._toggle += 1
        inp = Input.from_byte(self.rec.inputs[self.frame])
        self.frame += 1
        return inp

    def stepped(self) -> None:
        cps = self.rec.checkpoints
        if self._checkpoint < len(cps) and cps[self._checkpoint][0] == self.world.frame:
            frame, expected = cps[self._checkpoint]
            self._checkpoint += 1
            got = self.world.state_hash()
            if got != expected and self.mismatch is None:
                self.mismatch = Mismatch(frame, expected, got)

    def final_check(self) -> bool | None:
        """Whether the final state matches the recording's (None if it kept no final hash
        or the playback has not reached its end)."""
        if not self.rec.state_hash or not self.done:
            return None
        return self.world.state_hash() == self.rec.state_hash
