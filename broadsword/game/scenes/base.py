"""The scene protocol, and what a scene asks of the app: its transitions.

A scene is one screen as one object (Python Arcade's ``View``; Game Programming Patterns'
State): it handles events, updates, draws. Scenes sit on a stack (:mod:`.stack`): pausing
pushes the pause screen over play, resuming pops it; the results, continue and game-over
screens are pushed over play the same way, so they draw over the frozen field. Only the top
scene gets events and updates; drawing starts at the highest ``opaque`` scene and goes up.

A scene never changes the stack or the app itself: :meth:`Scene.handle` and
:meth:`Scene.update` *return* a :data:`Transition` (push a scene, replace the top, pop it,
quit, back to the title, start a run...) and the app applies it
(:meth:`broadsword.game.app.App.apply`). What a scene may use -- the painter, audio, options,
controls, scores, replays, the window -- comes in its :class:`~.context.SceneContext`.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import NamedTuple, Protocol, runtime_checkable

import pygame

from ...runner import Runner, Stage
from ..practice_run import PracticeRun
from ..run import Run


@runtime_checkable
class Scene(Protocol):
    #: Draws the whole field itself (scenes below it are not drawn).
    opaque: bool

    def handle(self, event: pygame.event.Event) -> Handled:
        """React to one event: True if it was used (the app then gives it no global meaning,
        e.g. M typed into a name is not mute), False if not, or a transition (used, and the
        app applies it). A window close (``pygame.QUIT``) is offered too: True keeps the
        game open (the editor with unsaved changes warns first)."""

    def update(self, dt: float) -> Tick:
        """Advance by ``dt`` real seconds: the world steps taken (0 for menus), and the
        transition due, if one is."""

    def draw(self, surf: pygame.Surface) -> None:
        """Draw onto the field surface."""


class Go(Enum):
    """The transitions that need nothing more said."""

    POP = "pop"  # the top scene goes (an empty stack: the title)
    QUIT = "quit"  # the game closes
    TO_TITLE = "to title"  # every scene goes; the title (a run quit mid-way is kept first)
    START_RUN = "start run"  # a run from the stage and difficulty chosen on the title


@dataclass(frozen=True)
class Push:
    """``scene`` goes on top (the one under it stays, frozen)."""

    scene: Scene


@dataclass(frozen=True)
class Replace:
    """``scene`` takes the top scene's place."""

    scene: Scene


@dataclass(frozen=True)
class Reset:
    """Every scene goes; ``scene`` alone."""

    scene: Scene


@dataclass(frozen=True)
class NextStage:
    """The run's next stage (``run.level_index`` already moved on), recorded with the run in
    play; a stage that cannot load: the title, saying why."""

    run: Run


@dataclass(frozen=True)
class PlayStage:
    """Play ``stage`` (a world already made) as the only scene, in ``runner`` (which records
    it), as part of ``run``; ``practice``: as that practice."""

    stage: Stage
    run: Run
    runner: Runner
    practice: PracticeRun | None = None


#: What a scene may ask of the app.
Transition = Go | Push | Replace | Reset | NextStage | PlayStage
#: What :meth:`Scene.handle` returns: used (True) or not (False), or a transition (used).
Handled = bool | Transition


class Tick(NamedTuple):
    """What :meth:`Scene.update` did: the world ``steps`` it took, and the transition due
    after them (``then``; None: the scene stays)."""

    steps: int = 0
    then: Transition | None = None


#: An update that took no step and asks for nothing (every menu's).
IDLE = Tick()
