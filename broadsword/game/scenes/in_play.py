"""The stage in play as the screens over it see it (pause, the miss's freeze, results,
continue, game over): :class:`InPlay`, which :class:`.play.Play` is. The screens take this,
not the play scene itself, so the play scene can make them without an import loop."""

from __future__ import annotations

from typing import Protocol

from ...runner import Runner
from ...sim import World
from ..run import Run
from .base import Push


class InPlay(Protocol):
    """A stage in play: its ``world``, the ``run`` it belongs to, the ``runner`` that records
    it; ``accumulator`` is the wall-clock time not yet stepped (a screen leaving sets it to 0:
    no burst of catch-up steps); ``ended`` once its end brought a screen over it."""

    world: World
    run: Run
    runner: Runner
    accumulator: float
    ended: bool

    @property
    def ranked(self) -> bool:
        """The run may enter the high-score table."""
        ...

    def step(self) -> Push | None:
        """One fixed step; the screen its end brings, if any."""
        ...

    def resume(self) -> None:
        """Back from a continue: play on."""
        ...
