"""Running BulletML machines as numbers, and back: what a snapshot of the engine keeps.

A :class:`~.machine.Runner` refers to the pattern's model objects (the actions on its
stacks, the repeat bodies, the top actions). :class:`NodeTable` numbers every pattern the
game can run and every action and action reference in them, walking each pattern in its
file's order, so the same patterns loaded again number the same way; a runner is then two
flat streams (:func:`encode_runners`): whole numbers (indices, counters, frames) and
doubles (parameters, the ``sequence`` memory), bit-exact. :func:`decode_runners` checks
every index and count and raises ``ValueError`` naming the row and what is wrong.

Layout of one runner in the int stream (floats in the float stream, in the same order)::

    row, gone, threads
    per thread: pattern, nodes, node..., next_node, has_act_turn, act_turn, due, cut,
                has_prev_dir, has_prev_spd, params   [floats: prev_dir?, prev_spd?, params...]
                stack, per entry: kind (0 a command list, 1 a repeat), node, i or left,
                params   [floats: params...]

A command list is numbered by the action whose commands it runs; a repeat by its body.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .engine import Engine
from .limits import MAX_REPEAT
from .machine import Runner, Thread, _Rep, _Seq
from .model import Action, ActionRef, Bullet, Fire, Pattern, Repeat
from .store import NEVER

#: Stack entry kinds in the int stream.
SEQ, REP = 0, 1


class NodeTable:
    """Numbers for ``patterns`` and for every :class:`Action` and :class:`ActionRef` in them
    (in file order).

    Patterns are numbered by content, not by object: the same file loaded twice (two
    FireSpecs of one kind each load theirs, and which one a gun runs can depend on what ran
    first) gets one number, and its nodes the numbers of the first copy's nodes at the same
    place in the walk, so equal states give equal numbers. The content is the pattern's name,
    orientation and the kind, label and length of every node in walk order.

    Attributes
    ----------
    patterns : list of Pattern
        One per content, the first copy given.
    nodes : list of Action or ActionRef
        ``nodes[k]`` is node ``k``; ``index`` maps ``id(node)`` of any copy back to ``k``.
    """

    def __init__(self, patterns: Sequence[Pattern]):
        self.patterns: list[Pattern] = []
        self.pattern_index: dict[int, int] = {}
        self.nodes: list[Action | ActionRef] = []
        self.index: dict[int, int] = {}
        self.commands_of: dict[int, int] = {}  # id(action.commands) -> an action with them
        by_content: dict[tuple, tuple[int, list[int]]] = {}
        for p in patterns:
            if id(p) in self.pattern_index:
                continue
            walk: list[Action | ActionRef] = []
            _walk_pattern(p, walk, set())
            key = (p.name, p.orientation, tuple(_signature(n) for n in walk))
            if key in by_content:
                k, numbers = by_content[key]
            else:
                k, numbers = len(self.patterns), list(range(len(self.nodes), len(self.nodes) + len(walk)))
                by_content[key] = (k, numbers)
                self.patterns.append(p)
                self.nodes += walk
            self.pattern_index[id(p)] = k
            for node, number in zip(walk, numbers, strict=True):
                self.index[id(node)] = number
                if type(node) is Action:
                    self.commands_of.setdefault(id(node.commands), number)


def _signature(node: Action | ActionRef) -> tuple:
    if isinstance(node, Action):
        return ("action", node.label, len(node.commands))
    return ("ref", node.label, len(node.params))


def _walk_pattern(p: Pattern, out: list, seen: set[int]) -> None:
    """Every Action and ActionRef of ``p``, each once, in a fixed order: the top actions,
    then the labelled actions, bullets and fires in file order, depth first."""
    for a in p.top:
        _walk(a, out, seen)
    for a in p.actions.values():
        _walk(a, out, seen)
    for b in p.bullets.values():
        _walk(b, out, seen)
    for f in p.fires.values():
        _walk(f, out, seen)


def _walk(node, out: list, seen: set[int]) -> None:
    kind = type(node)
    if kind is Action or kind is ActionRef:
        if id(node) in seen:
            return
        seen.add(id(node))
        out.append(node)
        if kind is Action:
            for c in node.commands:
                _walk(c, out, seen)
    elif kind is Repeat:
        _walk(node.body, out, seen)
    elif kind is Fire:
        _walk(node.bullet, out, seen)
    elif kind is Bullet:
        for a in node.actions:
            _walk(a, out, seen)
    # FireRef, BulletRef and the plain commands hold no action of their own: what they
    # name is walked from the pattern's tables.


def encode_runners(table: NodeTable, rows: Sequence[int], runners: Sequence[Runner]) -> tuple[np.ndarray, np.ndarray]:
    """The ``runners`` of a store's ``rows`` (increasing; the rows with no runner left out)
    as an int64 and a float64 stream (see the module doc). ``ValueError`` if one runs a
    pattern the table does not number."""
    try:
        return _encode(table, rows, runners)
    except KeyError:
        names = ", ".join(
            sorted({t.pattern.name for r in runners for t in r.threads} - {p.name for p in table.patterns})
        )
        raise ValueError(
            f"a running pattern is not one the level can run ({names or 'a node outside the table'})"
        ) from None


def _encode(table: NodeTable, rows: Sequence[int], runners: Sequence[Runner]) -> tuple[np.ndarray, np.ndarray]:
    ints: list[int] = []
    floats: list[float] = []
    pidx, nidx, cidx = table.pattern_index, table.index, table.commands_of
    for row, r in zip(rows, runners, strict=True):
        ints += (row, int(r.gone), len(r.threads))
        for t in r.threads:
            ints.append(pidx[id(t.pattern)])
            ints.append(len(t.nodes))
            ints += [nidx[id(n)] for n in t.nodes]
            ints += (t.next_node, t.act_turn is not None, t.act_turn or 0, t.due, int(t.cut), t.prev_dir is not None)
            ints += (t.prev_spd is not None, len(t.params))
            if t.prev_dir is not None:
                floats.append(t.prev_dir)
            if t.prev_spd is not None:
                floats.append(t.prev_spd)
            floats += t.params
            ints.append(len(t.stack))
            for e in t.stack:
                if type(e) is _Rep:
                    ints += (REP, nidx[id(e.body)], e.left, len(e.params))
                else:
                    ints += (SEQ, cidx[id(e.commands)], e.i, len(e.params))
                floats += e.params
    return np.array(ints, dtype=np.int64), np.array(floats, dtype=np.float64)


class _Cursor:
    """Reads the two streams in order, with bounds checks (messages name the field only:
    :func:`decode_runners` adds where)."""

    def __init__(self, ints: np.ndarray, floats: np.ndarray):
        self.ints, self.floats = ints.tolist(), floats.tolist()
        self.i = self.f = 0

    def whole(self, what: str, lo: int = 0, hi: int | None = None) -> int:
        if self.i >= len(self.ints):
            raise ValueError(f"{what}: the runner stream ends early")
        v = self.ints[self.i]
        self.i += 1
        if v < lo or (hi is not None and v > hi):
            raise ValueError(f"{what}: {v} is out of range [{lo}, {hi}]")
        return v

    def params(self, k: int, what: str) -> tuple[float, ...]:
        if self.f + k > len(self.floats):
            raise ValueError(f"{what}: the runner float stream ends early")
        out = tuple(self.floats[self.f : self.f + k])
        self.f += k
        return out


def decode_runners(
    table: NodeTable, ints: np.ndarray, floats: np.ndarray, rows: int, where: str
) -> list[Runner | None]:
    """The runners of ``rows`` rows from :func:`encode_runners`' streams. ``ValueError``
    (starting with ``where``, then the row) for an index out of range, a count past the
    streams' end, a row out of order, or values left over."""
    out: list[Runner | None] = [None] * rows
    c = _Cursor(ints, floats)
    last = -1
    while c.i < len(c.ints):
        try:
            row = c.whole("runner row", last + 1, rows - 1)
        except ValueError as e:
            raise ValueError(f"{where}: {e}") from None
        last = row
        try:
            out[row] = _runner(table, c)
        except ValueError as e:
            raise ValueError(f"{where}: runner of row {row}: {e}") from None
    if c.f != len(c.floats):
        raise ValueError(f"{where}: {len(c.floats) - c.f} runner floats left over")
    return out


def _runner(table: NodeTable, c: _Cursor) -> Runner:
    """One runner from the streams (after its row number)."""
    nodes, n_nodes = table.nodes, len(table.nodes) - 1
    big = len(c.ints) + len(c.floats)  # no count can exceed what the streams hold
    gone = bool(c.whole("gone", 0, 1))
    threads = []
    for _ in range(c.whole("threads", 1, big)):
        pattern = table.patterns[c.whole("pattern", 0, len(table.patterns) - 1)]
        k = c.whole("nodes", 0, big)
        tnodes = tuple(nodes[c.whole("node", 0, n_nodes)] for _ in range(k))
        next_node = c.whole("next_node", 0, k)
        has_turn = c.whole("has act_turn", 0, 1)
        act_turn = c.whole("act_turn", -(1 << 62), 1 << 62)
        due = c.whole("due", -(1 << 62), NEVER)
        cut = bool(c.whole("cut", 0, 1))
        has_dir, has_spd = c.whole("has prev_dir", 0, 1), c.whole("has prev_spd", 0, 1)
        nparams = c.whole("params", 0, big)
        t = Thread(pattern, tnodes, ())
        t.next_node, t.act_turn = next_node, act_turn if has_turn else None
        t.due, t.cut = due, cut
        t.prev_dir = c.params(1, "prev_dir")[0] if has_dir else None
        t.prev_spd = c.params(1, "prev_spd")[0] if has_spd else None
        t.params = c.params(nparams, "params")
        for _ in range(c.whole("stack", 0, big)):
            kind = c.whole("stack entry kind", SEQ, REP)
            node = nodes[c.whole("stack node", 0, n_nodes)]
            count = c.whole("stack counter", 0, MAX_REPEAT if kind == REP else None)
            params = c.params(c.whole("stack params", 0, big), "stack params")
            if kind == REP:
                t.stack.append(_Rep(node, count, params))
            elif type(node) is not Action:
                raise ValueError(f"a command list's node {table.index[id(node)]} is not an action")
            elif count > len(node.commands):
                raise ValueError(f"command {count} is past the action's {len(node.commands)}")
            else:
                seq = _Seq(node.commands, params)
                seq.i = count
                t.stack.append(seq)
        threads.append(t)
    runner = Runner(threads)
    runner.gone = gone
    return runner


#: The engine's counters a snapshot keeps (its ``rank`` and ``max_steps`` are settings).
ENGINE_COUNTERS = ("frame", "fired", "peak", "budget", "busiest", "deferred")


def resume_rows(engine: Engine) -> tuple[int, int]:
    """The rows the engine serves first next frame (emitters, bullets), after a part of a
    frame that ran out of commands (0, 0: none waiting)."""
    return engine._resume["emitters"], engine._resume["bullets"]


def set_resume_rows(engine: Engine, emitters: int, bullets: int) -> None:
    engine._resume["emitters"], engine._resume["bullets"] = emitters, bullets
