"""What the side panel shows beside the field (:class:`~.sidebar.PanelInfo`), from the scene
stack: the best score on the difficulty in view, the run's mark, the last input."""

from __future__ import annotations

from ..data.recordings import RunKind
from ..sim import Input
from .scenes.context import SceneContext
from .scenes.play import Play
from .scenes.theatre import Theatre
from .sidebar import Mark, PanelInfo


def panel_info(ctx: SceneContext) -> PanelInfo:
    """The side panel's best score (on the difficulty of the world in view, else the chosen
    one) and its mark: "REPLAY" in the theatre, "DEMO" while the autopilot plays, "PRACTICE"
    in a practice, "TAKE-OVER" in a run taken over from a replay, none while the player plays
    a run; and the last step's input, as recorded, when the options show it."""
    play = ctx.scenes.find(Play)
    theatre = ctx.scenes.find(Theatre) if play is None else None
    mark = None
    if play is not None and play.watched:
        mark = Mark.DEMO
    elif play is not None and play.practice is not None:
        mark = Mark.PRACTICE
    elif play is not None and play.runner.recorder.info.kind is RunKind.TAKE_OVER:
        mark = Mark.TAKE_OVER
    elif theatre is not None:
        mark = Mark.REPLAY
    world = play.world if play is not None else theatre.world if theatre is not None else None
    difficulty = world.settings.difficulty if world is not None else ctx.difficulty
    held = None
    runner = play.runner if play is not None else theatre.runner if theatre is not None else None
    if runner is not None and ctx.options.input_display:
        # the last step's input, as recorded: the player's, the autopilot's, a replay's
        held = runner.recorder.last_input or Input()
    return PanelInfo(max((e.score for e in ctx.scores.of(difficulty)), default=0), mark, held)
