"""broadsword.data: level and asset files -> validated, typed objects. Parsing only.

Files are TOML read with :mod:`tomllib`; nothing in them is ever executed. A file that
fails to load raises :class:`DataError`, whose message names the file and the field.
"""

from .armatures import ArmatureFile, load_armature_file, load_armatures
from .errors import DataError
from .levels import BossPart, BossSpec, Level, PlayerSpec, SceneSpec, WaveSpec, check_level_sprites, load_level
from .resources import data_dir, list_levels, resolve_level

__all__ = [
    "ArmatureFile",
    "BossPart",
    "BossSpec",
    "DataError",
    "Level",
    "PlayerSpec",
    "SceneSpec",
    "WaveSpec",
    "check_level_sprites",
    "data_dir",
    "list_levels",
    "load_armature_file",
    "load_armatures",
    "load_level",
    "resolve_level",
]
