"""The game's side of the replay library: keeping each run the player ends, saving it under
a name (no pygame here; the screens are :mod:`.scenes.replay_list` and
:mod:`.scenes.save_replay`; :meth:`.scenes.context.SceneContext.keep_run` keeps a run).

A run is kept (written to ``replays/recent/``) once, when it ends: a game over with no
continue taken, its last stage cleared, or a quit to the title (or out of the game) in
the middle. Runs nobody played (the autopilot's, a replay being watched) are not kept. A
write that fails says one line (the menus' ``message``, and stderr) and the game goes on.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

from ..data.recordings import Recording
from ..runner import Runner
from .replaylib import ReplayLibrary


@dataclass(frozen=True)
class KeptRun:
    """A run kept when it ended: its runner (so it is kept once), its recording with its
    ``info`` filled, where it was written in ``recent/`` (None: the write failed, or the run
    was saved under a name since), why the write failed if it did, and the name it was
    saved under, if it was."""

    runner: Runner
    recording: Recording
    path: Path | None
    problem: str | None = None
    saved_as: str | None = None


class Replays:
    """The replay ``library`` and the run ``last`` kept (what "Save replay" after a run saves)."""

    def __init__(self, library: ReplayLibrary):
        self.library = library
        self.last: KeptRun | None = None

    def keep(self, runner: Runner, date: str) -> str | None:
        """Keep ``runner``'s run, which ended at ``date`` (ISO 8601), in ``recent/`` (its
        ``info`` as the runner's recorder fills it: kind, final score...), unless it was
        kept already. Returns the warning line for a failed write."""
        if self.last is not None and self.last.runner is runner:
            return None
        rec = runner.recording()
        rec = dataclasses.replace(rec, info=dataclasses.replace(rec.info, date=date))
        path, warning = None, None
        try:
            path = self.library.keep(rec)
        except OSError as exc:
            warning = f"could not keep the replay: {exc.strerror or exc}"
        self.last = KeptRun(runner, rec, path, warning)
        return warning

    def save_last(self, name: str, overwrite: bool = False) -> Path:
        """Save the run last kept as ``name`` and take it out of ``recent/``. ReplayExists
        (ask, then ``overwrite``) or OSError as :meth:`ReplayLibrary.save`."""
        last = self.last
        assert last is not None, "save_last needs a run kept"
        path = self.library.save(last.recording, name, overwrite)
        if last.path is not None:
            self.library.discard(last.path)
        self.last = dataclasses.replace(last, path=None, saved_as=name)
        return path


def now_iso() -> str:
    """The time now, ISO 8601 in UTC to the second (a replay's ``info.date``)."""
    return datetime.now(UTC).isoformat(timespec="seconds")
