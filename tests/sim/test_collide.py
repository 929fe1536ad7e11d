"""The collision step's record, the layer table and the armature kinds."""

import dataclasses

import numpy as np
import pytest
import shipped
from sim_bullets import add_bullets

from broadsword.data import load_level, resolve_level
from broadsword.sim import IDLE, GameLayer, Group, LayerIds, World
from broadsword.sim.collide import LaserTag, LaserTags
from broadsword.sim.items import ItemKind
from broadsword.sim.layers import game_layer_table

ARMATURES = shipped.armatures()


def test_layer_table__bullets_never_test_bullets_and_graze_is_optional():
    t = game_layer_table(graze=True)
    ids = LayerIds.of(t)
    assert t.names == tuple(g.value for g in GameLayer)
    assert set(t.entries) == {
        (ids.player, ids.enemy_ship),
        (ids.player, ids.enemy_bullet),
        (ids.graze, ids.enemy_bullet),
        (ids.enemy_ship, ids.player_bullet),
        (ids.graze, ids.item),
        (ids.bomb, ids.enemy_bullet),
        (ids.bomb, ids.enemy_ship),
        (ids.player_path, ids.enemy_laser),
        (ids.graze, ids.enemy_laser),
    }
    assert (ids.graze, ids.enemy_bullet) not in game_layer_table(graze=False).entries
    assert (ids.graze, ids.enemy_laser) not in game_layer_table(graze=False).entries
    assert (ids.graze, ids.item) in game_layer_table(graze=False).entries  # items are collected all the same


def test_kinds__each_sprite_frame_and_the_graze_shape():
    level = load_level(resolve_level("3-broadsword"))
    w = World(level, ARMATURES)
    k = w.kinds
    assert {"player", "shot", "graze"} <= set(k.base) and level.sprites <= set(k.base)
    assert k.names[k.base["graze"]] == "graze"
    assert len(k.shapes) == len(k.names) == len(k.frame)


def test_record__spans_cover_each_group_in_order():
    level = load_level(resolve_level("3-broadsword"))
    w = World(dataclasses.replace(level, waves=level.waves[:1]), ARMATURES, seed=2)
    w.player.invulnerable = 0.0
    for _ in range(120):  # the first wave arrives and fires
        w.step(IDLE)
    w.player.invulnerable = 0.0
    add_bullets(w.player_bullets, w.kinds.base["shot"], [[10.0, 10.0]], [[0.0, -100.0]])
    r = w.detect()
    n = len(r.layer)
    assert r.spans[Group.PLAYER] == slice(0, 1) and r.spans[Group.GRAZE] == slice(1, 2)
    order = [Group.SHIPS, Group.BOSS, Group.ENEMY_BULLETS, Group.PLAYER_BULLETS]
    assert [r.spans[g].start for g in order[1:]] == [r.spans[g].stop for g in order[:-1]]
    assert r.spans[Group.PLAYER_BULLETS].stop == n
    ids = w.layers
    assert (r.layer[r.spans[Group.SHIPS]] == ids.enemy_ship).all()
    assert (r.layer[r.spans[Group.ENEMY_BULLETS]] == ids.enemy_bullet).all()
    assert r.positions[r.spans[Group.PLAYER_BULLETS]].tolist() == [[10.0, 10.0]]
    # Only moving bullets are swept.
    assert not r.swept[: r.spans[Group.ENEMY_BULLETS].start].any()
    assert w.collision is r


def test_record__hits_from_picks_the_first_objects_group():
    w = World(load_level(resolve_level("1-picket")), ARMATURES)  # nothing has arrived yet
    w.player.invulnerable = 0.0
    p = w.player.pos
    add_bullets(w.enemy_bullets, w.kinds.base["needle"], [p, p + (300.0, 0.0)], [[0.0, 0.0], [0.0, 0.0]])
    r = w.detect()
    assert r.hits_from(Group.PLAYER).tolist() == [[0, 2]]
    assert r.hits_from(Group.GRAZE).tolist() == [[1, 2]]
    assert r.hits_from(Group.SHIPS, Group.BOSS).shape == (0, 2)


@pytest.mark.parametrize(
    "vulnerable, graze, items, heads",
    [(True, True, False, 2), (False, True, False, 1), (True, False, False, 1), (True, False, True, 2)],
)
def test_record__the_player_takes_part_only_as_it_may(vulnerable, graze, items, heads):
    """The hit shape while vulnerable; the graze shape while alive if the scene grazes, or
    if an item is out (it collects items even in a scene that does not score grazes)."""
    level = load_level(resolve_level("1-picket"))
    level = dataclasses.replace(level, waves=(), boss=None, scene=dataclasses.replace(level.scene, graze=graze))
    w = World(level, ARMATURES)
    w.player.invulnerable = 0.0 if vulnerable else 1.0
    if items:
        w.items.drop((100.0, 100.0), [ItemKind.POINT])
    r = w.detect()
    assert len(r.layer) == heads + int(items)
    assert (r.spans[Group.PLAYER].stop - r.spans[Group.PLAYER].start) == int(vulnerable)
    grazing = graze or items
    assert np.array_equal(r.layer[:heads], [w.layers.player] * int(vulnerable) + [w.layers.graze] * int(grazing))


def test_laser_tags__each_lasers_tag_made_when_asked_as_a_sequence():
    tags = LaserTags(np.array([4, 7, 9]), np.array([0, 1, 1]), np.array([2, 0, 1]), ("curvy", "beam", "straight"))
    assert len(tags) == 3 and bool(tags) and not LaserTags.empty()
    assert tags[1] == LaserTag(7, 1, 0, "beam") and tags[1].name() == "beam laser 1 of phase 2"
    assert tags[-1] == LaserTag(9, 1, 1, "straight") and isinstance(tags[0].row, int)
    assert tags[1:] == (LaserTag(7, 1, 0, "beam"), LaserTag(9, 1, 1, "straight"))
    assert [t.row for t in tags] == [4, 7, 9] and LaserTag(4, 0, 2, "curvy") in tags
    with pytest.raises(IndexError):
        tags[3]
