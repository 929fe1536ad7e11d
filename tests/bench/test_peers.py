"""The benchmark's peer libraries answer the same question as broadsword, correctly.

Each available peer runs on small reference scenes and is compared pair by pair with
broadsword's exact answer (brute force, exact rotation). pymunk and shapely must agree
exactly, up to pairs within 1e-6 px of touching; pygame's masks must agree up to their
pixel approximations. Peers whose library is missing are skipped; the counts are printed.
"""

import sys

import numpy as np
import pytest

from broadsword.bench.peers import (
    PEERS,
    PygameMaskPeer,
    PymunkPeer,
    ShapelyPeer,
    convex_pieces,
)
from broadsword.collision import Pipeline, orient, pose
from broadsword.collision.scenarios import ReferenceScene, random_armature

TOUCH = 1e-6  # px: a disagreement this close to touching is a rounding tie, not an error


@pytest.fixture
def report(capsys):
    """Print a line to the terminal even under pytest's output capture."""

    def say(line: str) -> None:
        with capsys.disabled():
            print(f"\n  [peers] {line}", end="")

    return say


def _frames(scene: ReferenceScene, count: int):
    """``count`` frames of ``scene``: poses and broadsword's exact hits, as sets."""
    truth = Pipeline(scene.shapes, scene.table, tiers=("brute", "armature"), rotation="exact")
    out = []
    for _ in range(count):
        pos, ang = scene.advance()
        pos, ang = pos.copy(), ang.copy()
        hits = set(map(tuple, truth.step(scene.armature, scene.layer, pos, ang).hits.tolist()))
        out.append((pos, ang, hits))
    return out


def _peer(cls):
    peer = cls()
    if not peer.available:
        pytest.skip(f"{cls.name}: {peer.why}")
    return peer


# -- the geometry the comparison relies on ---------------------------------------------------


def _area(p: np.ndarray) -> float:
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _point_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance of each point ``p`` (m, 2) to each segment ``a``-``b`` (k, 2): (m, k)."""
    e = b - a
    t = np.clip(((p[:, None, :] - a[None]) * e[None]).sum(-1) / (e * e).sum(-1)[None], 0.0, 1.0)
    d = p[:, None, :] - a[None] - t[..., None] * e[None]
    return np.hypot(d[..., 0], d[..., 1])


def _depth(p: np.ndarray, q: np.ndarray) -> float:
    """Penetration depth of convex polygons (separating axes): > 0 overlap, <= 0 apart."""
    best = np.inf
    for poly in (p, q):
        e = np.roll(poly, -1, axis=0) - poly
        n = np.column_stack([e[:, 1], -e[:, 0]]) / np.hypot(e[:, 0], e[:, 1])[:, None]
        sp, sq = p @ n.T, q @ n.T
        best = min(best, float((np.minimum(sp.max(0), sq.max(0)) - np.maximum(sp.min(0), sq.min(0))).min()))
    return best


def touch_margin(p: np.ndarray, q: np.ndarray) -> float:
    """Signed distance from touching: the gap of disjoint polygons (> 0), or minus the
    largest penetration depth over their convex pieces (< 0) when they overlap."""
    depth = max(_depth(a, b) for a in convex_pieces(p) for b in convex_pieces(q))
    if depth > 0:
        return -depth
    pe, qe = np.roll(p, -1, axis=0), np.roll(q, -1, axis=0)
    return float(min(_point_segment(p, q, qe).min(), _point_segment(q, p, pe).min()))


def test_touch_margin__gap_touch_and_overlap():
    sq = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])
    assert touch_margin(sq, sq + [3.0, 0.0]) == pytest.approx(1.0)
    assert touch_margin(sq, sq + [2.0, 0.5]) == pytest.approx(0.0)
    assert touch_margin(sq, sq + [1.5, 1.0]) == pytest.approx(-0.5)
    notch = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [2.0, 1.0], [0.0, 4.0]])  # concave
    assert touch_margin(notch, sq + [1.0, 2.5]) == pytest.approx(0.0)  # a corner on the left arm
    assert touch_margin(notch, sq / 4 + [1.75, 3.0]) > 0.5  # in the notch: inside the hull, not the polygon


def test_convex_pieces__exact_convex_cover_of_every_armature():
    rng = np.random.default_rng(5)
    shapes = list(ReferenceScene(1, 2, seed=3).shapes.armatures)
    shapes += [random_armature(rng, int(rng.integers(5, 13)), 40.0) for _ in range(40)]
    for arm in shapes:
        pieces = convex_pieces(arm.vertices)
        assert sum(_area(p) for p in pieces) == pytest.approx(arm.area, rel=1e-12)
        verts = {tuple(v) for v in arm.vertices.tolist()}
        for p in pieces:
            k = len(p)
            assert k >= 3 and {tuple(v) for v in p.tolist()} <= verts  # no new points
            assert all(orient(*p[i - 1], *p[i], *p[(i + 1) % k]) >= 0 for i in range(k))
        if arm.convex:
            assert len(pieces) == 1


# -- availability ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "cls, modules, pip",
    [
        (PymunkPeer, ("pymunk", "pymunk.batch"), "pymunk"),
        (ShapelyPeer, ("shapely",), "shapely>=2"),
        (PygameMaskPeer, ("pygame", "pygame.mask"), "pygame-ce"),
    ],
)
def test_peer__missing_library_is_unavailable_and_names_the_pip_package(monkeypatch, cls, modules, pip):
    for m in modules:
        monkeypatch.setitem(sys.modules, m, None)  # makes `import m` raise ImportError
    peer = cls()
    assert peer.available is False
    assert f"pip install '{pip}" in peer.why
    if cls is PygameMaskPeer:
        assert "'pygame'" not in peer.why  # never the clashing `pygame` package
    with pytest.raises(RuntimeError, match="not available"):
        peer.setup(ReferenceScene(1, 2, seed=0))


def test_peers__listed_with_the_interface():
    assert PEERS == [PymunkPeer, ShapelyPeer, PygameMaskPeer]
    for cls in PEERS:
        peer = cls()
        assert isinstance(cls.name, str) and cls.name
        assert isinstance(peer.available, bool) and isinstance(peer.why, str)
        assert peer.available or peer.why


# -- correctness against broadsword's exact answer ----------------------------------------------

SCENES = [(20, 200, 2003, 12), (40, 1000, 11, 4)]  # enemies, bullets, seed, frames


@pytest.fixture(scope="module")
def scenes():
    out = []
    for e, b, seed, frames in SCENES:
        scene = ReferenceScene(e, b, seed=seed)
        out.append((scene, _frames(scene, frames)))
    return out


def _oriented(scene, hits):
    return all((scene.layer[i], scene.layer[j]) in scene.table.entries for i, j in hits)


@pytest.mark.parametrize("cls", [PymunkPeer, ShapelyPeer])
def test_exact_peer__agrees_with_broadsword_up_to_touching(scenes, report, cls):
    peer = _peer(cls)
    hits = extra = missed = 0
    for scene, frames in scenes:
        peer.setup(scene)
        for pos, ang, want in frames:
            got = peer.step(pos, ang, scene.layer)
            assert _oriented(scene, got)
            if got != want:
                polys = pose(scene.shapes, scene.armature, pos, ang, "exact").polygons()
                for i, j in got ^ want:
                    margin = touch_margin(polys[i], polys[j])
                    assert abs(margin) <= TOUCH, (
                        f"{cls.name}: pair {(i, j)} {'extra' if (i, j) in got else 'missed'}, {margin:+.3g} px from touching"
                    )
            hits += len(want)
            extra += len(got - want)
            missed += len(want - got)
    assert hits > 100  # the scenes exercise every table entry
    report(f"{cls.name}: {hits} exact hits, {extra} extra and {missed} missed (all within {TOUCH:g} px of touching)")


def test_pygame_masks__agree_up_to_pixels(scenes, report):
    peer = _peer(PygameMaskPeer)
    hits = extra = missed = 0
    rounded_hits = r_extra = r_missed = 0
    for scene, frames in scenes:
        peer.setup(scene)
        truth = Pipeline(scene.shapes, scene.table, tiers=("brute", "armature"), rotation="exact")
        for pos, ang, want in frames:
            got = peer.step(pos, ang, scene.layer)
            assert _oriented(scene, got)
            hits += len(want)
            extra += len(got - want)
            missed += len(want - got)
            # The exact answer at the poses the masks use (integer pixels and degrees)
            # separates the masks' own error from the rounding of the poses.
            r = truth.step(scene.armature, scene.layer, np.floor(pos + 0.5), np.floor(ang + 0.5))
            at_rounded = set(map(tuple, r.hits.tolist()))
            rounded_hits += len(at_rounded)
            r_extra += len(got - at_rounded)
            r_missed += len(at_rounded - got)
    rate = (extra + missed) / hits
    own = (r_extra + r_missed) / rounded_hits
    report(
        f"{PygameMaskPeer.name}: {hits} exact hits, {extra} extra and {missed} missed ({rate:.1%}); "
        f"against the exact answer at the rounded poses {r_extra} extra and {r_missed} missed ({own:.1%})"
    )
    assert hits > 100
    assert own < 0.05  # the pixel masks themselves
    assert rate < 0.08  # plus rounding every position by up to half a pixel per axis
