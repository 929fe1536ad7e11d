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
#: Commands one runner may execute in one frame; past it, it resumes next frame.
MAX_STEPS_PER_FRAME = 10_000
#: Commands all the runners of one engine may execute in one part of a frame (the emitters'
#: part, :meth:`~.engine.Engine.fire`, or the bullets', :meth:`~.engine.Engine.advance`);
#: past it, every runner not yet served waits for the next frame (and is served first then).
#: Bounds the work of a frame however many emitters fire (thousands of ships each firing
#: 256-bullet rings every frame would otherwise run a million commands a frame).
MAX_STEPS_PER_PART = 40_000
#: Live bullets one pattern run may hold (``trace`` and ``check``); fires past it are refused.
MAX_LIVE_BULLETS = 4_096
