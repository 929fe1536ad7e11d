"""Recording and playing back through the sim: inputs, live toggles and checkpoints."""

import dataclasses
import functools

import pytest
import shipped

from broadsword.data import load_level, resolve_level
from broadsword.data.recordings import CHECKPOINT_EVERY
from broadsword.sim import Carry, Input, Pilot, Settings, World
from broadsword.sim.replay import Playback, Recorder

ARMATURES = shipped.armatures()
LEVEL = load_level(resolve_level("3-broadsword"))
FRAMES = 2 * CHECKPOINT_EVERY + 150


@functools.cache
def record(seed=1, toggles_at=(200, 700), carry=None) -> tuple[World, object]:
    """An autopilot run that switches rotation mode at the given frames (as F4 does). Made
    once per process for each set of arguments and shared: tests must not change the world."""
    w = World(LEVEL, ARMATURES, seed, carry=carry)
    pilot = Pilot()
    rec = Recorder(w, "3-broadsword")
    for f in range(FRAMES):
        if f in toggles_at:
            w.set_rotation("exact" if w.rotation == "lut" else "lut")
        inp = pilot(w)
        w.step(inp)
        rec.stepped(inp)
        if w.over:
            break
    return w, rec.recording()


def play(rec) -> tuple[World, Playback]:
    w = World(LEVEL, ARMATURES, rec.seed, Settings(**rec.settings), Carry(**rec.carry))
    p = Playback(rec, w)
    while (inp := p.next_input()) is not None:
        w.step(inp)
        p.stepped()
    return w, p


def test_recording_carries_settings_toggles_and_checkpoints():
    w, rec = record()
    assert rec.settings == {"rotation": "lut", "difficulty": "normal"} and rec.frames == w.frame
    assert rec.toggles == ((200, "rotation", "exact"), (700, "rotation", "lut"))
    assert [c[0] for c in rec.checkpoints] == [CHECKPOINT_EVERY * (i + 1) for i in range(w.frame // CHECKPOINT_EVERY)]
    assert rec.state_hash == w.state_hash()


def test_playback_applies_the_toggles_and_matches_every_checkpoint():
    w, rec = record()
    again, p = play(rec)
    assert p.mismatch is None and p.final_check() is True
    assert again.state_hash() == w.state_hash()
    assert [(t.frame, t.value) for t in again.toggles] == [(200, "exact"), (700, "lut")]


def test_toggles_change_the_game():
    """The toggle matters (3 of 6 autopilot runs diverged when F4 went unrecorded, and the
    mode in force is part of the state): without it, the playback drifts, and says from
    which checkpoint."""
    w, rec = record(seed=1, toggles_at=(100,))
    _, p = play(dataclasses.replace(rec, toggles=()))
    assert p.mismatch is not None and p.final_check() is False
    k = [c[0] for c in rec.checkpoints].index(p.mismatch.frame)
    assert p.mismatch.expected == rec.checkpoints[k][1] != p.mismatch.got
    # It is the first: the checkpoints before it matched (re-played, compared one by one).
    again = World(LEVEL, ARMATURES, rec.seed, Settings(rotation="lut"))
    for b in rec.inputs[: p.mismatch.frame - 1]:
        again.step(Input.from_byte(b))
        if again.frame % CHECKPOINT_EVERY == 0 and again.frame < p.mismatch.frame:
            assert again.state_hash() == dict(rec.checkpoints)[again.frame]


def test_carry_is_part_of_the_recording():
    w, rec = record(toggles_at=(), carry=Carry(score=5000, lives=2, power=250))
    assert rec.carry == {"score": 5000, "lives": 2, "continues": 0, "power": 250}
    again, p = play(rec)
    assert p.mismatch is None and p.final_check() is True and again.score.points >= 5000


def test_carry__the_next_stage_starts_with_the_power_the_last_one_ended_with():
    """Power won in one stage is kept into the next (clamped to the ship's range); no carried
    power is the base power."""
    from broadsword.sim.player import POWER_MAX, POWER_MIN

    assert World(LEVEL, ARMATURES).player.power == POWER_MIN
    assert World(LEVEL, ARMATURES, carry=Carry(power=275)).player.power == 275
    assert World(LEVEL, ARMATURES, carry=Carry(power=POWER_MAX + 50)).player.power == POWER_MAX


def test_apply_refuses_a_toggle_for_another_frame():
    w = World(LEVEL, ARMATURES)
    from broadsword.sim import Toggle, ToggleEvent

    with pytest.raises(ValueError, match="frame 3"):
        w.apply(ToggleEvent(3, Toggle.ROTATION, "exact"))
