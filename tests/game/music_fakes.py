"""A stand-in for the music renderer, for tests that play music without spending time rendering it."""

from __future__ import annotations

import threading

import numpy as np

from broadsword.game.music.renderer import loop_samples


class FakeRender:
    """Counts calls; returns 0.2 s of a quiet stereo tone whose pitch depends on the song."""

    def __init__(self, gate: threading.Event | None = None, fail: bool = False):
        self.calls: list[str] = []
        self.gate, self.fail = gate, fail

    def __call__(self, song, rate):
        self.calls.append(song.title)
        if self.gate is not None:
            assert self.gate.wait(10)
        if self.fail:
            raise RuntimeError("synth exploded")
        n = loop_samples(song, rate) + (0 if song.loop else round(song.tail * rate))  # as render() makes
        t = np.arange(n) / rate
        x = np.round(3000 * np.sin(2 * np.pi * (200 + len(song.title) * 10) * t)).astype(np.int16)
        return np.stack([x, x], axis=1)
