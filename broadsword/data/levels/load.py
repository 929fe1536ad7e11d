"""Level files (``levels/*.toml``): the scene a level needs, its waves and its boss.

The format is documented, with an example, in docs/FORMATS.md. Every number is checked
against its range, every name against what the game knows, and unknown keys are errors
(a typo should not be silently ignored); a :class:`DataError` names the file and the
field, e.g. ``levels/1-picket.toml: wave[2].path: must be one of straight, sine, ...``.

Limits: a file of at most ``LEVEL_MAX_BYTES`` (1 MiB, checked before parsing), UTF-8
TOML; numbers finite (``nan`` and ``inf`` are refused) and in their ranges; at most
``WAVES_MAX`` waves sending ``SHIPS_MAX`` ships in all, and ``PARTS_MAX`` boss parts;
text one printable line of at most ``table.TEXT_MAX_CHARS``; sprite names are names
(``table.SPRITE_NAME``), never paths, so ``../x`` or ``/x`` cannot reach outside the assets.
"""

from __future__ import annotations

from pathlib import Path

from ...collision import ROTATION_MODES, Tier, check_tiers
from ..difficulty import DEFAULT_SPECS, Difficulty, DifficultySpec
from ..errors import DataError, shown
from ..patterns import load_pattern, resolve_pattern
from ..resources import read_toml
from ..table import MISSING, Table
from .specs import (
    BOSS_DROPS,
    LASER_NODES,
    PATHS,
    PATTERNS,
    THEMES,
    BossPart,
    BossPhaseSpec,
    BossSpec,
    Drops,
    FireKind,
    FireSpec,
    LaserKind,
    LaserSpec,
    Level,
    PathKind,
    PathSpec,
    PlayerSpec,
    SceneSpec,
    Theme,
    WaveSpec,
)

#: A level file is at most this big; a larger one is refused by its size, unparsed.
LEVEL_MAX_BYTES = 1 << 20
WAVES_MAX = 256
#: Ships all the waves of a level send, mirrored ones counted: more would only stall the game.
SHIPS_MAX = 10_000
PARTS_MAX = 16
#: A boss part sits at most this many px from the boss's centre, in x and in y.
OFFSET_MAX = 1000.0

#: The keys of a firing pattern (a wave's or a boss part's), read only when it fires.
FIRE_KEYS = (
    "bullet",
    "bullet_speed",
    "fire_every",
    "shots",
    "spread",
    "volley_turn",
    "fire_delay",
    "pattern",
    "pattern_params",
)
#: The keys only the original kinds (``fire = "aimed"``...) read; a pattern file says it all itself.
KIND_KEYS = ("bullet_speed", "fire_every", "shots", "spread", "volley_turn")
#: A pattern file gets at most this many ``pattern_params``.
PATTERN_PARAMS_MAX = 16


def _bulletml(t: Table) -> FireSpec:
    """``pattern = "FILE.xml"`` (beside the level or shipped; see :mod:`..patterns`), with
    optional ``pattern_params``, ``bullet`` and ``fire_delay``."""
    d = FireSpec()
    if "fire" in t.doc:
        raise t.error("fire", "give fire (one of the built-in kinds) or pattern (a BulletML file), not both")
    for key in KIND_KEYS:
        if key in t.doc:
            raise t.error(
                key,
                "only for the built-in kinds (fire = ...); a pattern file says how it fires "
                "(give it numbers with pattern_params)",
            )
    name = t.raw("pattern", "")
    try:
        path = resolve_pattern(name, t.path)
    except ValueError as exc:
        raise t.error("pattern", str(exc)) from None
    try:
        pattern = load_pattern(path)
    except ValueError as exc:
        raise t.error("pattern", f"the pattern file is bad: {exc}") from None
    params = t.raw("pattern_params", [])
    if not (
        isinstance(params, list)
        and len(params) <= PATTERN_PARAMS_MAX
        and all(_is_number(v) for v in params)
        and all(-1e6 <= v <= 1e6 for v in params)
    ):
        raise t.error(
            "pattern_params",
            f"must be a list of at most {PATTERN_PARAMS_MAX} numbers in [-1e6, 1e6] "
            f"($1, $2, ... of the pattern), got {shown(params)}",
        )
    return FireSpec(
        pattern=FireKind.BULLETML,
        bullet=t.sprite("bullet", d.bullet),
        delay=t.num("fire_delay", d.delay, 0, 600),
        file=name,
        params=tuple(params),
        bulletml=pattern,
    )


def _fire(t: Table) -> FireSpec:
    d = FireSpec()
    if "pattern" in t.doc:
        return _bulletml(t)
    if "pattern_params" in t.doc:
        raise t.error("pattern_params", "only with pattern (a BulletML file)")
    pattern = FireKind(t.str("fire", d.pattern.value, PATTERNS))
    if pattern is FireKind.NONE:
        for key in FIRE_KEYS:
            if key in t.doc:
                raise t.error(key, 'only for a ship that fires: set fire to a pattern, not "none"')
        return FireSpec()
    return FireSpec(
        pattern=pattern,
        bullet=t.sprite("bullet", d.bullet),
        speed=t.num("bullet_speed", d.speed, 10, 2000),
        every=t.num("fire_every", d.every, 0.02, 60),
        shots=t.int("shots", d.shots, 1, 256),
        spread=t.num("spread", d.spread, 0, 360),
        spin=t.num("volley_turn", d.spin, -360, 360),
        delay=t.num("fire_delay", d.delay, 0, 600),
    )


def _path(t: Table) -> PathSpec:
    d = PathSpec()
    return PathSpec(
        kind=PathKind(t.str("path", d.kind.value, PATHS)),
        x=t.num("x", d.x, -200, 2000),
        speed=t.num("speed", d.speed, 1, 2000),
        amplitude=t.num("amplitude", d.amplitude, 0, 1000),
        period=t.num("period", d.period, 0.1, 60),
        radius=t.num("radius", d.radius, 1, 2000),
        turn=t.num("turn", d.turn, -1080, 1080),
        dive_at=t.num("dive_at", d.dive_at, -100, 2000),
        hold_y=t.num("hold_y", d.hold_y, -100, 2000),
        hold_for=t.num("hold_for", d.hold_for, 0, 600),
    )


def _tiers(value, path: Path) -> tuple[str, ...]:
    """The scene's tiers, checked by the pipeline's own rule
    (:func:`broadsword.collision.check_tiers`), the error naming the file and field."""
    if not (isinstance(value, list) and value and all(isinstance(x, str) for x in value)):
        raise DataError(path, "scene.tiers", f"must be a list of tier names ({', '.join(Tier)}), got {shown(value)}")
    try:
        return tuple(t.value for t in check_tiers(value))
    except ValueError as err:
        raise DataError(path, "scene.tiers", str(err)) from None


def _scene(doc, path) -> SceneSpec:
    t = Table(doc, path, "scene")
    d = SceneSpec()
    tiers = _tiers(t.raw("tiers", list(d.tiers)), path)
    size = t.raw("bin_size", "auto")
    if size == "auto":
        bin_size = None
    elif _is_number(size) and 1 <= size <= 4096:  # nan and inf fail the range
        bin_size = float(size)
    else:
        raise DataError(
            path, "scene.bin_size", f'must be "auto" or a finite number of px in [1, 4096], got {shown(size)}'
        )
    spec = SceneSpec(tiers, t.str("rotation", d.rotation, ROTATION_MODES), bin_size, t.bool("graze", d.graze))
    t.done()
    return spec


#: A boss has at most this many phases.
PHASES_MAX = 8


def _drops(t: Table, default: Drops) -> Drops:
    """``drops = { power = n, point = n }``: the items left on death."""
    d = Table(t.raw("drops", {}), t.path, t.name_of("drops"))
    out = Drops(d.int("power", default.power, 0, 64), d.int("point", default.point, 0, 64))
    d.done()
    return out


def _phase_fire(p: Table, parts: int) -> tuple[tuple[int, FireSpec], ...]:
    """A phase's ``[[boss.phase.fire]]`` entries: ``part`` (1-based, into ``[[boss.part]]``)
    and that part's pattern in this phase, with the keys of a part's own ``fire``."""
    raw = p.raw("fire", [])
    if not isinstance(raw, list):
        raise p.error("fire", f"must be an array of tables ([[boss.phase.fire]]), got {shown(raw)}")
    out: dict[int, FireSpec] = {}
    for j, doc in enumerate(raw):
        f = Table(doc, p.path, f"{p.where}.fire[{j}]")
        part = f.int("part", MISSING, 1, max(1, parts)) - 1
        if part in out:
            raise f.error("part", f"part {part + 1} already has a pattern in this phase")
        out[part] = _fire(f)
        f.done(FIRE_KEYS)
    return tuple(sorted(out.items()))


#: A phase has at most this many ``[[boss.phase.laser]]`` entries, each a fan of at most LASER_FAN_MAX.
LASERS_MAX, LASER_FAN_MAX = 16, 16
#: The keys only some kinds of laser read.
LASER_KIND_KEYS = {
    LaserKind.STRAIGHT: ("length", "warn"),
    LaserKind.BEAM: ("length", "warn", "turn"),
    LaserKind.CURVY: ("turn", "speed", "nodes", "spacing", "wave", "period"),
}
LASER_KINDS = tuple(k.value for k in LaserKind)


def _laser(f: Table, parts: int) -> LaserSpec:
    """One ``[[boss.phase.laser]]`` (see docs/FORMATS.md, "Lasers")."""
    d = LaserSpec(0)
    kind = LaserKind(f.str("kind", d.kind.value, LASER_KINDS))
    mine = LASER_KIND_KEYS[kind]
    for key in sorted({k for ks in LASER_KIND_KEYS.values() for k in ks} - set(mine)):
        if key in f.doc:
            raise f.error(key, f"not for a {kind.value} laser (it reads {', '.join(mine)})")
    width = f.num("width", d.width, 1, 64)
    aim = f.bool("aim", d.aim)
    spec = LaserSpec(
        part=f.int("part", MISSING, 1, max(1, parts)) - 1,
        kind=kind,
        angle=f.num("angle", 0.0 if aim else d.angle, -360, 360),  # aimed: a turn off the aim
        aim=aim,
        count=f.int("count", d.count, 1, LASER_FAN_MAX),
        spread=f.num("spread", d.spread, 0, 360),
        length=f.num("length", d.length, 8, 2000),
        width=width,
        tip=f.num("tip", width, 0, 64),
        warn=f.num("warn", d.warn, 0.25, 10),  # never less: a straight laser is always seen coming
        on=f.num("on", d.on, 0.1, 30),
        every=f.num("every", d.every, 0.25, 120),
        delay=f.num("delay", d.delay, 0, 600),
        turn=f.num("turn", d.turn, -720, 720),
        speed=f.num("speed", d.speed, 10, 1000),
        nodes=f.int("nodes", d.nodes, 2, LASER_NODES),
        spacing=f.int("spacing", d.spacing, 1, 8),
        wave=f.num("wave", d.wave, 0, 180),
        period=f.num("period", d.period, 0.1, 60),
        difficulties=_difficulties(f),
    )
    if spec.count > 1 and "spread" not in f.doc:
        raise f.error("spread", f"a fan of {spec.count} lasers needs a spread (degrees across it)")
    f.done()
    return spec


def _phase_lasers(p: Table, parts: int) -> tuple[LaserSpec, ...]:
    """A phase's ``[[boss.phase.laser]]`` entries: ``part`` (1-based) and the laser it fires."""
    raw = p.raw("laser", [])
    if not isinstance(raw, list):
        raise p.error("laser", f"must be an array of tables ([[boss.phase.laser]]), got {shown(raw)}")
    if len(raw) > LASERS_MAX:
        raise p.error("laser", f"must be at most {LASERS_MAX} lasers a phase, got {len(raw)}")
    return tuple(_laser(Table(doc, p.path, f"{p.where}.laser[{j}]"), parts) for j, doc in enumerate(raw))


def _phases(t: Table, parts: int) -> tuple[BossPhaseSpec, ...]:
    """``[[boss.phase]]``: each phase's hp, time, bonus and what its parts fire (none: one
    phase of ``boss.hp``); ``parts`` is how many ``[[boss.part]]`` there are."""
    raw = t.raw("phase", [])
    if not isinstance(raw, list):
        raise t.error("phase", f"must be an array of tables ([[boss.phase]]), got {shown(raw)}")
    if len(raw) > PHASES_MAX:
        raise t.error("phase", f"must be at most {PHASES_MAX} phases, got {len(raw)}")
    if raw and "hp" in t.doc:
        raise t.error("hp", "give the hp of each [[boss.phase]] instead, not both")
    out = []
    for i, doc in enumerate(raw):
        p = Table(doc, t.path, f"{t.where}.phase[{i}]")
        d = BossPhaseSpec(1)
        out.append(
            BossPhaseSpec(
                p.int("hp", MISSING, 1, 10**7),
                p.num("time", d.time, 5, 600),
                p.int("bonus", d.bonus, 0, 10**8),
                _phase_fire(p, parts),
                p.str("name", ""),
                _phase_lasers(p, parts),
            )
        )
        p.done()
    return tuple(out)


DIFFICULTIES = tuple(d.value for d in Difficulty)


def _difficulties(t: Table) -> frozenset[Difficulty]:
    """A wave's ``difficulty``: the list of difficulties it flies on (default: all)."""
    v = t.raw("difficulty", list(DIFFICULTIES))
    if not (isinstance(v, list) and v and all(isinstance(x, str) and x in DIFFICULTIES for x in v)):
        raise t.error(
            "difficulty", f"must be a non-empty list of difficulties ({', '.join(DIFFICULTIES)}), got {shown(v)}"
        )
    return frozenset(Difficulty(x) for x in v)


def _difficulty(doc, path: Path) -> dict[Difficulty, DifficultySpec]:
    """The ``[difficulty.NAME]`` tables: each overrides the defaults of its difficulty."""
    top = Table(doc, path, "difficulty")
    out = {}
    for d in Difficulty:
        base = DEFAULT_SPECS[d]
        t = Table(top.raw(d.value, {}), path, f"difficulty.{d.value}")
        lives, bombs, miss_power = t.raw("lives", None), t.raw("bombs", None), t.raw("miss_power", None)
        out[d] = DifficultySpec(
            rank=t.num("rank", base.rank, 0, 1),
            lives=base.lives if lives is None else t.int("lives", base.lives, 1, 99),
            bombs=base.bombs if bombs is None else t.int("bombs", base.bombs, 0, 9),
            enemy_hp=t.num("enemy_hp", base.enemy_hp, 0.1, 10),
            fire_rate=t.num("fire_rate", base.fire_rate, 0.1, 10),
            aimed_rate=t.num("aimed_rate", base.aimed_rate, 0.1, 10),
            aimed_speed=t.num("aimed_speed", base.aimed_speed, 0.1, 10),
            miss_power=base.miss_power if miss_power is None else t.int("miss_power", base.miss_power, 0, 300),
            auto_bomb=t.bool("auto_bomb", base.auto_bomb),
        )
        t.done()
    top.done()
    return out


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _offset(t: Table) -> tuple[float, float]:
    off = t.raw("offset", [0.0, 0.0])
    lim = OFFSET_MAX
    if not (isinstance(off, list) and len(off) == 2 and all(_is_number(c) for c in off)):
        raise t.error("offset", f"must be an [x, y] pair of numbers, got {shown(off)}")
    if not all(-lim <= c <= lim for c in off):  # nan and inf fail the range
        raise t.error(
            "offset", f"must be finite, each in [{-lim:g}, {lim:g}] px; got [{shown(off[0])}, {shown(off[1])}]"
        )
    return float(off[0]), float(off[1])


def load_level(path: str | Path) -> Level:
    """Parse and validate a level file. Raises :class:`DataError` naming file and field.

    The file is at most ``LEVEL_MAX_BYTES`` (refused by its size before it is parsed),
    UTF-8 TOML; it has at most ``WAVES_MAX`` waves (``SHIPS_MAX`` ships in all) and
    ``PARTS_MAX`` boss parts, and is not empty (a level with tables but no wave and no boss
    is allowed: it is complete as soon as it starts). Sprite names are names, not
    paths; whether they name loaded armatures is :func:`check_level_sprites`'s job (the
    armatures are not loaded here).
    """
    path = Path(path)
    doc = read_toml(path, LEVEL_MAX_BYTES, "a level file")
    top = Table(doc, path, "")
    head = Table(top.raw("level", {}), path, "level")
    name = path.stem  # a level's name is its file's stem: never a path
    title = head.str("title", name)
    theme = Theme(head.str("theme", Theme.DEEP_SPACE.value, THEMES))
    head.done()
    scene = _scene(top.raw("scene", {}), path)
    p = Table(top.raw("player", {}), path, "player")
    d = PlayerSpec()
    player = PlayerSpec(
        p.num("speed", d.speed, 10, 2000),
        p.num("slow_speed", d.slow_speed, 10, 2000),
        p.num("fire_every", d.fire_every, 0.02, 5),
        p.num("shot_speed", d.shot_speed, 50, 200_000),
        p.int("lives", d.lives, 1, 99),
        p.int("bombs", d.bombs, 0, 9),
    )
    p.done()
    waves_doc = top.raw("wave", [])
    if not isinstance(waves_doc, list):
        raise DataError(path, "wave", f"must be an array of tables ([[wave]]), got {shown(waves_doc)}")
    if len(waves_doc) > WAVES_MAX:
        raise DataError(path, "wave", f"must be at most {WAVES_MAX} waves, got {len(waves_doc)}")
    waves, ships = [], 0
    for i, w in enumerate(waves_doc):
        t = Table(w, path, f"wave[{i}]")
        waves.append(
            WaveSpec(
                at=t.num("at", 0.0, 0, 3600),
                enemy=t.sprite("enemy", MISSING),
                count=t.int("count", 1, 1, 1000),
                every=t.num("every", 0.5, 0, 60),
                hp=t.int("hp", 1, 1, 100_000),
                score=t.int("score", 100, 0, 10**7),
                path=_path(t),
                fire=_fire(t),
                mirror=t.bool("mirror", False),
                difficulties=_difficulties(t),
                drops=_drops(t, Drops()),
                midboss=t.str("midboss", ""),
            )
        )
        if waves[-1].midboss and (waves[-1].count != 1 or waves[-1].mirror):
            raise t.error("midboss", "a mid-boss is one ship: its wave needs count = 1 and no mirror")
        t.done(FIRE_KEYS)
        ships += waves[-1].count * (2 if waves[-1].mirror else 1)
        if ships > SHIPS_MAX:
            raise t.error(
                "count", f"the waves up to here send {ships:,} ships; a level sends at most {SHIPS_MAX:,} in all"
            )
    boss = None
    if "boss" in doc:
        t = Table(top.raw("boss", {}), path, "boss")
        parts_doc = t.raw("part", [])
        if not isinstance(parts_doc, list) or not parts_doc:
            raise DataError(path, "boss.part", f"a boss needs at least one [[boss.part]], got {shown(parts_doc)}")
        if len(parts_doc) > PARTS_MAX:
            raise DataError(path, "boss.part", f"must be at most {PARTS_MAX} parts, got {len(parts_doc)}")
        parts = []
        for i, pd in enumerate(parts_doc):
            pt = Table(pd, path, f"boss.part[{i}]")
            parts.append(
                BossPart(pt.sprite("sprite", MISSING), _offset(pt), pt.num("spin", 0.0, -3600, 3600), _fire(pt))
            )
            pt.done(FIRE_KEYS)
        phases = _phases(t, len(parts))
        hp = sum(p.hp for p in phases) if phases else t.int("hp", 100, 1, 10**7)
        boss = BossSpec(
            t.num("at", 0.0, 0, 3600),
            hp,
            t.int("score", 10_000, 0, 10**8),
            t.num("y", 150.0, 0, 2000),
            t.num("sway", 80.0, 0, 1000),
            tuple(parts),
            phases,
            _drops(t, BOSS_DROPS),
            t.str("name", ""),
        )
        t.done()
    difficulty = _difficulty(top.raw("difficulty", {}), path)
    top.done(("boss",))
    if not doc:  # nothing at all is a broken file; a level that *declares* nothing to fight is fine
        raise DataError(path, "wave", "the file is empty: a level needs at least one [[wave]] or a [boss]")
    return Level(name, title, path, scene, player, tuple(waves), boss, difficulty, theme)


def check_level_sprites(level: Level, armatures) -> None:
    """Check that every sprite ``level`` names (waves' enemies and bullets, boss parts'
    sprites and bullets) is among ``armatures`` (a mapping or set of names, e.g. what
    :func:`broadsword.data.load_armatures` gives). Raises :class:`DataError` naming the
    level file and the first field that names an unknown sprite, and the known ones."""
    known = set(armatures)

    def check(field: str, name: str) -> None:
        if name not in known:
            raise DataError(level.path, field, f"unknown sprite {shown(name)}; known: {', '.join(sorted(known))}")

    for i, w in enumerate(level.waves):
        check(f"wave[{i}].enemy", w.enemy)
        if w.fire.fires:
            check(f"wave[{i}].bullet", w.fire.bullet)
    for i, part in enumerate(level.boss.parts if level.boss else ()):
        check(f"boss.part[{i}].sprite", part.sprite)
        if part.fire.fires:
            check(f"boss.part[{i}].bullet", part.fire.bullet)
    for i, phase in enumerate(level.boss.phases if level.boss else ()):
        for j, (_, spec) in enumerate(phase.fire):
            if spec.fires:
                check(f"boss.phase[{i}].fire[{j}].bullet", spec.bullet)
