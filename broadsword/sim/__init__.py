"""broadsword.sim: the game's rules and state. Deterministic; no pygame, no files, no clocks."""

from .autopilot import autopilot
from .input import IDLE, Input
from .pool import Pool
from .world import DT, FIELD, LAYERS, Events, World

__all__ = ["DT", "FIELD", "IDLE", "LAYERS", "Events", "Input", "Pool", "World", "autopilot"]
