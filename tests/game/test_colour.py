"""The palette check's colour science against published figures."""

from __future__ import annotations

import numpy as np
import pytest

from broadsword.game.colour import MACHADO, Vision, ciede2000, lab, simulate, to_linear, to_srgb

#: Sharma, Wu and Dalal 2005, Table 1 (pairs 1, 4, 7, 10, 11, 13, 15, 17, 19, 25): the hue
#: wrap-around and zero-chroma cases among them.
SHARMA = [
    ((50.0, 2.6772, -79.7751), (50.0, 0.0, -82.7485), 2.0425),
    ((50.0, -1.3802, -84.2814), (50.0, 0.0, -82.7485), 1.0000),
    ((50.0, 0.0, 0.0), (50.0, -1.0, 2.0), 2.3669),
    ((50.0, 2.49, -0.001), (50.0, -2.49, 0.0010), 7.1792),
    ((50.0, 2.49, -0.001), (50.0, -2.49, 0.0011), 7.2195),
    ((50.0, -0.001, 2.49), (50.0, 0.0009, -2.49), 4.8045),
    ((50.0, -0.001, 2.49), (50.0, 0.0011, -2.49), 4.7461),
    ((50.0, 2.5, 0.0), (73.0, 25.0, -18.0), 27.1492),
    ((50.0, 2.5, 0.0), (56.0, -27.0, -3.0), 31.9030),
    ((60.2574, -34.0099, 36.2677), (60.4626, -34.1751, 39.4387), 1.2644),
]


@pytest.mark.parametrize("one, two, expected", SHARMA)
def test_ciede2000__matches_sharmas_test_data_both_ways(one, two, expected):
    assert ciede2000(np.array(one), np.array(two)) == pytest.approx(expected, abs=5e-5)
    assert ciede2000(np.array(two), np.array(one)) == pytest.approx(expected, abs=5e-5)


def test_lab__of_srgb_white_black_and_red():
    got = lab(to_linear(np.array([[255, 255, 255], [0, 0, 0], [255, 0, 0]])))
    assert got[0] == pytest.approx([100.0, 0.0, 0.0], abs=0.01)
    assert got[1] == pytest.approx([0.0, 0.0, 0.0], abs=1e-9)
    assert got[2] == pytest.approx([53.24, 80.09, 67.20], abs=0.01)  # the usual sRGB red


def test_srgb__round_trips():
    values = np.arange(256, dtype=np.float64)[:, None].repeat(3, axis=1)
    assert to_srgb(to_linear(values)) == pytest.approx(values, abs=1e-9)


def test_simulate__keeps_greys_and_confuses_red_with_green_for_protans_only():
    grey = to_linear(np.array([128.0, 128.0, 128.0]))
    for vision in Vision:
        assert simulate(grey, vision) == pytest.approx(grey, abs=2e-3)  # each matrix row sums to ~1
    red, green = to_linear(np.array([200.0, 60.0, 40.0])), to_linear(np.array([70.0, 140.0, 40.0]))
    seen = {v: float(ciede2000(lab(simulate(red, v)), lab(simulate(green, v)))) for v in Vision}
    assert seen[Vision.PROTAN] < 0.3 * seen[Vision.NORMAL] and seen[Vision.DEUTAN] < 0.5 * seen[Vision.NORMAL]
    assert seen[Vision.TRITAN] > 0.7 * seen[Vision.NORMAL]
    assert set(MACHADO) == set(Vision) - {Vision.NORMAL}
