"""Arguments of the library's public entry points, checked once, at the boundary.

:meth:`Pipeline.step <broadsword.collision.Pipeline.step>`, :func:`~broadsword.collision.pose`,
:class:`~broadsword.collision.Armature` and the scalar predicates pass what they are given
through these functions before any arithmetic, so the kernels behind them never meet a value
they were not written for. Every message names the argument.

The rules, everywhere:

* **Coordinates and angles** are real numbers: Python ``int`` and ``float``, numpy integer
  and floating types. ``bool``, ``complex``, strings and other objects are refused with an
  :class:`ArgumentTypeError`, never silently truncated or converted. A number that is not
  exactly a double (an integer beyond 2**53 that doubles skip, a ``longdouble`` with extra
  bits) is refused with a ``ValueError``: "exact" is defined on the doubles passed in
  (DESIGN.md), and rounding the input first would answer another question.
* **Finite**: nan and +-inf are refused (``ValueError``). Every finite double is accepted, up
  to +-1.7976931348623157e308, and gets the exact answer.
* **Ids** (armature indices, layer ids) are integers -- an integer array or Python ``int``
  values -- in their range. ``0.7`` and ``True`` are refused (:class:`ArgumentTypeError`),
  not truncated; ``-1`` or an id past the end is a ``ValueError``.
* **Shapes** are exact: ``positions`` is ``(n, 2)``; a ``(2, n)`` or flat array is refused,
  not reshaped; every per-object array has the ``n`` of ``armature``. Nothing is broadcast:
  a ``prev_angles`` of length 1 for 2 objects is a ``ValueError``.
* **Flags** (``swept``) are booleans: a bool array or Python ``bool`` values.

:class:`ArgumentTypeError` is both a ``TypeError`` and a ``ValueError``: the right kind for a
wrong type, still caught by code written when every refusal was a ``ValueError``.
"""

import math
import numbers
from typing import NamedTuple

import numpy as np

__all__ = [
    "ArgumentTypeError",
    "Frame",
    "bounds4",
    "flag",
    "flags",
    "frame",
    "ids",
    "instance",
    "point",
    "points",
    "polygon",
    "positive",
    "ready",
    "real_array",
    "reals",
    "sequence",
    "usable",
    "whole",
]

_KINDS = {
    "b": "booleans",
    "c": "complex numbers",
    "U": "strings",
    "S": "bytes",
    "O": "Python objects",
    "M": "datetimes",
    "m": "timedeltas",
    "V": "records",
}


class ArgumentTypeError(TypeError, ValueError):
    """An argument of the wrong type: complex, bool, str, a float where an id belongs..."""


def _array(value, name: str) -> np.ndarray:
    """``np.asarray(value)``; ragged nesting and the like are refused naming ``name``.

    Python sequences are scanned for ``bool`` first: numpy would turn ``[True, 2]`` into
    integers. (Arrays are typed already: a bool array says so by its dtype.)
    """
    try:
        a = np.asarray(value)
        if not isinstance(value, np.ndarray) and a.dtype.kind in "iuf" and a.size:
            if any(isinstance(v, (bool, np.bool_)) for v in np.asarray(value, dtype=object).reshape(-1).tolist()):
                raise ArgumentTypeError(f"{name} must hold numbers, not booleans")
        return a
    except ArgumentTypeError:
        raise
    except (TypeError, ValueError, OverflowError) as exc:
        raise ValueError(f"{name} must be an array of numbers ({exc})") from None


def _shape_name(shape: tuple[int | None, ...]) -> str:
    dims = ["n" if s is None else str(s) for s in shape]
    return "(" + ", ".join(dims) + ("," if len(dims) == 1 else "") + ")"


def _shaped(a: np.ndarray, name: str, shape: tuple[int | None, ...]) -> np.ndarray:
    """``a`` if it has ``shape`` exactly (``None``: any length); an empty ``[]`` takes the shape."""
    if a.size == 0 and a.ndim == 1 and shape[0] in (0, None):
        return a.reshape(tuple(0 if s is None else s for s in shape))
    if a.ndim != len(shape) or any(s is not None and got != s for got, s in zip(a.shape, shape, strict=True)):
        raise ValueError(f"{name} must have shape {_shape_name(shape)}, got {a.shape}")
    return a


def _is_real(v) -> bool:
    return isinstance(v, numbers.Real) and not isinstance(v, (bool, np.bool_))


def real_array(value, name: str, shape: tuple[int | None, ...], item: str = "object") -> np.ndarray:
    """``value`` as float64 of ``shape`` (``None``: any length), every entry a finite double.

    ``item`` names a row in the message for a non-finite value ("object 3", "vertex 2").
    """
    if ready(value, np.float64, shape) and np.isfinite(value).all():
        return value  # the common case, checked in a few calls: float64 already, shaped, finite
    a = _array(value, name)
    kind = a.dtype.kind
    if kind == "O":  # mixed Python numbers numpy could not type (ints beyond int64, ...)
        flat = a.reshape(-1).tolist()
        bad = [v for v in flat if not _is_real(v)][:1]  # a list: the bad value may be None
        if bad:
            raise ArgumentTypeError(f"{name} must hold real numbers, got {type(bad[0]).__name__} {bad[0]!r}")
        a = np.array([_exact_double(v, name) for v in flat], dtype=np.float64).reshape(a.shape)
    elif kind not in "iuf" and a.size:
        raise ArgumentTypeError(f"{name} must hold real numbers, got {_KINDS.get(kind, str(a.dtype))}")
    a = _shaped(a, name, shape)
    if kind in "iu" and a.dtype.itemsize == 8 and a.size:
        big = np.abs(a.astype(np.float64)) >= 2.0**53
        for v in a[big].tolist():
            _exact_double(int(v), name)
    out = a.astype(np.float64, copy=False)
    if kind == "f" and a.dtype.itemsize > 8 and not np.array_equal(out, a):
        raise ValueError(f"{name} holds {a.dtype} values that are not doubles; round them with .astype(float)")
    ok = np.isfinite(out)
    if not ok.all():
        row = int(np.argwhere(~ok)[0][0])
        raise ValueError(f"{name}: {item} {row} is not finite: {out[row].tolist()}")
    return usable(out)


def _exact_double(v, name: str) -> float:
    """``float(v)`` when that is exactly ``v``; else a ``ValueError`` naming ``name``."""
    if isinstance(v, (int, np.integer)):
        i = int(v)
        try:
            f = float(i)
        except OverflowError:
            f = math.inf
        if f != i:
            raise ValueError(f"{name}: {i} is not a double (it would round); pass float({i}) to round it")
        return f
    f = float(v)
    if f != v:  # a Fraction or another exact real that is not a double
        raise ValueError(f"{name}: {v!r} is not a double (it would round); pass float() of it to round it")
    return f


def reals(value, name: str, n: int | None = None) -> np.ndarray:
    """``(n,)`` float64, finite: angles."""
    return real_array(value, name, (n,), "object")


def points(value, name: str, n: int | None = None) -> np.ndarray:
    """``(n, 2)`` float64, finite: positions. A ``(2, n)`` array is refused, not transposed."""
    return real_array(value, name, (n, 2), "object")


def ids(value, name: str, n: int | None, limit: int | None = None, what: str = "") -> np.ndarray:
    """``(n,)`` int64 ids, in ``0..limit-1`` when ``limit`` is given (:func:`in_range`).

    Integer arrays or Python ints only: ``0.7`` and ``True`` are refused, not truncated.
    """
    if ready(value, np.int64, (n,)):
        a = value
        if limit is not None:
            in_range(a, name, limit, what)
        return a
    a = _array(value, name)
    if a.dtype.kind not in "iu" and a.size:
        got = _KINDS.get(a.dtype.kind, str(a.dtype))
        if a.dtype.kind == "f":
            flat = a.reshape(-1)
            odd = flat[~np.isfinite(flat) | (flat != np.round(flat))]
            got = f"{a.dtype} values such as {odd[0].item()!r}" if odd.size else f"{a.dtype} values (pass integers)"
        raise ArgumentTypeError(f"{name} must hold integer indices, got {got}")
    a = usable(_shaped(a, name, (n,)).astype(np.int64, copy=False))
    if limit is not None:
        in_range(a, name, limit, what)
    return a


def in_range(a: np.ndarray, name: str, limit: int, what: str) -> None:
    """Every id of the int array ``a`` lies in ``0..limit-1``; ``what`` says why ("the pipeline has 2 armatures")."""
    if not a.size:
        return
    if a.dtype == np.int64:
        # One reduction for both bounds: read as unsigned, a negative id is above 2**63.
        outside = np.maximum.reduce(a.view(np.uint64), axis=None) >= limit
    else:
        outside = a.min() < 0 or a.max() >= limit
    if outside:
        bad = a[(a < 0) | (a >= limit)][0]
        raise ValueError(f"{name} ids must lie in 0..{limit - 1} ({what}), got {bad}")


def flags(value, name: str, n: int | None) -> np.ndarray:
    """``(n,)`` bool: a bool array or Python bools; ``0`` and ``1`` are refused, not converted."""
    a = _array(value, name)
    if a.dtype.kind != "b" and a.size:
        raise ArgumentTypeError(f"{name} must hold booleans, got {_KINDS.get(a.dtype.kind, str(a.dtype))}")
    return usable(_shaped(a, name, (n,)).astype(bool, copy=False))


def ready(value, dtype, shape: tuple[int | None, ...]) -> bool:
    """``value`` is an array of ``dtype`` and ``shape`` (``None``: any length) that the
    kernels take as it is (writeable, aligned): the fast path of the checks."""
    if type(value) is not np.ndarray or value.dtype != dtype or value.ndim != len(shape):
        return False
    if shape[-1] is not None and value.shape[-1] != shape[-1]:
        return False
    if shape[0] is not None and value.shape[0] != shape[0]:
        return False
    flags = value.flags
    return flags.writeable and flags.aligned


def usable(a: np.ndarray) -> np.ndarray:
    """``a``, or a copy of it when the compiled kernels could not take it as it is: read-only
    (a memory map, ``np.frombuffer``, a view its owner froze) or unaligned. numba refuses
    such arrays ("No matching definition ... readonly array"); the copy has the same values,
    so both backends give the same answers."""
    return a if a.flags.writeable and a.flags.aligned else a.copy()


class Frame(NamedTuple):
    """One frame's arguments of :meth:`Pipeline.step` and :func:`pose`, checked."""

    armature: np.ndarray  #: (n,) int64
    layer: np.ndarray | None  #: (n,) int64; None for pose()
    positions: np.ndarray  #: (n, 2) float64
    angles: np.ndarray  #: (n,) float64
    prev_positions: np.ndarray | None  #: (n, 2) float64
    prev_angles: np.ndarray | None  #: (n,) float64
    swept: np.ndarray | None  #: (n,) bool; None when nothing is swept


def frame(
    armature, layer, positions, angles, prev_positions, prev_angles, swept, *, armatures: int, layers: int | None
) -> Frame:
    """Check one frame's arguments (``layer`` and ``layers`` ``None`` for :func:`pose`).

    ``n`` is the length of ``armature``; every other per-object argument must have it.
    ``prev_positions`` and ``prev_angles`` are checked whenever given, and required when
    ``swept`` marks an object; a ``swept`` with no True entry becomes ``None``.
    """
    arm = ids(armature, "armature", None, armatures, f"the pipeline has {armatures} armatures")
    n = len(arm)
    lay = None if layers is None else ids(layer, "layer", n, layers, f"the layer table has {layers} layers")
    pos = points(positions, "positions", n)
    ang = reals(angles, "angles", n)
    sw = None if swept is None else flags(swept, "swept", n)
    if sw is not None and not sw.any():
        sw = None
    if sw is not None and (prev_positions is None or prev_angles is None):
        raise ValueError("prev_positions and prev_angles (last frame's poses) are needed for swept objects")
    prev_pos = None if prev_positions is None else points(prev_positions, "prev_positions", n)
    prev_ang = None if prev_angles is None else reals(prev_angles, "prev_angles", n)
    return Frame(arm, lay, pos, ang, prev_pos, prev_ang, sw)


# ----------------------------------------------------------------- the scalar predicates
def coordinate(v, name: str) -> float:
    """One coordinate: a real number whose value is a finite double."""
    if not _is_real(v):
        raise ArgumentTypeError(f"{name} must be a real number, got {type(v).__name__} {v!r}")
    if isinstance(v, np.floating) and np.dtype(type(v)).itemsize > 8 and float(v) != v:
        raise ValueError(f"{name}: {v!r} is not a double; round it with float()")
    f = _exact_double(v, name)
    if not math.isfinite(f):
        raise ValueError(f"{name} is {f}: coordinates must be finite")
    return f


def point(p, name: str) -> tuple[float, float]:
    """An ``(x, y)`` pair of real numbers, each a finite double."""
    if isinstance(p, (str, bytes)):
        raise ArgumentTypeError(f"{name} must be an (x, y) pair of real numbers, got {p!r}")
    try:
        x, y = p
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an (x, y) pair of real numbers, got {p!r}") from None
    return coordinate(x, f"{name} x"), coordinate(y, f"{name} y")


def polygon(vs, name: str) -> list[tuple[float, float]]:
    """At least 3 ``(x, y)`` vertices, each checked by :func:`point`."""
    if isinstance(vs, (str, bytes)):
        raise ArgumentTypeError(f"{name} must be a sequence of (x, y) vertices, got {vs!r}")
    try:
        items = list(vs)
    except TypeError:
        raise ArgumentTypeError(f"{name} must be a sequence of (x, y) vertices, got {type(vs).__name__}") from None
    out = [point(v, f"{name} vertex {i}") for i, v in enumerate(items)]
    if len(out) < 3:
        raise ValueError(f"{name} needs at least 3 vertices, got {len(out)}")
    return out


# ------------------------------------------------------- configuration (constructors)
def _described(v) -> str:
    """``v`` for a message: its type and a short repr."""
    r = repr(v)
    return f"{type(v).__name__} {r if len(r) <= 60 else r[:57] + '...'}"


def instance(value, name: str, kind: type, what: str):
    """``value`` if it is a ``kind``; else an :class:`ArgumentTypeError` saying ``name`` must
    be ``what``."""
    if not isinstance(value, kind):
        raise ArgumentTypeError(f"{name} must be {what}, got {_described(value)}")
    return value


def flag(value, name: str) -> bool:
    """A Python or numpy ``bool``; ``1``, ``"yes"`` and ``None`` are refused."""
    if not isinstance(value, (bool, np.bool_)):
        raise ArgumentTypeError(f"{name} must be True or False, got {_described(value)}")
    return bool(value)


def positive(value, name: str) -> float:
    """A real number (not ``bool``, not a string), finite and above zero, as a double."""
    if not _is_real(value):
        raise ArgumentTypeError(f"{name} must be a positive real number, got {_described(value)}")
    f = float(value)
    if not (math.isfinite(f) and f > 0):
        raise ValueError(f"{name} must be a positive, finite number, got {value!r}")
    return f


def whole(value, name: str, least: int) -> int:
    """An integer (Python or numpy, not ``bool``) of at least ``least``."""
    if not isinstance(value, (int, np.integer)) or isinstance(value, (bool, np.bool_)):
        raise ArgumentTypeError(f"{name} must be an integer, got {_described(value)}")
    if value < least:
        raise ValueError(f"{name} must be at least {least}, got {value}")
    return int(value)


def bounds4(value, name: str) -> tuple[float, float, float, float]:
    """``(x0, y0, x1, y1)``: four real, finite numbers with ``x0 <= x1`` and ``y0 <= y1``."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
        raise ArgumentTypeError(f"{name} must be four numbers (x0, y0, x1, y1), got {_described(value)}")
    items = list(value)
    if len(items) != 4:
        raise ValueError(f"{name} must be four numbers (x0, y0, x1, y1), got {len(items)}: {value!r}")
    bad = [v for v in items if not _is_real(v)][:1]  # a list: the bad value may be None
    if bad:
        raise ArgumentTypeError(f"{name} must hold real numbers, got {_described(bad[0])}")
    x0, y0, x1, y1 = (float(v) for v in items)
    if not all(math.isfinite(v) for v in (x0, y0, x1, y1)):
        raise ValueError(f"{name} must be four finite numbers, got {value!r}")
    if x0 > x1 or y0 > y1:
        raise ValueError(f"{name} must have x0 <= x1 and y0 <= y1 (x0, y0, x1, y1), got {value!r}")
    return x0, y0, x1, y1


def sequence(value, name: str, what: str) -> list:
    """``value``'s items as a list: a sequence, not a lone string (``"bins"`` would be read as
    the tiers ``b``, ``i``, ``n``, ``s``); ``what`` names an item ("tier names"). The items
    are the caller's to check."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        raise ArgumentTypeError(f"{name} must be a sequence of {what}, got {_described(value)}")
    return list(value)
