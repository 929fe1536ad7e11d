"""Compiled expressions against a plain left-to-right evaluation of the same text.

The compiler folds constants and turns ``a op b`` into one closure; whatever shape it
picks, the value, its clamping and the order of ``$rand`` draws must be the grammar's."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from broadsword.patterns.bulletml.expr import Scope, compile_expression
from broadsword.patterns.bulletml.limits import MAX_VALUE

_OPERANDS = ("3", "0", "-2.5", "1e300", "$1", "$2", "$3", "$rand", "$rank")
_OPS = "+-*/%"


def _plain(operands: list[str], ops: list[str], params: tuple[float, ...], rank: float, seed: int) -> float:
    """The chain ``o0 op o1 op ...`` evaluated as the grammar
    says (``*``, ``/``, ``%`` before ``+``, ``-``; left to right; ``$rand`` drawn in text
    order; ``/`` or ``%`` by zero, and anything non-finite, gives 0 in the end)."""
    rng = np.random.Generator(np.random.PCG64(seed))

    def read(text: str) -> float:
        if text == "$rand":
            return float(rng.random())
        if text == "$rank":
            return rank
        if text.startswith("$"):
            k = int(text[1:]) - 1
            return params[k] if k < len(params) else 0.0
        return float(text)

    def apply(a: float, op: str, b: float) -> float:
        if op == "+":
            return a + b
        if op == "-":
            return a - b
        if op == "*":
            return a * b
        if op == "/":
            return a / b if b != 0 else math.nan
        return math.fmod(a, b) if b != 0 and math.isfinite(a) and not math.isnan(b) else math.nan

    values = [read(o) for o in operands]  # read in text order: the $rand draws
    terms, term = [], values[0]
    for op, v in zip(ops, values[1:], strict=True):
        if op in "*/%":
            term = apply(term, op, v)
        else:
            terms.append(term)
            terms.append(op)  # type: ignore[arg-type]
            term = v
    terms.append(term)
    total = terms[0]
    for i in range(1, len(terms), 2):
        total = apply(total, terms[i], terms[i + 1])
    if not math.isfinite(total):
        return 0.0
    return max(-MAX_VALUE, min(MAX_VALUE, total))


@settings(max_examples=300, deadline=None)
@given(
    st.lists(st.sampled_from(_OPERANDS), min_size=2, max_size=5).flatmap(
        lambda ops: st.tuples(
            st.just(ops), st.lists(st.sampled_from(_OPS), min_size=len(ops) - 1, max_size=len(ops) - 1)
        )
    ),
    st.lists(st.floats(-1e6, 1e6), max_size=3).map(tuple),
    st.floats(0, 1),
    st.integers(0, 2**32),
)
def test_expression__is_the_plain_left_to_right_evaluation(chain, params, rank, seed):
    operands, ops = chain
    text = operands[0] + "".join(f" {op} {o}" for op, o in zip(ops, operands[1:], strict=True))
    try:
        expr = compile_expression(text)
    except ValueError as exc:  # only a constant division by zero or overflow is refused at load
        assert "division by zero" in str(exc) or "overflows" in str(exc)
        return
    got = expr.value(Scope(params, rank, np.random.Generator(np.random.PCG64(seed))))
    want = _plain(operands, ops, params, rank, seed)
    assert got == want or (math.isnan(got) and math.isnan(want)), (text, got, want)
    assert math.copysign(1.0, got) == math.copysign(1.0, want) or got != 0.0  # the same signed zero


def test_expression__a_binary_of_each_shape_reads_its_operands_in_order():
    rng_seed = 7
    for text, want in (("$rand - $rand", None), ("$1 / 4", 0.5), ("4 / $1", 2.0), ("$1 * $2", 6.0), ("$1 % $3", 0.0)):
        got = compile_expression(text).value(Scope((2.0, 3.0), 0.5, np.random.Generator(np.random.PCG64(rng_seed))))
        if want is None:
            r = np.random.Generator(np.random.PCG64(rng_seed))
            want = float(r.random()) - float(r.random())
        assert got == want, text
