"""One backend object for the stages of a frame that have a compiled twin.

The stages of the pipeline below run either as numpy code (the reference) or as numba
kernels (``pip install 'broadsword[fast]'``), with the same answers in the same order:

===================  ==========================================  ===========================================
stage (``Backend``)  numpy reference                             compiled twin (numba)
===================  ==========================================  ===========================================
``sincos_deg``       ``detmath.sincos_deg`` (``"exact"`` poses)  ``_trig_kernel``: the same operations, bits
``atan2_deg``        ``detmath.atan2_deg``                       ``_trig_kernel``: its scalar code compiled, bits
``pose_and_box``     ``posing.pose_checked`` + ``bounds.aabbs``  ``_pose_kernel`` (rotating by ``sincos_deg``)
``grid_pairs``       ``BinGrid.reference_query``                 ``BinGrid.compiled_query`` (``_grid_kernel``)
``boxes_overlap``    ``bounds.boxes_overlap`` (``aabb`` tier)    ``_bounds_kernel``
``collide_columns``  ``narrow.polygons_collide_reference``       ``_narrow_kernel``: a float filter; what it
``collide_padded``   (the exact narrow phase)                    cannot certify goes to the reference
``laser_pieces``     ``laserpieces.laser_pieces``                ``_laser_kernel``: the same operations, bits
``chain_outlines``   ``raster.chain_outlines``                   ``_raster_kernel``: the same operations, bits
``chain_keep``       ``raster.chain_keep``                       ``_raster_kernel``: the same nodes
``fill_polygons``    ``raster.fill_polygons``                    ``_raster_kernel``: the same rule, pixels
``paint_chains``     ``raster.paint_chains``                     ``_raster_kernel``: the three above in one
                                                                 call, the GIL released
===================  ==========================================  ===========================================

``sincos_deg`` and ``atan2_deg`` are also what the game's state takes its trigonometry
from where it has many angles a frame (:class:`Trig`: the curvy lasers' heads, a BulletML
volley's new bullets), through the world's pipeline's backend: the bits are the same
either way, so a replay does not depend on the backend.

``laser_pieces`` makes the pieces of the lasers the broad phase let through (the pipeline
passes its backend to :func:`.laserframe.join`). The last four are not pipeline stages:
they outline chains of nodes, choose the nodes to draw, fill polygons into a pixel
buffer and do all three at once (the pixel tier's rule, :mod:`.raster`), and the game draws its lasers with
them through the world's pipeline's backend (200 curvy lasers of 64 nodes are 22,000
outline edges a pass: the compiled twins take a millisecond or so where pygame's polygon
fill and the numpy outlines took tens; docs/PERFORMANCE.md).

:func:`backend_for` is the one place a backend is chosen, with the one default: an explicit
choice (a backend, a :class:`~._kernel.Kernel` or its name), else the ``BROADSWORD_KERNEL``
environment variable, else numba when it imports, else numpy. The pipeline, its bin grid
and its tiers hold the backend object and call its stages with no branch on which it is.

Every stage gives a full answer: where a compiled kernel declines what the numpy code
handles on a special path (a posing frame with a turning sweep or a path past the doubles;
a grid allowed more cells than the dense key table; pairs whose signs the float filter
cannot certify), the numba backend hands it to the numpy reference itself.

Layering (no import loop): this module imports posing, bounds and the kernels. The narrow
phase and the bin grid sit above it, since their public functions take a backend, so the
narrow stages receive the reference as an argument and a grid is passed in holding both of
its queries (its layout rules are its own). Sweeps are built in one place per path: by
:class:`posing.Sweeps` for numpy, inside the narrow kernel (the same operations) for numba.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol, TypeVar

import numpy as np

from . import (
    _bounds_kernel,
    _laser_kernel,
    _narrow_kernel,
    _pose_kernel,
    _raster_kernel,
    _trig_kernel,
    bounds,
    detmath,
    laserpieces,
    raster,
)
from ._kernel import Kernel, check_kernel
from ._warm import warm_kernel
from .arguments import ArgumentTypeError
from .layers import LayerTable
from .posing import ArmatureSet, Posed, SinCos, pose_checked
from .workspace import Workspace

__all__ = ["Backend", "GridQuery", "NumbaBackend", "NumpyBackend", "PaddedNarrow", "backend_for"]

#: The exact narrow phase on padded polygons: ``(px, py (K1, P), qx, qy (K2, P), workspace)
#: -> (P,) bool`` (:func:`narrow.polygons_collide_reference`).
PaddedNarrow = Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray, Workspace], np.ndarray]


#: A grid's statistics type (:class:`.broadphase.BroadPhaseStats`), left open here so that
#: this module does not import the broad phases, which import it.
Stats = TypeVar("Stats")
Stats_co = TypeVar("Stats_co", covariant=True)


class GridQuery(Protocol[Stats_co]):
    """A bin grid (:class:`.broadphase.BinGrid`) as the ``grid_pairs`` stage runs it: the
    grid holds both of its queries (the grid's layout rules are its own), the backend picks
    one. Each returns ``(pairs (m, 2) int64, stats)`` for ``boxes`` (n, 4) and ``layers``
    (n,) (checked by the query), the same pairs in the same order."""

    def reference_query(self, boxes: np.ndarray, layers: np.ndarray, table: LayerTable) -> tuple[np.ndarray, Stats_co]:
        """The numpy query."""
        ...

    def compiled_query(self, boxes: np.ndarray, layers: np.ndarray, table: LayerTable) -> tuple[np.ndarray, Stats_co]:
        """The compiled query (:mod:`._grid_kernel`; numba)."""
        ...


class Trig(Protocol):
    """Where a game's state takes its trigonometry from, a frame's angles at once: a
    :class:`Backend` (numpy or compiled), whose bits are :mod:`.detmath`'s either way."""

    def sincos_deg(self, angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """As :meth:`Backend.sincos_deg`."""
        ...

    def atan2_deg(self, y: np.ndarray, x: np.ndarray) -> np.ndarray:
        """As :meth:`Backend.atan2_deg`."""
        ...


class Backend(Protocol):
    """The stages of a frame that have a compiled twin. Every stage gives the numpy
    reference's answer, in its order (the game applies hits in pipeline order, so a replay
    must not depend on the backend); arrays passed in are not modified."""

    #: Which implementation this is (for reports and the pipeline's ``kernel`` attribute).
    kernel: Kernel

    def warm(self) -> None:
        """Load (or compile, saying so on stderr) whatever the stages need, so that no
        frame waits for it."""
        ...

    def sincos_deg(self, angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(sin, cos)`` of ``angles`` (n,) float64 degrees: two (n,) float64 arrays with
        :func:`detmath.sincos_deg`'s bits (signed zeros, nan for nan and +-inf included).
        What ``pose_and_box`` rotates by in the ``"exact"`` mode."""
        ...

    def atan2_deg(self, y: np.ndarray, x: np.ndarray) -> np.ndarray:
        """The arctangent of ``y / x`` in degrees, ``y`` and ``x`` (n,) float64: an (n,)
        float64 array with :func:`detmath.atan2_deg`'s bits (signs, zeros, infinities and
        nan included)."""
        ...

    def pose_and_box(
        self,
        shapes: ArmatureSet,
        armature: np.ndarray,
        positions: np.ndarray,
        angles: np.ndarray,
        rotation: str,
        prev_positions: np.ndarray | None,
        prev_angles: np.ndarray | None,
        swept: np.ndarray | None,
        workspace: Workspace,
    ) -> tuple[Posed, np.ndarray]:
        """``(posed, boxes (n, 4))``: every object posed with its vertices (swept from its
        previous pose where ``swept`` (n,) bool says so) and its tight axis-aligned box, as
        ``pose_checked(..., vertices=True)`` and ``bounds.aabbs`` give them, rotated by
        this backend's :meth:`sincos_deg` in the ``"exact"`` mode. Arguments are
        the checked ones of :func:`posing.pose_checked`; arrays come from ``workspace``
        (valid until its next use)."""
        ...

    def grid_pairs(
        self, grid: GridQuery[Stats], boxes: np.ndarray, layers: np.ndarray, table: LayerTable
    ) -> tuple[np.ndarray, Stats]:
        """The bin grid's candidate pairs ``(m, 2) int64`` and statistics for ``boxes`` (n, 4)
        and ``layers`` (n,) (unchecked: the query checks them)."""
        ...

    def boxes_overlap(self, boxes: np.ndarray, pairs: np.ndarray) -> np.ndarray:
        """(m,) bool: the closed boxes ``boxes`` (n, 4) of each pair ``pairs`` (m, 2) overlap."""
        ...

    def collide_columns(
        self,
        posed: Posed,
        k1: int,
        cols1: np.ndarray,
        k2: int,
        cols2: np.ndarray,
        workspace: Workspace,
        reference: PaddedNarrow,
    ) -> np.ndarray:
        """(P,) bool: exact collision of the posed polygons of columns ``cols1`` (P,) of
        size class ``k1`` and ``cols2`` (P,) of class ``k2``, pair by pair (sweeps built for
        these columns only). ``reference`` is the exact numpy narrow phase."""
        ...

    def collide_padded(
        self,
        px: np.ndarray,
        py: np.ndarray,
        qx: np.ndarray,
        qy: np.ndarray,
        workspace: Workspace,
        reference: PaddedNarrow,
    ) -> np.ndarray:
        """(P,) bool: exact collision of the padded polygons ``px, py`` (K1, P) and ``qx, qy``
        (K2, P) (writeable float64), pair by column. ``reference`` as above."""
        ...

    def laser_pieces(
        self, nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(x, y, owner)``: the pieces of the lasers ``nodes`` (N, 2), ``widths`` (N,),
        ``starts`` (L,) (:func:`.laserpieces.laser_pieces`: x, y (4, 2N - 3L), owner (2N - 3L,))."""
        ...

    def chain_outlines(self, nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray) -> np.ndarray:
        """(2n, 2) float64: the chains of ``nodes`` (n, 2) float64, ``widths`` (n,) float64 wide,
        chain ``j`` from ``starts[j]`` (k,) int64, each outlined as one polygon for
        :meth:`fill_polygons` (from row ``2 * starts[j]``; :func:`.raster.chain_outlines`);
        (m, 2n, 2) for ``widths`` (m, n), an outline of every chain for each row.
        Raises ``ValueError`` naming the argument that is not as stated
        (:func:`.raster.check_chains`)."""
        ...

    def chain_keep(
        self, nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray, tolerance: float, widest: float
    ) -> np.ndarray:
        """(n,) bool: the nodes of the chains (as :meth:`chain_outlines` takes them, ``widths``
        (n,)) a drawing keeps so that every outline up to ``widest`` times as wide stays within
        ``tolerance`` px of the outline through every node (:func:`.raster.chain_keep`).
        Raises ``ValueError`` naming the argument that is not as stated (:func:`.raster.check_keep`)."""
        ...

    def fill_polygons(self, buf: np.ndarray, points: np.ndarray, starts: np.ndarray, value: int | np.ndarray) -> None:
        """Set the pixels of ``buf`` (h, w) uint32 inside the polygons ``points`` (n, 2)
        float64, polygon ``j`` from ``starts[j]`` (k,) int64, to ``value`` (an int) or to
        ``value[j]`` ((k,) integers), polygon after polygon (:mod:`.raster`'s rule: pixel
        centres, nonzero winding, clipped to ``buf``; where two overlap, the later one's
        value stays). Raises ``ValueError`` naming the argument that is not as stated
        (:func:`.raster.check_fill`, :func:`.raster.check_values`)."""
        ...

    def paint_chains(
        self,
        buf: np.ndarray,
        nodes: np.ndarray,
        widths: np.ndarray,
        starts: np.ndarray,
        values: np.ndarray,
        scales: np.ndarray,
        floors: np.ndarray,
        tolerance: float,
    ) -> None:
        """Paint the chains ``nodes`` (n, 2), ``widths`` (n,), ``starts`` (k,) into ``buf``
        (h, w) uint32 in passes, as the game draws its lasers: pass ``p`` fills each chain's
        outline at ``widths * scales[p]`` (at least ``floors[p]``) with ``values[p, j]``
        ((m, k) integers), every chain drawn from the nodes :meth:`chain_keep` keeps for
        ``tolerance`` (:func:`.raster.paint_chains`: :meth:`chain_keep`,
        :meth:`chain_outlines` and :meth:`fill_polygons` in one call). Raises
        ``ValueError`` naming the argument that is not as stated (:func:`.raster.check_paint`)."""
        ...


class NumpyBackend:
    """The reference: every stage is the numpy code."""

    kernel = Kernel.NUMPY

    def warm(self) -> None:
        """Nothing to load."""

    def sincos_deg(self, angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return detmath.sincos_deg(np.asarray(angles, dtype=np.float64))

    def atan2_deg(self, y: np.ndarray, x: np.ndarray) -> np.ndarray:
        return detmath.atan2_deg(np.asarray(y, dtype=np.float64), np.asarray(x, dtype=np.float64))

    def pose_and_box(
        self,
        shapes: ArmatureSet,
        armature: np.ndarray,
        positions: np.ndarray,
        angles: np.ndarray,
        rotation: str,
        prev_positions: np.ndarray | None,
        prev_angles: np.ndarray | None,
        swept: np.ndarray | None,
        workspace: Workspace,
    ) -> tuple[Posed, np.ndarray]:
        return pose_and_box_reference(
            shapes,
            armature,
            positions,
            angles,
            rotation,
            prev_positions,
            prev_angles,
            swept,
            workspace,
            self.sincos_deg,
        )

    def grid_pairs(
        self, grid: GridQuery[Stats], boxes: np.ndarray, layers: np.ndarray, table: LayerTable
    ) -> tuple[np.ndarray, Stats]:
        return grid.reference_query(boxes, layers, table)

    def boxes_overlap(self, boxes: np.ndarray, pairs: np.ndarray) -> np.ndarray:
        return bounds.boxes_overlap(boxes, pairs)

    def collide_columns(
        self,
        posed: Posed,
        k1: int,
        cols1: np.ndarray,
        k2: int,
        cols2: np.ndarray,
        workspace: Workspace,
        reference: PaddedNarrow,
    ) -> np.ndarray:
        return reference(*posed.gather(k1, cols1), *posed.gather(k2, cols2), workspace)

    def collide_padded(
        self,
        px: np.ndarray,
        py: np.ndarray,
        qx: np.ndarray,
        qy: np.ndarray,
        workspace: Workspace,
        reference: PaddedNarrow,
    ) -> np.ndarray:
        return reference(px, py, qx, qy, workspace)

    def laser_pieces(
        self, nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return laserpieces.laser_pieces(nodes, widths, starts)

    def chain_outlines(self, nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray) -> np.ndarray:
        raster.check_chains(nodes, widths, starts)
        return raster.chain_outlines(nodes, widths, starts)

    def chain_keep(
        self, nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray, tolerance: float, widest: float
    ) -> np.ndarray:
        raster.check_keep(nodes, widths, starts, tolerance, widest)
        return raster.chain_keep(nodes, widths, starts, tolerance, widest)

    def fill_polygons(self, buf: np.ndarray, points: np.ndarray, starts: np.ndarray, value: int | np.ndarray) -> None:
        raster.check_fill(buf, points, starts)
        raster.fill_polygons(buf, points, starts, raster.check_values(value, len(starts)))

    def paint_chains(
        self,
        buf: np.ndarray,
        nodes: np.ndarray,
        widths: np.ndarray,
        starts: np.ndarray,
        values: np.ndarray,
        scales: np.ndarray,
        floors: np.ndarray,
        tolerance: float,
    ) -> None:
        colours = raster.check_paint(buf, nodes, widths, starts, values, scales, floors, tolerance)
        raster.paint_chains(buf, nodes, widths, starts, colours, scales, floors, tolerance)


class NumbaBackend:
    """The compiled kernels (numba), each handing what it declines to the numpy reference."""

    kernel = Kernel.NUMBA

    def warm(self) -> None:
        """Import numba and load every kernel (:func:`._warm.warm_kernel`)."""
        warm_kernel()

    def sincos_deg(self, angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return _trig_kernel.sincos_deg(angles)

    def atan2_deg(self, y: np.ndarray, x: np.ndarray) -> np.ndarray:
        return _trig_kernel.atan2_deg(y, x)

    def pose_and_box(
        self,
        shapes: ArmatureSet,
        armature: np.ndarray,
        positions: np.ndarray,
        angles: np.ndarray,
        rotation: str,
        prev_positions: np.ndarray | None,
        prev_angles: np.ndarray | None,
        swept: np.ndarray | None,
        workspace: Workspace,
    ) -> tuple[Posed, np.ndarray]:
        args = (shapes, armature, positions, angles, rotation, prev_positions, prev_angles, swept, workspace)
        compiled = _pose_kernel.pose(*args, self.sincos_deg)  # None: a frame for numpy's special paths
        return compiled if compiled is not None else pose_and_box_reference(*args, self.sincos_deg)

    def grid_pairs(
        self, grid: GridQuery[Stats], boxes: np.ndarray, layers: np.ndarray, table: LayerTable
    ) -> tuple[np.ndarray, Stats]:
        return grid.compiled_query(boxes, layers, table)

    def boxes_overlap(self, boxes: np.ndarray, pairs: np.ndarray) -> np.ndarray:
        return _bounds_kernel.boxes_overlap(boxes, pairs)

    def collide_columns(
        self,
        posed: Posed,
        k1: int,
        cols1: np.ndarray,
        k2: int,
        cols2: np.ndarray,
        workspace: Workspace,
        reference: PaddedNarrow,
    ) -> np.ndarray:
        # The filter reads the class arrays in place and builds the sweeps it reads; the
        # pairs it leaves undecided are gathered and settled by the reference.
        verdict, undecided = _narrow_kernel.decide(
            posed.vx[k1],
            posed.vy[k1],
            cols1,
            posed.vx[k2],
            posed.vy[k2],
            cols2,
            posed.sweeps.get(k1),
            posed.sweeps.get(k2),
        )
        out = verdict == _narrow_kernel.HIT
        if undecided:
            rest = np.flatnonzero(verdict == _narrow_kernel.UNDECIDED)
            ra, rb = np.take(cols1, rest), np.take(cols2, rest)
            out[rest] = reference(*posed.gather(k1, ra), *posed.gather(k2, rb), workspace)
        return out

    def collide_padded(
        self,
        px: np.ndarray,
        py: np.ndarray,
        qx: np.ndarray,
        qy: np.ndarray,
        workspace: Workspace,
        reference: PaddedNarrow,
    ) -> np.ndarray:
        verdict = _narrow_kernel.filter_pairs(px, py, qx, qy)
        out = verdict == _narrow_kernel.HIT
        rest = np.flatnonzero(verdict == _narrow_kernel.UNDECIDED)
        if rest.size:
            out[rest] = reference(px[:, rest], py[:, rest], qx[:, rest], qy[:, rest], workspace)
        return out

    def laser_pieces(
        self, nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return _laser_kernel.laser_pieces(nodes, widths, starts)

    def chain_outlines(self, nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray) -> np.ndarray:
        raster.check_chains(nodes, widths, starts)
        return _raster_kernel.chain_outlines(nodes, widths, starts)

    def chain_keep(
        self, nodes: np.ndarray, widths: np.ndarray, starts: np.ndarray, tolerance: float, widest: float
    ) -> np.ndarray:
        raster.check_keep(nodes, widths, starts, tolerance, widest)
        return _raster_kernel.chain_keep(nodes, widths, starts, tolerance, widest)

    def fill_polygons(self, buf: np.ndarray, points: np.ndarray, starts: np.ndarray, value: int | np.ndarray) -> None:
        raster.check_fill(buf, points, starts)
        _raster_kernel.fill_polygons(buf, points, starts, raster.check_values(value, len(starts)))

    def paint_chains(
        self,
        buf: np.ndarray,
        nodes: np.ndarray,
        widths: np.ndarray,
        starts: np.ndarray,
        values: np.ndarray,
        scales: np.ndarray,
        floors: np.ndarray,
        tolerance: float,
    ) -> None:
        colours = raster.check_paint(buf, nodes, widths, starts, values, scales, floors, tolerance)
        _raster_kernel.paint_chains(buf, nodes, widths, starts, colours, scales, floors, tolerance)


def pose_and_box_reference(
    shapes: ArmatureSet,
    armature: np.ndarray,
    positions: np.ndarray,
    angles: np.ndarray,
    rotation: str,
    prev_positions: np.ndarray | None,
    prev_angles: np.ndarray | None,
    swept: np.ndarray | None,
    workspace: Workspace,
    sincos: SinCos,
) -> tuple[Posed, np.ndarray]:
    """The numpy ``pose_and_box`` (:meth:`Backend.pose_and_box`), rotating by ``sincos`` in
    the ``"exact"`` mode (the calling backend's own stage)."""
    posed = pose_checked(
        shapes,
        armature,
        positions,
        angles,
        rotation,
        prev_positions,
        prev_angles,
        swept,
        workspace=workspace,
        sincos=sincos,
    )
    return posed, bounds.aabbs(posed)


#: The two backends (stateless: one of each serves every pipeline).
NUMPY = NumpyBackend()
NUMBA = NumbaBackend()
_BY_KERNEL: dict[Kernel, Backend] = {Kernel.NUMPY: NUMPY, Kernel.NUMBA: NUMBA}


def backend_for(choice: Backend | Kernel | str | None = None) -> Backend:
    """The backend for ``choice``: a backend as it is; a :class:`Kernel` or its name
    (``"numpy"``, ``"numba"``); ``None`` for the default: ``BROADSWORD_KERNEL`` when set, else
    numba when it imports, else numpy (:func:`._kernel.check_kernel`).

    Raises ``ArgumentTypeError`` (a ``TypeError`` and a ``ValueError``) naming ``kernel`` for
    another type, ``ValueError`` naming it (or the variable) for an unknown name, and
    ``ImportError`` saying why when numba is asked for but cannot be used.
    """
    if isinstance(choice, (NumpyBackend, NumbaBackend)):
        return choice
    if choice is not None and not isinstance(choice, (Kernel, str)):
        raise ArgumentTypeError(f"kernel must be 'numpy', 'numba', a Kernel, a Backend or None, got {choice!r}")
    return _BY_KERNEL[check_kernel(choice)]
