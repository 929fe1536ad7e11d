"""Lasers in play: straight lasers, rotating beams and curvy lasers fired by boss parts.

A boss phase's ``[[boss.phase.laser]]`` entries (:class:`~broadsword.data.levels.LaserSpec`,
docs/FORMATS.md "Lasers") fire from their part every ``every`` s from ``delay`` s into the
phase, counted by the boss's phase clock (``Boss.phase_frames``), so firing needs no state
of its own. Each laser in play is a row of :attr:`Lasers.pool`:

* a **straight** laser is a warning line for ``warn`` s (drawn, never collided), then on for
  ``on`` s, then gone; it runs from its part (it follows the part) ``length`` px along its
  heading;
* a **beam** is a straight laser that, once on, turns about its part at ``turn`` degrees a
  second;
* a **curvy** laser is a chain of up to ``nodes`` nodes: each step its head (node 0) moves
  ``speed`` along a heading that turns at ``turn`` and wobbles ``wave`` degrees every
  ``period`` s, and every ``spacing`` steps the trail takes a node where the head was the
  step before, every node moving back one place (with ``spacing`` 1, node ``i`` is where the
  head was ``i`` steps ago). It lives ``on`` s, and goes when its every node has left the field.

A laser's shape is :mod:`broadsword.collision.lasers`' (a bevel-joined thick polyline, width
``width`` at its origin or head, ``tip`` at the far end, linear between). The lit lasers go
through the frame's one pipeline call with everything else (:mod:`.collide`:
:meth:`frame_lasers` hands them over), tested against the player's hit polygon swept back
along this step's move, so a ship crossing a laser between two steps is hit, and against
the graze shape; :meth:`collide` applies what that found. A hit is a miss like a bullet's
(the death-bomb window opens; a bomb in it saves the ship; the hit log names the laser and
the piece). A laser inside the graze shape (and not hitting) counts one graze, then again
every ``GRAZE_EVERY`` steps while it stays there. A bomb cancels every laser on the
field (each leaves stars along it) and no laser fires while it lasts; a phase's lasers end
with the phase.

Every number is computed with correctly rounded operations and :mod:`~broadsword.collision.detmath`
angles, so lasers replay bit for bit.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..collision import detmath
from ..collision.backend import NumpyBackend, Trig
from ..collision.lasers import LaserSet, laser_pieces
from ..data.difficulty import Difficulty
from ..data.levels import LASER_NODES, LaserKind, LaserSpec, Level
from .boss import Boss
from .collide import CollisionRecord, Group, LaserTags
from .emitters import on_field
from .events import Events
from .field import DT, FIELD
from .items import ItemKind, Items
from .pool import Pool

if TYPE_CHECKING:
    from .player import Player
    from .scoring import Score

#: A laser inside the graze shape counts a graze at most once in this many steps.
GRAZE_EVERY = 8
#: A curvy laser whose every node is this far past the field's edges is gone, px.
CULL_MARGIN = 32.0
#: A cancelled straight laser leaves a star every this many px along it (at most STARS_MAX).
STAR_SPACING, STARS_MAX = 48.0, 12
#: At most this many lasers at once; a phase that would fire more fires fewer.
LASERS_LIMIT = 256


def frames(seconds: float, least: int = 1) -> int:
    """Whole steps in ``seconds`` (at least ``least``)."""
    return max(least, round(seconds / DT))


def laser_pool(capacity: int = 8) -> Pool:
    """The lasers in play: ``which`` (index into :attr:`Lasers.specs`), ``phase`` (the boss
    phase that fired it), ``part`` (the boss part it comes from), ``age`` (steps since it was
    fired), ``heading`` (its heading when fired, degrees), ``head`` ((2,): a curvy laser's
    head), ``nodes`` ((LASER_NODES, 2): its chain, the first ``count`` rows in use; a
    straight laser's origin and end) and ``graze_wait`` (steps before it may count a graze)."""
    return Pool(
        capacity=capacity,
        limit=LASERS_LIMIT,
        which=((), int),
        phase=((), int),
        part=((), int),
        age=((), int),
        heading=((), float),
        head=((2,), float),
        nodes=((LASER_NODES, 2), float),
        count=((), int),
        graze_wait=((), int),
    )


#: Every laser kind, in the order :attr:`SpecTable.kind` numbers them.
KINDS = tuple(LaserKind)
_KIND_NAMES = tuple(k.value for k in KINDS)  # as LaserTag names them


class SpecTable:
    """The level's laser specs as parallel arrays (each (S,), indexed by a row's ``which``),
    so the step reads every row's spec at once: ``curvy`` (bool), ``part``, ``warn`` and
    ``on`` (whole steps, :func:`frames`), ``kind`` (each spec's :class:`LaserKind` as its
    index in ``KINDS``), ``nodes`` and ``spacing`` (int64); ``turn``,
    ``wave``, ``period``, ``step`` (``speed * DT``: a curvy head's move a step), ``width``
    and ``tip`` (float64). Each value is computed as the per-row code did, so it is the
    same double."""

    def __init__(self, specs: tuple[LaserSpec, ...]):
        def ints(values: list[int]) -> np.ndarray:
            return np.array(values, dtype=np.int64)

        def floats(values: list[float]) -> np.ndarray:
            return np.array(values, dtype=np.float64)

        self.curvy = np.array([s.kind is LaserKind.CURVY for s in specs], dtype=bool)
        self.kind = ints([KINDS.index(s.kind) for s in specs])
        self.part = ints([s.part for s in specs])
        self.warn = ints([frames(s.warn) for s in specs])
        self.on = ints([frames(s.on) for s in specs])
        self.nodes = ints([s.nodes for s in specs])
        self.spacing = ints([s.spacing for s in specs])
        self.turn = floats([s.turn for s in specs])
        self.wave = floats([s.wave for s in specs])
        self.period = floats([s.period for s in specs])
        self.step = floats([s.speed * DT for s in specs])
        self.width = floats([s.width for s in specs])
        self.tip = floats([s.tip for s in specs])


def part_rows(parts: Pool, part: np.ndarray) -> np.ndarray:
    """(K,) int64: the row of each boss part in ``part`` (K,) in ``parts`` (kept in part
    order), -1 where it is gone."""
    i = np.searchsorted(parts.part, part)
    at = np.minimum(i, max(parts.n - 1, 0))
    found = (i < parts.n) & (parts.part[at] == part) if parts.n else np.zeros(len(part), dtype=bool)
    return np.where(found, i, -1)


def part_row(parts: Pool, part: int) -> int | None:
    """The row of boss part ``part`` in ``parts`` (kept in part order), or None if it is gone."""
    i = int(np.searchsorted(parts.part, part))
    return i if i < parts.n and int(parts.part[i]) == part else None


class Lasers:
    """The level's lasers: the specs of every boss phase (``specs``, flat, phase after phase;
    ``first[p]`` is phase ``p``'s first) and the pool of lasers in play."""

    def __init__(self, level: Level, difficulty: Difficulty, trig: Trig | None = None):
        self.trig: Trig = NumpyBackend() if trig is None else trig
        phases = level.boss.phases if level.boss is not None else ()
        self.specs: tuple[LaserSpec, ...] = tuple(s for ph in phases for s in ph.lasers)
        self.first = np.cumsum([0] + [len(ph.lasers) for ph in phases]).tolist()
        self.difficulty = difficulty
        self.table = SpecTable(self.specs)
        self.pool = laser_pool()

    # ------------------------------------------------------------------ what each is now
    def spec_of(self, row: int) -> LaserSpec:
        return self.specs[int(self.pool.which[row])]

    def warning(self, row: int) -> bool:
        """Row ``row`` is a straight laser or beam still showing its warning line."""
        s = self.spec_of(row)
        return s.kind is not LaserKind.CURVY and int(self.pool.age[row]) < frames(s.warn)

    def _warning(self) -> np.ndarray:
        """(n,) bool: each row is a straight laser or beam still showing its warning line."""
        p = self.pool
        t, j = self.table, p.which[: p.n]
        return ~t.curvy[j] & (p.age[: p.n] < t.warn[j])

    def warning_rows(self) -> list[int]:
        """The rows showing their warning line (:meth:`warning`), all at once."""
        return np.flatnonzero(self._warning()).tolist()

    def live_rows(self) -> list[int]:
        """The rows that collide now: on (past their warning), with at least two nodes."""
        return np.flatnonzero((self.pool.count[: self.pool.n] >= 2) & ~self._warning()).tolist()

    def by_kind(self, rows: list[int]) -> dict[LaserKind, list[int]]:
        """``rows`` grouped by their laser's kind (kinds in :data:`KINDS` order, rows in
        their order within each)."""
        kind = self.table.kind[self.pool.which[np.asarray(rows, dtype=np.int64)]]
        return {k: np.asarray(rows)[kind == i].tolist() for i, k in enumerate(KINDS) if (kind == i).any()}

    def widths(self, row: int) -> np.ndarray:
        """(count,) float64: the full width at each node of row ``row``, ``width`` at the
        first node to ``tip`` at the last, linear in the node's index."""
        s, n = self.spec_of(row), int(self.pool.count[row])
        if s.tip == s.width:
            return np.full(n, s.width)
        return s.width + (s.tip - s.width) * (np.arange(n, dtype=np.float64) / (n - 1))

    def chains(self, rows: list[int]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(nodes (N, 2), widths (N,), starts (L,))`` of ``rows``, for
        :func:`~broadsword.collision.lasers.laser_pieces`."""
        p, t = self.pool, self.table
        at = np.asarray(rows, dtype=np.int64)
        counts = p.count[at]
        starts = np.zeros(len(at), dtype=np.int64)
        np.cumsum(counts[:-1], out=starts[1:])
        # Node k of each row, row after row: the flat index of (row, k) in the pool's nodes.
        owner = np.repeat(np.arange(len(at)), counts)
        k = np.arange(len(owner)) - np.repeat(starts, counts)
        # np.take, not [...]: indexing the rows of an (n, 2) array is ~20x slower (measured)
        nodes = np.take(p.nodes.reshape(-1, 2), np.repeat(at, counts) * LASER_NODES + k, axis=0)
        # As widths(): width, or width + (tip - width) (k / (count - 1)), the same operations a node.
        w, tip = t.width[p.which[at]][owner], t.tip[p.which[at]][owner]
        tapered = w + (tip - w) * (k / np.maximum(counts - 1, 1)[owner])
        widths = np.where(tip == w, w, tapered)
        return nodes, widths, starts

    def pieces(self, rows: list[int]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The pieces of ``rows``: ``x, y`` (4, P) and each piece's index into ``rows`` (P,)."""
        if not rows:
            return np.empty((4, 0)), np.empty((4, 0)), np.empty(0, dtype=np.int64)
        return laser_pieces(*self.chains(rows))

    def frame_lasers(self, rows: list[int]) -> tuple[LaserSet, LaserTags]:
        """The lasers of ``rows`` (:meth:`live_rows`) for the frame's pipeline call, packed,
        and which game laser each is (:class:`~.collide.LaserTags`), in the same order."""
        if not rows:
            return LaserSet.pack(()), LaserTags.empty()
        p = self.pool
        at = np.asarray(rows, dtype=np.int64)
        which, phase = p.which[at], p.phase[at]
        entry = which - np.asarray(self.first, dtype=np.int64)[phase]
        kinds = tuple(_KIND_NAMES[k] for k in self.table.kind[which].tolist())
        tags = LaserTags(at, phase, entry, kinds)
        return LaserSet.of(*self.chains(rows)), tags

    def segments_ahead(self, ahead: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Where the lasers' segments will be ``ahead`` (H,) steps from now, as a player sees
        them going (for the autopilot): warning lines as the lasers they announce, beams
        turning on at their rate, straight and curvy lasers where they are. Returns ``a, b``
        (H, S, 2), each segment's ends at each time, and ``half`` (S,), its largest half width."""
        p = self.pool
        ahead = np.asarray(ahead, dtype=np.float64)
        a_all, b_all, half = [], [], []
        for i in range(p.n):
            s, n = self.spec_of(i), int(p.count[i])
            if n < 2:
                continue
            nodes = p.nodes[i, :n]
            a = np.broadcast_to(nodes[:-1], (len(ahead), n - 1, 2))
            b = np.broadcast_to(nodes[1:], (len(ahead), n - 1, 2))
            if s.kind is LaserKind.BEAM:
                lit = np.maximum(int(p.age[i]) + ahead - frames(s.warn), 0.0)
                vx, vy = detmath.velocity_deg(float(p.heading[i]) + s.turn * (lit * DT), s.length)
                b = a + np.stack([vx, vy], axis=1)[:, None, :]
            a_all.append(a)
            b_all.append(b)
            half.append(np.full(n - 1, 0.5 * max(s.width, s.tip)))
        if not half:
            empty = np.empty((len(ahead), 0, 2))
            return empty, empty, np.empty(0)
        return np.concatenate(a_all, axis=1), np.concatenate(b_all, axis=1), np.concatenate(half)

    # ------------------------------------------------------------------ the step
    def move(self, boss: Boss | None, bomb_active: bool, items: Items) -> None:
        """Age every laser and put it where it is this step; end those whose time is up,
        whose phase or part is gone; a bomb cancels all of them (stars along the lit ones)."""
        p = self.pool
        if not p.n:
            return
        if bomb_active:
            self.cancel(items)
            return
        if boss is None or not boss.fighting:
            p.clear()
            return
        parts, t, j = boss.parts, self.table, p.which
        p.age[:] += 1  # (in place: the pool's columns are views of its live rows)
        age = p.age
        row = part_rows(parts, t.part[j])
        keep = (p.phase == boss.phase) & (row >= 0)
        curvy = t.curvy[j]
        straight = keep & ~curvy
        keep &= np.where(curvy, age < t.on[j], age < t.warn[j] + t.on[j])
        for i in np.flatnonzero(keep & straight).tolist():  # a few a phase: one at a time
            self._straight(i, self.spec_of(i), int(age[i]), parts.pos[row[i]])
        moving = np.flatnonzero(keep & curvy)
        if len(moving):
            keep[moving] = self._curve(moving)
        if not keep.all():
            p.keep(keep)

    def _straight(self, i: int, s: LaserSpec, age: int, origin: np.ndarray) -> None:
        """Row ``i``, a straight laser or beam, from ``origin`` along its heading now."""
        p = self.pool
        heading = float(p.heading[i])
        lit = age - frames(s.warn)
        if s.kind is LaserKind.BEAM and lit > 0:
            heading += s.turn * (lit * DT)
        vx, vy = detmath.velocity_deg(heading, s.length)
        p.nodes[i, 0] = origin
        p.nodes[i, 1, 0], p.nodes[i, 1, 1] = origin[0] + vx, origin[1] + vy
        p.count[i] = 2

    def _curve(self, rows: np.ndarray) -> np.ndarray:
        """Move the heads of curvy rows ``rows`` (K,) and trail their nodes, all at once
        (each row the same operations, in the same order, as one at a time). Returns (K,)
        bool: False where a row's every node is off the field."""
        p, t = self.pool, self.table
        j = p.which[rows]
        tt = p.age[rows] * DT
        heading = p.heading[rows] + t.turn[j] * tt
        wave = t.wave[j]
        w = wave != 0  # a row with no wave adds nothing (not even a signed zero)
        if w.any():
            heading[w] += wave[w] * self.trig.sincos_deg(360.0 * (tt[w] / t.period[j][w]))[0]
        vx, vy = detmath.velocity_deg(heading, t.step[j], self.trig.sincos_deg)
        p.head[rows, 0] += vx
        p.head[rows, 1] += vy
        n = p.count[rows]
        take = (p.age[rows] % t.spacing[j] == 0) | (n == 1)  # the trail takes a new node
        n = np.where(take, np.minimum(n + 1, t.nodes[j]), n)
        most = int(n.max())
        trail = rows[take]  # only the rows taking a node shift (every ``spacing`` steps each)
        if len(trail):  # node k takes node k - 1's place, 1 <= k < the new count
            moved = n[take] - 1
            pairs = p.nodes.view(np.complex128).reshape(-1)  # each node's (x, y) as one item
            assert np.shares_memory(pairs, p.nodes)  # a view (the pool's rows are contiguous)
            to = np.repeat(trail * LASER_NODES + 1 - (np.cumsum(moved) - moved), moved) + np.arange(int(moved.sum()))
            pairs[to] = pairs[to - 1]  # one gather, one scatter (the gather copies first)
        p.nodes[rows, 0] = p.head[rows]  # the head moves on from the new node
        p.count[rows] = n
        chain = p.nodes[rows, :most]
        m = CULL_MARGIN
        x, y = chain[:, :, 0], chain[:, :, 1]
        inside = (x > -m) & (x < FIELD[0] + m) & (y > -m) & (y < FIELD[1] + m)
        return (inside & (np.arange(most)[None, :] < n[:, None])).any(axis=1)

    def fire(self, boss: Boss | None, player: np.ndarray, player_alive: bool, bomb_active: bool) -> int:
        """Fire the current phase's lasers that are due this step (by the boss's phase clock)
        from parts on the field, while the player is alive and no bomb lasts. Returns how
        many lasers were fired."""
        if boss is None or not boss.fighting or not boss.parts.n or not player_alive or bomb_active:
            return 0
        k, made = boss.phase_frames, 0
        for j in range(self.first[boss.phase], self.first[boss.phase + 1]):
            s = self.specs[j]
            start = frames(s.delay, least=0)
            if self.difficulty not in s.difficulties or k < start or (k - start) % frames(s.every):
                continue
            row = part_row(boss.parts, s.part)
            if row is None or not on_field(boss.parts.pos[row : row + 1])[0]:
                continue
            made += self._add(j, s, boss.phase, boss.parts.pos[row].copy(), player)
        return made

    def _add(self, j: int, s: LaserSpec, phase: int, origin: np.ndarray, player: np.ndarray) -> int:
        base = s.angle
        if s.aim:
            base += detmath.heading_deg(float(player[0] - origin[0]), float(player[1] - origin[1]))
        c = s.count
        headings = [base + (s.spread * (i / (c - 1)) - 0.5 * s.spread if c > 1 else 0.0) for i in range(c)]
        nodes = np.zeros((c, LASER_NODES, 2))
        nodes[:, 0] = origin
        added = self.pool.add(
            which=np.full(c, j),
            phase=np.full(c, phase),
            part=np.full(c, s.part),
            age=np.zeros(c, dtype=np.int64),
            heading=np.array(headings, dtype=np.float64),
            head=np.repeat(origin[None, :], c, axis=0),
            nodes=nodes,
            count=np.ones(c, dtype=np.int64),
            graze_wait=np.zeros(c, dtype=np.int64),
        )
        for i in range(self.pool.n - added, self.pool.n):  # where a straight laser will be
            if s.kind is not LaserKind.CURVY:
                self._straight(i, s, 0, origin)
        return added

    def cancel(self, items: Items) -> None:
        """End every laser; each lit one leaves homing stars along it (as cancelled bullets do)."""
        p = self.pool
        for i in self.live_rows():
            s = self.spec_of(i)
            if s.kind is LaserKind.CURVY:
                at = p.nodes[i, : int(p.count[i]) : 4]
            else:
                a, b = p.nodes[i, 0], p.nodes[i, 1]
                k = min(STARS_MAX, max(1, math.ceil(s.length / STAR_SPACING)))
                f = np.arange(1, k + 1, dtype=np.float64) / k
                at = a + (b - a) * f[:, None]
            inside = (at[:, 0] >= 0) & (at[:, 0] <= FIELD[0]) & (at[:, 1] >= 0) & (at[:, 1] <= FIELD[1])
            items.drop_many(at[inside], ItemKind.STAR, homing=True)
        p.clear()

    def collide(self, record: CollisionRecord, player: Player, score: Score | None, ev: Events) -> bool:
        """Apply what the lit lasers touched in the frame's collision ``record`` (after the
        bullets' and ships' hits): a laser on the player's path strikes the ship, unless
        something struck it already this step; a laser in the graze shape counts a graze on
        ``score`` (throttled per laser; none while the ship is stricken; ``score`` None: the
        stage has no graze). Returns whether a laser struck the ship."""
        p = self.pool
        if not p.n:
            return False
        struck = False
        if player.vulnerable and len(record.laser_hits_on(Group.PLAYER_PATH)):
            player.strike()
            ev.player_struck = struck = True
        if score is not None and not player.stricken:
            near = {record.lasers[k].row for k in record.laser_hits_on(Group.GRAZE)[:, 1].tolist()}
            grazed = [i for i in sorted(near) if p.graze_wait[i] == 0]
            if grazed:
                p.graze_wait[grazed] = GRAZE_EVERY  # counted down from this step on
                ev.grazes += len(grazed)
                score.graze(len(grazed))
        p.graze_wait[:] = np.maximum(p.graze_wait - 1, 0)
        return struck
