"""The pipeline's scratch buffers (``collision/workspace.py``): a name's buffer grows on
demand, a view of the last shape asked for is handed back again (a small frame's look-ups
are dict hits), and a grown buffer drops the views into the one it replaces."""

from __future__ import annotations

import numpy as np

from broadsword.collision.workspace import Workspace


def test_get__the_same_shape_again_is_the_same_view():
    ws = Workspace()
    a = ws.get("x", (3, 5))
    assert a.shape == (3, 5) and a.dtype == np.float64 and a.flags.c_contiguous
    a[:] = 7.0
    b = ws.get("x", (3, 5))
    assert b is a  # a look-up, not a new view
    assert ws.get("x", 15) is not a and np.shares_memory(ws.get("x", 15), a)


def test_get__another_shape_is_a_view_of_that_shape_into_the_same_buffer():
    ws = Workspace()
    a = ws.get("x", 40)
    b = ws.get("x", (4, 6))
    assert b.shape == (4, 6) and b.flags.c_contiguous and np.shares_memory(a, b)
    c = ws.get("x", 40)
    assert c.shape == (40,) and np.shares_memory(c, b)
    assert ws.get("x", (4, 6)).shape == (4, 6)


def test_get__names_and_dtypes_have_buffers_of_their_own():
    ws = Workspace()
    x, y = ws.get("x", 10), ws.get("y", 10)
    i = ws.get("x", 10, np.int64)
    assert i.dtype == np.int64 and not np.shares_memory(x, y) and not np.shares_memory(x, i)
    assert ws.nbytes == 3 * 64 * 8  # three buffers of the smallest size, 64 items of 8 bytes
    ws.get("x", 10)
    assert ws.nbytes == 3 * 64 * 8  # a look-up adds nothing


def test_get__a_larger_shape_grows_the_buffer_and_forgets_the_old_view():
    ws = Workspace()
    small = ws.get("x", 100)
    small[:] = 1.0
    before = ws.nbytes
    big = ws.get("x", (100, 100))
    assert big.shape == (100, 100) and ws.nbytes > before
    assert not np.shares_memory(small, big)  # a new buffer: the old view stays the caller's
    again = ws.get("x", 100)
    assert again is not small and np.shares_memory(again, big)  # the new buffer's view
    assert ws.get("x", 0).shape == (0,) and ws.get("x", (0, 3)).shape == (0, 3)
