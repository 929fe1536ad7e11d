"""The game's collision layers and the one table that says which test which.

Layer ids are never written as numbers: they come from the table by name
(:class:`LayerIds`), so a layer added later cannot shift another's meaning.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from ..collision import LayerTable


class GameLayer(str, Enum):
    """A collision layer of the game (the paper's entity lists, section 2.3)."""

    PLAYER = "player"  # the player's small hit armature
    GRAZE = "graze"  # the player's larger graze shape: near misses score
    ENEMY_SHIP = "enemy_ship"  # wave ships and boss parts
    ENEMY_BULLET = "enemy_bullet"
    PLAYER_BULLET = "player_bullet"
    ITEM = "item"  # power and point items, collected by the graze shape
    BOMB = "bomb"  # the player's bomb: clears enemy bullets, hurts enemy ships
    PLAYER_PATH = "player_path"  # the hit armature swept along the player's step: what lasers hit
    ENEMY_LASER = "enemy_laser"  # the boss's lasers (no objects: the pipeline's ``lasers``, as pieces)


def game_layer_table(graze: bool = True) -> LayerTable:
    """The game's table: the player against enemy ships and enemy bullets, the graze shape
    against enemy bullets (when the scene grazes) and items, enemy ships against player
    bullets, the bomb against enemy bullets and enemy ships; the enemy lasers against the
    player's path (its hit armature swept along its step: a ship crossing a laser between
    two steps is hit) and the graze shape (when the scene grazes). Bullets never test
    bullets; lasers never test lasers (the pipeline's rule)."""
    tests = [(GameLayer.PLAYER, GameLayer.ENEMY_SHIP), (GameLayer.PLAYER, GameLayer.ENEMY_BULLET)]
    if graze:
        tests.append((GameLayer.GRAZE, GameLayer.ENEMY_BULLET))
    tests += [
        (GameLayer.ENEMY_SHIP, GameLayer.PLAYER_BULLET),
        (GameLayer.GRAZE, GameLayer.ITEM),
        (GameLayer.BOMB, GameLayer.ENEMY_BULLET),
        (GameLayer.BOMB, GameLayer.ENEMY_SHIP),
        (GameLayer.PLAYER_PATH, GameLayer.ENEMY_LASER),
    ]
    if graze:
        tests.append((GameLayer.GRAZE, GameLayer.ENEMY_LASER))
    return LayerTable([g.value for g in GameLayer], [(a.value, b.value) for a, b in tests])


@dataclass(frozen=True)
class LayerIds:
    """Each game layer's id in a table, looked up by name once."""

    player: int
    graze: int
    enemy_ship: int
    enemy_bullet: int
    player_bullet: int
    item: int
    bomb: int
    player_path: int
    enemy_laser: int

    @classmethod
    def of(cls, table: LayerTable) -> LayerIds:
        return cls(*(table.id(g.value) for g in GameLayer))
