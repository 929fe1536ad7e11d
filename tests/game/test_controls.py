"""Controls: one binding table from keys and pad buttons to actions and the sim's Input;
rebinding; the bindings file (atomic, and a broken one falls back to the defaults)."""

from __future__ import annotations

import json

import pygame
import pytest

from broadsword.game.controls import (
    BOUND_MAX,
    DEFAULT_KEYS,
    FIXED_KEYS,
    REBINDABLE,
    Action,
    Bindings,
    Controls,
    PadButton,
    confirm_label,
    keys_label,
    load_bindings,
    save_bindings,
)
from broadsword.sim import Input


@pytest.fixture(autouse=True)
def _pygame():
    pygame.init()
    yield


class StubPad:
    """A gamepad as pygame's joystick API presents it, with ``pressed`` buttons held."""

    def __init__(self, *pressed: int, axis=(0.0, 0.0), hat=(0, 0)):
        self.pressed, self.axis, self.hat = set(pressed), axis, hat

    def get_axis(self, i):
        return self.axis[i]

    def get_numhats(self):
        return 1

    def get_hat(self, i):
        return self.hat

    def get_numbuttons(self):
        return 12

    def get_button(self, i):
        return i in self.pressed


def held(*keys: int) -> Controls:
    c = Controls()
    c.pad = None
    c.held = set(keys)
    return c


def keydown(k: int, unicode: str = "") -> pygame.event.Event:
    return pygame.event.Event(pygame.KEYDOWN, key=k, mod=0, unicode=unicode, scancode=0)


def test_input__default_keys_move_fire_slow_and_bomb():
    assert held().input() == Input()
    assert held(pygame.K_LEFT, pygame.K_z).input() == Input(-1, 0, True, False, False)
    assert held(pygame.K_d, pygame.K_s, pygame.K_LSHIFT).input() == Input(1, 1, False, True, False)
    assert held(pygame.K_x).input() == Input(bomb=True)  # X bombs
    assert held(pygame.K_LEFT, pygame.K_RIGHT).input().dx == 0  # both ways: still


def test_input__pad_buttons_are_named_and_bombs_on_x():
    c = held()
    c.pad = StubPad(PadButton.X)
    assert c.input() == Input(bomb=True)
    c.pad = StubPad(PadButton.A, PadButton.B, axis=(-0.9, 0.0), hat=(0, 1))
    assert c.input() == Input(-1, -1, True, True, False)
    c.pad = StubPad(axis=(0.2, -0.3))  # inside the dead zone
    assert c.input() == Input()


def test_actions__one_table_for_menus_and_toggles():
    c = held()
    assert c.actions(keydown(pygame.K_ESCAPE)) == {Action.PAUSE, Action.BACK}
    assert c.actions(keydown(pygame.K_RETURN)) == {Action.CONFIRM}
    assert c.actions(keydown(pygame.K_F11)) == {Action.FULLSCREEN}
    assert c.actions(keydown(pygame.K_x)) == {Action.BOMB}
    start = pygame.event.Event(pygame.JOYBUTTONDOWN, button=PadButton.START, joy=0, instance_id=0)
    assert Action.PAUSE in c.actions(start) and Action.CONFIRM in c.actions(start)
    hat = pygame.event.Event(pygame.JOYHATMOTION, value=(-1, 1), hat=0, joy=0, instance_id=0)
    assert c.actions(hat) == {Action.LEFT, Action.UP}


def test_rebind__a_replacing_key_alone_presses_the_action_and_leaves_the_others():
    b = Bindings()
    b.bind_key(Action.FIRE, pygame.K_c, replace=True)
    b.bind_key(Action.BOMB, pygame.K_LEFT, replace=True)  # taken from LEFT
    c = Controls(b)
    c.pad = None
    c.held = {pygame.K_c, pygame.K_LEFT}
    assert c.input() == Input(0, 0, True, False, True)
    c.held = {pygame.K_z, pygame.K_a}
    assert c.input() == Input(-1, 0, False, False, False)
    assert b.keys[Action.LEFT] == (pygame.K_a,)
    # arrows still move through menus, whatever movement is bound to
    assert Action.LEFT in c.actions(keydown(pygame.K_LEFT))
    b.bind_button(Action.BOMB, PadButton.Y, replace=True)
    c.held, c.pad = set(), StubPad(PadButton.Y, PadButton.X)
    assert c.input() == Input(bomb=True)
    c.pad = StubPad(PadButton.X)
    assert c.input() == Input()
    with pytest.raises(ValueError):
        b.bind_key(Action.MUTE, pygame.K_q)


def test_rebind__an_added_key_keeps_the_others():
    """Slow -> C adds C: both Shifts still slow (issue 22: it silently dropped them)."""
    b = Bindings()
    b.bind_key(Action.SLOW, pygame.K_c)
    assert b.keys[Action.SLOW] == (pygame.K_LSHIFT, pygame.K_RSHIFT, pygame.K_c)
    b.bind_key(Action.SLOW, pygame.K_c)  # again: still once
    assert b.keys[Action.SLOW] == (pygame.K_LSHIFT, pygame.K_RSHIFT, pygame.K_c)
    b.bind_key(Action.BOMB, pygame.K_c)  # taken by another action: gone from Slow
    assert b.keys[Action.SLOW] == (pygame.K_LSHIFT, pygame.K_RSHIFT) and b.keys[Action.BOMB] == (pygame.K_x, pygame.K_c)
    b.bind_button(Action.FIRE, PadButton.Y)
    assert b.buttons[Action.FIRE] == (PadButton.A, PadButton.Y)
    for k in range(pygame.K_a, pygame.K_a + 12):  # at most BOUND_MAX: the oldest go
        b.bind_key(Action.PAUSE, k)
    assert b.keys[Action.PAUSE] == tuple(range(pygame.K_a + 12 - BOUND_MAX, pygame.K_a + 12))


def test_keys_label__names_the_bound_keys():
    b = Bindings()
    assert confirm_label(b) == "Enter or Z / Space"
    assert keys_label(b, Action.SLOW) == "Shift"
    b.bind_key(Action.FIRE, pygame.K_j, replace=True)
    assert confirm_label(b) == "Enter or J"
    b.keys[Action.FIRE] = ()
    assert confirm_label(b) == "Enter" and keys_label(b, Action.FIRE) == "(none)"


def test_bindings_file__round_trip_is_atomic_and_readable(tmp_path):
    path = tmp_path / "d" / "controls.json"
    b = Bindings()
    b.bind_key(Action.BOMB, pygame.K_v, replace=True)
    b.bind_button(Action.SLOW, PadButton.RB, replace=True)
    save_bindings(b, path)
    assert sorted(p.name for p in path.parent.iterdir()) == ["controls.json"]  # no temporaries left
    doc = json.loads(path.read_text())
    assert doc["keys"]["bomb"] == ["v"] and doc["buttons"]["slow"] == ["RB"]
    loaded, warning = load_bindings(path)
    assert warning is None and loaded == b


def test_bindings_file__missing_is_the_defaults_silently(tmp_path):
    b, warning = load_bindings(tmp_path / "none.json")
    assert warning is None and b == Bindings() and b.keys == DEFAULT_KEYS


@pytest.mark.parametrize(
    "content, field",
    [
        (b"\xff\xfe not json", "controls.json"),
        (b"[1, 2]", "JSON object"),
        (b'{"version": 0}', "version"),
        (b'{"version": 1, "keys": {"fire": ["no such key"]}}', "keys.fire"),
        (b'{"version": 1, "keys": {"mute": ["q"]}}', "keys.mute"),
        (b'{"version": 1, "keys": {"jump": ["q"]}}', "keys.jump"),
        (b'{"version": 1, "keys": {"fire": ["return"]}}', "keys.fire"),  # a fixed key
        (b'{"version": 1, "keys": {"fire": ["f1"]}}', "keys.fire"),
        (b'{"version": 1, "buttons": {"bomb": ["Z9"]}}', "buttons.bomb"),
        ('{"version": 1, "buttons": {"bomb": ["\u00b2"]}}'.encode(), "buttons.bomb"),  # "2" in superscript
        (b'{"version": 1, "keys": []}', "keys"),
        (b"[" * 100_000, "controls.json"),
        (b'{"version": 1, "keys": {"fire": ["q', "controls.json"),  # truncated
    ],
)
def test_bindings_file__a_bad_file_or_name_falls_back_with_a_message(tmp_path, content, field):
    path = tmp_path / "controls.json"
    path.write_bytes(content)
    b, warning = load_bindings(path)
    assert b == Bindings()
    assert warning is not None and str(path) in warning and field in warning and "\n" not in warning
    assert "int()" not in warning and "invalid literal" not in warning
    assert (tmp_path / "controls.json.bad").read_bytes() == content
    assert not path.exists() if len(content) > 64 << 10 else path.read_bytes() == content  # too big: moved


def _table(b: Bindings) -> tuple[dict, dict]:
    return {a: b.keys.get(a, ()) for a in REBINDABLE}, {a: b.buttons.get(a, ()) for a in REBINDABLE}


def test_bindings_file__one_bad_name_keeps_every_valid_one(tmp_path):
    path = tmp_path / "controls.json"
    doc = {
        "version": 1,
        "keys": {"bomb": ["v", "no such key"], "slow": ["c"], "fire": ["escape"], "pause": ["p", "escape"]},
        "buttons": {"fire": ["Y", "\u00b2"], "slow": ["RB"]},
    }
    path.write_text(json.dumps(doc))
    b, warning = load_bindings(path)
    expected = Bindings()
    expected.bind_key(Action.BOMB, pygame.K_v, replace=True)  # a file lists an action's keys in full
    expected.bind_key(Action.SLOW, pygame.K_c, replace=True)
    expected.keys[Action.PAUSE] = (pygame.K_p, pygame.K_ESCAPE)  # Esc pauses by default: allowed
    expected.bind_button(Action.FIRE, PadButton.Y, replace=True)
    expected.bind_button(Action.SLOW, PadButton.RB, replace=True)
    assert _table(b) == _table(expected)  # fire's only key was refused: it keeps its defaults
    assert warning is not None
    for named in ("keys.bomb: unknown key 'no such key'", "keys.fire: 'escape' is a fixed key", "buttons.fire"):
        assert named in warning
    assert "'²'" in warning


def test_bindings_file__a_key_bound_twice_is_refused_the_second_time(tmp_path):
    path = tmp_path / "controls.json"
    path.write_text(json.dumps({"version": 1, "keys": {"fire": ["q"], "bomb": ["q", "v"]}}))
    b, warning = load_bindings(path)
    assert b.keys[Action.FIRE] == (pygame.K_q,) and b.keys[Action.BOMB] == (pygame.K_v,)
    assert warning is not None and "keys.bomb: 'q' is bound twice" in warning


def test_bindings_file__a_file_key_leaves_the_defaults_of_other_actions(tmp_path):
    path = tmp_path / "controls.json"
    path.write_text(json.dumps({"version": 1, "keys": {"fire": ["a"]}}))  # A moves left by default
    b, warning = load_bindings(path)
    assert warning is None and b.keys[Action.FIRE] == (pygame.K_a,) and b.keys[Action.LEFT] == (pygame.K_LEFT,)


def test_bindings_file__a_newer_versions_additions_survive_a_save(tmp_path):
    path = tmp_path / "controls.json"
    path.write_text(json.dumps({"version": 3, "keys": {"bomb": ["v"], "dash": ["q"]}, "mouse": {"aim": True}}))
    b, warning = load_bindings(path)
    assert warning is None and b.keys[Action.BOMB] == (pygame.K_v,)
    b.bind_key(Action.SLOW, pygame.K_c, replace=True)
    save_bindings(b, path)
    doc = json.loads(path.read_text())
    assert doc["keys"]["dash"] == ["q"] and doc["mouse"] == {"aim": True} and doc["version"] == 3
    assert doc["keys"]["slow"] == ["c"] and doc["keys"]["bomb"] == ["v"]


def test_bindings_file__a_fifo_is_refused_at_once(tmp_path):
    import os

    path = tmp_path / "controls.json"
    os.mkfifo(path)
    b, warning = load_bindings(path)
    assert b == Bindings() and warning is not None and "a FIFO, not a regular file" in warning


def test_bindings_file__a_directory_in_its_place_is_not_a_crash(tmp_path):
    (tmp_path / "controls.json").mkdir()
    b, warning = load_bindings(tmp_path / "controls.json")
    assert b == Bindings() and "default keys" in warning


def test_fixed_keys_cannot_be_lost_by_rebinding():
    b = Bindings()
    for action in (Action.PAUSE, Action.FIRE):
        b.bind_key(action, pygame.K_q)
    assert Action.BACK in b.key_actions(pygame.K_ESCAPE) and Action.CONFIRM in b.key_actions(pygame.K_RETURN)
    assert all(a not in Bindings().keys for a in FIXED_KEYS.values())
