"""A corpus of legal BulletML files that push the documented limits (docs/PATTERNS.md,
"Limits"), for the benchmark's worst-step line and the tests that hold the engine's work per
frame bounded. Each is inside every load-time limit; each asks for far more work a frame than
the frame can afford, so the engine's budget of steps (``limits.MAX_STEPS_PER_PART``) is what
keeps it cheap.
"""

from __future__ import annotations

#: A 31-deep fan of action references (each action runs the next twice): 2**31 fires a frame asked.
_FAN = "".join(
    f'<action label="a{i}"><actionRef label="a{i + 1}"/><actionRef label="a{i + 1}"/></action>' for i in range(30)
)
_FAN += '<action label="a30"><fire><direction type="sequence">7</direction><speed>2</speed><bullet/></fire></action>'

#: An expression just under the 2,000-character limit, re-evaluated at every command.
_LONG = "+".join(["$rand*$rank"] * 166)

_FOREVER = "<repeat><times>100000</times><action>{}</action></repeat>"

CORPUS: dict[str, str] = {
    # one ship firing 10,000 bullets every frame
    "ring-10000": "<bulletml><action label='top'>"
    + _FOREVER.format(
        "<repeat><times>10000</times><action><fire><direction type='sequence'>0.036</direction>"
        "<speed>3</speed><bullet/></fire></action></repeat><wait>1</wait>"
    )
    + "</action></bulletml>",
    # the fan above, once a frame
    "fan-31": "<bulletml><action label='top'>"
    + _FOREVER.format("<actionRef label='a0'/><wait>1</wait>")
    + "</action>"
    + _FAN
    + "</bulletml>",
    # 10**10 commands that do nothing
    "busy-loop": "<bulletml><action label='top'>"
    + _FOREVER.format(_FOREVER.format("<wait>0</wait>"))
    + "</action></bulletml>",
    # 4,000 bullets, each firing an aimed bullet every frame
    "bullets-fire": "<bulletml><action label='top'><repeat><times>4000</times><action><fire>"
    "<direction type='sequence'>0.09</direction><speed>0.1</speed><bulletRef label='b'/></fire></action></repeat>"
    "</action><bullet label='b'><action>"
    + _FOREVER.format("<fire><speed>1</speed><bullet/></fire><wait>1</wait>")
    + "</action></bullet></bulletml>",
    # the longest expression, evaluated by commands that do nothing
    "long-expr": "<bulletml><action label='top'>"
    + _FOREVER.format(_FOREVER.format(f"<wait>0*({_LONG})</wait>"))
    + "</action></bulletml>",
    # 500 aimed bullets a frame at the speed limit (1e9 px a frame)
    "fast-aimed": "<bulletml><action label='top'>"
    + _FOREVER.format(
        "<repeat><times>500</times><action><fire><speed>1e9</speed><bullet/></fire></action></repeat><wait>1</wait>"
    )
    + "</action></bulletml>",
}
