"""One frame of player input, as plain data (keys, gamepad, replay or autopilot alike)."""

from __future__ import annotations

from dataclasses import dataclass

from ..data.recordings import decode_input, encode_input


@dataclass(frozen=True)
class Input:
    """``dx``, ``dy`` in {-1, 0, 1} (+y is down), ``fire``, ``slow`` (the precise mode) and
    ``bomb``."""

    dx: int = 0
    dy: int = 0
    fire: bool = False
    slow: bool = False
    bomb: bool = False

    def __post_init__(self):
        if self.dx not in (-1, 0, 1) or self.dy not in (-1, 0, 1):
            raise ValueError(f"dx and dy must be -1, 0 or 1, got {self.dx}, {self.dy}")

    def to_byte(self) -> int:
        """One byte, for recordings (layout: :data:`broadsword.data.recordings.INPUT_BITS`)."""
        return encode_input(self.dx, self.dy, self.fire, self.slow, self.bomb)

    @classmethod
    def from_byte(cls, b: int) -> Input:
        return cls(*decode_input(b))


IDLE = Input()
