"""BulletML number expressions, read by our own parser (never ``eval``).

Grammar (usual precedence, left to right)::

    expr    := term (("+" | "-") term)*
    term    := unary (("*" | "/" | "%") unary)*
    unary   := ("-" | "+") unary | primary
    primary := NUMBER | "$rand" | "$rank" | "$" DIGITS | "(" expr ")"

An expression compiles once, at load, to a tree of small closures; sub-expressions without
``$`` variables are folded to constants. Bounds: text length, nesting depth and ``$n`` index
(``limits``); at load a constant that overflows or divides by zero is refused. At run time a
division or ``%`` by zero gives 0, a non-finite result gives 0 and any result is clamped to
``±MAX_VALUE``, so evaluation never raises and never loops. ``%`` is C's ``fmod`` (the sign
of the dividend).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .limits import MAX_EXPRESSION_CHARS, MAX_EXPRESSION_DEPTH, MAX_PARAM_INDEX, MAX_VALUE


class Scope:
    """What an expression reads while it runs: ``params`` (``$1`` is ``params[0]``; a missing
    one reads 0), ``rank`` (``$rank``) and ``rng`` (a numpy ``Generator``; ``$rand`` is its
    next ``random()`` draw, uniform in [0, 1))."""

    __slots__ = ("params", "rank", "rng")

    def __init__(self, params: tuple[float, ...], rank: float, rng: np.random.Generator):
        self.params, self.rank, self.rng = params, rank, rng


Fn = Callable[[Scope], float]

_TOKEN = re.compile(r"\s*(?:(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)|(?P<var>\$[A-Za-z0-9_]+)|(?P<op>[-+*/%()]))")


def _div(a: float, b: float) -> float:
    return a / b if b != 0 else math.nan


def _mod(a: float, b: float) -> float:
    if b == 0 or not math.isfinite(a) or math.isnan(b):
        return math.nan
    return math.fmod(a, b)


_BINARY = {"+": lambda a, b: a + b, "-": lambda a, b: a - b, "*": lambda a, b: a * b, "/": _div, "%": _mod}


def clamp(value: float) -> float:
    """A raw result made safe: non-finite -> 0, magnitude at most ``MAX_VALUE``."""
    if value != value or value in (math.inf, -math.inf):
        return 0.0
    return max(-MAX_VALUE, min(MAX_VALUE, value))


@dataclass(frozen=True)
class Expr:
    """A compiled expression. ``const`` is its value when it reads no ``$`` variable.
    ``max_param`` is the highest ``$n`` it reads (0 for none). ``steps`` is what evaluating
    it costs the engine's budget (its tokens; 0 for a constant): a 2,000-character expression
    is hundreds of Python operations, so it counts as hundreds of commands. ``random``: it
    reads ``$rand`` (else its value depends only on the ``$n`` parameters and ``$rank``)."""

    text: str
    const: float | None
    fn: Fn
    max_param: int
    steps: int = 0
    random: bool = False

    def value(self, scope: Scope) -> float:
        """The expression's value in ``scope`` (finite, clamped; see the module doc)."""
        if self.const is not None:
            return self.const
        v = self.fn(scope)
        return v if -MAX_VALUE <= v <= MAX_VALUE else clamp(v)  # NaN fails both: clamped to 0


class _Parser:
    def __init__(self, text: str):
        self.text = text
        self.tokens: list[tuple[str, str]] = []
        pos = 0
        stripped = text.rstrip()
        while pos < len(stripped):
            m = _TOKEN.match(stripped, pos)
            if not m:
                bad = stripped[pos:].lstrip()[:12]
                raise ValueError(f"expression {_short(text)}: unexpected {bad!r}")
            kind = m.lastgroup
            assert kind is not None  # every alternative of _TOKEN is a named group
            self.tokens.append((kind, m.group(kind)))
            pos = m.end()
        self.i = 0
        self.max_param = 0

    def peek(self) -> tuple[str, str] | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self) -> tuple[str, str]:
        tok = self.peek()
        if tok is None:
            raise ValueError(f"expression {_short(self.text)}: ends too early")
        self.i += 1
        return tok

    def parse(self) -> tuple[float | None, Fn]:
        if not self.tokens:
            raise ValueError("expression is empty")
        node = self.expr(0)
        extra = self.peek()
        if extra is not None:
            raise ValueError(f"expression {_short(self.text)}: unexpected {extra[1]!r}")
        return node

    def expr(self, depth: int):
        return self.chain(depth, "+-", self.term)

    def term(self, depth: int):
        return self.chain(depth, "*/%", self.unary)

    def chain(self, depth: int, ops: str, operand):
        """A left-associative run ``a op b op c ...``, evaluated by a loop (never one
        closure per term, so a long sum cannot exhaust Python's stack)."""
        first = operand(depth)
        rest = []
        while (tok := self.peek()) is not None and tok[0] == "op" and tok[1] in ops:
            self.i += 1
            rest.append((tok[1], operand(depth)))
        if not rest:
            return first
        return _chain(first, rest, self.text)

    def unary(self, depth: int):
        if depth > MAX_EXPRESSION_DEPTH:
            raise ValueError(f"expression {_short(self.text)}: nested deeper than {MAX_EXPRESSION_DEPTH}")
        tok = self.peek()
        if tok is not None and tok[0] == "op" and tok[1] in "+-":
            self.i += 1
            const, fn = self.unary(depth + 1)
            if tok[1] == "+":
                return const, fn
            if const is not None:
                return -const, None
            return None, lambda s: -fn(s)
        return self.primary(depth)

    def primary(self, depth: int):
        kind, text = self.take()
        if kind == "num":
            value = float(text)
            if not math.isfinite(value):
                raise ValueError(f"expression {_short(self.text)}: number {text[:20]!r} is out of range")
            return value, None
        if kind == "var":
            return self.variable(text)
        if text == "(":
            node = self.expr(depth + 1)
            if self.take()[1] != ")":
                raise ValueError(f"expression {_short(self.text)}: expected ')'")
            return node
        raise ValueError(f"expression {_short(self.text)}: unexpected {text!r}")

    def variable(self, text: str):
        if text == "$rand":
            return None, lambda s: float(s.rng.random())
        if text == "$rank":
            return None, lambda s: s.rank
        digits = text[1:]
        if digits.isdigit() and digits.isascii():
            n = int(digits) if len(digits) <= 4 else MAX_PARAM_INDEX + 1
            if 1 <= n <= MAX_PARAM_INDEX:
                self.max_param = max(self.max_param, n)
                k = n - 1
                return None, lambda s: s.params[k] if k < len(s.params) else 0.0
        raise ValueError(
            f"expression {_short(self.text)}: unknown variable {text[:20]!r} "
            f"(expected $rand, $rank or $1..${MAX_PARAM_INDEX})"
        )


def _chain(first, rest, text: str):
    """Fold the constant prefix of a chain; the remainder runs as one loop."""
    const, fn = first
    i = 0
    while const is not None and i < len(rest) and rest[i][1][0] is not None:
        op, (rc, _) = rest[i]
        if op in "/%" and rc == 0:
            raise ValueError(f"expression {_short(text)}: division by zero")
        const = _BINARY[op](const, rc)
        if not math.isfinite(const):
            raise ValueError(f"expression {_short(text)}: overflows")
        i += 1
    if i == len(rest):
        return const, None
    for op, (rc, _) in rest[i:]:
        if op in "/%" and rc == 0:
            raise ValueError(f"expression {_short(text)}: division by zero")
    head = (lambda s, c=const: c) if const is not None else fn
    steps = tuple((_BINARY[op], rc, rf) for op, (rc, rf) in rest[i:])
    if len(steps) == 1:  # ``a op b``, the usual case, as one closure (no loop)
        return None, _binary(const, head, *steps[0])

    def run(s: Scope) -> float:
        value = head(s)
        for f, rc, rf in steps:
            value = f(value, rc if rf is None else rf(s))
        return value

    return None, run


def _binary(const: float | None, head: Fn, f, rc: float | None, rf: Fn | None) -> Fn:
    """``head op b`` for :func:`_chain`: the same operations as its loop, in one closure
    (a constant on either side read as it is, not called)."""
    if const is not None:
        assert rf is not None  # a constant on both sides was folded
        return lambda s: f(const, rf(s))
    if rf is None:
        return lambda s: f(head(s), rc)
    return lambda s: f(head(s), rf(s))


def _short(text: str) -> str:
    text = " ".join(text.split())
    return repr(text if len(text) <= 40 else text[:37] + "...")


def compile_expression(text: str) -> Expr:
    """Compile ``text``; raises ``ValueError`` (without file or element: the loader adds
    them) for a malformed, too long or too deep expression, an unknown variable, or a
    constant that overflows or divides by zero."""
    if len(text) > MAX_EXPRESSION_CHARS:
        raise ValueError(f"expression is {len(text)} characters long (at most {MAX_EXPRESSION_CHARS})")
    parser = _Parser(text)
    const, fn = parser.parse()
    if const is not None:
        value = clamp(const)
        return Expr(text, value, lambda s: value, 0)
    return Expr(text, None, fn, parser.max_param, len(parser.tokens), ("var", "$rand") in parser.tokens)
