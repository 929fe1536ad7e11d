"""broadsword.sim: the game's rules and state. Deterministic; no pygame, no files, no clocks.

:class:`World` orders the systems, one module each: :mod:`.player`, :mod:`.weapons`,
:mod:`.motion` (one function per path kind), :mod:`.waves` (the timeline and the ships it
sends), :mod:`.boss`, :mod:`.emitters` (enemy volleys), :mod:`.collide` (the one pipeline
call a frame, and its typed record), :mod:`.combat` (applying hits), :mod:`.scoring`;
with :mod:`.layers`, :mod:`.kinds`, :mod:`.events`, :mod:`.settings`, :mod:`.hashing`,
:mod:`.field`, :mod:`.input`, :mod:`.pool`, the :mod:`.autopilot` and the naive scripted
players of :mod:`.naive` (beginners, for ``broadsword balance``). :mod:`.snapshot` saves and
restores the whole state exactly (:mod:`broadsword.runner.seek` reaches any frame of a run by it).
"""

from .autopilot import Pilot
from .collide import CollisionRecord, Group
from .events import Events
from .field import DT, FIELD, SPAWN
from .input import IDLE, Input
from .layers import GameLayer, LayerIds
from .pool import Pool
from .settings import Carry, Settings, Toggle, ToggleEvent
from .snapshot import Snapshots
from .world import World

__all__ = [
    "DT",
    "FIELD",
    "IDLE",
    "SPAWN",
    "Carry",
    "CollisionRecord",
    "Events",
    "GameLayer",
    "Group",
    "Input",
    "LayerIds",
    "Pool",
    "Settings",
    "Snapshots",
    "Toggle",
    "ToggleEvent",
    "Pilot",
    "World",
]
