"""The BulletML machine: runs one mover's actions, command by command, frame by frame.

A :class:`Runner` belongs to one row of a :class:`~.store.Movers` (an emitter or a bullet)
and holds one :class:`Thread` per action list: an emitter has one per top action (they run
together, in file order); a bullet has one whose actions run one after another. A thread
follows libBulletML's timing (docs/PATTERNS.md, "Semantics"): ``act_turn`` is the frame its
next command may run; ``wait N`` adds ``int(N)`` when positive; a change started at
``act_turn`` runs to ``act_turn + int(term)``; an action list's next action starts on the
frame after the previous one ends.
"""

from __future__ import annotations

import math

from .limits import MAX_REPEAT, MAX_STEPS_PER_FRAME
from .model import (
    Accel,
    Action,
    ActionRef,
    Bullet,
    BulletRef,
    ChangeDirection,
    ChangeSpeed,
    Direction,
    DirKind,
    Fire,
    FireRef,
    Orientation,
    Repeat,
    Speed,
    SpeedKind,
    Vanish,
    Wait,
)
from .store import AX, AY, DIR, NEVER, SPD, Movers


def normalise_deg(d: float) -> float:
    """``d`` degrees brought into [0, 360] as libBulletML does (subtract 360 while above 360,
    add 360 while below 0): 360 stays 360 (and 720 gives 360), where ``d % 360`` would give 0.
    The turn of a ``changeDirection`` is measured from the stored direction, so the two are
    not interchangeable: exactly half a turn from 360 goes the other way than from 0. The
    loops' result in closed form (their subtractions are exact, as ``fmod`` is; only the last
    addition to a negative remainder rounds), so a huge value costs no loop."""
    if d > 360.0:
        r = math.fmod(d, 360.0)
        return r if r != 0.0 else 360.0
    if d < 0.0:
        r = math.fmod(d, 360.0)
        return r + 360.0 if r != 0.0 else 0.0
    return d


class _Seq:
    """A command list being run: ``commands[i]`` is next; ``params`` are its ``$1``..."""

    __slots__ = ("commands", "i", "params")

    def __init__(self, commands, params):
        self.commands, self.i, self.params = commands, 0, params


class _Rep:
    """A repeat: ``left`` more runs of ``body`` (an Action or an ActionRef, re-entered each
    time, so an actionRef's params are evaluated afresh). ``fire``: the body's one command
    when the body is an inline action of a single fire (a ring's or a spread's volley),
    which :meth:`Thread._run` runs without entering the action (the same steps counted).
    ``same``: that fire is an inline ``<fire>`` of an inline ``<bullet>`` whose values
    (speeds, directions) read no ``$rand``, so they are the same every time it fires in a
    frame (the same params and ``$rank``): a volley evaluates them once, and counts each
    bullet's evaluations (``cost``, the budget they take) all the same."""

    __slots__ = ("body", "left", "params", "fire", "same", "cost")

    def __init__(self, body, left, params):
        self.body, self.left, self.params = body, left, params
        one = type(body) is Action and len(body.commands) == 1
        self.fire = fire = body.commands[0] if one and type(body.commands[0]) in (Fire, FireRef) else None
        values = _values_of(fire) if type(fire) is Fire and type(fire.bullet) is Bullet else None
        self.same = values is not None and not any(v.expr.random for v in values)
        self.cost = sum(v.expr.steps for v in values) if values is not None else 0


def _values_of(fire: Fire) -> list[Speed | Direction]:
    """The speeds and directions of an inline fire and its inline bullet, in evaluation order."""
    bullet = fire.bullet
    assert type(bullet) is Bullet
    return [v for v in (fire.speed, fire.direction, bullet.speed, bullet.direction) if v is not None]


#: A fire's evaluated values: its speed and direction, its bullet's speed and direction
#: (each None where the file gives none).
Values = tuple[float | None, float | None, float | None, float | None]


def _evaluate(eng, pattern, cmd: Fire, params) -> tuple[Bullet, tuple[float, ...], Values]:
    """The values of fire ``cmd`` with ``params``, in libBulletML's order (so ``$rand``
    draws in turn): the fire's speed and direction, then its bullet's params (a
    ``<bulletRef>``) and its speed and direction. Returns the bullet, its params, the values."""
    fs = None if cmd.speed is None else eng.evaluate(cmd.speed.expr, params)
    fd = None if cmd.direction is None else eng.evaluate(cmd.direction.expr, params)
    bullet = cmd.bullet
    if type(bullet) is BulletRef:
        params = eng.eval_params(bullet.params, params)
        bullet = pattern.bullets[bullet.label]
    assert type(bullet) is Bullet
    bs = None if bullet.speed is None else eng.evaluate(bullet.speed.expr, params)
    bd = None if bullet.direction is None else eng.evaluate(bullet.direction.expr, params)
    return bullet, params, (fs, fd, bs, bd)


class Thread:
    """One libBulletML runner: its action list, stack, clock and ``sequence`` memory."""

    __slots__ = ("pattern", "nodes", "next_node", "stack", "act_turn", "prev_dir", "prev_spd", "params", "due", "cut")

    def __init__(self, pattern, nodes, params: tuple[float, ...]):
        self.pattern, self.nodes, self.next_node, self.params = pattern, nodes, 0, params
        self.stack: list = []
        self.act_turn: int | None = None
        self.prev_dir: float | None = None  # sequence direction: the last fire's, or unset
        self.prev_spd: float | None = None
        self.due = NEVER  # the frame the last run asked to run next
        self.cut = False  # the last run stopped at a step limit, not at a wait

    def run(self, eng, movers: Movers, row: int, now: int) -> int:
        """Run this frame's commands; returns the frame at which it must run next.

        A thread the engine kept waiting (its due frame passed while the engine's budget was
        spent) or cut short at a step limit resumes with its clock moved on to ``now``: it
        carries on where it stopped, later, rather than running every frame it missed at once
        (which would turn one deferred frame into a burst)."""
        if self.act_turn is None:
            self.act_turn = now
        elif self.due < now:
            self.act_turn += now - self.due
        if self.cut:
            self.act_turn, self.cut = max(self.act_turn, now), False
        self.due = self._run(eng, movers, row, now)
        return self.due

    def _run(self, eng, movers: Movers, row: int, now: int) -> int:
        assert self.act_turn is not None
        if not self.stack:
            if self.next_node >= len(self.nodes):
                return NEVER
            self._enter(eng, self.nodes[self.next_node], self.params)
            self.next_node += 1
        steps = 0
        stack = self.stack
        while stack and self.act_turn <= now:
            steps += 1
            if steps > MAX_STEPS_PER_FRAME or eng.budget <= 0:
                self.cut = True  # a hostile loop, or the engine's work for this frame done
                return now + 1  # resume next frame
            eng.budget -= 1
            top = stack[-1]
            if type(top) is _Rep:
                if top.left <= 0:
                    stack.pop()
                elif top.fire is None:
                    top.left -= 1
                    self._enter(eng, top.body, top.params)
                else:  # a volley: enter the body, fire, leave it, three steps a bullet as the general path counts them
                    fired = None  # (bullet, params, values) of a same-valued fire, once evaluated
                    while True:
                        # the budget before a bullet after the evaluated one (None: before the first)
                        before: int | None = eng.budget if fired is not None else None
                        top.left -= 1
                        if steps >= MAX_STEPS_PER_FRAME or eng.budget <= 0:  # cut before the fire
                            stack.append(_Seq(top.body.commands, top.params))
                            break
                        steps += 1
                        eng.budget -= 1
                        if not top.same:
                            self._fire(eng, movers, row, top.fire, top.params)
                        else:
                            if fired is None:
                                fired = _evaluate(eng, self.pattern, top.fire, top.params)
                            else:
                                eng.budget -= top.cost  # what evaluating them again would have cost
                            self._shoot(eng, movers, row, top.fire, *fired)
                        if steps >= MAX_STEPS_PER_FRAME or eng.budget <= 0:  # cut before leaving the body
                            done = _Seq(top.body.commands, top.params)
                            done.i = 1
                            stack.append(done)
                            break
                        steps += 1
                        eng.budget -= 1
                        # the loop's next step, which would come straight back here: taken here
                        if top.left <= 0 or steps + 1 > MAX_STEPS_PER_FRAME or eng.budget <= 0:
                            break
                        steps += 1
                        eng.budget -= 1
                        if before is not None:  # a same-valued volley's bullets from here on: at once
                            steps = self._volley(eng, movers, row, top, fired, before - eng.budget, steps)
                continue
            if top.i >= len(top.commands):
                stack.pop()
                continue
            cmd = top.commands[top.i]
            top.i += 1
            self._do(eng, movers, row, cmd, top.params)
        if stack or self.next_node < len(self.nodes):
            return max(self.act_turn, now + 1)
        return NEVER

    def _volley(self, eng, movers: Movers, row: int, top: _Rep, fired, per: int, steps: int) -> int:
        """Fire at once every bullet of a same-valued volley that the loop in :meth:`_run`
        would fire with no cut and no end between them, and return the steps counted.

        ``per``: the budget the bullet just fired took, past the first (its re-evaluation
        ``cost``, the fire's, its aims and three steps): every following one takes the same
        (the same values and kinds, the sequence memory set). A bullet is taken at once
        when the loop would have gone through all three of its checks and on to the next:
        ``steps`` and the budget leave room for all its steps (the budget stays positive at
        its last check: ``per`` each), and another bullet is left after it."""
        k = min((MAX_STEPS_PER_FRAME - steps) // 3, eng.budget // per, top.left - 1)
        if k <= 0:
            return steps
        bullet, params, values = fired
        assert type(top.fire) is Fire  # a same-valued volley's: an inline fire
        self._shoot_many(eng, movers, row, top.fire, bullet, params, values, k)  # takes the fires' and aims' budget
        eng.budget -= (3 + top.cost) * k
        top.left -= k
        return steps + 3 * k

    # -- helpers ------------------------------------------------------------------------
    def _turn(self) -> int:
        """The frame the running action started on (set by :meth:`run` before any command)."""
        assert self.act_turn is not None
        return self.act_turn

    def _enter(self, eng, node, params) -> None:
        if type(node) is ActionRef:
            params = eng.eval_params(node.params, params)
            node = self.pattern.actions[node.label]
        self.stack.append(_Seq(node.commands, params))

    def _speed(self, eng, spd: Speed, params, movers: Movers, row: int) -> float:
        return self._speed_at(spd.kind, eng.evaluate(spd.expr, params), movers, row)

    def _speed_at(self, kind: SpeedKind, v: float, movers: Movers, row: int) -> float:
        """A speed of ``kind`` whose expression's value is ``v``."""
        if kind is SpeedKind.RELATIVE:
            v += float(movers.state[row, SPD])
        elif kind is SpeedKind.SEQUENCE:
            v = 1.0 if self.prev_spd is None else v + self.prev_spd
        self.prev_spd = v
        return v

    def _direction(self, eng, d: Direction, params, movers: Movers, row: int, remember: bool) -> float:
        return self._direction_at(eng, d.kind, eng.evaluate(d.expr, params), movers, row, remember)

    def _direction_at(self, eng, kind: DirKind, v: float, movers: Movers, row: int, remember: bool) -> float:
        """A direction of ``kind`` whose expression's value is ``v``."""
        aim = kind is DirKind.AIM
        if kind is DirKind.ABSOLUTE:
            if self.pattern.orientation is Orientation.HORIZONTAL:
                v -= 90.0
        elif kind is DirKind.RELATIVE:
            v += float(movers.state[row, DIR])  # as stored, not reduced (libBulletML)
        elif kind is DirKind.SEQUENCE:
            if self.prev_dir is None:
                v, aim = 0.0, True  # the first fire of a sequence aims (libBulletML)
            else:
                v += self.prev_dir
        if aim:
            v += eng.aim(movers, row)
        v = normalise_deg(v)
        if remember:
            self.prev_dir = v
        return v

    def _term(self, eng, expr, params) -> int:
        return int(eng.evaluate(expr, params))

    # -- commands -----------------------------------------------------------------------
    def _do(self, eng, movers: Movers, row: int, cmd, params) -> None:
        kind = type(cmd)
        if kind is Fire or kind is FireRef:
            self._fire(eng, movers, row, cmd, params)
        elif kind is Wait:
            frames = int(eng.evaluate(cmd.frames, params))
            if frames > 0:
                self.act_turn = self._turn() + frames
        elif kind is Repeat:
            times = min(int(eng.evaluate(cmd.times, params)), MAX_REPEAT)
            if times > 0:  # the specification's count; libBulletML would run the body once (docs/PATTERNS.md)
                self.stack.append(_Rep(cmd.body, times, params))
        elif kind is Action or kind is ActionRef:
            self._enter(eng, cmd, params)
        elif kind is ChangeDirection:
            term = self._term(eng, cmd.term, params)
            first = float(movers.state[row, DIR])  # as stored: the turn is measured from it (libBulletML)
            if cmd.direction.kind is DirKind.SEQUENCE:
                final = first + eng.evaluate(cmd.direction.expr, params) * term
            else:
                target = self._direction(eng, cmd.direction, params, movers, row, remember=False)
                space = target - first
                other = space - 360.0 if space > 0 else space + 360.0
                final = first + (space if abs(space) < abs(other) else other)  # the shorter way round
            movers.set_channel(row, DIR, self._turn(), self._turn() + term, first, final)
        elif kind is ChangeSpeed:
            term = self._term(eng, cmd.term, params)
            first = float(movers.state[row, SPD])
            if cmd.speed.kind is SpeedKind.SEQUENCE:
                final = eng.evaluate(cmd.speed.expr, params) * term + first
            else:
                final = self._speed(eng, cmd.speed, params, movers, row)
            movers.set_channel(row, SPD, self._turn(), self._turn() + term, first, final)
        elif kind is Accel:
            self._accel(eng, movers, row, cmd, params)
        elif kind is Vanish:
            eng.vanish(movers, row)

    def _accel(self, eng, movers: Movers, row: int, cmd: Accel, params) -> None:
        term = self._term(eng, cmd.term, params)
        if self.pattern.orientation is Orientation.HORIZONTAL:
            axes = ((cmd.vertical, AX, 1.0), (cmd.horizontal, AY, -1.0))
        else:
            axes = ((cmd.horizontal, AX, 1.0), (cmd.vertical, AY, 1.0))
        for spd, ch, sign in axes:
            if spd is None:
                continue
            v = sign * eng.evaluate(spd.expr, params)
            first = float(movers.state[row, ch])
            if spd.kind is SpeedKind.SEQUENCE:
                final = first + v * term
            elif spd.kind is SpeedKind.RELATIVE:
                final = first + v
            else:
                final = v
            movers.set_channel(row, ch, self._turn(), self._turn() + term, first, final)

    def _fire(self, eng, movers: Movers, row: int, cmd, params) -> None:
        if type(cmd) is FireRef:
            params = eng.eval_params(cmd.params, params)
            cmd = self.pattern.fires[cmd.label]
        self._shoot(eng, movers, row, cmd, *_evaluate(eng, self.pattern, cmd, params))

    def _shoot(self, eng, movers: Movers, row: int, cmd: Fire, bullet: Bullet, params, values: Values) -> None:
        """Fire ``bullet`` as ``cmd`` says, their speeds and directions valued ``values``
        (:func:`_evaluate`): see :meth:`_aimed`."""
        direction, speed = self._aimed(eng, movers, row, cmd, bullet, values)
        eng.spawn(movers, row, [direction], [speed], self.pattern, bullet.actions, params)

    def _shoot_many(
        self, eng, movers: Movers, row: int, cmd: Fire, bullet: Bullet, params, values: Values, k: int
    ) -> None:
        """``k`` fires of a same-valued volley at once: as ``k`` calls of :meth:`_shoot`,
        each bullet's direction and speed in turn (the sequences move on from one to the
        next), then one spawn of them all. Nothing a spawn changes is read in between (it
        queues the bullets and takes the budget), so the state is the same bits."""
        aimed = [self._aimed(eng, movers, row, cmd, bullet, values) for _ in range(k)]
        eng.spawn(movers, row, [d for d, _ in aimed], [s for _, s in aimed], self.pattern, bullet.actions, params)

    def _aimed(self, eng, movers: Movers, row: int, cmd: Fire, bullet: Bullet, values: Values) -> tuple[float, float]:
        """``(direction, speed)`` of one fire of ``bullet`` as ``cmd`` says, valued
        ``values``: the fire's first, then the bullet's, which win (libBulletML); each
        updates the sequence memory."""
        fs, fd, bs, bd = values
        speed = direction = None
        if cmd.speed is not None:
            assert fs is not None
            speed = self._speed_at(cmd.speed.kind, fs, movers, row)
        if cmd.direction is not None:
            assert fd is not None
            direction = self._direction_at(eng, cmd.direction.kind, fd, movers, row, remember=True)
        if bullet.speed is not None:
            assert bs is not None
            speed = self._speed_at(bullet.speed.kind, bs, movers, row)
        if bullet.direction is not None:
            assert bd is not None
            direction = self._direction_at(eng, bullet.direction.kind, bd, movers, row, remember=True)
        if speed is None:
            speed = self.prev_spd = 1.0
        if direction is None:
            direction = self.prev_dir = eng.aim(movers, row)  # the aim as it is, (-180, 180] (libBulletML)
        return direction, speed


class Runner:
    """All the threads of one row. ``gone`` is set when the row vanished (an emitter that
    vanishes stops its pattern)."""

    __slots__ = ("threads", "gone")

    def __init__(self, threads: list[Thread]):
        self.threads, self.gone = threads, False

    def run(self, eng, movers: Movers, row: int, now: int) -> int:
        wake = NEVER
        for t in self.threads:
            if self.gone:
                break
            wake = min(wake, t.run(eng, movers, row, now))
        return NEVER if self.gone else wake

    def pending(self) -> bool:
        return not self.gone and any(t.stack or t.next_node < len(t.nodes) for t in self.threads)
