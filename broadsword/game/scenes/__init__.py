"""The game's screens, one object each, run on a stack (:mod:`.stack`); each gets a typed
context (:mod:`.context`) and returns its transitions (:mod:`.base`) for the app to apply.

:class:`Title` (choose a stage and difficulty) -> :class:`Play` (a stage in play) with
:class:`Pause`, :class:`Results` (after each stage), :class:`Continue` (after a game over,
while continues remain) and :class:`GameOver` (the run's end, or its victory) pushed over
it; :class:`NameEntry` and :class:`HighScoresScene` after a run; :class:`OptionsScene`
from the title; the replay list and the theatre (:mod:`.replay_list`, :mod:`.theatre`); the lab
(:mod:`.lab`) and the editor (:mod:`.editor`) wrap their own objects.
"""

from .base import Scene
from .continue_screen import Continue
from .game_over import GameOver
from .high_scores import HighScoresScene
from .name_entry import NameEntry
from .options_screen import OptionsScene
from .pause import Pause
from .play import Play
from .results import Results
from .stack import SceneStack
from .title import Title

__all__ = [
    "Continue",
    "GameOver",
    "HighScoresScene",
    "NameEntry",
    "OptionsScene",
    "Pause",
    "Play",
    "Results",
    "Scene",
    "SceneStack",
    "Title",
]
