"""The typed objects a level file becomes: its scene, player, waves and boss."""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import TYPE_CHECKING

from ..difficulty import DEFAULT_SPECS, Difficulty, DifficultySpec

if TYPE_CHECKING:
    from ...patterns.bulletml import Pattern


class PathKind(str, Enum):
    """How a wave's ships fly (``path`` in a level file); each kind is one function in
    :mod:`broadsword.sim.motion`."""

    STRAIGHT = "straight"
    SINE = "sine"
    ARC = "arc"
    DIVE = "dive"
    HOLD = "hold"


class Theme(str, Enum):
    """A stage's look: its backdrop and palette (drawn by :mod:`broadsword.game.backdrop`)."""

    DEEP_SPACE = "deep_space"
    DUST_BELT = "dust_belt"
    CRIMSON_NEBULA = "crimson_nebula"
    ION_STORM = "ion_storm"
    CITADEL = "citadel"


THEMES = tuple(t.value for t in Theme)


class FireKind(str, Enum):
    """What a ship fires: ``fire`` in a level file names one of the original kinds, each a
    shipped BulletML file fed the level's numbers; ``pattern`` names a BulletML file
    (BULLETML)."""

    NONE = "none"
    AIMED = "aimed"
    SPREAD = "spread"
    RING = "ring"
    SPIRAL = "spiral"
    BULLETML = "bulletml"


PATHS = tuple(k.value for k in PathKind)
#: What ``fire`` may say (a BulletML file is named by ``pattern`` instead).
PATTERNS = tuple(k.value for k in FireKind if k is not FireKind.BULLETML)


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
    bombs: int = 3


@dataclass(frozen=True)
class FireSpec:
    """What one ship or boss part fires: always a BulletML pattern (``bulletml``) run from
    the shooter, starting ``delay`` s after it appears. The original kinds (``aimed``...)
    are the shipped files ``assets/patterns/KIND.xml`` fed ``speed``, ``shots``,
    ``spread``/``spin`` and ``every`` as ``$1``..``$4`` (the sim converts them to frames);
    a level's own ``pattern`` file gets ``params`` as ``$1``, ``$2``..."""

    pattern: FireKind = FireKind.NONE
    bullet: str = "pellet"
    speed: float = 160.0  # px/s
    every: float = 1.5  # s between volleys
    shots: int = 1  # bullets per volley
    spread: float = 0.0  # degrees across a spread volley
    spin: float = 0.0  # degrees the volley turns each time (spirals)
    delay: float = 0.5  # s after spawning before the first volley
    file: str = ""  # BULLETML: the level's ``pattern`` value, as written
    params: tuple[float, ...] = ()  # BULLETML: ``$1``, ``$2``...
    bulletml: Pattern | None = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        object.__setattr__(self, "pattern", FireKind(self.pattern))  # a name from a file or a test
        object.__setattr__(self, "params", tuple(float(p) for p in self.params))
        if self.bulletml is None and self.fires:
            if self.pattern is FireKind.BULLETML:
                raise ValueError("a BulletML FireSpec needs its loaded pattern (bulletml=...)")
            from ..patterns import shipped_kind  # the original kinds are shipped files

            object.__setattr__(self, "bulletml", shipped_kind(self.pattern.value))

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
class Drops:
    """Items an enemy leaves when it dies."""

    power: int = 1
    point: int = 1


#: The time limit of a boss given without phases (its one phase), s.
FLAT_PHASE_TIME = 600.0
#: What a boss leaves when it dies, unless its level says otherwise.
BOSS_DROPS = Drops(power=8, point=16)


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
    difficulties: frozenset[Difficulty] = frozenset(Difficulty)  # the difficulties it flies on
    drops: Drops = Drops()
    midboss: str = ""  # a mid-boss's name, shown over its health bar ("": an ordinary wave)


@dataclass(frozen=True)
class BossPart:
    sprite: str
    offset: tuple[float, float]
    spin: float  # degrees per second
    fire: FireSpec


#: What a part that does not fire in a phase fires.
SILENT = FireSpec()


class LaserKind(str, Enum):
    """How a laser moves (``kind`` of a ``[[boss.phase.laser]]``); each is drawn, collided and
    moved by :mod:`broadsword.sim.lasers`."""

    STRAIGHT = "straight"  # a warning line, then on for a while, then gone
    BEAM = "beam"  # a straight laser that turns about its origin while on
    CURVY = "curvy"  # a chain of nodes trailing a moving head


#: A curvy laser has at most this many nodes (the sim keeps a fixed row of them per laser).
LASER_NODES = 64


@dataclass(frozen=True)
class LaserSpec:
    """One laser (or fan of lasers) a boss part fires in a phase, every ``every`` s from
    ``delay`` s after the phase starts. Angles are BulletML headings (degrees, 0 = up,
    clockwise on screen: 180 is straight down); ``aim`` adds the heading to the player
    (a level file's aimed laser has ``angle`` 0 unless it says).

    ``length`` and ``warn`` are for straight lasers and beams, ``turn`` (degrees per second)
    turns a beam while it is on and a curvy laser's head all its life; ``speed``, ``nodes``,
    ``spacing``, ``wave`` and ``period`` shape a curvy laser (its head wobbles ``wave`` degrees each way
    every ``period`` s). ``width`` is the full width at the origin (a curvy laser's head),
    ``tip`` at the far end (its tail): equal for a uniform laser, else tapered."""

    part: int  # 0-based, into BossSpec.parts
    kind: LaserKind = LaserKind.STRAIGHT
    angle: float = 180.0
    aim: bool = False
    count: int = 1
    spread: float = 0.0  # degrees across the fan
    length: float = 480.0  # px
    width: float = 10.0  # px
    tip: float = 10.0  # px
    warn: float = 1.0  # s of warning line before a straight laser or beam turns on
    on: float = 1.5  # s on (a curvy laser: its whole life)
    every: float = 4.0  # s between firings
    delay: float = 1.0  # s after the phase starts
    turn: float = 0.0  # degrees per second
    speed: float = 180.0  # px/s, a curvy laser's head
    nodes: int = 32  # a curvy laser's
    spacing: int = 1  # steps of the head's path between two of a curvy laser's nodes
    wave: float = 0.0  # degrees
    period: float = 1.0  # s
    difficulties: frozenset[Difficulty] = frozenset(Difficulty)

    def __post_init__(self):
        object.__setattr__(self, "kind", LaserKind(self.kind))  # a name from a file or a test


@dataclass(frozen=True)
class BossPhaseSpec:
    """One phase of a boss fight: the damage that ends it, the seconds it lasts at most
    (running out ends it with no bonus), the bonus for ending it without a miss or a
    bomb, and what its parts fire.

    ``fire`` pairs a part's index (0-based, into :attr:`BossSpec.parts`) with its pattern
    in this phase; when ``fire`` is empty every part fires its own ``fire``, otherwise only
    the parts named here fire."""

    hp: int
    time: float = 40.0
    bonus: int = 10_000
    fire: tuple[tuple[int, FireSpec], ...] = ()
    name: str = ""  # shown on the boss bar while the phase lasts ("": "phase N")
    lasers: tuple[LaserSpec, ...] = ()  # what the parts fire besides bullets


@dataclass(frozen=True)
class BossSpec:
    at: float
    hp: int  # in all, over every phase
    score: int
    y: float  # where it holds
    sway: float  # px of side-to-side sway
    parts: tuple[BossPart, ...]
    phases: tuple[BossPhaseSpec, ...] = ()  # () : one phase of ``hp``
    drops: Drops = field(default_factory=lambda: BOSS_DROPS)
    name: str = ""  # shown on the boss bar and the side panel ("": "BOSS")

    def __post_init__(self):
        if not self.phases:  # the flat form: one phase with all the hit points and no hurry
            object.__setattr__(self, "phases", (BossPhaseSpec(self.hp, time=FLAT_PHASE_TIME, bonus=0),))

    def fire_of(self, phase: int, part: int) -> FireSpec:
        """What part ``part`` fires in phase ``phase`` (both 0-based); a silent part gets
        ``FireSpec()`` (pattern ``none``)."""
        own = self.phases[phase].fire
        if not own:
            return self.parts[part].fire
        return next((spec for i, spec in own if i == part), SILENT)


@dataclass(frozen=True)
class Level:
    name: str
    title: str
    path: Path
    scene: SceneSpec
    player: PlayerSpec
    waves: tuple[WaveSpec, ...]
    boss: BossSpec | None
    difficulty: dict[Difficulty, DifficultySpec] = field(default_factory=lambda: dict(DEFAULT_SPECS))
    theme: Theme = Theme.DEEP_SPACE

    @property
    def sprites(self) -> set[str]:
        """Every sprite/armature name the level uses."""
        names = {w.enemy for w in self.waves} | {w.fire.bullet for w in self.waves if w.fire.fires}
        if self.boss:
            names |= {p.sprite for p in self.boss.parts}
            names |= {p.fire.bullet for p in self.boss.parts if p.fire.fires}
            names |= {f.bullet for phase in self.boss.phases for _, f in phase.fire if f.fires}
        return names
