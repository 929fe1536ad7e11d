"""What one step did, as data: read after the step, never delivered by callback."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .hitlog import HitRecord


@dataclass
class Events:
    """The outcome of one :meth:`broadsword.sim.World.step`.

    ``kills`` holds ``(x, y, sprite)`` of everything destroyed (``"player"`` for the player's
    ship, ``"boss"`` for each part of a boss that dies); ``damaged`` holds ``(x, y)`` of
    ships hit but not killed; ``bonuses`` ``(name, points)`` awarded this step (a boss
    phase's, the stage's); ``hit`` the player's hit whose death-bomb window closed this
    step (a life lost, or saved by a bomb: :mod:`.hitlog`), an observation.
    """

    hits: int = 0  # hit pairs the pipeline reported (all layers)
    grazes: int = 0
    shots: int = 0  # player bullets fired
    enemy_shots: int = 0
    items: int = 0  # items collected
    kills: list[tuple[float, float, str]] = field(default_factory=list)
    damaged: list[tuple[float, float]] = field(default_factory=list)
    bonuses: list[tuple[str, int]] = field(default_factory=list)
    player_struck: bool = False  # the death-bomb window opened
    player_hit: bool = False  # a life was lost
    bomb: bool = False  # a bomb went off
    extend: bool = False  # an extra life was earned
    phase_ended: bool = False  # a boss phase ended (its bullets became stars)
    boss_arrived: bool = False
    boss_killed: bool = False
    level_complete: bool = False
    game_over: bool = False
    hit: HitRecord | None = None  # what hit the player, when a hit was resolved this step
