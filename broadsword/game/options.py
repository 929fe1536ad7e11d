"""The player's options: difficulty, volumes, fullscreen, always showing the hit shape, the
game speed, the input display, showing what hit on a miss, the bullet palette (and whether a
stage has been played here yet, for the first run's hints).

Kept as ``options.json`` in the user's data directory (beside the high scores and the
controls), written atomically (:mod:`.settingsfile`). Read value by value: a bad value (a
volume of 11 or NaN, a difficulty "Insane", an unknown option) is named in a one-line
``warning`` (shown on the title) and only that value falls back to its default; the file
is first copied aside as ``options.json.bad``. A file that is no options file at all (not
JSON, too big, a FIFO or a device in its place) gives the defaults and a warning, never a
crash or a hang. A newer version's options (a higher ``version``, keys this one does not
know) are kept silently and survive a save.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, replace
from pathlib import Path

from ..data.difficulty import Difficulty
from ..fileio import write_atomic
from .palettes import BulletPalette
from .scores import data_home
from .settingsfile import load_settings, merged_for_save, one_line

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
    show_hits: bool = True  # on a miss, freeze a moment and show what hit (game/hitview.py)
    palette: BulletPalette = BulletPalette.STANDARD  # the bullets' colours (:mod:`.palettes`)

    def __post_init__(self):
        object.__setattr__(self, "difficulty", Difficulty(self.difficulty))
        try:
            object.__setattr__(self, "palette", BulletPalette(self.palette))
        except ValueError:
            names = ", ".join(p.value for p in BulletPalette)
            raise ValueError(f"palette: must be one of {names}, got {self.palette!r}") from None
        for name in ("music", "sound"):
            v = getattr(self, name)
            if type(v) is not int or not 0 <= v <= VOLUME_STEPS:
                raise ValueError(f"{name}: must be a whole number in [0, {VOLUME_STEPS}], got {v!r}")
        if type(self.speed) is not int or not SPEED_MIN <= self.speed <= 100 or self.speed % SPEED_STEP:
            raise ValueError(f"speed: must be {SPEED_MIN} to 100 in steps of {SPEED_STEP}, got {self.speed!r}")
        for name in ("fullscreen", "always_hitbox", "played", "input_display", "show_hits"):
            if type(getattr(self, name)) is not bool:
                raise ValueError(f"{name}: must be true or false, got {getattr(self, name)!r}")

    def volume(self, name: str) -> float:
        """``music`` or ``sound`` as a mixer volume in [0, 1]."""
        return getattr(self, name) / VOLUME_STEPS

    def to_json(self) -> dict:
        doc = asdict(self)
        doc["difficulty"] = self.difficulty.value
        doc["palette"] = self.palette.value
        return {"version": FORMAT_VERSION, **doc}

    @classmethod
    def from_json(cls, doc) -> tuple[Options, list[str]]:
        """The options ``doc`` holds, value by value, and one ``"field: what"`` per value
        that was refused (it keeps its default). Keys unknown to this version are refused
        by name unless ``version`` says a newer version wrote the file."""
        if not isinstance(doc, dict):
            return cls(), ["the file must be a JSON object of version and options"]
        problems = []
        version = doc.get("version")
        newer = type(version) is int and version > FORMAT_VERSION
        if not newer and version != FORMAT_VERSION:
            problems.append(f"version: must be {FORMAT_VERSION}, got {version!r}")
        known = set(cls.__dataclass_fields__)
        if not newer:
            for key in sorted(set(doc) - known - {"version"}):
                problems.append(f"{key}: unknown option (options are {', '.join(sorted(known))})")
        options = cls()
        for key in sorted(known & set(doc)):
            value = doc[key]
            if key == "difficulty":
                try:
                    value = Difficulty(value)
                except (ValueError, TypeError):
                    names = ", ".join(d.value for d in Difficulty)
                    problems.append(f"difficulty: must be one of {names}, got {value!r}")
                    continue
            try:
                options = replace(options, **{key: value})
            except ValueError as exc:
                problems.append(str(exc))
        return options, [one_line(p) for p in problems]


def options_path() -> Path:
    return data_home() / "options.json"


def load_options(path: Path | None = None) -> tuple[Options, str | None]:
    """The saved options, value by value, and a one-line warning naming each value not
    used (None when all were); a missing file is the defaults, silently. A file with any
    bad content is copied aside (``options.json.bad``) before anything can be written
    over it, and the warning says where."""
    path = Path(path) if path is not None else options_path()
    return load_settings(path, FILE_MAX_BYTES, "options", "defaults", Options(), Options.from_json)


def save_options(options: Options, path: Path | None = None) -> None:
    """Write atomically (temp file + os.replace), keeping what the file holds that this
    version does not know (:func:`~.settingsfile.merged_for_save`); OSError propagates,
    and a FIFO or device in the file's place is never replaced."""
    path = Path(path) if path is not None else options_path()
    doc = merged_for_save(path, options.to_json(), FILE_MAX_BYTES, FORMAT_VERSION)
    write_atomic(path, (json.dumps(doc, indent=1) + "\n").encode())
