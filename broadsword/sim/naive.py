"""Naive scripted players: how a beginner plays, for measuring whether Easy forgives one.

Each holds fire all the time and moves by a fixed script, never dodging:

* ``stand``: never moves (stays where the ship enters, and re-enters);
* ``weave``: sweeps side to side along the row it enters on, at full speed, turning every
  ``half_period`` frames (a triangle wave in x about where it started);
* ``stream``: drops to the bottom row, then streams along it at the precise (slow) speed,
  turning when it sees itself near an edge.

They have the autopilot's human limits (:mod:`.autopilot`): they see only the present frame,
and what they decide from frame ``t`` is pressed at frame ``t + REACTION``. The one thing they
react to is a crowd: when at least ``CROWD`` enemy bullets or ships are within ``CROWD_PX`` of
the ship, they press bomb (200 ms late, as every decision). A seed only varies the script
(the weave's first direction and its period), drawn from its own generator, never the
world's: a player is a pure function of its seed and what it saw, so a run is reproducible.
"""

from __future__ import annotations

from collections import deque
from enum import Enum
from typing import TYPE_CHECKING

import numpy as np

from .autopilot import REACTION
from .field import FIELD
from .input import IDLE, Input

if TYPE_CHECKING:
    from .world import World

#: Bomb when at least this many enemy bullets or ships are within CROWD_PX px of the ship.
CROWD, CROWD_PX = 5, 48.0
#: The weave's half period (frames of one sweep) is drawn from this range (inclusive).
WEAVE_FRAMES = (54, 72)
#: The streamer turns back when it sees itself this near an edge, px; it rides this far above
#: the field's bottom edge, px.
STREAM_TURN_PX, STREAM_ROW_PX = 40.0, 24.0


class Script(str, Enum):
    """The naive scripts, by their ``--players`` name."""

    STAND = "stand"
    WEAVE = "weave"
    STREAM = "stream"


class Naive:
    """A scripted player: call it once per frame with the world; it returns the input to press
    now (decided ``reaction`` frames ago). ``seed`` varies the script (see the module)."""

    def __init__(self, script: Script, seed: int = 0, reaction: int = REACTION):
        self.script = Script(script)
        rng = np.random.default_rng([0x6E61, int(seed)])  # its own stream, never the world's
        self.half_period = int(rng.integers(WEAVE_FRAMES[0], WEAVE_FRAMES[1] + 1))
        self.direction = 1 if rng.integers(2) else -1  # the weave's and the stream's first way
        self.frames = 0  # decisions made
        self.pending: deque[Input] = deque([IDLE] * reaction)

    def __call__(self, world: World) -> Input:
        self.pending.append(self.decide(world))
        return self.pending.popleft()

    def decide(self, world: World) -> Input:
        """What to press ``REACTION`` frames from now, judged from this frame."""
        self.frames += 1
        p = world.player
        if not p.alive:
            return IDLE
        dx, dy, slow = self._move(p.pos)
        return Input(dx, dy, fire=True, slow=slow, bomb=self._crowded(world, p.pos))

    def _move(self, pos: np.ndarray) -> tuple[int, int, bool]:
        """The script's stick and speed for this decision; ``pos`` is the ship's (2,) position."""
        if self.script is Script.STAND:
            return 0, 0, False
        if self.script is Script.WEAVE:
            # the first sweep is half as long, so the weave is centred where it started
            leg = (self.frames + self.half_period // 2) // self.half_period
            return (self.direction if leg % 2 == 0 else -self.direction), 0, False
        # STREAM: down to the bottom row first, then along it, turning near the edges
        if pos[0] < STREAM_TURN_PX:
            self.direction = 1
        elif pos[0] > FIELD[0] - STREAM_TURN_PX:
            self.direction = -1
        down = 1 if pos[1] < FIELD[1] - STREAM_ROW_PX else 0
        return self.direction, down, True

    @staticmethod
    def _crowded(world: World, pos: np.ndarray) -> bool:
        """At least ``CROWD`` enemy bullets or ships within ``CROWD_PX`` of ``pos``, a bomb in
        stock and none going off."""
        if world.player.bombs <= 0 or world.bomb.active:
            return False
        seen = np.concatenate([world.enemy_bullets.pos, world.ships.pool.pos, world.parts.pos])
        d = seen - pos
        return int((d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1] < CROWD_PX * CROWD_PX).sum()) >= CROWD
