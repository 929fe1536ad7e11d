"""The pattern model: a BulletML file as typed, validated, immutable objects.

References (``actionRef``, ``fireRef``, ``bulletRef``) keep their label and are looked up in
the :class:`Pattern`'s tables when they run; the loader has checked that every label exists
and that no chain of references loops.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from .expr import Expr


class Orientation(Enum):
    """``<bulletml type=...>``. HORIZONTAL turns absolute directions by -90 degrees and
    swaps accel's axes (horizontal -> -y, vertical -> x), as libBulletML does."""

    NONE = "none"
    VERTICAL = "vertical"
    HORIZONTAL = "horizontal"


class DirKind(Enum):
    """``<direction type=...>``; the default is AIM."""

    AIM = "aim"
    ABSOLUTE = "absolute"
    RELATIVE = "relative"
    SEQUENCE = "sequence"


class SpeedKind(Enum):
    """``type`` of ``<speed>``, ``<horizontal>`` and ``<vertical>``; the default is ABSOLUTE."""

    ABSOLUTE = "absolute"
    RELATIVE = "relative"
    SEQUENCE = "sequence"


@dataclass(frozen=True)
class Direction:
    kind: DirKind
    expr: Expr


@dataclass(frozen=True)
class Speed:
    """A ``<speed>``, ``<horizontal>`` or ``<vertical>`` value."""

    kind: SpeedKind
    expr: Expr


@dataclass(frozen=True)
class Ref:
    """A reference to the labelled element ``label``, passing ``params`` as ``$1``, ``$2``..."""

    label: str
    params: tuple[Expr, ...]


class ActionRef(Ref):
    pass


class FireRef(Ref):
    pass


class BulletRef(Ref):
    pass


@dataclass(frozen=True)
class Action:
    label: str | None
    commands: tuple[Command, ...]


@dataclass(frozen=True)
class Bullet:
    """``actions`` run one after another in the bullet's own runner: first its ``<action>``
    children, then its ``<actionRef>`` children (libBulletML's order)."""

    label: str | None
    direction: Direction | None
    speed: Speed | None
    actions: tuple[Action | ActionRef, ...]


@dataclass(frozen=True)
class Fire:
    label: str | None
    direction: Direction | None
    speed: Speed | None
    bullet: Bullet | BulletRef


@dataclass(frozen=True)
class ChangeDirection:
    direction: Direction
    term: Expr


@dataclass(frozen=True)
class ChangeSpeed:
    speed: Speed
    term: Expr


@dataclass(frozen=True)
class Accel:
    horizontal: Speed | None
    vertical: Speed | None
    term: Expr


@dataclass(frozen=True)
class Wait:
    frames: Expr


@dataclass(frozen=True)
class Vanish:
    pass


@dataclass(frozen=True)
class Repeat:
    times: Expr
    body: Action | ActionRef


Command = Action | ActionRef | Fire | FireRef | ChangeDirection | ChangeSpeed | Accel | Wait | Vanish | Repeat


@dataclass(frozen=True)
class Pattern:
    """A loaded BulletML file. ``top`` are the actions labelled ``top``, ``top1``, ``top2``...
    (every label starting with "top", in file order), which run together (none: the file
    fires nothing); the tables map labels to every labelled action, bullet and fire in the
    file. ``warnings`` are the leniencies the loader allowed (docs/PATTERNS.md, "Leniencies"),
    one line each, never printed by the loader. ``top_params`` is the highest ``$n`` the top
    actions read from the parameters they are given (0: they need none)."""

    name: str
    orientation: Orientation
    top: tuple[Action, ...]
    actions: dict[str, Action]
    bullets: dict[str, Bullet]
    fires: dict[str, Fire]
    warnings: tuple[str, ...] = ()
    top_params: int = 0
