"""One frame of player input, as plain data (keys, gamepad, replay or autopilot alike)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Input:
    """``dx``, ``dy`` in {-1, 0, 1} (+y is down), ``fire`` and ``slow`` (the precise mode)."""

    dx: int = 0
    dy: int = 0
    fire: bool = False
    slow: bool = False

    def __post_init__(self):
        if self.dx not in (-1, 0, 1) or self.dy not in (-1, 0, 1):
            raise ValueError(f"dx and dy must be -1, 0 or 1, got {self.dx}, {self.dy}")

    def to_byte(self) -> int:
        """Pack into one byte (for recordings): 2 bits per axis, then fire and slow."""
        return (self.dx + 1) | (self.dy + 1) << 2 | int(self.fire) << 4 | int(self.slow) << 5

    @classmethod
    def from_byte(cls, b: int) -> "Input":
        if not 0 <= b < 64 or (b & 3) == 3 or (b >> 2 & 3) == 3:
            raise ValueError(f"not an input byte: {b}")
        return cls((b & 3) - 1, (b >> 2 & 3) - 1, bool(b >> 4 & 1), bool(b >> 5 & 1))


IDLE = Input()
