"""Hostile and broken files are data: each is refused with 'FILE: ELEMENT-PATH (line N): what',
or runs within its bounds; nothing crashes, hangs or reaches outside the file."""

import numpy as np
import pytest
from bml import fire, run, top
from hypothesis import given, settings
from hypothesis import strategies as st

from broadsword.patterns import bulletml
from broadsword.patterns.bulletml import limits

GOOD = '<bulletml><action label="top"><fire><bullet/></fire></action></bulletml>'


def refused(text, name="bad.xml") -> str:
    with pytest.raises(ValueError) as err:
        bulletml.loads(text, name)
    msg = str(err.value)
    assert msg.startswith(name + ": "), msg
    assert "\n" not in msg
    return msg


@pytest.mark.parametrize(
    "text, path, what",
    [
        (
            '<bulletml><action label="top"><fire><bulet/></fire></action></bulletml>',
            "bulletml/action/fire/bulet",
            "not allowed inside <fire>",
        ),
        (
            '<bulletml><action label="top"><fire/></action></bulletml>',
            "bulletml/action/fire",
            "needs a <bullet> or <bulletRef>",
        ),
        ('<bulletml><action label="top"><wait>1+</wait></action></bulletml>', "bulletml/action/wait", "ends too early"),
        (
            '<bulletml><action label="top"><wait>$foo</wait></action></bulletml>',
            "bulletml/action/wait",
            "unknown variable",
        ),
        (
            '<bulletml><action label="top"><wait>1e999</wait></action></bulletml>',
            "bulletml/action/wait",
            "out of range",
        ),
        (
            '<bulletml><action label="top"><wait>1/0</wait></action></bulletml>',
            "bulletml/action/wait",
            "division by zero",
        ),
        (
            '<bulletml><action label="top"><wait>' + "1+" * 5000 + "1</wait></action></bulletml>",
            "bulletml/action/wait",
            "characters long",
        ),
        (
            '<bulletml><action label="top"><wait>' + "(" * 100 + "1" + ")" * 100 + "</wait></action></bulletml>",
            "bulletml/action/wait",
            "nested deeper",
        ),
        (
            '<bulletml><action label="top"><fire><direction type="up">1</direction><bullet/></fire></action></bulletml>',
            "bulletml/action/fire/direction",
            "type 'up'",
        ),
        ('<bulletml type="diagonal"><action label="top"/></bulletml>', "bulletml", "type 'diagonal'"),
        (
            '<bulletml><action label="top"><fireRef label="nope"/></action></bulletml>',
            "bulletml/action/fireRef",
            "no fire labelled 'nope'",
        ),
        ('<bulletml><action label="top"/><action label="top"/></bulletml>', "bulletml/action[2]", "already used"),
        (
            '<bulletml><action label="top"><repeat><times>1e9</times><action/></repeat></action></bulletml>',
            "bulletml/action/repeat/times",
            "at most",
        ),
        (
            '<bulletml><action label="top"><repeat><action/></repeat></action></bulletml>',
            "bulletml/action/repeat",
            "needs a <times>",
        ),
        (
            '<bulletml><action label="top"><changeSpeed><speed>1</speed></changeSpeed></action></bulletml>',
            "bulletml/action/changeSpeed",
            "needs a <term>",
        ),
        ('<bulletml><action label="top"><vanish>x</vanish></action></bulletml>', "bulletml/action/vanish", "text"),
        ("<bml/>", "bml", "expected <bulletml>"),
        ('<bulletml><action label="top"><actionRef/></action></bulletml>', "bulletml/action/actionRef", "label"),
    ],
)
def test_refused__names_file_then_element_then_problem(text, path, what):
    msg = refused(text)
    assert msg.startswith(f"bad.xml: {path} (line "), msg
    assert what in msg, msg


def test_refused__actionref_loop_named():
    msg = refused(
        '<bulletml><action label="top"><actionRef label="a"/></action>'
        '<action label="a"><repeat><times>2</times><actionRef label="b"/></repeat></action>'
        '<action label="b"><wait>1</wait><actionRef label="a"/></action></bulletml>'
    )
    assert "actionRef loop" in msg and "a -> b -> a" in msg


def test_refused__self_reference_and_fireref_loops():
    assert "loop" in refused('<bulletml><action label="top"><actionRef label="top"/></action></bulletml>')


def test_accepted__a_bullet_that_fires_itself_is_not_a_loop():
    p = bulletml.loads(
        '<bulletml><action label="top"><fire><bulletRef label="b"/></fire></action>'
        '<bullet label="b"><action><wait>1</wait><fire><bulletRef label="b"/></fire></action></bullet>'
        "</bulletml>"
    )
    # each fires one more a frame after its first run; a bullet fired by a bullet runs in the
    # frame it is fired (libBulletML), so from frame 2 the chain grows by one every frame
    assert [len(f) for f in run(p, 5)] == [1, 1, 2, 3, 4]


def test_refused__long_reference_chain():
    chain = "".join(f'<action label="a{i}"><actionRef label="a{i + 1}"/></action>' for i in range(40))
    msg = refused(
        f'<bulletml><action label="top"><actionRef label="a0"/></action>{chain}<action label="a40"/></bulletml>'
    )
    assert "deeper than" in msg


def test_refused__entity_bomb_and_external_entities():
    bomb = (
        '<?xml version="1.0"?><!DOCTYPE lolz [<!ENTITY lol "lol"><!ENTITY lol2 "&lol;&lol;&lol;&lol;">]>'
        "<bulletml>&lol2;</bulletml>"
    )
    assert "internal subset" in refused(bomb)
    xxe = '<?xml version="1.0"?><!DOCTYPE bulletml SYSTEM "file:///etc/passwd"><bulletml>&xxe;</bulletml>'
    assert "entity reference &xxe;" in refused(xxe)
    param = '<!DOCTYPE b [<!ENTITY % p SYSTEM "http://example.com/x.dtd"> %p;]><bulletml/>'
    assert "internal subset" in refused(param)


def test_accepted__the_public_files_doctype_line_is_read_not_fetched():
    text = (
        '<?xml version="1.0" ?>\n<!DOCTYPE bulletml SYSTEM "http://www.asahi-net.or.jp/~cs8k-cyu/bulletml/bulletml.dtd">\n'
        '<bulletml type="vertical" xmlns="http://www.asahi-net.or.jp/~cs8k-cyu/bulletml">\n'
        '<action label="top"><fire><bullet/></fire></action></bulletml>'
    )
    assert bulletml.loads(text).top[0].label == "top"


def test_refused__too_deep_too_big_too_many(tmp_path):
    assert "nested deeper" in refused("<bulletml>" + "<action>" * 100 + "</action>" * 100 + "</bulletml>")
    big = tmp_path / "big.xml"
    big.write_bytes(b" " * (limits.MAX_FILE_BYTES + 1) + GOOD.encode())
    with pytest.raises(ValueError, match=r"^.*big\.xml: file is \d+ bytes"):
        bulletml.load(big)
    many = '<bulletml><action label="top">' + "<vanish/>" * (limits.MAX_ELEMENTS + 1) + "</action></bulletml>"
    assert "more than" in refused(many)


def test_refused__missing_binary_and_malformed(tmp_path):
    with pytest.raises(ValueError, match=r"nope\.xml: cannot read"):
        bulletml.load(tmp_path / "nope.xml")
    assert "not well-formed" in refused(b"\x00\xff\xfe garbage")
    assert "not well-formed" in refused("<bulletml><action label='top'></bulletml>")


def test_bounded__huge_loops_yield_and_finish_fast(monkeypatch):
    """10**10 zero waits: the runner yields after MAX_STEPS_PER_FRAME commands a frame, so three
    frames evaluate a bounded number of expressions (counted, not timed)."""
    from broadsword.patterns.bulletml.engine import Engine

    p = top(
        "<repeat><times>100000</times><action><repeat><times>100000</times><action><wait>0</wait></action>"
        "</repeat></action></repeat>"
    )
    calls = []
    original = Engine.evaluate
    monkeypatch.setattr(Engine, "evaluate", lambda self, e, params: calls.append(1) or original(self, e, params))
    run(p, 3)
    assert 0 < len(calls) <= 3 * 2 * limits.MAX_STEPS_PER_FRAME


def test_bounded__live_bullets_are_capped():
    p = top("<repeat><times>$rank * 100000</times><action>" + fire() + "</action></repeat>")
    frames = run(p, 30, rank=1.0)  # the engine fires a few hundred a frame (its budget of steps)
    assert len(frames[-1]) == limits.MAX_LIVE_BULLETS


def test_bounded__an_engine_runs_at_most_max_steps_commands_a_part_and_serves_everyone_in_turn():
    """Ten emitters each firing a 30-bullet volley every frame (about 60 commands each) under a
    budget of 100 commands a part: each part stops at 100 commands, and the emitters left
    waiting go first next frame, so every emitter fires within a few frames (none starves)."""
    from broadsword.patterns.bulletml.engine import Engine

    p = top(
        "<repeat><times>1000</times><action><repeat><times>30</times><action>"
        + fire()
        + "</action></repeat><wait>1</wait></action></repeat>"
    )
    eng = Engine(max_steps=100)
    for k in range(10):
        eng.add_emitter(p, (0.0, 0.0), tag=k)
    fired = []
    for _ in range(12):
        before = eng.fired
        eng.step()
        fired.append(eng.fired - before)
    assert eng.busiest == 100 and eng.deferred >= 12
    assert 0 < max(fired) <= 100 and sum(fired) < 12 * 10 * 30
    assert set(eng.bullets.tag.tolist()) == set(range(10))  # every emitter was served
    # The same emitters without a binding budget fire every volley in full each frame.
    free = Engine()
    for k in range(10):
        free.add_emitter(p, (0.0, 0.0), tag=k)
    free.step()
    assert free.fired == 10 * 30 and free.deferred == 0 and 0 < free.busiest < free.max_steps
    with pytest.raises(ValueError, match="max_steps"):
        Engine(max_steps=0)


def test_bounded__runtime_overflow_and_division_by_zero_are_finite():
    p = top(
        fire('<direction type="absolute">$rank / ($rank - $rank)</direction>', "<speed>$rank * 1e300 * 1e300</speed>")
        + "<wait>1e300 * $rank</wait>"
        + fire()
    )
    frames = run(p, 3)
    assert all(np.isfinite(f).all() for f in frames)
    assert [len(f) for f in frames] == [1, 1, 1]


_PIECES = [
    "<bulletml>",
    "</bulletml>",
    '<action label="top">',
    "</action>",
    "<fire>",
    "</fire>",
    "<bullet>",
    "</bullet>",
    "<bullet/>",
    "<wait>",
    "</wait>",
    "<repeat>",
    "</repeat>",
    "<times>",
    "</times>",
    "1",
    "$rand",
    "$1",
    "+",
    "/",
    "0",
    '<actionRef label="top"/>',
    '<direction type="sequence">',
    "</direction>",
    "<speed>",
    "</speed>",
    "<vanish/>",
    "<changeSpeed>",
    "</changeSpeed>",
    "<term>",
    "</term>",
    "&lol;",
    "<!DOCTYPE x>",
    '<action label="a">',
    '<actionRef label="a"/>',
    "<accel>",
    "</accel>",
    "<horizontal>",
    "</horizontal>",
]


@settings(max_examples=150, deadline=None)
@given(st.lists(st.sampled_from(_PIECES), max_size=40) | st.binary(max_size=200))
def test_fuzz__load_refuses_cleanly_or_runs(parts):
    text = parts if isinstance(parts, bytes) else "".join(parts)
    try:
        p = bulletml.loads(text, "fuzz.xml")
    except ValueError as exc:
        assert str(exc).startswith("fuzz.xml: ")
        return
    for f in run(p, 5):
        assert f.dtype == np.float64 and f.ndim == 2 and f.shape[1] == 2


@settings(max_examples=100, deadline=None)
@given(st.text(alphabet="0123456789.+-*/%()$rankd12 e", max_size=60))
def test_fuzz__expressions_compile_or_refuse(text):
    try:
        p = top(fire(f'<direction type="absolute">{text}</direction>', f"<speed>{text}</speed>"))
    except ValueError as exc:
        assert str(exc).startswith("snippet.xml: bulletml/action/fire/")
        return
    assert all(np.isfinite(f).all() for f in run(p, 2))
