"""Lasers in the game (issue 23, part 2): they move deterministically, hit the player exactly
(swept along its move, through the frame's one pipeline call) as a miss a bomb can save,
and the hit log names the laser and its piece; they count grazes throttled per laser, are
cancelled by a bomb, survive a snapshot exactly, and are read from level files with clear
errors."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import shipped

from broadsword.collision import Verdict, detmath, explain, posed_polygon
from broadsword.collision.lasers import Laser, laser_pieces, laser_touches
from broadsword.data import DataError, load_level
from broadsword.data.levels import BossPhaseSpec, FireSpec, LaserKind, LaserSpec
from broadsword.runner.hits import LoggedHit, hit_json
from broadsword.sim import Events, Input, World
from broadsword.sim.bombs import DEATHBOMB_FRAMES
from broadsword.sim.collide import Group
from broadsword.sim.field import DT
from broadsword.sim.hashing import Part, differing_part, part_digests
from broadsword.sim.hitlog import HitSource, Outcome, hit_record
from broadsword.sim.input import IDLE
from broadsword.sim.lasers import GRAZE_EVERY, frames
from broadsword.sim.snapshot import Snapshots

#: The boss (stage 3's, its core at the centre) holds at y = 150 with no sway; its part 0
#: reaches the field 0.9 s after it arrives at t = 0.
CORE_Y = 150.0


def laser_world(*lasers: LaserSpec, seed: int = 1) -> World:
    """Stage 3's boss alone, holding still at the top centre, one phase that fires only
    ``lasers`` (no bullet), the player at its spawn and not invulnerable."""
    level = shipped.level("3-broadsword")
    phase = BossPhaseSpec(hp=10**6, time=600, fire=((0, FireSpec()),), lasers=lasers)
    boss = dataclasses.replace(level.boss, at=0.0, y=CORE_Y, sway=0.0, phases=(phase,))
    w = World(dataclasses.replace(level, waves=(), boss=boss), shipped.armatures(), seed)
    w.player.invulnerable = 0.0
    return w


def straight(**kw) -> LaserSpec:
    base = dict(part=0, kind=LaserKind.STRAIGHT, angle=180.0, length=560.0, width=10.0, tip=10.0)
    return LaserSpec(**(base | dict(warn=0.5, on=1.0, every=60.0, delay=3.0) | kw))


def step_until(w: World, done, limit: int = 600, inp: Input = IDLE) -> Events:
    for _ in range(limit):
        ev = w.step(inp)
        if done(w, ev):
            return ev
    raise AssertionError("never happened")


def lit(w: World) -> bool:
    return bool(w.lasers.live_rows())


# ------------------------------------------------------------------------- motion
def test_straight__warns_then_lights_then_goes():
    w = laser_world(straight())
    step_until(w, lambda w, ev: w.lasers.pool.n)
    fired = w.frame
    assert w.lasers.warning(0) and not lit(w)
    step_until(w, lambda w, ev: lit(w))
    assert w.frame - fired == frames(0.5)  # the warning lasts its time exactly
    a, b = w.lasers.pool.nodes[0, :2]
    assert a.tolist() == w.parts.pos[0].tolist() and b.tolist() == [a[0] + 0.0, a[1] + 560.0]
    step_until(w, lambda w, ev: not w.lasers.pool.n)
    assert w.frame - fired == frames(0.5) + frames(1.0)


def test_beam__turns_about_its_part_by_exact_arithmetic():
    w = laser_world(straight(kind=LaserKind.BEAM, turn=30.0, warn=0.25, on=2.0))
    step_until(w, lambda w, ev: lit(w))
    for _ in range(40):
        w.step(Input())
    p = w.lasers.pool
    lit_for = int(p.age[0]) - frames(0.25)
    vx, vy = detmath.velocity_deg(180.0 + 30.0 * (lit_for * DT), 560.0)
    origin = w.parts.pos[0]
    assert p.nodes[0, 1].tolist() == [origin[0] + vx, origin[1] + vy]
    assert p.nodes[0, 1, 0] < origin[0]  # clockwise from straight down: toward -x


def test_curvy__nodes_trail_the_head_and_two_runs_agree_bit_for_bit():
    spec = LaserSpec(0, LaserKind.CURVY, angle=150.0, speed=150.0, nodes=24, wave=30.0, period=0.8, on=5.0, every=60)
    runs = []
    for _ in range(2):
        w = laser_world(spec)
        step_until(w, lambda w, ev: w.lasers.pool.n)
        heads = []
        for _ in range(40):
            w.step(Input())
            heads.append(w.lasers.pool.head[0].copy())
        runs.append(w.lasers.pool.nodes.copy())
        p = w.lasers.pool
        assert int(p.count[0]) == 24
        np.testing.assert_array_equal(p.nodes[0, :24], np.array(heads[::-1][:24]))  # node i: the head i steps ago
    np.testing.assert_array_equal(runs[0], runs[1])


def test_curvy__spacing_takes_a_node_every_few_steps_from_the_heads_path():
    spec = LaserSpec(0, LaserKind.CURVY, angle=170.0, speed=150.0, nodes=24, spacing=3, wave=25.0, on=5.0, every=60)
    w = laser_world(spec)
    step_until(w, lambda w, ev: w.lasers.pool.n)
    origin = w.lasers.pool.head[0].copy()
    head = {0: origin}
    for age in range(1, 41):
        w.step(IDLE)
        head[age] = w.lasers.pool.head[0].copy()
    p = w.lasers.pool
    assert int(p.count[0]) == 15  # the first step's node, then one every 3 steps (ages 3..39)
    expected = [head[40]] + [head[41 - 3 * j] for j in range(1, 14)] + [origin]
    np.testing.assert_array_equal(p.nodes[0, :15], np.array(expected))


def test_curvy__many_rows_trail_at_once_as_each_would_alone():
    """Rows of different spacings, node limits and ages, moved in one call: each step a row
    that takes a node moves its nodes 1 .. count - 1 back one place, and every other slot
    keeps its bits (the slots past a row's count are state too: they are hashed)."""
    fast = LaserSpec(0, LaserKind.CURVY, angle=160.0, speed=150.0, nodes=24, wave=20.0, on=9.0, every=0.5, count=2)
    slow = LaserSpec(0, LaserKind.CURVY, angle=200.0, speed=90.0, nodes=10, spacing=3, on=9.0, every=0.7)
    w = laser_world(fast, slow)
    step_until(w, lambda w, ev: w.lasers.pool.n >= 5)
    p, seen = w.lasers.pool, set()
    for _ in range(90):
        before, counts, n = p.nodes.copy(), p.count.copy(), p.n
        w.step(IDLE)
        assert p.n >= n  # none ended: rows keep their places
        for i in range(n):
            c, was = int(p.count[i]), int(counts[i])
            took = c > was or not np.array_equal(p.nodes[i, 1:c], before[i, 1:c])
            want = before[i].copy()
            if took:
                want[1:c] = before[i, : c - 1]
            want[0] = p.head[i]
            np.testing.assert_array_equal(p.nodes[i], want)
            seen.add((took, c == was))
    assert seen >= {(True, True), (True, False), (False, True)}  # full rows, growing rows, rows waiting


# ------------------------------------------------------------------------- hits, grazes, bombs
def test_hit__is_a_miss_like_a_bullets():
    w = laser_world(straight())
    struck = step_until(w, lambda w, ev: ev.player_struck or ev.player_hit)
    assert struck.player_struck and lit(w)  # struck by the lit laser, never by its warning
    assert w.player.misses == 0
    for _ in range(DEATHBOMB_FRAMES):
        w.step(Input())
    assert w.player.misses == 1


def test_hit__a_death_bomb_saves_and_cancels_the_lasers_into_stars():
    w = laser_world(straight(), straight(angle=160.0))
    step_until(w, lambda w, ev: ev.player_struck)
    assert w.lasers.pool.n == 2
    items = w.items.pool.n
    w.step(Input(bomb=True))
    assert w.lasers.pool.n == 0 and w.items.pool.n > items  # stars along the cancelled lasers
    for _ in range(2 * DEATHBOMB_FRAMES):
        w.step(Input())
    assert w.player.misses == 0 and w.progress.bombs_used == 1


def test_bomb__no_laser_fires_while_it_lasts():
    w = laser_world(straight(every=0.5, delay=1.0))
    w.player.bombs = 9
    step_until(w, lambda w, ev: w.lasers.pool.n)
    w.step(Input(bomb=True))
    for _ in range(60):
        w.step(Input())
        assert w.bomb.active and w.lasers.pool.n == 0


def test_graze__once_every_GRAZE_EVERY_steps_while_near_and_never_a_hit():
    w = laser_world(straight())
    w.player.pos[:] = w.player.prev[:] = (252.0, 570.0)  # the graze shape overlaps the laser, the hit shape not
    step_until(w, lambda w, ev: lit(w))
    grazes = w.score.grazes
    assert grazes == 1
    while lit(w):
        w.step(Input())
    assert w.player.misses == 0 and not w.player.stricken
    assert w.score.grazes == len(range(0, frames(1.0), GRAZE_EVERY))


def test_hit__swept_along_the_players_move():
    """A thin laser between where the ship was and where it is: neither pose touches it,
    the swept one does."""
    w = laser_world(straight(width=1.0, tip=1.0))
    w.player.pos[:] = w.player.prev[:] = (228.0, 570.0)
    step_until(w, lambda w, ev: lit(w))
    assert not w.player.stricken
    w.player.prev[:], w.player.pos[:] = (228.0, 570.0), (252.0, 570.0)
    hit = w.kinds.shapes.armatures[w.kinds.base["player"]].vertices
    laser = Laser.of(w.lasers.pool.nodes[0, :2], 1.0)
    assert not laser_touches(laser, hit + w.player.pos) and not laser_touches(laser, hit + w.player.prev)
    record = w.detect()  # the lasers go through the frame's one pipeline call
    assert record.laser_hits_on(Group.PLAYER_PATH)[:, 1].tolist() == [0]  # the swept path touches
    assert record.result.hits.shape == (0, 2)  # and nothing else does
    assert w.lasers.collide(record, w.player, w.score, Events())
    assert w.player.stricken


def test_phase_end__takes_its_lasers():
    w = laser_world(straight())
    w.boss.spec = dataclasses.replace(w.boss.spec, phases=w.boss.spec.phases * 2)
    w.boss.phase_hp, w.boss.phase_limits = w.boss.phase_hp * 2, w.boss.phase_limits * 2
    w.lasers.first.append(w.lasers.first[-1])  # phase 2 fires none
    step_until(w, lambda w, ev: w.lasers.pool.n)
    w.damage_boss(w.boss.hp, Events())
    w.step(Input())
    assert w.boss.phase == 1 and w.lasers.pool.n == 0


# ------------------------------------------------------------------------- state
def test_snapshot__restores_lasers_exactly_and_steps_on_alike():
    specs = (
        straight(kind=LaserKind.BEAM, turn=20.0, warn=0.25, on=3.0, every=2.0),
        LaserSpec(0, LaserKind.CURVY, angle=200.0, speed=120.0, nodes=32, wave=20.0, on=4.0, every=1.0, delay=1.0),
    )
    a = laser_world(*specs)
    a.player.invulnerable = 1e9  # keep it alive and moving
    step_until(a, lambda w, ev: lit(w) and w.lasers.pool.n >= 3, inp=Input(dx=1))
    snaps = Snapshots(a)
    data = snaps.save(a)
    b = laser_world(*specs)
    snaps.restore(b, data)
    assert snaps.save(b) == data and b.lasers.pool.n == a.lasers.pool.n
    for k in range(90):
        inp = Input(dx=1 if (k // 20) % 2 else -1, fire=True)
        a.step(inp)
        b.step(inp)
        assert b.state_hash() == a.state_hash() and part_digests(b) == part_digests(a)
    assert snaps.save(b) == snaps.save(a)


def test_hashing__a_laser_is_in_the_bullets_part_and_the_state_hash():
    w = laser_world(straight())
    step_until(w, lambda w, ev: lit(w))
    digests, digest = part_digests(w), w.state_hash()
    w.lasers.pool.nodes[0, 1, 0] = np.nextafter(w.lasers.pool.nodes[0, 1, 0], np.inf)
    assert differing_part(digests, part_digests(w)) is Part.BULLETS
    w.lasers.pool.nodes[0, 1, 0] += 1.0
    assert w.state_hash() != digest


# ------------------------------------------------------------------------- level syntax
LEVEL = """
[boss]
[[boss.part]]
sprite = "boss_core"
[[boss.phase]]
hp = 100
[[boss.phase.laser]]
{laser}
"""


def load(tmp_path, laser: str):
    path = tmp_path / "lasers.toml"
    path.write_text(LEVEL.format(laser=laser))
    return load_level(path)


def test_level__reads_each_kind(tmp_path):
    aimed = load(tmp_path, 'part = 1\naim = true\ncount = 3\nspread = 40\nwarn = 0.8\ndifficulty = ["hard"]')
    s = aimed.boss.phases[0].lasers[0]
    assert (s.part, s.kind, s.aim, s.angle, s.count, s.spread, s.warn) == (0, LaserKind.STRAIGHT, True, 0.0, 3, 40, 0.8)
    assert s.width == s.tip == 10.0 and [d.value for d in s.difficulties] == ["hard"]
    curvy = load(
        tmp_path, 'part = 1\nkind = "curvy"\nspeed = 90\nnodes = 64\nspacing = 2\nwidth = 8\ntip = 1\nwave = 20'
    )
    s = curvy.boss.phases[0].lasers[0]
    assert (s.kind, s.angle, s.speed, s.nodes, s.spacing, s.width, s.tip, s.wave) == (
        LaserKind.CURVY,
        180.0,
        90,
        64,
        2,
        8,
        1,
        20,
    )


@pytest.mark.parametrize(
    "laser, field, message",
    [
        ('part = 1\nkind = "zigzag"', "kind", "must be one of straight, beam, curvy"),
        ('part = 1\nkind = "curvy"\nwarn = 1', "warn", "not for a curvy laser"),
        ("part = 1\nturn = 30", "turn", "not for a straight laser"),
        ('part = 1\nkind = "beam"\nnodes = 8', "nodes", "not for a beam laser"),
        ("part = 2", "part", "must lie in [1, 1]"),
        ("kind = 'beam'", "part", "missing"),
        ("part = 1\ncount = 3", "spread", "needs a spread"),
        ("part = 1\nwarn = 0.1", "warn", "must lie in [0.25, 10]"),
        ("part = 1\nwidth = nan", "width", "must be finite"),
        ('part = 1\nkind = "curvy"\nnodes = 65', "nodes", "must lie in [2, 64]"),
        ('part = 1\nkind = "curvy"\nspacing = 0', "spacing", "must lie in [1, 8]"),
        ("part = 1\ncolour = 'red'", "colour", "unknown field"),
    ],
)
def test_level__refuses_bad_lasers_naming_file_and_field(tmp_path, laser, field, message):
    with pytest.raises(DataError) as err:
        load(tmp_path, laser)
    text = str(err.value)
    assert text.startswith(f"{tmp_path / 'lasers.toml'}: boss.phase[0].laser[0].{field}: "), text
    assert message in text, text


def test_level__laser_must_be_an_array_of_tables(tmp_path):
    path = tmp_path / "lasers.toml"
    path.write_text('[boss]\n[[boss.part]]\nsprite = "boss_core"\n[[boss.phase]]\nhp = 100\nlaser = 5\n')
    with pytest.raises(DataError, match=r"boss\.phase\[0\]\.laser: must be an array of tables"):
        load_level(path)


def test_shipped__bosses_of_stages_3_to_5_fire_lasers_each_kind_among_them():
    kinds = set()
    for name in ("3-broadsword", "4-storm", "5-citadel"):
        lasers = [s for phase in shipped.level(name).boss.phases for s in phase.lasers]
        assert lasers, name
        assert all(s.kind is LaserKind.CURVY or s.warn >= 0.25 for s in lasers)
        kinds |= {s.kind for s in lasers}
    assert kinds == set(LaserKind)


LASER_LEVEL = """
[player]
lives = 9
[boss]
at = 0
sway = 60
[[boss.part]]
sprite = "boss_core"
[[boss.phase]]
hp = 100000
time = 600
[[boss.phase.laser]]
part = 1
aim = true
count = 2
spread = 30
warn = 0.5
on = 1.0
every = 2.0
delay = 1.0
[[boss.phase.laser]]
part = 1
kind = "beam"
angle = 120
turn = 25
warn = 0.5
on = 2.0
every = 3.0
delay = 1.5
[[boss.phase.laser]]
part = 1
kind = "curvy"
aim = true
speed = 160
nodes = 40
wave = 40
period = 0.9
on = 4.0
every = 1.0
delay = 1.0
"""


def test_recording__a_laser_fight_replays_to_the_same_state_every_frame(tmp_path):
    """The runner records the autopilot against all three kinds; the playback matches each
    frame's part digests and the final hash."""
    from broadsword.headless import run_headless
    from broadsword.runner import Runner, StageStart
    from broadsword.sim import Pilot

    path = tmp_path / "lasers.toml"
    path.write_text(LASER_LEVEL)
    r = Runner.open(StageStart(str(path), 3), shipped.armatures())
    pilot, seen = Pilot(), 0
    while r.frame < 480:
        r.step(pilot(r.world))
        seen = max(seen, len(r.world.lasers.live_rows()))
    assert seen >= 3 and r.world.score.grazes + r.world.player.misses + r.world.progress.bombs_used
    rec = r.recording()
    s = run_headless("", rec.frames, 0, False, rec, str(tmp_path / "run.json"))[0]
    assert s["replay_matches"] is True and s["state_hash"] == r.world.state_hash()


def test_snapshot__format_2_is_still_read_with_no_laser_in_play():
    """A snapshot written before lasers (version 2: no ``lasers`` section) restores, and the
    world it makes has none in play."""
    import zlib

    from broadsword.sim.snapshot import MAGIC

    a = laser_world(straight())
    step_until(a, lambda w, ev: w.frame >= 30)
    snaps = Snapshots(a)
    data = snaps.save(a)
    assert a.lasers.pool.n == 0
    body = data[: data.index(b"\x06\x00\x00\x00lasers")]
    body = (
        body[: len(MAGIC)] + (2).to_bytes(8, "little") + (len(body) + 4).to_bytes(8, "little") + body[len(MAGIC) + 16 :]
    )
    old = body + zlib.crc32(body).to_bytes(4, "little")
    b = laser_world(straight())
    step_until(b, lambda w, ev: w.lasers.pool.n)
    snaps.restore(b, old)
    assert b.lasers.pool.n == 0 and snaps.save(b) == data


# ------------------------------------------------------------------------- the hit log
def test_hit_log__a_laser_death_names_the_laser_and_its_piece():
    w = laser_world(straight(), straight(angle=120.0))  # the second points away from the player
    step_until(w, lambda w, ev: ev.player_struck)
    record, pending = w.collision, w.hit_log.pending
    assert pending is not None and pending.frame == w.frame and len(pending.hitters) == 1
    h = pending.hitters[0]
    assert h.source is HitSource.LASER and h.kind == "straight laser 1 of phase 1"
    assert h.laser is not None and h.laser.laser.row == 0 and (h.laser.piece, h.laser.join) == (0, False)
    x, y, _ = laser_pieces(w.lasers.pool.nodes[0, :2], w.lasers.widths(0))
    np.testing.assert_array_equal(h.polygon, np.stack([x[:, 0], y[:, 0]], axis=1))  # the piece itself
    path = record.spans[Group.PLAYER_PATH].start
    np.testing.assert_array_equal(h.laser.path, posed_polygon(record.result.posed, path))
    assert h.explanation.touching and h.explanation == explain(h.laser.path, h.polygon)
    assert [t.tier for t in h.tiers] == ["layers", *record.result.tiers]
    assert all(t.verdict is Verdict.PASSED for t in h.tiers)
    hit = step_until(w, lambda w, ev: ev.hit is not None).hit
    assert hit.outcome is Outcome.MISS and hit.hitters[0].laser.laser.kind == "straight"
    doc = hit_json(LoggedHit(hit, 0, "3-broadsword", w.frame))
    assert doc["hit_by"][0]["what"] == "laser"
    assert doc["hit_by"][0]["laser"] | {"path": None} == {
        "kind": "straight",
        "phase": 1,
        "entry": 1,
        "piece": 0,
        "join": False,
        "path": None,
    }


def test_hit_log__a_laser_crossed_between_steps_touches_the_path_not_the_pose():
    w = laser_world(straight(width=1.0, tip=1.0))
    w.player.pos[:] = w.player.prev[:] = (228.0, 570.0)
    step_until(w, lambda w, ev: lit(w))
    w.player.prev[:], w.player.pos[:] = (228.0, 570.0), (252.0, 570.0)
    hit = hit_record(w.detect(), w.kinds, w.frame)
    assert hit is not None and [h.source for h in hit.hitters] == [HitSource.LASER]
    h = hit.hitters[0]
    assert h.explanation.touching and not explain(hit.player, h.polygon).touching
    assert len(h.laser.path) > len(hit.player)  # the hull swept: both ends' vertices
