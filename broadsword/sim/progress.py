"""A stage's progress: bombs used, boss phases ended, extends, continues, the final bonuses.

The rules that sit between systems: a bomb costs one from the stock and shields the player;
a boss phase's end turns every enemy bullet into a star and draws the items in, and pays
its bonus if the phase saw no miss and no bomb; crossing a score threshold gives a life; a
continue revives the player with the score reset to the continues used (its last digit);
clearing the stage pays for the clear, for no miss and for no bomb.
"""

from __future__ import annotations

import weakref

from .bombs import FRAMES as BOMB_FRAMES
from .bombs import GRACE_S
from .boss import PhaseEnd
from .events import Events
from .field import DT
from .hitlog import Outcome
from .items import ItemKind
from .scoring import CLEAR_BONUS, NO_BOMB_BONUS, NO_MISS_BONUS
from .stage_parts import StageParts

#: Continues a run may use.
CONTINUES = 3


class Progress:
    """The world's stage-level rules and tallies (``bombs_used``, ``continues_used``,
    ``phases_beaten`` (boss phases whose hit points ran out), ``bonuses``).

    It refers to its world weakly (a :func:`weakref.proxy`): the world owns it, and a
    strong reference back would make every world a reference cycle, freed only when the
    cyclic collector gets round to it -- a soak's finished games piled up until then
    (docs/RELIABILITY.md). Its methods need the world alive."""

    def __init__(self, world: StageParts, continues_used: int = 0):
        self.world: StageParts = weakref.proxy(world)
        self.bombs_used = 0
        self.continues_used = continues_used
        self.phases_beaten = 0
        self.bonuses: list[tuple[str, int]] = []  # every bonus paid this stage
        self._phase_clean = True  # no miss and no bomb since the current phase began

    # ------------------------------------------------------------------ bombs
    def bomb(self, ev: Events) -> bool:
        """Set off a bomb if one is in stock and none is going off; a stricken player is
        saved by it (the death-bomb). Returns whether it went off."""
        w = self.world
        p = w.player
        if not p.alive or p.bombs <= 0 or w.bomb.active:
            return False
        p.bombs -= 1
        if p.stricken:  # the death-bomb: the hit is saved
            ev.hit = w.hit_log.resolve(Outcome.SAVED) or ev.hit
        p.stricken = 0
        p.invulnerable = max(p.invulnerable, BOMB_FRAMES * DT + GRACE_S)
        w.bomb.start()
        self.bombs_used += 1
        self._phase_clean = False
        ev.bomb = True
        return True

    def missed(self) -> None:
        self._phase_clean = False

    # ------------------------------------------------------------------ the boss
    def phase_ended(self, how: PhaseEnd, ev: Events) -> None:
        """A boss phase ended: bullets become stars, items come in, the bonus if earned; and
        the wreck and its drops if it was the last."""
        w = self.world
        boss = w.boss
        if boss is None:
            raise ValueError("a boss phase ended in a level without a boss")
        ended = boss.phase if boss.dead else boss.phase - 1
        ev.phase_ended = True
        if how is PhaseEnd.BEATEN:
            self.phases_beaten += 1
        eb = w.enemy_bullets
        w.items.drop_many(eb.pos, ItemKind.STAR, homing=True)
        eb.clear()
        if how is not PhaseEnd.TIMED_OUT and self._phase_clean:
            self._pay(f"phase {ended + 1}", boss.spec.phases[ended].bonus, ev)
        self._phase_clean = True
        if boss.dead:  # the last phase: the boss is done; beaten, it pays and drops its load
            at = boss.pos.copy()
            ev.boss_killed = True
            ev.kills.extend((x, y, "boss") for x, y in boss.wreck())
            if how is PhaseEnd.BEATEN:
                w.score.award(boss.spec.score)
                drops = boss.spec.drops
                w.items.drop(at, [ItemKind.POWER] * drops.power + [ItemKind.POINT] * drops.point)
        w.items.call_all()

    # ------------------------------------------------------------------ score
    def extends(self, ev: Events) -> None:
        w = self.world
        while w.score.extend_due():
            w.player.extend()
            ev.extend = True

    def cleared(self, ev: Events) -> None:
        """The stage is over, cleared: its bonuses."""
        self._pay("stage clear", CLEAR_BONUS, ev)
        if not self.world.player.misses:
            self._pay("no miss", NO_MISS_BONUS, ev)
        if not self.bombs_used:
            self._pay("no bomb", NO_BOMB_BONUS, ev)

    def _pay(self, name: str, points: int, ev: Events) -> None:
        self.world.score.award(points)
        self.bonuses.append((name, points))
        ev.bonuses.append((name, points))

    # ------------------------------------------------------------------ continues
    @property
    def can_continue(self) -> bool:
        return self.world.over and self.continues_used < CONTINUES

    def continue_game(self) -> None:
        """Play on after a game over: lives and bombs as at the start, base power, and the
        score reset to the number of continues used (its last digit, for all to see)."""
        w = self.world
        if not self.can_continue:
            raise ValueError("no continue: the game is not over, or every continue is used")
        self.continues_used += 1
        w.score.points = self.continues_used
        w.score.extends = 0
        w.player.revive(w.start_lives, w.player.start_bombs)
        w.over = False
