"""The bin grid's sizing rules, shared by the numpy grid (:mod:`.broadphase.grid`) and its
compiled twin (:mod:`._grid_kernel`). Plain numbers: this module imports nothing, so both
can read it without the kernel importing the broad phases."""

from __future__ import annotations

__all__ = ["AUTO_BIN_FACTOR", "DENSE_KEYS", "DIRECT_PAIRS", "DIRECT_SIDE", "MEDIAN_SAMPLE", "MIN_BIN"]

#: The automatic bin size reads at most about this many boxes of a layer (a strided sample).
MEDIAN_SAMPLE = 64
#: Bins this much larger than the largest layer's median object (docs/PERFORMANCE.md).
AUTO_BIN_FACTOR = 1.25
#: A layer of at most this many objects is *few*: a table entry with a side this small
#: compares bin ranges directly (the bin grid's ``ranges_meet``), never registering in
#: bins, so its objects' size does not choose the bin size (``auto_bin_size``).
DIRECT_SIDE = 8
#: ... and so does one with at most this many object pairs (small scenes: comparing every
#: pair's bin ranges is a handful of numpy calls, registering in bins a few dozen).
DIRECT_PAIRS = 1 << 14
#: Key spaces up to this size are joined with a counting sort instead of binary search.
DENSE_KEYS = 1 << 17
#: The smallest bin side: the smallest normal double, whose inverse is finite. Smaller bins
#: (a frame of subnormal-sized boxes) made ``1 / size`` infinite and ``0 * inf`` a nan bin.
MIN_BIN = 2.0**-1022
