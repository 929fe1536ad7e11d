"""Keys and gamepad -> actions and the sim's :class:`~broadsword.sim.Input`, through one binding table.

:class:`Bindings` is that table: for each rebindable :class:`Action` (movement, fire, slow,
bomb, pause), the keys and gamepad buttons that press it. The fixed keys (F1-F4, F11, M,
Return, Esc) sit in :data:`FIXED_KEYS`, so a rebinding can never lose the way out of a menu.
:class:`Controls` keeps what is held (keys, the pad) and answers two questions: which
actions an event presses (menus and toggles), and what the ship is told this frame
(:meth:`Controls.input`).

Bindings are saved as JSON in the user's data directory (``controls.json`` beside the high
scores), written atomically (:mod:`.settingsfile`). The file is read name by name: a bad
one (an unknown key or pad button, an action that is not rebindable, a fixed key, a key
already bound to another action: what the options screen refuses) is named in a one-line
``warning`` the title shows and left out, the rest is kept, an action left with none of its
names keeps its defaults, and the file is first copied aside as ``controls.json.bad``. A
file that is no controls file at all gives the default keys and a warning, never a crash
or a hang; what a newer version adds survives a save.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from enum import Enum, IntEnum
from pathlib import Path

import pygame

from ..fileio import write_atomic
from ..sim import Input
from .scores import data_home
from .settingsfile import load_settings, merged_for_save, one_line

#: The file's format, and its largest sensible size (anything bigger is not a bindings file).
FORMAT_VERSION = 1
FILE_MAX_BYTES = 64 << 10
#: At most this many keys (and as many pad buttons) press one action (the file's limit too).
BOUND_MAX = 8
#: A stick pushed further than this (of 1.0) counts as a direction.
STICK_DEAD_ZONE = 0.35


class Action(Enum):
    """What a key or button can mean. The first eight are rebindable (:class:`Bindings`)."""

    LEFT = "left"
    RIGHT = "right"
    UP = "up"
    DOWN = "down"
    FIRE = "fire"
    SLOW = "slow"
    BOMB = "bomb"
    PAUSE = "pause"
    # fixed (FIXED_KEYS, FIXED_BUTTONS)
    CONFIRM = "confirm"
    BACK = "back"
    OVERLAY = "overlay"
    STEP = "step"
    SLOW_MOTION = "slow motion"
    ROTATION = "rotation"
    FULLSCREEN = "fullscreen"
    MUTE = "mute"

    @property
    def title(self) -> str:
        return self.value.capitalize()


#: Ship actions a tap shorter than a step still performs (:meth:`Controls.take_input`).
TAPPED = frozenset({Action.FIRE, Action.BOMB})


REBINDABLE = (Action.LEFT, Action.RIGHT, Action.UP, Action.DOWN, Action.FIRE, Action.SLOW, Action.BOMB, Action.PAUSE)


class PadButton(IntEnum):
    """Gamepad buttons by their SDL joystick index (the XInput layout most pads report)."""

    A = 0
    B = 1
    X = 2
    Y = 3
    LB = 4
    RB = 5
    BACK = 6
    START = 7


#: Keys that always mean the same thing, whatever the bindings say.
FIXED_KEYS: dict[int, Action] = {
    pygame.K_RETURN: Action.CONFIRM,
    pygame.K_KP_ENTER: Action.CONFIRM,
    pygame.K_ESCAPE: Action.BACK,
    pygame.K_F1: Action.OVERLAY,
    pygame.K_F2: Action.STEP,
    pygame.K_F3: Action.SLOW_MOTION,
    pygame.K_F4: Action.ROTATION,
    pygame.K_F11: Action.FULLSCREEN,
    pygame.K_m: Action.MUTE,
}
FIXED_BUTTONS: dict[int, Action] = {PadButton.START: Action.CONFIRM, PadButton.BACK: Action.BACK}
#: The arrow keys always move through menus, whatever movement is bound to.
MENU_KEYS: dict[int, Action] = {
    pygame.K_LEFT: Action.LEFT,
    pygame.K_RIGHT: Action.RIGHT,
    pygame.K_UP: Action.UP,
    pygame.K_DOWN: Action.DOWN,
}

DEFAULT_KEYS: dict[Action, tuple[int, ...]] = {
    Action.LEFT: (pygame.K_LEFT, pygame.K_a),
    Action.RIGHT: (pygame.K_RIGHT, pygame.K_d),
    Action.UP: (pygame.K_UP, pygame.K_w),
    Action.DOWN: (pygame.K_DOWN, pygame.K_s),
    Action.FIRE: (pygame.K_z, pygame.K_SPACE),
    Action.SLOW: (pygame.K_LSHIFT, pygame.K_RSHIFT),
    Action.BOMB: (pygame.K_x,),
    Action.PAUSE: (pygame.K_ESCAPE, pygame.K_p),
}
DEFAULT_BUTTONS: dict[Action, tuple[int, ...]] = {
    Action.FIRE: (PadButton.A,),
    Action.SLOW: (PadButton.B,),
    Action.BOMB: (PadButton.X,),
    Action.PAUSE: (PadButton.START,),
}


def key_label(key: int) -> str:
    """A key's name as a player reads it ("Left", "Z", "Left Shift")."""
    name = pygame.key.name(key)
    return name.title() if name else f"key {key}"


@dataclass
class Bindings:
    """For each rebindable action, its keys and pad buttons (pygame key codes, PadButton values)."""

    keys: dict[Action, tuple[int, ...]] = field(default_factory=lambda: dict(DEFAULT_KEYS))
    buttons: dict[Action, tuple[int, ...]] = field(default_factory=lambda: dict(DEFAULT_BUTTONS))

    def bind_key(self, action: Action, key: int, replace: bool = False) -> None:
        """``key`` now presses ``action``, besides its other keys (the oldest dropped past
        ``BOUND_MAX``), or instead of them if ``replace``; no other rebindable action keeps it."""
        self._check(action)
        self.keys = _bind(self.keys, action, key, replace)

    def bind_button(self, action: Action, button: int, replace: bool = False) -> None:
        """``button`` now presses ``action``, as :meth:`bind_key` binds a key."""
        self._check(action)
        self.buttons = _bind(self.buttons, action, int(button), replace)

    @staticmethod
    def _check(action: Action) -> None:
        if action not in REBINDABLE:
            raise ValueError(f"{action.title} cannot be rebound")

    def key_actions(self, key: int) -> set[Action]:
        out = {a for a in REBINDABLE if key in self.keys.get(a, ())}
        if key in FIXED_KEYS:
            out.add(FIXED_KEYS[key])
        return out

    def button_actions(self, button: int) -> set[Action]:
        out = {a for a in REBINDABLE if button in self.buttons.get(a, ())}
        if button in FIXED_BUTTONS:
            out.add(FIXED_BUTTONS[button])
        if Action.FIRE in out:
            out.add(Action.CONFIRM)  # the fire button also picks in menus
        return out

    def describe(self, action: Action) -> str:
        """What presses ``action``, for the options screen ("Z, Space / pad A")."""
        keys = ", ".join(key_label(k) for k in self.keys.get(action, ())) or "no key"
        pads = ", ".join(
            PadButton(b).name if b in PadButton._value2member_map_ else str(b) for b in self.buttons.get(action, ())
        )
        return f"{keys} / pad {pads}" if pads else keys

    # ------------------------------------------------------------------ the file
    def to_json(self) -> dict:
        return {
            "version": FORMAT_VERSION,
            "keys": {a.value: [pygame.key.name(k) for k in self.keys.get(a, ())] for a in REBINDABLE},
            "buttons": {a.value: [_button_name(b) for b in self.buttons.get(a, ())] for a in REBINDABLE},
        }

    @classmethod
    def from_json(cls, doc) -> tuple[Bindings, list[str]]:
        """The bindings ``doc`` describes, name by name, and one ``"field: what"`` for each
        name refused. Refused as the options screen refuses them: an unknown key or pad
        button, an action that is not rebindable, a fixed key (:data:`FIXED_KEYS`) unless
        it is among the action's own defaults (Esc pauses), a key or button the file
        already gave another action. An action the file leaves out, or whose names are
        all refused, keeps its defaults, less what the file gives other actions (as
        :meth:`bind_key` takes a key from every other action)."""
        if not isinstance(doc, dict):
            return cls(), ["the file must be a JSON object of version, keys and buttons"]
        problems = []
        version = doc.get("version")
        newer = type(version) is int and version > FORMAT_VERSION  # its new actions: kept, not named
        if not newer and version != FORMAT_VERSION:
            problems.append(f"version: must be {FORMAT_VERSION}, got {version!r}")
        b = cls()
        for part, parse, table in (("keys", _key_code, b.keys), ("buttons", _button_code, b.buttons)):
            given = doc.get(part, {})
            if not isinstance(given, dict):
                problems.append(f"{part}: must be a table of action -> list of names")
                continue
            chosen: dict[Action, tuple[int, ...]] = {}
            taken: set[int] = set()
            for name, values in given.items():
                where = f"{part}.{name}"
                try:
                    action = Action(name)
                except ValueError:
                    if not newer:
                        problems.append(
                            f"{where}: not an action (rebindable: {', '.join(a.value for a in REBINDABLE)})"
                        )
                    continue
                if action not in REBINDABLE or not isinstance(values, list) or len(values) > BOUND_MAX:
                    problems.append(f"{where}: must be a list of at most {BOUND_MAX} names of a rebindable action")
                    continue
                codes = []
                for value in values:
                    try:
                        code = parse(where, value)
                        if part == "keys" and code in FIXED_KEYS and code not in DEFAULT_KEYS.get(action, ()):
                            raise ValueError(f"{where}: {value!r} is a fixed key ({FIXED_KEYS[code].title})")
                        if code in taken or code in codes:
                            raise ValueError(f"{where}: {value!r} is bound twice")
                    except ValueError as exc:
                        problems.append(str(exc))
                        continue
                    codes.append(code)
                if codes or not values:
                    chosen[action] = tuple(codes)
                    taken.update(codes)
            for action in REBINDABLE:
                if action in chosen:
                    table[action] = chosen[action]
                elif action in table:
                    table[action] = tuple(c for c in table[action] if c not in taken)
        return b, [one_line(p) for p in problems]


def _bind(table: dict[Action, tuple[int, ...]], action: Action, code: int, replace: bool) -> dict:
    """``table`` with ``code`` bound to ``action`` (added last, or alone if ``replace``) and
    taken from every other rebindable action; at most ``BOUND_MAX`` codes an action."""
    out = {a: tuple(c for c in table.get(a, ()) if c != code) for a in REBINDABLE}
    out[action] = ((code,) if replace else (*out[action], code))[-BOUND_MAX:]
    return out


def keys_label(bindings: Bindings, action: Action) -> str:
    """The keys that press ``action``, as a player reads them: "Z / Space", "Shift" (both
    Shifts are one word), "(none)"."""
    labels = [key_label(k).removeprefix("Left ").removeprefix("Right ") for k in bindings.keys.get(action, ())]
    return " / ".join(dict.fromkeys(labels)) or "(none)"


def move_label(bindings: Bindings) -> str:
    """The movement keys: "Arrows / WASD" while they are the defaults, else the four keys
    (left, right, up, down), each action's first."""
    moves = (Action.LEFT, Action.RIGHT, Action.UP, Action.DOWN)
    if all(bindings.keys.get(a) == DEFAULT_KEYS[a] for a in moves):
        return "Arrows / WASD"
    return " ".join(key_label(bindings.keys[a][0]) for a in moves if bindings.keys.get(a))


def confirm_label(bindings: Bindings) -> str:
    """What confirms on a menu, for its help line: "Enter or Z / Space" (Enter and the Fire keys)."""
    fire = keys_label(bindings, Action.FIRE)
    return "Enter" if fire == "(none)" else f"Enter or {fire}"


def _button_name(b: int) -> str:
    return PadButton(b).name if b in PadButton._value2member_map_ else str(b)


def _key_code(where: str, name) -> int:
    if not isinstance(name, str) or not name:
        raise ValueError(f"{where}: key names must be non-empty strings, got {name!r}")
    try:
        return pygame.key.key_code(name)
    except (ValueError, pygame.error):
        raise ValueError(f"{where}: unknown key {name!r}") from None


def _button_code(where: str, name) -> int:
    if isinstance(name, str) and name in PadButton.__members__:
        return int(PadButton[name])
    if isinstance(name, str) and name.isascii() and name.isdecimal() and len(name) <= 2 and int(name) < 32:
        return int(name)
    raise ValueError(f"{where}: unknown pad button {name!r} (A, B, X, Y, LB, RB, BACK, START or 0-31)")


def bindings_path() -> Path:
    return data_home() / "controls.json"


def load_bindings(path: Path | None = None) -> tuple[Bindings, str | None]:
    """The saved bindings, name by name, and a one-line warning naming each name not used
    (None when all were); a missing file is the defaults, silently. A file with any bad
    content is copied aside (``controls.json.bad``) first, and the warning says where."""
    path = Path(path) if path is not None else bindings_path()
    return load_settings(path, FILE_MAX_BYTES, "controls", "default keys", Bindings(), Bindings.from_json)


def save_bindings(bindings: Bindings, path: Path | None = None) -> None:
    """Write atomically (temp file + os.replace), keeping what the file holds that this
    version does not know; OSError propagates, and a FIFO or device in the file's place is
    never replaced."""
    path = Path(path) if path is not None else bindings_path()
    doc = merged_for_save(path, bindings.to_json(), FILE_MAX_BYTES, FORMAT_VERSION)
    write_atomic(path, (json.dumps(doc, indent=1) + "\n").encode())


class Controls:
    """What is held now -- keys and the first gamepad -- read through :class:`Bindings`."""

    def __init__(self, bindings: Bindings | None = None):
        self.bindings = bindings or Bindings()
        self.held: set[int] = set()
        #: Ship actions pressed since the last step took them (:meth:`take_input`): a tap whose
        #: key goes down and up between two steps still fires once or bombs.
        self.tapped: set[Action] = set()
        self.pad: pygame.joystick.JoystickType | None = None
        self.connect_pad()

    def connect_pad(self) -> None:
        """Use the first gamepad, if any (called at start and when one is plugged in)."""
        try:
            pygame.joystick.init()
            self.pad = pygame.joystick.Joystick(0) if pygame.joystick.get_count() else None
        except pygame.error:
            self.pad = None

    def track(self, event: pygame.event.Event) -> None:
        """Keep ``held`` up to date (call for every event, before any scene sees it)."""
        if event.type in (pygame.KEYDOWN, pygame.JOYBUTTONDOWN):
            if event.type == pygame.KEYDOWN:
                self.held.add(event.key)
            self.tapped |= self.actions(event) & TAPPED
        elif event.type == pygame.KEYUP:
            self.held.discard(event.key)
        elif event.type == pygame.JOYDEVICEADDED:
            self.connect_pad()

    def release_all(self) -> None:
        """Forget held keys (the window lost focus: their KEYUPs will never come to us)."""
        self.held.clear()
        self.tapped.clear()

    def take_input(self) -> Input:
        """This step's :class:`Input`: what is held, plus a fire or bomb tapped since the last
        step (even if already let go), which this call uses up. :meth:`input` only looks."""
        inp = self.input()
        taps, self.tapped = self.tapped, set()
        if not taps:
            return inp
        return Input(inp.dx, inp.dy, inp.fire or Action.FIRE in taps, inp.slow, inp.bomb or Action.BOMB in taps)

    def actions(self, event: pygame.event.Event) -> set[Action]:
        """The actions ``event`` presses: a key or button going down, or the d-pad pushed."""
        if event.type == pygame.KEYDOWN:
            actions = self.bindings.key_actions(event.key)
            if event.key in MENU_KEYS:
                actions.add(MENU_KEYS[event.key])
            return actions
        if event.type == pygame.JOYBUTTONDOWN:
            return self.bindings.button_actions(event.button)
        if event.type == pygame.JOYHATMOTION:
            x, y = event.value
            return {
                a
                for a, on in ((Action.LEFT, x < 0), (Action.RIGHT, x > 0), (Action.UP, y > 0), (Action.DOWN, y < 0))
                if on
            }
        return set()

    def holding(self, action: Action) -> bool:
        """Whether a key or pad button bound to ``action`` is down now."""
        if self.held & set(self.bindings.keys.get(action, ())):
            return True
        pad = self.pad
        if pad is None:
            return False
        try:
            n = pad.get_numbuttons()
            return any(b < n and pad.get_button(b) for b in self.bindings.buttons.get(action, ()))
        except pygame.error:
            self.pad = None
            return False

    def input(self) -> Input:
        """This frame's :class:`Input` from everything held."""
        h = self.holding
        dx = h(Action.RIGHT) - h(Action.LEFT)
        dy = h(Action.DOWN) - h(Action.UP)
        pad = self.pad
        if pad is not None:
            try:
                ax, ay = pad.get_axis(0), pad.get_axis(1)
                hx, hy = pad.get_hat(0) if pad.get_numhats() else (0, 0)
                dx += (ax > STICK_DEAD_ZONE) - (ax < -STICK_DEAD_ZONE) + int(hx)
                dy += (ay > STICK_DEAD_ZONE) - (ay < -STICK_DEAD_ZONE) - int(hy)
            except pygame.error:
                self.pad = None
        return Input(_clamp(dx), _clamp(dy), h(Action.FIRE), h(Action.SLOW), h(Action.BOMB))


def _clamp(v: int) -> int:
    return max(-1, min(1, int(v)))
