"""The player's options: difficulty, volumes, fullscreen, always showing the hit shape (and
whether a stage has been played here yet, for the first run's hints).

Kept as ``options.json`` in the user's data directory (beside the high scores and the
controls), written atomically. A file that cannot be read or makes no sense falls back to
the defaults with a one-line ``warning`` (shown on the title), never a crash; a value out
of range in an otherwise good file is named in the warning too.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, replace
from pathlib import Path

from ..data.difficulty import Difficulty
from ..fileio import write_atomic
from .scores import data_home

FORMAT_VERSION = 1
FILE_MAX_BYTES = 64 << 10
#: Volumes run from 0 to VOLUME_STEPS (shown as 0-100 %); a step on the options screen is one.
VOLUME_STEPS = 10
#: The game speed, % of real time: SPEED_MIN to 100 in steps of SPEED_STEP. It scales only the
#: wall-clock time fed to the fixed-step loop, so the world takes the same steps, slower.
SPEED_MIN, SPEED_STEP = 50, 10


@dataclass(frozen=True)
class Options:
    """``music`` and ``sound`` are volumes in 0..VOLUME_STEPS."""

    difficulty: Difficulty = Difficulty.NORMAL
    music: int = 7
    sound: int = 8
    fullscreen: bool = False
    always_hitbox: bool = False
    played: bool = False  # a stage has been played here: the first run's hints are not shown again
    speed: int = 100  # the game speed, % (SPEED_MIN..100)
    input_display: bool = False  # show the input held (arrows, fire, slow, bomb) on the side panel

    def __post_init__(self):
        object.__setattr__(self, "difficulty", Difficulty(self.difficulty))
        for name in ("music", "sound"):
            v = getattr(self, name)
            if type(v) is not int or not 0 <= v <= VOLUME_STEPS:
                raise ValueError(f"{name}: must be a whole number in [0, {VOLUME_STEPS}], got {v!r}")
        if type(self.speed) is not int or not SPEED_MIN <= self.speed <= 100 or self.speed % SPEED_STEP:
            raise ValueError(f"speed: must be {SPEED_MIN} to 100 in steps of {SPEED_STEP}, got {self.speed!r}")
        for name in ("fullscreen", "always_hitbox", "played", "input_display"):
            if type(getattr(self, name)) is not bool:
                raise ValueError(f"{name}: must be true or false, got {getattr(self, name)!r}")

    def volume(self, name: str) -> float:
        """``music`` or ``sound`` as a mixer volume in [0, 1]."""
        return getattr(self, name) / VOLUME_STEPS

    def to_json(self) -> dict:
        doc = asdict(self)
        doc["difficulty"] = self.difficulty.value
        return {"version": FORMAT_VERSION, **doc}

    @classmethod
    def from_json(cls, doc) -> Options:
        if not isinstance(doc, dict) or doc.get("version") != FORMAT_VERSION:
            raise ValueError(f"version: must be {FORMAT_VERSION}")
        known = set(cls.__dataclass_fields__)
        extra = sorted(set(doc) - known - {"version"})
        if extra:
            raise ValueError(f"{extra[0]}: unknown option (options are {', '.join(sorted(known))})")
        values = {k: v for k, v in doc.items() if k in known}
        if "difficulty" in values:
            try:
                values["difficulty"] = Difficulty(values["difficulty"])
            except ValueError:
                raise ValueError(
                    f"difficulty: must be one of {', '.join(d.value for d in Difficulty)}, got {values['difficulty']!r}"
                ) from None
        return replace(cls(), **values)


def options_path() -> Path:
    return data_home() / "options.json"


def load_options(path: Path | None = None) -> tuple[Options, str | None]:
    """The saved options, or the defaults and a one-line warning saying why not (a missing
    file is the defaults, silently)."""
    path = Path(path) if path is not None else options_path()
    try:
        if path.stat().st_size > FILE_MAX_BYTES:
            raise ValueError(f"larger than {FILE_MAX_BYTES:,} bytes")
        return Options.from_json(json.loads(path.read_text(encoding="utf-8"))), None
    except FileNotFoundError:
        return Options(), None
    except (OSError, ValueError, UnicodeDecodeError, RecursionError, TypeError) as exc:
        why = " ".join(str(exc).split())[:160] or type(exc).__name__
        return Options(), f"options file {path} not used ({why}): defaults"


def save_options(options: Options, path: Path | None = None) -> None:
    """Write atomically (temp file + os.replace); OSError propagates."""
    path = Path(path) if path is not None else options_path()
    write_atomic(path, (json.dumps(options.to_json(), indent=1) + "\n").encode())
