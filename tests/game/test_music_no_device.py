"""Launching on a machine without a sound card says so in one line, not 16 ALSA lines.

The launch runs in a subprocess with ``SDL_AUDIODRIVER=alsa`` (the dummy video driver, and
``App.run`` replaced so the window closes at once): on a host with no sound card that
reproduces the defect (libasound prints 8 ``ALSA lib`` lines each time SDL opens audio,
once in ``pygame.init()`` and once in ``Audio``). Wherever it runs, stderr must hold at
most one line and no ``ALSA lib`` line; without a card, that line says there is no audio
device and the game is silent.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from broadsword.game.quiet import filtered_stderr, is_audio_noise

LAUNCH = """
import sys
from broadsword.game import app as m
m.App.run = lambda self: print("available", self.ctx.audio.available, self.ctx.audio.problem is not None)
from broadsword.cli import main
sys.exit(main(sys.argv[1:]))
"""

NO_CARD = not Path("/dev/snd").exists()


def launch(tmp_path, *args):
    env = {
        **os.environ,
        "SDL_AUDIODRIVER": "alsa",
        "SDL_VIDEODRIVER": "dummy",
        "BROADSWORD_DATA_DIR": str(tmp_path / "data"),
        "BROADSWORD_CACHE_DIR": str(tmp_path / "cache"),
        "PYGAME_HIDE_SUPPORT_PROMPT": "1",
    }
    return subprocess.run(
        [sys.executable, "-c", LAUNCH, *args],
        capture_output=True,
        text=True,
        env=env,
        timeout=60,
        cwd=Path(__file__).resolve().parents[2],
    )


def test_launch__at_most_one_line_of_our_own(tmp_path):
    r = launch(tmp_path)
    assert r.returncode == 0, r.stderr
    lines = r.stderr.splitlines()
    assert not [line for line in lines if "ALSA lib" in line], r.stderr
    assert len(lines) <= 1, r.stderr
    if NO_CARD:
        assert lines == [lines[0]] and lines[0].startswith("broadsword: no audio device")
        assert lines[0].endswith("sound off")
        assert "available False True" in r.stdout


@pytest.mark.skipif(not NO_CARD, reason="needs a host without a sound card to reproduce the noise")
def test_launch__the_noise_is_real_here_without_the_filter(tmp_path):
    """The precondition: unfiltered, opening ALSA audio on this host does print the noise."""
    code = "import pygame; pygame.init()"
    env = {**os.environ, "SDL_AUDIODRIVER": "alsa", "SDL_VIDEODRIVER": "dummy", "PYGAME_HIDE_SUPPORT_PROMPT": "1"}
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=60)
    assert sum("ALSA lib" in line for line in r.stderr.splitlines()) >= 2


def test_filtered_stderr__drops_noise_keeps_the_rest_in_order(capfd):
    with filtered_stderr():
        os.write(2, b"ALSA lib conf.c:5180:(_snd_config_evaluate) function returned error\n")
        print("first real line", file=sys.stderr)
        os.write(2, b"second real line\nALSA lib pcm.c:2666:(snd_pcm_open_noupdate) Unknown PCM default\n")
    os.write(2, b"after\n")
    err = capfd.readouterr().err
    assert err == "first real line\nsecond real line\nafter\n"


def test_filtered_stderr__nests_and_restores_on_error(capfd):
    with pytest.raises(RuntimeError):
        with filtered_stderr():
            with filtered_stderr():
                os.write(2, b"ALSA lib x\ninner\n")
            os.write(2, b"outer\n")
            raise RuntimeError("boom")
    os.write(2, b"free\n")
    assert capfd.readouterr().err == "inner\nouter\nfree\n"


@pytest.mark.parametrize(
    "line,noise",
    [
        ("ALSA lib confmisc.c:855:(parse_card) cannot find card '0'\n", True),
        ("  ALSA lib pcm.c:2666:(snd_pcm_open_noupdate) Unknown PCM default", True),
        ("broadsword: no audio device (x); sound off\n", False),
        ("Traceback (most recent call last):\n", False),
        ("", False),
    ],
)
def test_is_audio_noise(line, noise):
    assert is_audio_noise(line) is noise
