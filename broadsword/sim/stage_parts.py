"""What the stage-level systems (:mod:`.combat`, :mod:`.progress`) read and change of the
world: a typed, narrow contract (a :class:`typing.Protocol`) instead of the whole
:class:`~broadsword.sim.world.World`, so mypy sees the coupling and the modules do not
import the world that owns them (no import loop)."""

from __future__ import annotations

from typing import Protocol

from ..data.difficulty import DifficultySpec
from .bombs import Bomb
from .boss import Boss
from .bullets import EnemyBullets
from .events import Events
from .hitlog import HitLog
from .items import Items
from .kinds import Kinds
from .player import Player
from .pool import Pool
from .scoring import Score
from .waves import WaveShips


class StageParts(Protocol):
    """The parts of a world in play that applying hits and the stage's rules touch."""

    score: Score
    player: Player
    items: Items
    ships: WaveShips
    enemy_bullets: EnemyBullets
    player_bullets: Pool
    bomb: Bomb
    boss: Boss | None
    over: bool
    start_lives: int
    difficulty: DifficultySpec
    kinds: Kinds
    frame: int
    hit_log: HitLog  # an observation: what hit the player (never state)

    def damage_boss(self, amount: int, ev: Events) -> None:
        """Hurt the boss; a phase that ends goes through the stage's rules."""
