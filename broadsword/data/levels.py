"""Level files (``levels/*.toml``): the scene a level needs, its waves and its boss.

The format is documented, with an example, in docs/FORMATS.md. Every number is checked
against its range, every name against what the game knows, and unknown keys are errors
(a typo should not be silently ignored); a :class:`DataError` names the file and the
field, e.g. ``levels/1-picket.toml: wave[2].path: must be one of straight, sine, ...``.

Limits: a file of at most ``LEVEL_MAX_BYTES`` (1 MiB, checked before parsing), UTF-8
TOML; numbers finite (``nan`` and ``inf`` are refused) and in their ranges; at most
``WAVES_MAX`` waves sending ``SHIPS_MAX`` ships in all, and ``PARTS_MAX`` boss parts;
text one printable line of at most ``TEXT_MAX_CHARS``; sprite names are names
(``SPRITE_NAME``), never paths, so ``../x`` or ``/x`` cannot reach outside the assets.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from enum import Enum
from pathlib import Path

from ..collision import BOUND_TIERS, BROAD_PHASES, LAST_TIERS, ROTATION_MODES
from .errors import DataError, shown
from .resources import read_toml



class PathKind(str, Enum):
    """How a wave's ships fly (``path`` in a level file); each kind is one function in
    :mod:`broadsword.sim.motion`."""

    STRAIGHT = "straight"
    SINE = "sine"
    ARC = "arc"
    DIVE = "dive"
    HOLD = "hold"


class FireKind(str, Enum):
    """What a ship fires (``fire`` in a level file)."""

    NONE = "none"
    AIMED = "aimed"
    SPREAD = "spread"
    RING = "ring"
    SPIRAL = "spiral"


PATHS = tuple(k.value for k in PathKind)
PATTERNS = tuple(k.value for k in FireKind)
#: A level file is at most this big; a larger one is refused by its size, unparsed.
LEVEL_MAX_BYTES = 1 << 20
WAVES_MAX = 256
#: Ships all the waves of a level send, mirrored ones counted: more would only stall the game.
SHIPS_MAX = 10_000
PARTS_MAX = 16
#: A boss part sits at most this many px from the boss's centre, in x and in y.
OFFSET_MAX = 1000.0
#: Titles, names and other text: one line of at most this many characters.
TEXT_MAX_CHARS = 80
#: Sprite names, as armature files name themselves: never a path.
SPRITE_NAME = re.compile(r"[a-z][a-z0-9_-]{0,31}\Z")


@dataclass(frozen=True)
class SceneSpec:
    """What the level's collision scene computes; nothing it does not name is computed."""

    tiers: tuple[str, ...] = ("bins", "aabb", "armature")
    rotation: str = "lut"
    bin_size: float | None = None  # None: automatic
    graze: bool = True


@dataclass(frozen=True)
class PlayerSpec:
    speed: float = 240.0  # px/s
    slow_speed: float = 110.0
    fire_every: float = 0.07  # s between volleys
    shot_speed: float = 900.0
    lives: int = 3


@dataclass(frozen=True)
class FireSpec:
    pattern: FireKind = FireKind.NONE
    bullet: str = "pellet"
    speed: float = 160.0  # px/s
    every: float = 1.5  # s between volleys
    shots: int = 1  # bullets per volley
    spread: float = 0.0  # degrees across a spread volley
    spin: float = 0.0  # degrees the volley turns each time (spirals)
    delay: float = 0.5  # s after spawning before the first volley

    def __post_init__(self):
        object.__setattr__(self, "pattern", FireKind(self.pattern))  # a name from a file or a test

    @property
    def fires(self) -> bool:
        return self.pattern is not FireKind.NONE


@dataclass(frozen=True)
class PathSpec:
    kind: PathKind = PathKind.STRAIGHT
    x: float = 240.0  # entry x, px
    speed: float = 120.0  # px/s
    amplitude: float = 60.0  # sine
    period: float = 2.0  # sine, s
    radius: float = 120.0  # arc
    turn: float = 180.0  # arc, degrees (sign = direction)
    dive_at: float = 200.0  # dive: y where it turns toward the player
    hold_y: float = 160.0  # hold
    hold_for: float = 4.0  # hold, s

    def __post_init__(self):
        object.__setattr__(self, "kind", PathKind(self.kind))  # a name from a file or a test


@dataclass(frozen=True)
class WaveSpec:
    at: float  # s after the level starts
    enemy: str  # armature/sprite name
    count: int
    every: float
    hp: int
    score: int
    path: PathSpec
    fire: FireSpec
    mirror: bool  # also spawn each ship mirrored about the centre line


@dataclass(frozen=True)
class BossPart:
    sprite: str
    offset: tuple[float, float]
    spin: float  # degrees per second
    fire: FireSpec


@dataclass(frozen=True)
class BossPhaseSpec:
    """One phase of a boss fight: the damage it takes to end it."""

    hp: int


@dataclass(frozen=True)
class BossSpec:
    at: float
    hp: int  # in all, over every phase
    score: int
    y: float  # where it holds
    sway: float  # px of side-to-side sway
    parts: tuple[BossPart, ...]
    phases: tuple[BossPhaseSpec, ...] = ()  # () : one phase of ``hp``

    def __post_init__(self):
        if not self.phases:
            object.__setattr__(self, "phases", (BossPhaseSpec(self.hp),))


@dataclass(frozen=True)
class Level:
    name: str
    title: str
    path: Path
    scene: SceneSpec
    player: PlayerSpec
    waves: tuple[WaveSpec, ...]
    boss: BossSpec | None

    @property
    def sprites(self) -> set[str]:
        """Every sprite/armature name the level uses."""
        names = {w.enemy for w in self.waves} | {w.fire.bullet for w in self.waves if w.fire.fires}
        if self.boss:
            names |= {p.sprite for p in self.boss.parts}
            names |= {p.fire.bullet for p in self.boss.parts if p.fire.fires}
        return names


_MISSING = object()  # a required key's "default"


class _Table:
    """Typed, range-checked access to one TOML table; errors name file and field.

    Every getter takes the key and its default (``_MISSING``: the key is required) and
    refuses a value of the wrong type or out of range, saying what is expected.
    """

    def __init__(self, doc, path: Path, where: str):
        if not isinstance(doc, dict):
            raise DataError(path, where, f"must be a table, got {shown(doc)}")
        self.doc, self.path, self.where, self.used = doc, path, where, set()

    def _field(self, key):
        return f"{self.where}.{key}" if self.where else key

    def _get(self, key, default):
        self.used.add(key)
        v = self.doc.get(key, default)
        if v is _MISSING:
            raise DataError(self.path, self._field(key), "missing: this field is required")
        return v

    def error(self, key, message) -> DataError:
        return DataError(self.path, self._field(key), message)

    def num(self, key, default, lo=-math.inf, hi=math.inf) -> float:
        """A finite number (whole or not) in [lo, hi]."""
        v = self._get(key, default)
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise self.error(key, f"must be a number in [{lo:g}, {hi:g}], got {shown(v)}")
        if isinstance(v, float) and not math.isfinite(v):
            raise self.error(key, f"must be finite, a number in [{lo:g}, {hi:g}]; got {shown(v)}")
        if not lo <= v <= hi:
            raise self.error(key, f"must lie in [{lo:g}, {hi:g}], got {shown(v)}")
        return float(v)

    def int(self, key, default, lo=0, hi=10**9) -> int:
        """A whole number in [lo, hi]."""
        v = self._get(key, default)
        if isinstance(v, bool) or not isinstance(v, int):
            raise self.error(key, f"must be a whole number in [{lo}, {hi}], got {shown(v)}")
        if not lo <= v <= hi:
            raise self.error(key, f"must lie in [{lo}, {hi}], got {shown(v)}")
        return v

    def str(self, key, default, choices=None) -> str:
        """A non-empty one-line string of at most ``TEXT_MAX_CHARS`` (one of ``choices`` if
        given). A default is returned as it is."""
        if key not in self.doc and default is not _MISSING:
            self.used.add(key)
            return default
        v = self._get(key, default)
        if choices is not None and v not in choices:
            raise self.error(key, f"must be one of {', '.join(choices)}; got {shown(v)}")
        if not isinstance(v, str) or not v:
            raise self.error(key, f"must be a non-empty string, got {shown(v)}")
        if len(v) > TEXT_MAX_CHARS or not v.isprintable():
            raise self.error(key, f"must be one line of at most {TEXT_MAX_CHARS} printable characters, got {shown(v)}")
        return v

    def sprite(self, key, default) -> str:
        """A sprite's name (an armature in assets/sprites): a name, never a path."""
        v = self.str(key, default)
        if not SPRITE_NAME.match(v):
            raise self.error(key, "must be a sprite name (a-z first, then a-z, 0-9, _ or -; at most 32), "
                                  f"not a path; got {shown(v)}")
        return v

    def bool(self, key, default) -> bool:
        v = self._get(key, default)
        if not isinstance(v, bool):
            raise self.error(key, f"must be true or false, got {shown(v)}")
        return v

    def done(self, also=()) -> None:
        extra = set(self.doc) - self.used - set(also)
        if extra:
            known = ", ".join(sorted(self.used | set(also)))
            raise self.error(sorted(extra)[0], f"unknown field (expected some of {known})")


#: The keys of a firing pattern (a wave's or a boss part's), read only when it fires.
FIRE_KEYS = ("bullet", "bullet_speed", "fire_every", "shots", "spread", "volley_turn", "fire_delay")


def _fire(t: _Table) -> FireSpec:
    d = FireSpec()
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


def _path(t: _Table) -> PathSpec:
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
    """The scene's tiers, checked as :class:`broadsword.collision.Pipeline` requires: one
    broad phase first, then bounds tiers, then at most one exact tier, last; none twice."""
    known = tuple(BROAD_PHASES) + BOUND_TIERS + LAST_TIERS
    if not (isinstance(value, list) and value and all(isinstance(x, str) for x in value)):
        raise DataError(path, "scene.tiers", f"must be a list of tier names ({', '.join(known)}), got {shown(value)}")
    for x in value:
        if x not in known:
            raise DataError(path, "scene.tiers", f"unknown tier {shown(x)}; tiers are {', '.join(known)}")
    if value[0] not in BROAD_PHASES:
        raise DataError(path, "scene.tiers", f"the first tier must be a broad phase ({', '.join(BROAD_PHASES)})")
    if len(set(value)) != len(value):
        raise DataError(path, "scene.tiers", "must name each tier once")
    rest = value[1:]
    if any(x in BROAD_PHASES for x in rest):
        raise DataError(path, "scene.tiers", "must name only one broad phase, first")
    exact = [x for x in rest if x in LAST_TIERS]
    if len(exact) > 1 or (exact and rest[-1] != exact[0]):
        raise DataError(path, "scene.tiers", f"may end with one exact tier ({', '.join(LAST_TIERS)}), only last")
    return tuple(value)


def _scene(doc, path) -> SceneSpec:
    t = _Table(doc, path, "scene")
    d = SceneSpec()
    tiers = _tiers(t._get("tiers", list(d.tiers)), path)
    size = t._get("bin_size", "auto")
    if size == "auto":
        bin_size = None
    elif _is_number(size) and 1 <= size <= 4096:  # nan and inf fail the range
        bin_size = float(size)
    else:
        raise DataError(path, "scene.bin_size",
                        f'must be "auto" or a finite number of px in [1, 4096], got {shown(size)}')
    spec = SceneSpec(tiers, t.str("rotation", d.rotation, ROTATION_MODES), bin_size, t.bool("graze", d.graze))
    t.done()
    return spec


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _offset(t: _Table) -> tuple[float, float]:
    off = t._get("offset", [0.0, 0.0])
    lim = OFFSET_MAX
    if not (isinstance(off, list) and len(off) == 2 and all(_is_number(c) for c in off)):
        raise t.error("offset", f"must be an [x, y] pair of numbers, got {shown(off)}")
    if not all(-lim <= c <= lim for c in off):  # nan and inf fail the range
        raise t.error("offset", f"must be finite, each in [{-lim:g}, {lim:g}] px; "
                                f"got [{shown(off[0])}, {shown(off[1])}]")
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
    top = _Table(doc, path, "")
    head = _Table(top._get("level", {}), path, "level")
    name = head.str("name", path.stem)
    title = head.str("title", name)
    head.done()
    scene = _scene(top._get("scene", {}), path)
    p = _Table(top._get("player", {}), path, "player")
    d = PlayerSpec()
    player = PlayerSpec(
        p.num("speed", d.speed, 10, 2000), p.num("slow_speed", d.slow_speed, 10, 2000),
        p.num("fire_every", d.fire_every, 0.02, 5), p.num("shot_speed", d.shot_speed, 50, 200_000),
        p.int("lives", d.lives, 1, 99),
    )
    p.done()
    waves_doc = top._get("wave", [])
    if not isinstance(waves_doc, list):
        raise DataError(path, "wave", f"must be an array of tables ([[wave]]), got {shown(waves_doc)}")
    if len(waves_doc) > WAVES_MAX:
        raise DataError(path, "wave", f"must be at most {WAVES_MAX} waves, got {len(waves_doc)}")
    waves, ships = [], 0
    for i, w in enumerate(waves_doc):
        t = _Table(w, path, f"wave[{i}]")
        waves.append(WaveSpec(
            at=t.num("at", 0.0, 0, 3600), enemy=t.sprite("enemy", _MISSING), count=t.int("count", 1, 1, 1000),
            every=t.num("every", 0.5, 0, 60), hp=t.int("hp", 1, 1, 100_000), score=t.int("score", 100, 0, 10**7),
            path=_path(t), fire=_fire(t), mirror=t.bool("mirror", False),
        ))
        t.done(FIRE_KEYS)
        ships += waves[-1].count * (2 if waves[-1].mirror else 1)
        if ships > SHIPS_MAX:
            raise t.error("count", f"the waves up to here send {ships:,} ships; "
                                   f"a level sends at most {SHIPS_MAX:,} in all")
    boss = None
    if "boss" in doc:
        t = _Table(top._get("boss", {}), path, "boss")
        parts_doc = t._get("part", [])
        if not isinstance(parts_doc, list) or not parts_doc:
            raise DataError(path, "boss.part", f"a boss needs at least one [[boss.part]], got {shown(parts_doc)}")
        if len(parts_doc) > PARTS_MAX:
            raise DataError(path, "boss.part", f"must be at most {PARTS_MAX} parts, got {len(parts_doc)}")
        parts = []
        for i, pd in enumerate(parts_doc):
            pt = _Table(pd, path, f"boss.part[{i}]")
            parts.append(BossPart(pt.sprite("sprite", _MISSING), _offset(pt), pt.num("spin", 0.0, -3600, 3600),
                                  _fire(pt)))
            pt.done(FIRE_KEYS)
        boss = BossSpec(t.num("at", 0.0, 0, 3600), t.int("hp", 100, 1, 10**7), t.int("score", 10_000, 0, 10**8),
                        t.num("y", 150.0, 0, 2000), t.num("sway", 80.0, 0, 1000), tuple(parts))
        t.done()
    top.done(("boss",))
    if not doc:  # nothing at all is a broken file; a level that *declares* nothing to fight is fine
        raise DataError(path, "wave", "the file is empty: a level needs at least one [[wave]] or a [boss]")
    return Level(name, title, path, scene, player, tuple(waves), boss)


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
