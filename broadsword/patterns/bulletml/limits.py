"""Every cap that keeps a hostile BulletML file or expression harmless, in one place.

A file past a load-time cap is refused with a ``ValueError``; a value past a run-time cap is
clamped (documented in docs/PATTERNS.md, "Limits"), so a running pattern never raises.
"""

from __future__ import annotations

#: Largest file read, bytes (checked before parsing). Public patterns are a few KB.
MAX_FILE_BYTES = 1 << 20
#: Deepest element nesting accepted.
MAX_DEPTH = 64
#: Most elements in one file.
MAX_ELEMENTS = 20_000
#: Longest expression text, characters.
MAX_EXPRESSION_CHARS = 2_000
#: Deepest parenthesis / unary-minus nesting inside one expression.
MAX_EXPRESSION_DEPTH = 48
#: Longest chain of actionRef / fireRef / bulletRef hops inside one runner.
MAX_REF_CHAIN = 32
#: Most parameters a reference may pass.
MAX_PARAMS = 64
#: Highest ``$n`` an expression may name.
MAX_PARAM_INDEX = 64
#: A ``<times>`` value is clamped to this (a constant above it is refused at load).
MAX_REPEAT = 100_000
#: Largest magnitude an expression yields at run time (non-finite results become 0).
MAX_VALUE = 1e9
#: The work of a frame is counted in steps: a command is one step; firing a bullet costs
#: ``FIRE_STEPS`` more, measuring an aim (the deterministic arctangent) ``AIM_STEPS`` more,
#: waking a runner ``WAKE_STEPS``, and evaluating an expression one step per token (a constant
#: nothing). The weights follow what each costs in Python (a fire with an
#: aim is about ten times a ``wait``), so a budget of steps is a budget of time.
FIRE_STEPS = 4
AIM_STEPS = 4
WAKE_STEPS = 1
#: Steps one runner may take in one frame; past it, it resumes next frame.
MAX_STEPS_PER_FRAME = 4_000
#: Steps all the runners of one engine may take in one part of a frame (the emitters'
#: part, :meth:`~.engine.Engine.fire`, or the bullets', :meth:`~.engine.Engine.advance`);
#: past it, every runner not yet served waits for the next frame (and is served first then).
#: Bounds the work of a frame however many emitters fire: about 4 ms a part on this project's
#: benchmark machine (docs/PERFORMANCE.md), where 40,000 commands took 50 to 90 ms.
MAX_STEPS_PER_PART = 4_000
#: Fastest a mover goes, px per frame on each axis (its velocity is clamped to it). A speed
#: near ``MAX_VALUE`` crosses the field a million times a frame: swept against the player, such
#: bullets cost the collision's exact fallback thousands of calls a frame. 64 px a frame is
#: 3,840 px/s, six field heights a second.
MAX_SPEED = 64.0
#: Live bullets one pattern run may hold (``trace`` and ``check``); fires past it are refused.
MAX_LIVE_BULLETS = 4_096
