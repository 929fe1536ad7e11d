"""No tunnelling (issue 6): fast bullets are always caught, and nothing is hit that a
sweep did not pass through.

Every test drives a :class:`~broadsword.sim.World` built from a shipped level's scene (its
tiers, rotation mode and bin size), so the layers, the sweep rule (``World._collide``
sweeps a bullet that moved more than half its smallest extent) and the pipeline are the
game's own. The batch tests move bullets with ``broadsword.sim.bullets.move_bullets`` and collide them with
``World._collide`` -- the first two stages of ``World.step`` -- without applying the hits, so
thousands of bullets can cross one target in the same frames; the end-to-end tests call
``World.step`` itself.

The targets are found from the data, not named: the thinnest ship armature (smallest
minimum width over every hit armature of a ship that the player's bullets can hit in a
shipped level), every other ship at its centre, and the player's hit armature against
every kind of enemy bullet the levels fire.

Geometry of a shot: a bullet's centre moves along the line through an aim point (the
target's centre when it lies inside the armature, every vertex, every edge midpoint, all
as the pipeline posed them) at angle ``theta``. The centre of a bullet lies inside the
bullet, so the continuous motion makes the two share a point: a hit is owed at every
speed. The bullet starts outside the disc of radius ``R_target + R_bullet`` (plus a
margin) around the target's centre, a varying fraction of a step before it, and runs
until it is beyond it. When a frame's step is at least the chord the line cuts from that
disc, the start is placed so that one step carries the bullet from clear before to clear
after: no sampled pose overlaps the target, and only the sweep can catch it (asserted).
"""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np
import pytest
import shipped
from sim_bullets import add_bullets

from broadsword.collision import point_in_polygon, pose
from broadsword.data import list_levels, load_level, resolve_level
from broadsword.data.levels import FireSpec, PathSpec, WaveSpec
from broadsword.sim import DT, IDLE, LayerIds, World
from broadsword.sim.bombs import DEATHBOMB_FRAMES
from broadsword.sim.bullets import move_bullets
from broadsword.sim.layers import game_layer_table

_IDS = LayerIds.of(game_layer_table())  # layer ids come from the table, by name
ENEMY, ENEMY_BULLET, PLAYER, PLAYER_BULLET = _IDS.enemy_ship, _IDS.enemy_bullet, _IDS.player, _IDS.player_bullet
ARMATURES = shipped.armatures()
LEVELS = [load_level(resolve_level(n)) for n in list_levels()]
#: Sprites of ships the player's bullets can hit, and of the bullets enemies fire.
SHIPS = sorted(
    {w.enemy for lv in LEVELS for w in lv.waves} | {p.sprite for lv in LEVELS if lv.boss for p in lv.boss.parts}
)
ENEMY_SHOTS = sorted(
    {w.fire.bullet for lv in LEVELS for w in lv.waves if w.fire.fires}
    | {p.fire.bullet for lv in LEVELS if lv.boss for p in lv.boss.parts if p.fire.fires}
)
#: The distinct collision scenes of the shipped levels.
SCENES = list(dict.fromkeys(lv.scene for lv in LEVELS))
#: 100 px/s to 100,000 px/s, four steps a decade.
SPEEDS = 100.0 * 10.0 ** (np.arange(13) / 4.0)
ANGLES = np.arange(360.0)  # every integer degree (aim points other than the centre add a fraction)
GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0
CENTRE = np.array([240.0, 320.0])  # middle of the field
TARGET_ANGLE = 17.3  # ships turn; a target at a non-integer angle exercises the rotation table


def min_width(armature) -> float:
    """Minimum width of an armature: the least distance between two parallel lines
    enclosing it, attained with one line along an edge of its convex hull."""
    v = np.asarray(armature.hull, dtype=np.float64)
    best = math.inf
    for i in range(len(v)):
        e = v[(i + 1) % len(v)] - v[i]
        n = np.array([-e[1], e[0]]) / math.hypot(*e)
        d = (v - v[i]) @ n
        best = min(best, float(d.max() - d.min()))
    return best


def arena(scene) -> World:
    """A World with the given collision scene whose level knows every ship and bullet
    sprite: one wave per ship (stationary, never due) so :meth:`WaveShips.spawn` can
    place any of them, the bullet sprites named by the waves' fire specs."""
    shots = itertools.cycle(ENEMY_SHOTS)
    still = PathSpec(kind="straight", x=CENTRE[0], speed=0.0)
    waves = [
        WaveSpec(at=1e9, enemy=s, count=1, every=0.0, hp=1, score=0, path=still, fire=FireSpec(), mirror=False)
        for s in SHIPS
    ]
    waves += [
        WaveSpec(
            at=1e9,
            enemy=SHIPS[0],
            count=1,
            every=0.0,
            hp=1,
            score=0,
            path=still,
            fire=FireSpec(pattern="aimed", bullet=next(shots)),
            mirror=False,
        )
        for _ in ENEMY_SHOTS
    ]
    level = dataclasses.replace(LEVELS[0], scene=scene, waves=tuple(waves), boss=None)
    w = World(level, ARMATURES, seed=0)
    w.player.invulnerable = 1e9  # the player stays out of the collision unless a test exposes it
    return w


def kinds(w: World, name: str) -> list[int]:
    """Armature kinds (indices into ``w.kinds.shapes``) of sprite ``name``: one per animation frame."""
    return [k for k, n in enumerate(w.kinds.names) if n == name]


def radius(w: World, name: str) -> float:
    return max(w.kinds.shapes.armatures[k].radius for k in kinds(w, name))


def thinnest_ship(w: World) -> tuple[str, int]:
    cand = [(min_width(w.kinds.shapes.armatures[k]), k) for s in SHIPS for k in kinds(w, s)]
    _, k = min(cand)
    return w.kinds.names[k], k


def place_ship(w: World, name: str, kind: int, centre=CENTRE, angle=TARGET_ANGLE) -> None:
    """Put one stationary ship of sprite ``name`` showing armature ``kind`` at ``centre``."""
    w.ships.pool.clear()
    w.ships.spawn(next(i for i, wave in enumerate(w.level.waves) if wave.enemy == name and not wave.fire.fires), w.rng)
    frame_time = getattr(ARMATURES[name], "frame_time", 0.1)
    w.ships.pool.age[:] = (kind - w.kinds.base[name] + 0.5) * frame_time  # the animation frame showing `kind`
    w.ships.pool.pos[:] = centre
    w.ships.pool.prev[:] = centre
    w.ships.pool.angle[:] = angle
    w.ships.pool.hp[:] = 10**9


def bullet_hits(w: World, target_layer: int, bullet_layer: int) -> np.ndarray:
    """Pool indices of the bullets (layer ``bullet_layer``) that the last collision found
    touching an object of ``target_layer``."""
    layer = w.collision.layer
    first = np.flatnonzero(layer == bullet_layer)
    if not first.size:
        return np.zeros(0, dtype=np.int64)
    h = w.collision.result.hits
    h = h[layer[h[:, 0]] == target_layer]
    return h[:, 1] - first[0]


def pose_of(w: World, target_layer: int) -> tuple[np.ndarray, int]:
    """The target's posed polygon as the pipeline posed it in the last collision, and its kind."""
    i = int(np.flatnonzero(w.collision.layer == target_layer)[0])
    return w.collision.result.posed.polygon(i), int(w.collision.armature[i])


def aim_points(posed: np.ndarray, centre=CENTRE) -> np.ndarray:
    """(m, 2) points of a posed polygon (k, 2), world coordinates as the pipeline posed it:
    its centre when the centre lies inside it, every vertex and every edge midpoint."""
    v = np.asarray(posed, dtype=np.float64)
    inside = [np.asarray(centre, dtype=np.float64)] if point_in_polygon(tuple(centre), v) else []
    return np.vstack([*inside, v, 0.5 * (v + np.roll(v, -1, axis=0))])


def centre_or_vertex(posed: np.ndarray, centre=CENTRE) -> np.ndarray:
    """(1, 2): the centre if the posed polygon contains it, else its first vertex."""
    return np.array([centre if point_in_polygon(tuple(centre), posed) else posed[0]], dtype=np.float64)


def launch(points: np.ndarray, u: np.ndarray, speed: float, rho: float, seed: int = 0):
    """Starting positions and frame count for bullets whose centres run along the lines
    ``points + t u`` (points, u: (n, 2), u unit) at ``speed`` px/s.

    Each line crosses the disc of radius ``rho`` around the target's centre (``rho`` beyond
    the target's and bullet's bounding radii together) between ``t_in`` and ``t_out``. A
    bullet starts outside the disc, before ``t_in``, by a phase in [0, 1) of a step (the
    phases differ from bullet to bullet); when one step ``d`` is at least the chord
    ``t_out - t_in``, it starts so that its first step carries it from before the disc to
    beyond it. After ``frames`` steps every bullet is past ``t_out``.
    """
    rel = points - CENTRE
    b = (rel * u).sum(axis=1)
    root = np.sqrt(np.maximum(b * b - ((rel * rel).sum(axis=1) - rho * rho), 0.0))
    t_in, t_out = -b - root, -b + root
    chord = t_out - t_in
    d = speed * DT
    phase = (np.arange(len(points)) * GOLDEN + 0.5 + seed * 0.1) % 1.0
    s0 = t_in - phase * np.where(d >= chord, d - chord, d)
    frames = math.ceil(float((t_out - s0).max()) / d) + 1
    return points + u * s0[:, None], frames


def run_shots(
    w: World, pool, target_layer: int, bullet_layer: int, base_kind: int, aims: np.ndarray, speed: float, clear: float
):
    """Fire one bullet per (aim point, angle) at ``speed`` and step until all are past.

    ``aims`` (m, 2) world points; angle ``ANGLES[j]`` plus a fraction that differs per aim
    point. ``clear`` is the distance from the target's centre beyond which a bullet cannot
    touch it (R_target + R_bullet). Returns ``(hit, clean, swept)``, (m*360,) bool each: hit
    in some frame; every sampled pose clear of the target (so only a sweep could find the
    hit); swept in every frame.
    """
    m = len(aims)
    frac = (np.arange(m) * GOLDEN) % 1.0  # 0 for the centre: exact integer degrees there
    theta = np.radians((ANGLES[None, :] + frac[:, None]).ravel())
    u = np.column_stack([np.cos(theta), np.sin(theta)])
    start, frames = launch(np.repeat(aims, len(ANGLES), axis=0), u, speed, clear + 0.5)
    n = len(start)
    pool.clear()
    add_bullets(pool, base_kind, start, u * speed)
    hit = np.zeros(n, dtype=bool)
    clean = np.hypot(*(start - CENTRE).T) > clear
    swept = np.ones(n, dtype=bool)
    for _ in range(frames):
        move_bullets(pool)
        w.detect()
        hit[bullet_hits(w, target_layer, bullet_layer)] = True
        clean &= np.hypot(*(pool.pos - CENTRE).T) > clear
        first = int(np.flatnonzero(w.collision.layer == bullet_layer)[0])
        swept &= w.collision.swept[first : first + n]
    gone = ((pool.pos - start) * u).sum(axis=1) - ((CENTRE - start) * u).sum(axis=1)
    assert (gone > 0).all() and (np.hypot(*(pool.pos - CENTRE).T) > clear).all()  # every bullet ended past the target
    return hit, clean, swept


def check_ladder(w, pool, target_layer, bullet_layer, base_kind, aims, clear):
    for speed in SPEEDS:
        hit, clean, swept = run_shots(w, pool, target_layer, bullet_layer, base_kind, aims, speed, clear)
        missed = np.flatnonzero(~hit)
        assert not missed.size, (
            f"{speed:.0f} px/s: {missed.size} of {hit.size} bullets tunnelled, "
            f"first: aim {missed[0] // len(ANGLES)}, angle index {missed[0] % len(ANGLES)}"
        )
        if speed * DT >= 2 * (clear + 0.5):  # one step from clear before to clear after: only the sweep sees it
            assert clean.all() and swept.all()


@pytest.mark.parametrize("scene", SCENES, ids=lambda s: "+".join(s.tiers) + "-" + s.rotation)
def test_player_bullets_never_tunnel_through_the_thinnest_ship(scene):
    w = arena(scene)
    name, kind = thinnest_ship(w)
    place_ship(w, name, kind)
    w.detect()
    posed, used = pose_of(w, ENEMY)
    assert used == kind  # the World shows the armature chosen as the thinnest
    aims = aim_points(posed)
    assert len(aims) >= 2 * len(w.kinds.shapes.armatures[kind].vertices)
    r_t, r_b = w.kinds.shapes.armatures[kind].radius, radius(w, "shot")
    check_ladder(w, w.player_bullets, ENEMY, PLAYER_BULLET, w.kinds.base["shot"], aims, r_t + r_b)


@pytest.mark.parametrize("ship", SHIPS)
def test_player_bullets_never_tunnel_through_any_ship_aimed_at_its_centre(ship):
    w = arena(SCENES[0])
    for kind in kinds(w, ship):
        place_ship(w, ship, kind)
        w.detect()
        posed, used = pose_of(w, ENEMY)
        assert used == kind
        r_t, r_b = w.kinds.shapes.armatures[kind].radius, radius(w, "shot")
        check_ladder(
            w, w.player_bullets, ENEMY, PLAYER_BULLET, w.kinds.base["shot"], centre_or_vertex(posed), r_t + r_b
        )


def expose_player(w: World, at=CENTRE) -> None:
    w.player.pos = np.array(at, dtype=np.float64)
    w.player.prev = w.player.pos.copy()
    w.player.invulnerable = 0.0


@pytest.mark.parametrize("shot", ENEMY_SHOTS)
@pytest.mark.parametrize("scene", SCENES, ids=lambda s: "+".join(s.tiers) + "-" + s.rotation)
def test_enemy_bullets_never_tunnel_through_the_player(scene, shot):
    w = arena(scene)
    expose_player(w)
    w.detect()
    posed, used = pose_of(w, PLAYER)
    assert w.kinds.names[used] == "player"
    aims = aim_points(posed)
    r_t, r_b = w.kinds.shapes.armatures[used].radius, radius(w, shot)
    check_ladder(w, w.enemy_bullets, PLAYER, ENEMY_BULLET, w.kinds.base[shot], aims, r_t + r_b)


# ---------------------------------------------------------------------- near misses and near hits
def support(points: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """max over points (k, 2) of point . direction, for each direction (m, 2): (m,)."""
    return (direction @ points.T).max(axis=1)


@pytest.mark.parametrize("target, shot", [("thinnest ship", "shot")] + [("player", b) for b in ENEMY_SHOTS])
def test_a_path_that_misses_by_a_hair_never_hits_and_one_that_touches_always_does(target, shot):
    """Every half degree, every speed: a straight path whose swept shape stays DELTA clear
    of the target never hits; one that overlaps it by DELTA always hits, even a sliver of
    overlap between two sampled poses of a slow bullet (every moving bullet is swept)."""
    delta = 1e-3
    w = arena(SCENES[0])
    if target == "player":
        expose_player(w)
        target_layer, pool, bullet_layer = PLAYER, w.enemy_bullets, ENEMY_BULLET
    else:
        name, kind = thinnest_ship(w)
        place_ship(w, name, kind)
        target_layer, pool, bullet_layer = ENEMY, w.player_bullets, PLAYER_BULLET
    w.detect()
    target_poly, used = pose_of(w, target_layer)
    theta = np.radians(np.arange(0.0, 360.0, 0.5))
    u = np.column_stack([np.cos(theta), np.sin(theta)])
    nrm = np.column_stack([-u[:, 1], u[:, 0]])  # the path runs on this side of the target
    heading = np.degrees(np.arctan2(u[:, 0], -u[:, 1]))
    base = w.kinds.base[shot]
    kind = int(w.kinds.current(np.array([base]), w.time)[0]) if hasattr(w, "current_kind") else base
    shapes = pose(w.kinds.shapes, np.full(len(u), kind), np.zeros((len(u), 2)), heading, w.pipeline.rotation).polygons()
    h_bullet = np.array([support(p, -n[None])[0] for p, n in zip(shapes, nrm)])  # the bullet's reach towards the target
    h_target = support(target_poly - CENTRE, nrm)
    rho = w.kinds.shapes.armatures[used].radius + radius(w, shot) + 1.0
    for speed in SPEEDS:
        for sign in (+1, -1):  # +1: clear by delta, -1: overlapping by delta
            offset = h_target + h_bullet + sign * delta
            assert (np.abs(offset) < rho).all()
            start, frames = launch(CENTRE + nrm * offset[:, None], u, speed, rho, seed=sign)
            pool.clear()
            add_bullets(pool, base, start, u * speed)
            hit = np.zeros(len(u), dtype=bool)
            swept = np.ones(len(u), dtype=bool)
            for _ in range(frames):
                move_bullets(pool)
                w.detect()
                hit[bullet_hits(w, target_layer, bullet_layer)] = True
                first = int(np.flatnonzero(w.collision.layer == bullet_layer)[0])
                swept &= w.collision.swept[first : first + len(u)]
            assert swept.all(), f"{speed:.0f} px/s: a moving bullet was not swept"
            if sign > 0:
                assert not hit.any(), f"{speed:.0f} px/s: {hit.sum()} paths {delta} px clear were called hits"
            else:
                assert hit.all(), f"{speed:.0f} px/s: {(~hit).sum()} paths overlapping by {delta} px missed"


# ---------------------------------------------------------------------- teleports
@pytest.mark.parametrize("shot", ["shot", *ENEMY_SHOTS])
def test_a_teleported_bullet_hits_only_what_its_jump_passed_through(shot):
    """A bullet whose previous position is far from its current one (a jump of 500 px to
    100,000 px in one frame) is swept along the straight segment between them: it hits a
    target on that segment, and not one that lies inside the segment's bounding box but
    off the segment (so the box tiers keep the pair and the exact tier must drop it)."""
    w = arena(SCENES[0])
    if shot == "shot":
        name, kind = thinnest_ship(w)
        place_ship(w, name, kind)
        target_layer, pool, bullet_layer = ENEMY, w.player_bullets, PLAYER_BULLET
    else:
        expose_player(w)
        target_layer, pool, bullet_layer = PLAYER, w.enemy_bullets, ENEMY_BULLET
    w.detect()
    target_poly, used = pose_of(w, target_layer)
    clear = w.kinds.shapes.armatures[used].radius + radius(w, shot)
    rng = np.random.default_rng(6)
    m = 400
    theta = np.radians(rng.uniform(25.0, 65.0, m) + 90.0 * rng.integers(0, 4, m))  # away from the axes: fat boxes
    u = np.column_stack([np.cos(theta), np.sin(theta)])
    nrm = np.column_stack([-u[:, 1], u[:, 0]])
    length = 10.0 ** rng.uniform(2.7, 5.0, m)  # 500 px to 100,000 px in one frame
    t0 = rng.uniform(0.3, 0.7, m) * length  # where along the jump the target lies
    miss = rng.uniform(clear + 0.5, 1.5 * clear, m) * rng.choice([-1.0, 1.0], m)
    for line, expect in (
        (CENTRE + nrm * miss[:, None], False),  # passes the target's bounding circle by
        (np.repeat(target_poly[:1], m, axis=0), True),
    ):  # through a vertex of the target
        prev = line - u * t0[:, None]
        pos = line + u * (length - t0)[:, None]
        box_has_target = ((np.minimum(prev, pos) <= CENTRE) & (CENTRE <= np.maximum(prev, pos))).all(axis=1)
        assert box_has_target.all()
        pool.clear()
        add_bullets(pool, w.kinds.base[shot], pos, np.zeros((m, 2)), prev=prev)
        w.detect()
        hit = np.zeros(m, dtype=bool)
        hit[bullet_hits(w, target_layer, bullet_layer)] = True
        first = int(np.flatnonzero(w.collision.layer == bullet_layer)[0])
        assert w.collision.swept[first : first + m].all()
        assert (hit == expect).all(), f"{(hit != expect).sum()} of {m} jumps wrong (expected hit={expect})"
        if not expect and "aabb" in w.pipeline.tiers:
            aabb = next(s for s in w.collision.result.stats if s.name == "aabb")
            assert aabb.pairs_out >= m  # the box tier kept every one of them; the exact tier said no


def test_a_teleported_player_is_not_hit_by_what_lies_between_its_two_places():
    """The player is never swept: jumping (a respawn, or a set position) past bullets does
    not touch them; a bullet where it lands does."""
    w = arena(SCENES[0])
    shot = ENEMY_SHOTS[0]
    start, end = np.array([240.0, 560.0]), np.array([240.0, 120.0])
    expose_player(w, start)
    clear = radius(w, "player") + radius(w, shot) + 1.0
    ys = np.arange(end[1] + clear, start[1] - clear, 6.0)
    add_bullets(
        w.enemy_bullets, w.kinds.base[shot], np.column_stack([np.full(len(ys), 240.0), ys]), np.zeros((len(ys), 2))
    )
    assert not w.step(IDLE).player_hit
    w.player.pos = end.copy()  # teleport between two steps
    ev = w.step(IDLE)
    assert not ev.player_hit and w.player.lives == w.level.player.lives and w.enemy_bullets.n == len(ys)
    add_bullets(w.enemy_bullets, w.kinds.base[shot], end[None, :], np.zeros((1, 2)))
    assert w.step(IDLE).player_struck


def test_the_respawn_jump_does_not_hit_bullets_on_the_way():
    """After a hit the player reappears at the spawn point; bullets lying between the wreck
    and the spawn point (beyond the mercy radius) are not hit by that jump."""
    from broadsword.sim import SPAWN
    from broadsword.sim.combat import CLEAR_RADIUS

    w = arena(SCENES[0])
    shot = ENEMY_SHOTS[0]
    wreck = np.array([SPAWN[0], 150.0])
    expose_player(w, wreck)
    add_bullets(w.enemy_bullets, w.kinds.base[shot], wreck[None, :], np.zeros((1, 2)))
    clear = radius(w, "player") + radius(w, shot) + 1.0
    ys = np.arange(wreck[1] + CLEAR_RADIUS + 2.0, SPAWN[1] - clear, 5.0)
    add_bullets(
        w.enemy_bullets, w.kinds.base[shot], np.column_stack([np.full(len(ys), SPAWN[0]), ys]), np.zeros((len(ys), 2))
    )
    assert w.step(IDLE).player_struck
    assert w.enemy_bullets.n == len(ys)  # the bullet that struck is gone
    for _ in range(DEATHBOMB_FRAMES - 1):  # the death-bomb window: no bomb comes
        assert not w.step(IDLE).player_hit
    ev = w.step(IDLE)
    assert ev.player_hit and np.array_equal(w.player.pos, SPAWN)
    assert w.enemy_bullets.n == len(ys)  # only the mercy radius was cleared
    w.player.invulnerable = 0.0
    lives = w.player.lives
    for _ in range(3):
        assert not w.step(IDLE).player_hit
    assert w.player.lives == lives


def test_a_teleported_ship_is_not_hit_by_shots_between_its_two_places():
    w = arena(SCENES[0])
    name, kind = thinnest_ship(w)
    start, end = np.array([240.0, 120.0]), np.array([240.0, 480.0])
    place_ship(w, name, kind, centre=start)
    clear = w.kinds.shapes.armatures[kind].radius + radius(w, "shot") + 1.0
    ys = np.arange(start[1] + clear, end[1] - clear, 4.0)
    add_bullets(
        w.player_bullets, w.kinds.base["shot"], np.column_stack([np.full(len(ys), 240.0), ys]), np.zeros((len(ys), 2))
    )
    assert not w.step(IDLE).damaged
    w.ships.pool.pos[:] = end  # teleport between two steps
    ev = w.step(IDLE)
    assert not ev.damaged and not ev.hits and w.player_bullets.n == len(ys)
    add_bullets(w.player_bullets, w.kinds.base["shot"], end[None, :], np.zeros((1, 2)))
    assert w.step(IDLE).damaged


# ---------------------------------------------------------------------- end to end through World.step
@pytest.mark.parametrize("shot", ENEMY_SHOTS)
def test_world_step_loses_a_life_for_every_aimed_bullet_at_every_speed(shot):
    """The full step, one bullet at a time: 36 angles x every other speed of the ladder,
    each aimed at the player's centre (or a vertex, were the centre outside its armature),
    each costs exactly one life."""
    w = arena(SCENES[0])
    w.player.lives = 10**6
    expose_player(w, CENTRE)
    w.detect()
    aim = centre_or_vertex(pose_of(w, PLAYER)[0])[0]
    rho = radius(w, "player") + radius(w, shot) + 0.5
    theta = np.radians(np.arange(0.0, 360.0, 10.0) + 0.37)
    u = np.column_stack([np.cos(theta), np.sin(theta)])
    cases = 0
    for speed in SPEEDS[::2]:
        starts, frames = launch(np.repeat(aim[None, :], len(u), axis=0), u, speed, rho)
        for start, uj, deg in zip(starts, u, np.degrees(theta)):
            expose_player(w, CENTRE)
            w.enemy_bullets.clear()
            add_bullets(w.enemy_bullets, w.kinds.base[shot], start, uj * speed)
            lives = w.player.lives
            hits = 0
            for _ in range(frames):
                w.player.pos = CENTRE.copy()  # hold the player still (a hit respawns it)
                hits += w.step(IDLE).player_struck
            for _ in range(DEATHBOMB_FRAMES):  # the death-bomb window closes: the life goes
                w.step(IDLE)
            assert hits == 1 and w.player.lives == lives - 1, f"{shot} at {speed:.0f} px/s, {deg:.2f} deg: {hits} hits"
            cases += 1
    assert cases == len(SPEEDS[::2]) * 36


def test_world_step_damages_the_thinnest_ship_once_per_aimed_shot_at_every_speed():
    """The full step with every shot of a speed in flight at once, 360 angles (player
    bullets are removed when they hit, so the hit count is the number that hit)."""
    w = arena(SCENES[0])
    name, kind = thinnest_ship(w)
    rho = w.kinds.shapes.armatures[kind].radius + radius(w, "shot") + 0.5
    theta = np.radians(ANGLES + 0.5)
    u = np.column_stack([np.cos(theta), np.sin(theta)])
    for speed in SPEEDS:
        place_ship(w, name, kind)
        w.player_bullets.clear()
        w.step(IDLE)  # the ship takes the pose it keeps (a still ship faces down)
        posed, used = pose_of(w, ENEMY)
        assert used == kind
        aim = centre_or_vertex(posed)[0]
        hp = int(w.ships.pool.hp[0])
        start, frames = launch(np.repeat(aim[None, :], len(u), axis=0), u, speed, rho)
        add_bullets(w.player_bullets, w.kinds.base["shot"], start, u * speed)
        hits = 0
        for _ in range(frames):
            hits += w.step(IDLE).hits
        assert hits == len(u) and hp - int(w.ships.pool.hp[0]) == len(u), f"{speed:.0f} px/s: {hits} of {len(u)} hit"
