"""What one step did, as data: read after the step, never delivered by callback."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class Events:
    """The outcome of one :meth:`broadsword.sim.World.step`.

    ``kills`` holds ``(x, y, sprite)`` of everything destroyed (``"player"`` for the player's
    ship, ``"boss"`` for each part of a boss that dies); ``damaged`` holds ``(x, y)`` of
    ships hit but not killed.
    """

    hits: int = 0  # hit pairs the pipeline reported (all layers)
    grazes: int = 0
    shots: int = 0  # player bullets fired
    enemy_shots: int = 0
    kills: list[tuple[float, float, str]] = field(default_factory=list)
    damaged: list[tuple[float, float]] = field(default_factory=list)
    player_hit: bool = False
    boss_killed: bool = False
    level_complete: bool = False
    game_over: bool = False
