"""Every numerical tolerance of ``broadsword.collision``, in one place, with its proof.

Two kinds of number live here:

* Error bounds of the floating-point *filters* in front of the exact predicates. A filter
  may only answer when the rounding error provably cannot flip the sign; otherwise the
  caller falls back to exact rational arithmetic. So these bounds decide speed, never
  answers.
* Slack added to *conservative* bounding volumes (circles, oriented boxes) so that a
  rounding error can only make a tier keep a pair, never drop one.

Orientation filter (``orient(a, b, c) = (bx-ax)(cy-ay) - (by-ay)(cx-ax)``)
----------------------------------------------------------------------
Shewchuk (1997, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
Predicates", section 4.2) proves that with ``l = fl(fl(bx-ax) * fl(cy-ay))``,
``r = fl(fl(by-ay) * fl(cx-ax))`` and ``det = fl(l - r)``, the true determinant has the
sign of ``det`` whenever ``|det| > (3 + 16 eps) eps (|l| + |r|)``, ``eps = 2**-53`` -- but
only when no operation overflows or underflows. The textbook filter is wrong in three
places, and the filter here closes each:

1. Overflow. A difference or product that overflows gives ``inf`` (or ``inf - inf = nan``,
   ``inf * 0 = nan``). Then ``s = |l| + |r|`` is ``inf`` or ``nan``; ``err = ORIENT_EPS * s``
   is ``inf`` or ``nan``, and ``det > err`` / ``det < -err`` are both False: the filter
   declines and the exact path answers. (A filter written ``det - err > 0`` or one that
   compares ``abs(det)`` against a finite constant would let ``inf`` through.)
2. Underflow. A product that underflows to a subnormal or to zero has an *absolute* error
   of up to ``2**-1075`` that no relative bound covers; two tiny products can both round
   to zero and fake a collinear answer. The filter answers only when
   ``s >= UNDERFLOW_GUARD = 2**-960``. Then ``err = 2**-51 * s >= 2**-1011`` is computed
   exactly (a power-of-two scaling of a normal number), and the slack between our bound
   ``4 eps s`` and Shewchuk's ``(3 + 16 eps) eps s`` is at least ``(1 - 16 eps) eps s
   > 2**-1014``, far more than the ``<= 2 * 2**-1075`` that underflowing products add.
   Differences never hurt: a floating-point subtraction whose result is subnormal is exact.
3. nan and inf *inputs* are rejected before any arithmetic (``ValueError``), so they never
   reach a comparison.

``ORIENT_EPS = 4 eps`` is slightly looser than Shewchuk's constant, which costs a vanishing
number of extra exact evaluations and buys the underflow slack above.

Static (per-pair) filter for the vectorised narrow phase
--------------------------------------------------------
For one polygon pair let ``D`` be the larger side of the box around both polygons,
computed in floating point from the vertices. Rounding is monotone, so every computed
edge component ``fl(P_i+1 - P_i)`` and every computed difference ``fl(Q_j - P_i)`` is at
most ``D`` in magnitude, hence ``|l| + |r| <= 2 D^2 (1 + eps)^2`` for every orientation of
the pair, and ``PAIR_EPS * D^2`` with ``PAIR_EPS = 16 eps`` exceeds Shewchuk's
``(3 + 16 eps) eps (|l| + |r|)`` with room for the rounding of ``D^2`` itself. The same
underflow guard applies to ``D^2``, and an infinite or nan ``D`` (overflow) makes every
entry of the pair undecided.
"""

from __future__ import annotations

import sys

#: Unit roundoff of float64 (half an ulp of 1.0).
EPS = 2.0**-53

#: Relative error bound of the orientation filter (see module docstring).
ORIENT_EPS = 4.0 * EPS

#: Below this value of ``|l| + |r|`` the filter never answers: products may have underflowed.
UNDERFLOW_GUARD = 2.0**-960

#: Per-pair static filter constant of the batch narrow phase (see module docstring).
PAIR_EPS = 16.0 * EPS

#: Relative slack added to conservative bounding volumes (circles, oriented boxes). Posed
#: vertices carry a few ulps of rounding relative to ``|position| + radius``; ``2**-40`` is
#: about 8000 ulps, so the inflated volume always contains the posed float vertices.
BOUND_SLACK = 2.0**-40

#: Largest finite double, for documentation and tests.
DBL_MAX = sys.float_info.max
