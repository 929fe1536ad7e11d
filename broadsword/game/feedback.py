"""What the player sees and hears of each step: the step's :class:`~broadsword.sim.events.Events`
turned into effects and captions on the field (:class:`~.render.Renderer`) and sounds
(:class:`~.audio.Audio`).

Presentation only: it reads the events and the world, never changes either (its only
randomness is the renderer's cosmetic generator), so a replay is the same with or without it.

=================  ====================================  ==============
event              seen                                   heard
=================  ====================================  ==============
shot, hit          --                                     shot, hit
graze              sparks off the ship                    graze
kill               an explosion                           explosion
boss killed        a big explosion                        big_explosion
miss               a white flash                          player_hit
bomb               its rings (drawn from the world)       bomb
bonus              "<NAME> BONUS +points"                 bonus
extend             "EXTEND"                               extend
boss phase ended   the next phase's number and name       phase
boss on its way    "WARNING" and its name, ``WARNING_S``  warning
=================  ====================================  ==============
"""

from __future__ import annotations

from ..sim import DT, World
from ..sim.events import Events
from .audio import Audio
from .hud import WARNING_S, phase_name, warning_due
from .render import Renderer


def warning_starts(world: World) -> bool:
    """This step is the first of the boss's warning."""
    return warning_due(world) and world.boss is not None and world.boss.spec.at - world.time > WARNING_S - DT


class Feedback:
    """The step's events -> effects, captions and sounds (see the module's table)."""

    def __init__(self, renderer: Renderer, audio: Audio):
        self.renderer, self.audio = renderer, audio

    def stepped(self, ev: Events, world: World) -> None:
        """Show and sound what ``ev`` (the step ``world`` just took) says happened."""
        r, play = self.renderer, self.audio.play
        r.on_events(ev, world)
        for happened, sound in (
            (ev.shots, "shot"),
            (ev.grazes, "graze"),
            (ev.damaged, "hit"),
            (ev.player_hit, "player_hit"),
            (ev.bomb, "bomb"),
        ):
            if happened:
                play(sound)
        if ev.kills:
            play("big_explosion" if ev.boss_killed else "explosion")
        for name, points in ev.bonuses:
            r.caption(world, f"{name.upper()} BONUS  +{points:,}", "bonus")
        if ev.bonuses:
            play("bonus")
        if ev.extend:
            r.caption(world, "EXTEND!", "extend")
            play("extend")
        if ev.phase_ended and not ev.boss_killed and world.boss is not None:
            r.caption(world, phase_name(world.boss), "phase")  # the next phase, by name
            play("phase")
        if warning_starts(world):
            play("warning")
