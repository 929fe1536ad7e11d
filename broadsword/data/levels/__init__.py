"""Level files (``levels/*.toml``): the typed objects (:mod:`.specs`) and the loader (:mod:`.load`)."""

from .load import (FIRE_KEYS, LEVEL_MAX_BYTES, OFFSET_MAX, PARTS_MAX, SHIPS_MAX, WAVES_MAX, check_level_sprites,
                   load_level)
from .specs import (PATHS, PATTERNS, BossPart, BossPhaseSpec, BossSpec, Drops, FireKind, FireSpec, Level, PathKind,
                    PathSpec, PlayerSpec, SceneSpec, THEMES, Theme, WaveSpec)

__all__ = ["FIRE_KEYS", "LEVEL_MAX_BYTES", "OFFSET_MAX", "PARTS_MAX", "PATHS", "PATTERNS", "SHIPS_MAX", "WAVES_MAX",
           "BossPart", "BossPhaseSpec", "BossSpec", "Drops", "FireKind", "FireSpec", "Level", "PathKind", "PathSpec", "PlayerSpec",
           "SceneSpec", "THEMES", "Theme", "WaveSpec", "check_level_sprites", "load_level"]
