"""Every library argument handled (issue 24.5), on both kernels.

A table of bad arguments of the ``Pipeline`` constructor, ``Pipeline.step``/``run``,
``BinGrid`` and ``BinGrid.query``: each is refused with a ``TypeError`` or ``ValueError``
whose message starts with the argument's name (never ``AttributeError``, numpy's or numba's
own message, or silent acceptance). Read-only arrays -- ``np.frombuffer``, memory maps,
views whose owner froze them -- are accepted with the same answers as writeable ones, on
the numpy and the compiled backend alike.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from support.compiled import KERNELS

from broadsword.collision import (
    Armature,
    BinGrid,
    FrameObjects,
    Kernel,
    LayerTable,
    Pipeline,
    polygons_collide_padded,
)

SHIP = Armature([(0, -12), (14, 12), (5, 6), (0, 9), (-5, 6), (-14, 12)], name="ship")
BULLET = Armature.box(4, 10, name="bullet")
TABLE = LayerTable.shmup()
P, B = TABLE.id("player"), TABLE.id("enemy_bullet")
GOOD = dict(armatures=[SHIP, BULLET], layers=TABLE)
FRAME = dict(armature=[0, 1], layer=[P, B], positions=[[0.0, 0.0], [5.0, 0.0]], angles=[0.0, 0.0])
SWEPT = dict(prev_positions=[[0.0, 0.0], [0.0, 0.0]], prev_angles=[0.0, 0.0], swept=[False, True])

# (changes to the constructor's arguments, the argument the message names first)
BAD_PIPELINES = [
    (dict(armatures=[[(0, 0), (1, 0), (0, 1)]]), "armatures"),  # vertex lists, not Armatures
    (dict(armatures=[(0, 0), (1, 0), (0, 1)]), "armatures"),
    (dict(armatures=np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])), "armatures"),
    (dict(armatures="abc"), "armatures"),
    (dict(armatures=None), "armatures"),
    (dict(armatures=5), "armatures"),
    (dict(armatures=[]), "armatures"),
    (dict(armatures=[SHIP, "x"]), "armatures"),
    (dict(armatures=[SHIP, None]), "armatures"),
    (dict(armatures={"ship": SHIP}), "armatures"),
    (dict(armatures=SHIP), "armatures"),  # one Armature, not a sequence of them
    (dict(layers=("player", "enemy_bullet")), "layers"),  # a tuple, not a LayerTable
    (dict(layers=["player"]), "layers"),
    (dict(layers="shmup"), "layers"),
    (dict(layers=5), "layers"),
    (dict(layers={"player": ["enemy_bullet"]}), "layers"),
    (dict(layers=LayerTable), "layers"),  # the class, not a table
    (dict(tiers="bins"), "tiers"),
    (dict(tiers=["bins", 5]), "tiers"),
    (dict(tiers=[]), "tiers"),
    (dict(tiers=None), "tiers"),
    (dict(tiers=5), "tiers"),
    (dict(tiers=["nope"]), "tiers"),
    (dict(tiers=["aabb", "bins"]), "tiers"),
    (dict(tiers=[b"bins"]), "tiers"),
    (dict(rotation="LUT"), "rotation"),
    (dict(rotation=None), "rotation"),
    (dict(rotation=["lut"]), "rotation"),
    (dict(rotation=5), "rotation"),
    (dict(bin_size="16"), "bin_size"),
    (dict(bin_size=-1), "bin_size"),
    (dict(bin_size=0), "bin_size"),
    (dict(bin_size=math.nan), "bin_size"),
    (dict(bin_size=math.inf), "bin_size"),
    (dict(bin_size=True), "bin_size"),
    (dict(bin_size=[16]), "bin_size"),
    (dict(bin_size=1j), "bin_size"),
    (dict(bin_size=np.array([16.0])), "bin_size"),
    (dict(field="abcd"), "field"),
    (dict(field=(0, 0, 1)), "field"),
    (dict(field=(0, 0, 1, 1, 1)), "field"),
    (dict(field=(0, 0, 1, math.nan)), "field"),
    (dict(field=(0, 0, math.inf, 1)), "field"),
    (dict(field=(1, 0, 0, 1)), "field"),  # x1 < x0
    (dict(field=(0, 1, 1, 0)), "field"),
    (dict(field=[0, 0, "a", 1]), "field"),
    (dict(field=5), "field"),
    (dict(field=((0, 0), (1, 1))), "field"),
    (dict(field=(True, 0, 1, 1)), "field"),
    (dict(field=(0, 0, 1j, 1)), "field"),
    (dict(keep_tier_pairs="yes"), "keep_tier_pairs"),
    (dict(keep_tier_pairs=None), "keep_tier_pairs"),
    (dict(keep_tier_pairs=1), "keep_tier_pairs"),
    (dict(kernel="fast"), "kernel"),
    (dict(kernel=5), "kernel"),
    (dict(kernel="NUMBA"), "kernel"),
]

# (changes to FRAME, the argument the message names first); test_arguments.py has more
BAD_STEPS = [
    (dict(positions=None), "positions"),
    (dict(angles=None), "angles"),
    (dict(armature=None), "armature"),
    (dict(layer=None), "layer"),
    (dict(positions={"a": 1}), "positions"),
    (dict(positions="abc"), "positions"),
    (dict(positions={(0.0, 0.0), (5.0, 0.0)}), "positions"),
    (dict(positions=5.0), "positions"),
    (dict(positions=np.zeros((2, 2, 1))), "positions"),
    (dict(positions=[[0, 0], [None, 0]]), "positions"),
    (dict(positions=[[0, 0], [Fraction(1, 3), 0]]), "positions"),  # not a double: would round
    (dict(positions=np.array(["2020-01-01", "2020-01-02"], dtype="datetime64[D]")), "positions"),
    (dict(positions=[[0, 0], [1e400, 0]]), "positions"),
    (dict(angles=[0.0, None]), "angles"),
    (dict(angles="00"), "angles"),
    (dict(angles=[0.0, math.nan]), "angles"),
    (dict(armature="01"), "armature"),
    (dict(armature=[[0], [1]]), "armature"),
    (dict(armature=[0, math.nan]), "armature"),
    (dict(armature=[0, 2**70]), "armature"),
    (dict(layer=["player", "enemy_bullet"]), "layer"),  # names, not ids
    (dict(layer=[P, -1]), "layer"),
    (dict(layer=[P, 4]), "layer"),
    (dict(layer=[P, B, B]), "armature"),  # the lengths disagree: "armature: 3 layer ids but 2 armature"
    ({**SWEPT, "swept": "yes"}, "swept"),
    ({**SWEPT, "swept": [None, True]}, "swept"),
    ({**SWEPT, "swept": np.array([0.0, 1.0])}, "swept"),
    ({**SWEPT, "prev_positions": None}, "prev_positions"),
    ({**SWEPT, "prev_positions": [[0, 0], ["x", 0]]}, "prev_positions"),
    ({**SWEPT, "prev_angles": [0.0, math.inf]}, "prev_angles"),
    ({**SWEPT, "prev_angles": "ab"}, "prev_angles"),
]

# (BinGrid keyword arguments, the argument named)
BAD_GRIDS = [
    (dict(bin_size="16"), "bin_size"),
    (dict(bin_size=-2.0), "bin_size"),
    (dict(field="abcd"), "field"),
    (dict(field=(0, 0, 1)), "field"),
    (dict(max_cells="x"), "max_cells"),
    (dict(max_cells=0), "max_cells"),
    (dict(max_cells=2.5), "max_cells"),
    (dict(max_cells=True), "max_cells"),
]

BOXES = np.array([[0.0, 0.0, 4.0, 4.0], [2.0, 2.0, 6.0, 6.0], [10.0, 10.0, 12.0, 12.0]])
LAYERS = np.array([P, B, B])
# (query arguments: boxes, layers, table; the argument named)
BAD_QUERIES = [
    ((BOXES[:, :3], LAYERS, TABLE), "boxes"),
    ((BOXES.ravel(), LAYERS, TABLE), "boxes"),  # flat: not reshaped
    ((np.where(BOXES == 6.0, np.nan, BOXES), LAYERS, TABLE), "boxes"),
    ((BOXES.astype(str), LAYERS, TABLE), "boxes"),
    ((None, LAYERS, TABLE), "boxes"),
    ((BOXES, LAYERS[:2], TABLE), "layers"),
    ((BOXES, LAYERS + 0.5, TABLE), "layers"),
    ((BOXES, None, TABLE), "layers"),
    ((BOXES, LAYERS, ("player", "enemy_bullet")), "table"),
    ((BOXES, LAYERS, None), "table"),
]


def _refused(call, name):
    with pytest.raises((TypeError, ValueError)) as info:
        call()
    assert not isinstance(info.value, (AttributeError, KeyError, IndexError)), repr(info.value)
    assert str(info.value).startswith(name), str(info.value)


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("changes, name", BAD_PIPELINES)
def test_pipeline__bad_configuration_refused_naming_the_argument(changes, name, kernel):
    kwargs = {**GOOD, "kernel": kernel, **changes}
    _refused(lambda: Pipeline(**kwargs), name)


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("changes, name", BAD_STEPS)
def test_pipeline_step__bad_frame_refused_naming_the_argument(changes, name, kernel):
    pipe = Pipeline(**GOOD, kernel=kernel)
    _refused(lambda: pipe.step(**{**FRAME, **changes}), name)


@pytest.mark.parametrize("kernel", KERNELS)
def test_pipeline_run__refuses_what_is_not_frame_objects(kernel):
    pipe = Pipeline(**GOOD, kernel=kernel)
    _refused(lambda: pipe.run(FRAME), "objects")  # type: ignore[arg-type]


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("kwargs, name", BAD_GRIDS)
def test_bin_grid__bad_configuration_refused_naming_the_argument(kwargs, name, kernel):
    _refused(lambda: BinGrid(**kwargs, kernel=kernel), name)


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("args, name", BAD_QUERIES)
def test_bin_grid_query__bad_arguments_refused_naming_the_argument(args, name, kernel):
    _refused(lambda: BinGrid(kernel=kernel).query(*args), name)


def test_the_corpus_is_large():
    assert len(BAD_PIPELINES) + len(BAD_STEPS) + len(BAD_GRIDS) + len(BAD_QUERIES) >= 100


# --------------------------------------------------------------------- read-only arrays
def _scene(n: int = 40):
    """A frame with ships, bullets and sweeps (every compiled stage has work), writeable."""
    rng = np.random.default_rng(24)
    arm = (rng.random(n) < 0.7).astype(np.int64)
    lay = np.where(arm == 1, B, P).astype(np.int64)
    lay[:3] = TABLE.id("enemy_ship")
    pos = rng.uniform(0, 120, (n, 2))
    ang = rng.uniform(0, 360, n)
    prev = pos - rng.uniform(-30, 30, (n, 2))
    swept = arm == 1
    return dict(armature=arm, layer=lay, positions=pos, angles=ang, prev_positions=prev, prev_angles=ang, swept=swept)


def _frozen(a: np.ndarray) -> np.ndarray:
    v = a.view()
    v.setflags(write=False)
    return v


def _read_only(make: str, a: np.ndarray, path) -> np.ndarray:
    """``a``'s values in a read-only array: a frozen view, ``np.frombuffer`` or a memory map."""
    if make == "frozen":
        return _frozen(a)
    if make == "frombuffer":
        return np.frombuffer(a.tobytes(), dtype=a.dtype).reshape(a.shape)
    np.save(path, a)
    return np.load(path, mmap_mode="r")


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("make", ["frozen", "frombuffer", "memmap"])
@pytest.mark.parametrize("rotation", ["lut", "exact"])
def test_read_only_arrays__same_hits_on_both_kernels(kernel, make, rotation, tmp_path):
    frame = _scene()
    want = Pipeline(**GOOD, rotation=rotation, kernel="numpy").step(**frame).hits
    assert len(want)
    read_only = {k: _read_only(make, v, tmp_path / f"{k}.npy") for k, v in frame.items()}
    assert not any(v.flags.writeable for v in read_only.values())
    pipe = Pipeline(**GOOD, rotation=rotation, kernel=kernel)
    assert pipe.step(**read_only).hits.tolist() == want.tolist()
    assert pipe.run(FrameObjects(**read_only)).hits.tolist() == want.tolist()


@pytest.mark.parametrize("kernel", KERNELS)
def test_read_only_arrays__bin_grid_query_and_the_padded_narrow_phase(kernel):
    pairs = BinGrid(kernel="numpy").query(BOXES, LAYERS, TABLE)[0]
    got = BinGrid(kernel=kernel).query(_frozen(BOXES), _frozen(LAYERS), TABLE)[0]
    assert got.tolist() == pairs.tolist() == [[0, 1]]
    px, py = np.array([[0.0], [4.0], [0.0]]), np.array([[0.0], [0.0], [4.0]])
    qx, qy = px + 1.0, py + 1.0
    args = [_read_only("frombuffer", a, None) for a in (px, py, qx, qy)]
    assert polygons_collide_padded(*args, kernel=Kernel(kernel)).tolist() == [True]
