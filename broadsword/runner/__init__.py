"""The game runner, between ``sim`` and ``game`` (no pygame; it may read files): opening a
stage with its seed, settings and carried state, stepping it with inputs, recording the
run, checking a playback, and the observers a caller chooses. Headless play, the soak,
balance, the benchmark's game frame, the tools and the play scene all run the game here:
nothing else steps a :class:`~broadsword.sim.World` in a loop.
"""

from .observers import Observer, PeakBullets, StateHashes, TierTally
from .playback import CHECKPOINT, Divergence, Mismatch, Playback
from .recorder import PARTS, Recorder
from .runner import Runner
from .stages import Stage, StageStart, open_level, open_recorded, open_stage, shipped_armatures

__all__ = [
    "CHECKPOINT",
    "PARTS",
    "Divergence",
    "Mismatch",
    "Observer",
    "PeakBullets",
    "Playback",
    "Recorder",
    "Runner",
    "Stage",
    "StageStart",
    "StateHashes",
    "TierTally",
    "open_level",
    "open_recorded",
    "open_stage",
    "shipped_armatures",
]
