"""Running BulletML machines as number streams and back (what a snapshot keeps of them)."""

from __future__ import annotations

import numpy as np
import pytest

from broadsword.patterns import bulletml
from broadsword.patterns.bulletml.runstate import NodeTable, decode_runners, encode_runners

PATTERN = """<bulletml>
<action label="top"><repeat><times>50</times><action>
  <fire><direction type="sequence">13</direction><speed>2</speed><bulletRef label="b"/></fire>
  <wait>2</wait></action></repeat></action>
<bullet label="b"><action><wait>3</wait><changeSpeed><speed>$rand</speed><term>20</term></changeSpeed>
  <actionRef label="turn"><param>$rand * 90</param></actionRef></action></bullet>
<action label="turn"><repeat><times>4</times><action><wait>5</wait>
  <changeDirection><direction type="relative">$1</direction><term>5</term></changeDirection></action></repeat></action>
</bulletml>"""


def _engine(frames: int):
    p = bulletml.loads(PATTERN, name="p")
    eng = bulletml.Engine(seed=3)
    eng.target = np.array([100.0, 300.0])
    eng.add_emitter(p, (100.0, 50.0))
    for _ in range(frames):
        eng.step()
    return p, eng


def _streams(table, movers):
    rows = [i for i, r in enumerate(movers.runner) if r is not None]
    return encode_runners(table, rows, [movers.runner[i] for i in rows])


def test_runners__round_trip_runs_the_same():
    """Decoded runners, put in a second engine at the same point, fire and move the same."""
    p, a = _engine(23)
    _, b = _engine(23)
    table = NodeTable([p])
    for store in ("emitters", "bullets"):
        ma, mb = getattr(a, store), getattr(b, store)
        ints, floats = _streams(table, ma)
        assert len(ints) and len(floats)
        mb.runner[: mb.n] = decode_runners(table, ints, floats, ma.n, store)
        for ra, rb in zip(ma.runner, mb.runner, strict=True):
            assert (ra is None) == (rb is None) and (ra is None or ra is not rb)
        assert all(np.array_equal(x, y) for x, y in zip(_streams(table, mb), (ints, floats), strict=True))
    for _ in range(40):
        a.step()
        b.step()
    np.testing.assert_array_equal(a.bullets.pos, b.bullets.pos)


def test_runners__bad_streams_name_the_row_and_field():
    p, eng = _engine(23)
    table = NodeTable([p])
    ints, floats = _streams(table, eng.bullets)
    n = eng.bullets.n
    first = int(ints[0])
    bad = ints.copy()
    assert bad[4] >= 1  # row, gone, threads, pattern, nodes: the first thread's first node next
    bad[5] = 10_000
    with pytest.raises(ValueError, match=rf"^bullets: runner of row {first}: node: 10000 is out of range"):
        decode_runners(table, bad, floats, n, "bullets")
    with pytest.raises(ValueError, match=r"ends early"):
        decode_runners(table, ints[:-1], floats, n, "bullets")
    with pytest.raises(ValueError, match=r"^bullets: 1 runner floats left over$"):
        decode_runners(table, ints, np.append(floats, 1.0), n, "bullets")
    with pytest.raises(ValueError, match=r"^bullets: runner row: .* out of range"):
        decode_runners(table, ints, floats, first, "bullets")  # rows past the store's


def test_node_table__copies_of_one_pattern_number_alike():
    """The same pattern loaded twice (as two FireSpecs of one kind load theirs) gets one
    number, its nodes the first copy's: which copy a gun runs leaves no trace in a snapshot."""
    p, q = bulletml.loads(PATTERN, name="p"), bulletml.loads(PATTERN, name="p")
    other = bulletml.loads(PATTERN, name="other")
    table = NodeTable([p, q, other])
    assert table.pattern_index[id(p)] == table.pattern_index[id(q)] == 0 and table.pattern_index[id(other)] == 1
    assert table.patterns == [p, other]
    assert table.index[id(q.top[0])] == table.index[id(p.top[0])]
    assert table.index[id(other.top[0])] != table.index[id(p.top[0])]
