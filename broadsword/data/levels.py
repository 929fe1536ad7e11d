"""Level files (``levels/*.toml``): the scene a level needs, its waves and its boss.

The format is documented, with an example, in docs/FORMATS.md. Every number is checked
against its range, every name against what the game knows, and unknown keys are errors
(a typo should not be silently ignored); a :class:`DataError` names the file and the
field, e.g. ``levels/1-picket.toml: wave[2].path: must be one of straight, sine, ...``.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from ..collision import BOUND_TIERS, BROAD_PHASES, LAST_TIERS, ROTATION_MODES
from .errors import DataError

PATHS = ("straight", "sine", "arc", "dive", "hold")
PATTERNS = ("none", "aimed", "spread", "ring", "spiral")


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
    pattern: str = "none"
    bullet: str = "pellet"
    speed: float = 160.0  # px/s
    every: float = 1.5  # s between volleys
    shots: int = 1  # bullets per volley
    spread: float = 0.0  # degrees across a spread volley
    spin: float = 0.0  # degrees the volley turns each time (spirals)
    delay: float = 0.5  # s after spawning before the first volley


@dataclass(frozen=True)
class PathSpec:
    kind: str = "straight"
    x: float = 240.0  # entry x, px
    speed: float = 120.0  # px/s
    amplitude: float = 60.0  # sine
    period: float = 2.0  # sine, s
    radius: float = 120.0  # arc
    turn: float = 180.0  # arc, degrees (sign = direction)
    dive_at: float = 200.0  # dive: y where it turns toward the player
    hold_y: float = 160.0  # hold
    hold_for: float = 4.0  # hold, s


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
class BossSpec:
    at: float
    hp: int
    score: int
    y: float  # where it holds
    sway: float  # px of side-to-side sway
    parts: tuple[BossPart, ...]


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
        names = {w.enemy for w in self.waves} | {w.fire.bullet for w in self.waves if w.fire.pattern != "none"}
        if self.boss:
            names |= {p.sprite for p in self.boss.parts}
            names |= {p.fire.bullet for p in self.boss.parts if p.fire.pattern != "none"}
        return names


class _Table:
    """Typed, range-checked access to one TOML table; errors name file and field."""

    def __init__(self, doc, path: Path, where: str):
        if not isinstance(doc, dict):
            raise DataError(path, where, "must be a table")
        self.doc, self.path, self.where, self.used = doc, path, where, set()

    def _field(self, key):
        return f"{self.where}.{key}" if self.where else key

    def _get(self, key, default):
        self.used.add(key)
        return self.doc.get(key, default)

    def num(self, key, default, lo=-math.inf, hi=math.inf) -> float:
        v = self._get(key, default)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise DataError(self.path, self._field(key), f"must be a number, got {v!r}")
        if not lo <= v <= hi:
            raise DataError(self.path, self._field(key), f"must lie in [{lo:g}, {hi:g}], got {v!r}")
        return float(v)

    def int(self, key, default, lo=0, hi=10**9) -> int:
        v = self._get(key, default)
        if isinstance(v, bool) or not isinstance(v, int):
            raise DataError(self.path, self._field(key), f"must be a whole number, got {v!r}")
        if not lo <= v <= hi:
            raise DataError(self.path, self._field(key), f"must lie in [{lo}, {hi}], got {v!r}")
        return v

    def str(self, key, default, choices=None) -> str:
        v = self._get(key, default)
        if not isinstance(v, str) or not v:
            raise DataError(self.path, self._field(key), f"must be a non-empty string, got {v!r}")
        if choices is not None and v not in choices:
            raise DataError(self.path, self._field(key), f"must be one of {', '.join(choices)}; got {v!r}")
        return v

    def bool(self, key, default) -> bool:
        v = self._get(key, default)
        if not isinstance(v, bool):
            raise DataError(self.path, self._field(key), f"must be true or false, got {v!r}")
        return v

    def done(self, also=()) -> None:
        extra = set(self.doc) - self.used - set(also)
        if extra:
            raise DataError(self.path, self._field(sorted(extra)[0]), "unknown field")


def _fire(t: _Table) -> FireSpec:
    d = FireSpec()
    pattern = t.str("fire", d.pattern, PATTERNS)
    if pattern == "none":
        return FireSpec()
    return FireSpec(
        pattern=pattern,
        bullet=t.str("bullet", d.bullet),
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
        kind=t.str("path", d.kind, PATHS),
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


def _scene(doc, path) -> SceneSpec:
    t = _Table(doc, path, "scene")
    d = SceneSpec()
    tiers = t._get("tiers", list(d.tiers))
    known = tuple(BROAD_PHASES) + BOUND_TIERS + LAST_TIERS
    if not (isinstance(tiers, list) and tiers and all(isinstance(x, str) for x in tiers)):
        raise DataError(path, "scene.tiers", "must be a list of tier names")
    for x in tiers:
        if x not in known:
            raise DataError(path, "scene.tiers", f"unknown tier {x!r}; tiers are {', '.join(known)}")
    if tiers[0] not in BROAD_PHASES:
        raise DataError(path, "scene.tiers", f"the first tier must be a broad phase ({', '.join(BROAD_PHASES)})")
    size = t._get("bin_size", "auto")
    if size == "auto":
        bin_size = None
    elif isinstance(size, (int, float)) and not isinstance(size, bool) and 1 <= size <= 4096:
        bin_size = float(size)
    else:
        raise DataError(path, "scene.bin_size", f'must be "auto" or a number of px in [1, 4096], got {size!r}')
    spec = SceneSpec(tuple(tiers), t.str("rotation", d.rotation, ROTATION_MODES), bin_size, t.bool("graze", d.graze))
    t.done()
    return spec


def load_level(path: str | Path) -> Level:
    """Parse and validate a level file. Raises :class:`DataError` naming file and field."""
    path = Path(path)
    try:
        with open(path, "rb") as fh:
            doc = tomllib.load(fh)
    except OSError as exc:
        raise DataError(path, "", f"cannot read: {exc.strerror or exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise DataError(path, "", f"not valid TOML: {exc}") from None
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
        raise DataError(path, "wave", "must be an array of tables ([[wave]])")
    waves = []
    for i, w in enumerate(waves_doc):
        t = _Table(w, path, f"wave[{i}]")
        waves.append(WaveSpec(
            at=t.num("at", 0.0, 0, 3600), enemy=t.str("enemy", ""), count=t.int("count", 1, 1, 1000),
            every=t.num("every", 0.5, 0, 60), hp=t.int("hp", 1, 1, 100_000), score=t.int("score", 100, 0, 10**7),
            path=_path(t), fire=_fire(t), mirror=t.bool("mirror", False),
        ))
        t.done()
    boss = None
    if "boss" in doc:
        t = _Table(top._get("boss", {}), path, "boss")
        parts_doc = t._get("part", [])
        if not isinstance(parts_doc, list) or not parts_doc:
            raise DataError(path, "boss.part", "a boss needs at least one [[boss.part]]")
        parts = []
        for i, pd in enumerate(parts_doc):
            pt = _Table(pd, path, f"boss.part[{i}]")
            off = pt._get("offset", [0.0, 0.0])
            if not (isinstance(off, list) and len(off) == 2 and all(isinstance(c, (int, float)) and not isinstance(c, bool) for c in off)):
                raise DataError(path, f"boss.part[{i}].offset", f"must be an [x, y] pair, got {off!r}")
            parts.append(BossPart(pt.str("sprite", ""), (float(off[0]), float(off[1])),
                                  pt.num("spin", 0.0, -3600, 3600), _fire(pt)))
            pt.done()
        boss = BossSpec(t.num("at", 0.0, 0, 3600), t.int("hp", 100, 1, 10**7), t.int("score", 10_000, 0, 10**8),
                        t.num("y", 150.0, 0, 2000), t.num("sway", 80.0, 0, 1000), tuple(parts))
        t.done()
    top.done()
    return Level(name, title, path, scene, player, tuple(waves), boss)
