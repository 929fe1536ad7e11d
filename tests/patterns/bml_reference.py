"""An independent BulletML stepper that follows libBulletML's runner, for conformance tests.

It shares nothing with ``broadsword.patterns.bulletml``: its own XML walk (the standard
library's ElementTree), its own expression reader, its own runner. The runner is written
after libBulletML's ``BulletMLRunnerImpl`` (read, not copied): one *act* pointer walking
the element tree, a repeat stack and a reference stack; ``changes()`` then the commands
until the turn ends; linear changes ``first + (last - first) / (x1 - x0) * (now - x0)``
from the turn the command ran; directions normalised by adding or subtracting 360 until in
[0, 360]; the shortest turn measured from the mover's direction as it is stored (not
reduced); ``sequence`` against the last ``<fire>``/``<bullet>`` value of the same runner,
aiming (or 1 px/frame) on a runner's first; a default direction aims, a default speed is 1;
``horizontal`` files turn absolute directions by -90 and drive x with ``vertical`` and -y
with ``horizontal``; ``repeat`` runs its body at least once (libBulletML tests the count
after the body).

What libBulletML leaves to the game is done as Broadsword documents it (docs/PATTERNS.md,
"Semantics"): a frame runs the emitter, then the bullets alive before it in the order
fired, then the bullets those fired in this frame (in the same loop, libBulletML's manager
style); a bullet fired by the emitter first runs on the next frame; bullets appear at their
firer's position and first move on the next frame; a mover's velocity is its direction and
speed as a vector (0 = up, clockwise, y down) plus its accel velocity. ``$rand`` is one
shared ``numpy.random.Generator(PCG64(seed))``, drawn in the order expressions are
evaluated, so a run can be compared with ``broadsword.patterns.bulletml.trace`` draw for
draw. The emitter is fixed, or moved along ``path(frame)`` before each frame.

The trigonometry is ``math`` (not Broadsword's deterministic tables): compare with a
tolerance of about 1e-9 px a frame.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from collections.abc import Callable

import numpy as np

# -- the tree ---------------------------------------------------------------------------


class Node:
    """One element: ``name`` (tag without namespace), ``type`` and ``label`` attributes,
    ``text``, ``children``, ``parent``."""

    def __init__(self, el: ET.Element, parent: Node | None):
        self.name = el.tag.rsplit("}", 1)[-1]
        self.type = (el.get("type") or "none").strip()
        self.label = el.get("label")
        self.text = (el.text or "").strip()
        self.parent = parent
        self.children = [Node(c, self) for c in el]
        self.formula = Formula(self.text) if self.name in _NUMBERS else None

    def child(self, name: str) -> Node | None:
        return next((c for c in self.children if c.name == name), None)

    def all(self, name: str) -> list[Node]:
        return [c for c in self.children if c.name == name]

    def next(self) -> Node | None:
        """The next sibling (libBulletML's ``next()``), or None."""
        if self.parent is None:
            return None
        sib = self.parent.children
        i = next(k for k, c in enumerate(sib) if c is self)
        return sib[i + 1] if i + 1 < len(sib) else None


_NUMBERS = {"direction", "speed", "horizontal", "vertical", "term", "times", "wait", "param"}


class Document:
    """A parsed file: ``horizontal``, the top actions, and the labelled elements."""

    def __init__(self, text: str):
        text = re.sub(r"<!DOCTYPE[^>]*>", "", text)
        self.root = Node(ET.fromstring(text), None)
        self.horizontal = self.root.type == "horizontal"
        self.labels: dict[tuple[str, str], Node] = {}
        todo = [self.root]
        while todo:
            n = todo.pop()
            todo.extend(n.children)
            if n.label is not None and n.name in ("action", "bullet", "fire"):
                self.labels[(n.name, n.label)] = n
        self.top = [c for c in self.root.children if c.name == "action" and (c.label or "").startswith("top")]

    def ref(self, node: Node) -> Node:
        return self.labels[(node.name[: -len("Ref")], node.label or "")]


# -- expressions ------------------------------------------------------------------------


class Formula:
    """``+ - * /`` (left to right, usual precedence), unary minus, parentheses, numbers,
    ``$rand``, ``$rank``, ``$n``. Evaluated afresh every time (each ``$rand`` a new draw,
    left operand first)."""

    _TOKEN = re.compile(r"\s*(\d+\.?\d*|\.\d+|\$rand|\$rank|\$\d+|[-+*/()])")

    def __init__(self, text: str):
        self.tokens = []
        pos, text = 0, text.strip()
        while pos < len(text):
            m = self._TOKEN.match(text, pos)
            if not m:
                raise ValueError(f"cannot read {text!r}")
            self.tokens.append(m.group(1))
            pos = m.end()

    def value(self, ctx: Runner, params: list[float] | None) -> float:
        if not self.tokens:
            return 0.0  # libBulletML reads an empty expression as 0
        self._i, self._ctx, self._params = 0, ctx, params
        return self._sum()

    def _peek(self) -> str | None:
        return self.tokens[self._i] if self._i < len(self.tokens) else None

    def _sum(self) -> float:
        v = self._product()
        while self._peek() in ("+", "-"):
            op = self.tokens[self._i]
            self._i += 1
            r = self._product()
            v = v + r if op == "+" else v - r
        return v

    def _product(self) -> float:
        v = self._unary()
        while self._peek() in ("*", "/"):
            op = self.tokens[self._i]
            self._i += 1
            r = self._unary()
            v = v * r if op == "*" else v / r
        return v

    def _unary(self) -> float:
        if self._peek() == "-":
            self._i += 1
            return -self._unary()
        tok = self.tokens[self._i]
        self._i += 1
        if tok == "(":
            v = self._sum()
            self._i += 1  # ")"
            return v
        if tok == "$rand":
            return self._ctx.rand()
        if tok == "$rank":
            return self._ctx.rank
        if tok.startswith("$"):
            k = int(tok[1:])
            p = self._params
            return p[k] if p is not None and k < len(p) else 0.0
        return float(tok)


# -- the runner -------------------------------------------------------------------------


class Linear:
    """libBulletML's LinearFunc over whole frames."""

    def __init__(self, x0: int, x1: int, y0: float, y1: float):
        self.x0, self.x1, self.y0, self.y1 = x0, x1, y0, y1
        self.gradient = (y1 - y0) / (x1 - x0) if x1 != x0 else math.inf

    def value(self, x: int) -> float:
        return self.y0 + self.gradient * (x - self.x0)


class Mover:
    """An emitter or a bullet: position, direction, speed, accel velocity, its runners."""

    def __init__(self, x: float, y: float, d: float, s: float):
        self.x, self.y, self.dir, self.spd, self.ax, self.ay = x, y, d, s, 0.0, 0.0
        self.impls: list[Impl] = []
        self.dead = False
        self.first_turn = 0  # the frame its runners first run

    def velocity(self) -> tuple[float, float]:
        r = math.radians(self.dir)
        return math.sin(r) * self.spd + self.ax, -math.cos(r) * self.spd + self.ay


class Impl:
    """One libBulletML runner (``BulletMLRunnerImpl``) of ``mover``, over the action list
    ``nodes``."""

    def __init__(self, world: Runner, mover: Mover, nodes: list[Node], params: list[float] | None):
        self.w, self.m, self.nodes, self.params = world, mover, list(nodes), params
        self.roots = {id(n) for n in nodes}  # libBulletML cuts these nodes from their parents
        self.act: Node | None = self.nodes[0] if self.nodes else None
        self.ite = 0
        self.act_turn = -1
        self.end_turn = 0
        self.changes: dict[str, Linear] = {}
        self.spd: float | None = None
        self.dir: float | None = None
        self.prev_spd: float | None = None
        self.prev_dir: float | None = None
        self.repeats: list[list] = []  # [ite, end, body]
        self.refs: list[tuple[Node, list[float] | None]] = []

    def parent(self, n: Node) -> Node | None:
        return None if id(n) in self.roots else n.parent

    def num(self, n: Node) -> float:
        assert n.formula is not None
        return n.formula.value(self.w, self.params)

    # run() -----------------------------------------------------------------------------
    def run(self) -> None:
        now = self.w.turn
        for key in ("dir", "spd", "ax", "ay"):
            f = self.changes.get(key)
            if f is None:
                continue
            if now >= f.x1:
                setattr(self.m, key, f.y1)
                del self.changes[key]
            else:
                setattr(self.m, key, f.value(now))
        self.end_turn = now
        if self.act is None:
            return
        self.act = self.nodes[self.ite]
        if self.act_turn == -1:
            self.act_turn = now
        self.run_sub()
        if self.act is None:
            self.ite += 1
            if self.ite < len(self.nodes):
                self.act = self.nodes[self.ite]
        else:
            self.nodes[self.ite] = self.act

    def run_sub(self) -> None:
        while self.act is not None and self.act_turn <= self.end_turn:
            prev = self.act
            getattr(self, "do_" + self.act.name)()
            par = self.parent(prev)
            if self.act is None and par is not None and par.name == "bulletml":
                prev, self.params = self.refs.pop()
            if self.act is None:
                self.act = None if id(prev) in self.roots else prev.next()
            while self.act is None:
                par = self.parent(prev)
                if par is not None and par.name == "repeat":
                    rep = self.repeats[-1]
                    rep[0] += 1
                    if rep[0] < rep[1]:
                        self.act = rep[2]
                        break
                    self.repeats.pop()
                self.act = par
                if self.act is None:
                    break
                prev = self.act
                par = self.parent(prev)
                if par is not None and par.name == "bulletml":
                    prev, self.params = self.refs.pop()
                    self.act = prev
                self.act = None if id(self.act) in self.roots else self.act.next()

    # commands --------------------------------------------------------------------------
    def do_action(self) -> None:
        assert self.act is not None
        self.act = self.act.children[0] if self.act.children else None

    def do_repeat(self) -> None:
        assert self.act is not None
        times = self.act.child("times")
        body = self.act.child("action") or self.act.child("actionRef")
        assert times is not None and body is not None
        self.repeats.append([0, int(self.num(times)), body])
        self.act = body

    def _ref(self) -> None:
        assert self.act is not None
        old = self.params
        ps = self.act.all("param")
        self.params = [0.0] + [self.num(p) for p in ps] if ps else None
        self.refs.append((self.act, old))
        self.act = self.w.doc.ref(self.act)

    do_actionRef = do_bulletRef = do_fireRef = _ref

    def do_wait(self) -> None:
        assert self.act is not None
        frames = int(self.num(self.act))
        if frames > 0:
            self.act_turn += frames
        self.act = None

    def do_vanish(self) -> None:
        self.m.dead = True
        self.act = None

    def do_fire(self) -> None:
        assert self.act is not None
        self.spd = self.dir = None
        self.set_speed_direction()
        self.act = self.act.child("bullet") or self.act.child("bulletRef")

    def set_speed_direction(self) -> None:
        assert self.act is not None
        s, d = self.act.child("speed"), self.act.child("direction")
        if s is not None:
            self.spd = self.speed(s)
        if d is not None:
            self.dir = self.direction(d, True)

    def do_bullet(self) -> None:
        assert self.act is not None
        self.set_speed_direction()
        if self.spd is None:
            self.spd = self.prev_spd = 1.0
        if self.dir is None:
            self.dir = self.prev_dir = self.w.aim(self.m)
        acts = self.act.all("action") + self.act.all("actionRef")
        self.w.create(self.m, self.dir, self.spd, acts, self.params)
        self.act = None

    def speed(self, n: Node) -> float:
        s = self.num(n)
        if n.type == "relative":
            s += self.m.spd
        elif n.type == "sequence":
            s = 1.0 if self.prev_spd is None else s + self.prev_spd
        self.prev_spd = s
        return s

    def direction(self, n: Node, remember: bool) -> float:
        d = self.num(n)
        aim = n.type not in ("absolute", "relative", "sequence")
        if n.type == "absolute" and self.w.doc.horizontal:
            d -= 90
        elif n.type == "relative":
            d += self.m.dir
        elif n.type == "sequence":
            if self.prev_dir is None:
                d, aim = 0.0, True
            else:
                d += self.prev_dir
        if aim:
            d += self.w.aim(self.m)
        while d > 360:
            d -= 360
        while d < 0:
            d += 360
        if remember:
            self.prev_dir = d
        return d

    def do_changeDirection(self) -> None:
        assert self.act is not None
        term_n, n = self.act.child("term"), self.act.child("direction")
        assert term_n is not None and n is not None
        term = int(self.num(term_n))
        first = self.m.dir
        if n.type == "sequence":
            last = first + self.num(n) * term
        else:
            d1 = self.direction(n, False) - first
            d2 = d1 - 360 if d1 > 0 else d1 + 360
            last = first + (d1 if abs(d1) < abs(d2) else d2)
        self.changes["dir"] = Linear(self.act_turn, self.act_turn + term, first, last)
        self.act = None

    def do_changeSpeed(self) -> None:
        assert self.act is not None
        term_n, n = self.act.child("term"), self.act.child("speed")
        assert term_n is not None and n is not None
        term = int(self.num(term_n))
        if n.type == "sequence":
            last = self.num(n) * term + self.m.spd
        else:
            last = self.speed(n)
        self.changes["spd"] = Linear(self.act_turn, self.act_turn + term, self.m.spd, last)
        self.act = None

    def do_accel(self) -> None:
        assert self.act is not None
        term_n = self.act.child("term")
        assert term_n is not None
        term = int(self.num(term_n))
        h, v = self.act.child("horizontal"), self.act.child("vertical")
        if self.w.doc.horizontal:
            axes = [("ax", v, 1.0), ("ay", h, -1.0)]
        else:
            axes = [("ax", h, 1.0), ("ay", v, 1.0)]
        for key, n, sign in axes:
            if n is None:
                continue
            value = sign * self.num(n)
            first = getattr(self.m, key)
            if n.type == "sequence":
                last = first + value * term
            elif n.type == "relative":
                last = first + value
            else:
                last = value
            self.changes[key] = Linear(self.act_turn, self.act_turn + term, first, last)
        self.act = None


class Runner:
    """The game around the runners: one emitter at ``origin`` aiming at ``target``, its
    bullets, the frame counter ``turn``."""

    def __init__(self, text: str, origin, target, rank: float = 0.5, seed: int = 0):
        self.doc = Document(text)
        self.rank = float(rank)
        self.rng = np.random.Generator(np.random.PCG64(seed))
        self.target = (float(target[0]), float(target[1]))
        self.turn = 0
        self.emitter = Mover(float(origin[0]), float(origin[1]), 0.0, 0.0)
        self.emitter.impls = [Impl(self, self.emitter, [t], None) for t in self.doc.top]
        self.bullets: list[Mover] = []
        self._in_bullets = False

    def rand(self) -> float:
        return float(self.rng.random())

    def aim(self, m: Mover) -> float:
        return math.degrees(math.atan2(self.target[0] - m.x, -(self.target[1] - m.y)))

    def create(self, firer: Mover, d: float, s: float, acts: list[Node], params) -> None:
        b = Mover(firer.x, firer.y, d, s)
        if acts:
            b.impls = [Impl(self, b, acts, params)]
        b.first_turn = self.turn if self._in_bullets else self.turn + 1
        self.bullets.append(b)

    def step(self) -> None:
        old = len(self.bullets)
        for impl in self.emitter.impls:
            impl.run()
        self._in_bullets = True
        i = 0
        while i < len(self.bullets):
            b = self.bullets[i]
            if b.first_turn <= self.turn:
                for impl in b.impls:
                    impl.run()
            i += 1
        self._in_bullets = False
        for b in self.bullets[:old]:
            vx, vy = b.velocity()
            b.x += vx
            b.y += vy
        self.bullets = [b for b in self.bullets if not b.dead]
        self.turn += 1

    def positions(self) -> np.ndarray:
        return np.array([(b.x, b.y) for b in self.bullets], dtype=np.float64).reshape(-1, 2)


def trace(
    text: str,
    frames: int,
    origin,
    target,
    rank: float = 0.5,
    seed: int = 0,
    path: Callable[[int], tuple[float, float]] | None = None,
) -> list[np.ndarray]:
    """Like ``broadsword.patterns.bulletml.trace``: one (k, 2) array per frame. With
    ``path``, the emitter is put at ``path(frame)`` before each frame (as the game puts an
    emitter at its ship)."""
    r = Runner(text, origin, target, rank, seed)
    out = []
    for f in range(frames):
        if path is not None:
            r.emitter.x, r.emitter.y = path(f)
        r.step()
        out.append(r.positions())
    return out
