"""The hit log of a run: every hit on the player, as JSON (docs/FORMATS.md, "Hit log").

:class:`HitCollector` is an observer: after each step it takes the hit the world resolved
(``Events.hit``: a life lost or saved by a death-bomb; :mod:`broadsword.sim.hitlog`) with
the stage it happened in. :func:`hit_log_document` turns what it took into the JSON
document ``broadsword --headless --hit-log FILE`` writes (atomically, by the caller).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..collision import ContactKind, Explanation, Side
from ..sim import Events, Input
from ..sim.hitlog import HitRecord, Hitter, Outcome
from .observers import RunView

__all__ = ["FORMAT", "VERSION", "HitCollector", "LoggedHit", "hit_json", "hit_log_document"]

#: The document's ``format`` and ``version``.
FORMAT, VERSION = "broadsword-hit-log", 1


@dataclass(frozen=True)
class LoggedHit:
    """A resolved hit and where in the run it happened: ``stage`` (0-based, in run order),
    its ``level``'s name, and ``run_frame`` (the run's frames played when it was resolved)."""

    record: HitRecord
    stage: int
    level: str
    run_frame: int


class HitCollector:
    """Every hit a run resolved (``hits``, in order). An observer (:mod:`.observers`)."""

    def __init__(self) -> None:
        self.hits: list[LoggedHit] = []
        self.stage = -1

    def began(self, runner: RunView) -> None:
        self.stage += 1

    def stepped(self, runner: RunView, inp: Input, ev: Events) -> None:
        if ev.hit is not None:
            self.hits.append(LoggedHit(ev.hit, max(self.stage, 0), runner.world.level.name, runner.frame))


def _contact(e: Explanation) -> dict:
    if e.kind is ContactKind.CROSSING:
        edges = [
            {"player_edge": c.first, "hitter_edge": c.second, "signs": list(c.signs), "proper": c.proper}
            for c in e.crossings
        ]
        return {"kind": e.kind.value, "edges": edges}
    if e.kind is ContactKind.CONTAINMENT:
        c = e.containment
        assert c is not None  # a containment explanation names it
        outer = "hitter" if c.outer is Side.SECOND else "player"
        return {"kind": e.kind.value, "outer": outer, "vertex": c.vertex, "ray_edges": list(c.ray_edges)}
    return {"kind": e.kind.value}


def _hitter(h: Hitter) -> dict:
    out = {
        "what": h.source.value,
        "kind": h.kind,
        "swept": h.swept,
        "polygon": h.polygon.tolist(),
        "contact": _contact(h.explanation),
        "tiers": [{"tier": t.tier, "verdict": t.verdict.value, "recorded": t.recorded} for t in h.tiers],
    }
    if h.laser is not None:
        tag = h.laser.laser
        out["laser"] = {
            "kind": tag.kind,
            "phase": tag.phase + 1,
            "entry": tag.entry + 1,
            "piece": h.laser.piece,
            "join": h.laser.join,
            "path": h.laser.path.tolist(),
        }
    return out


def hit_json(hit: LoggedHit) -> dict:
    """One hit as a JSON object (docs/FORMATS.md, "Hit log")."""
    r = hit.record
    assert r.outcome is not None  # only resolved hits are logged
    return {
        "frame": r.frame,
        "run_frame": hit.run_frame,
        "stage": hit.stage,
        "level": hit.level,
        "outcome": r.outcome.value,
        "player": {"kind": r.player_kind, "polygon": r.player.tolist()},
        "hit_by": [_hitter(h) for h in r.hitters],
    }


def hit_log_document(hits: list[LoggedHit]) -> dict:
    """The hit log: ``misses`` (one object per life lost) and ``saved`` (one per hit a
    death-bomb saved), each in run order."""
    return {
        "format": FORMAT,
        "version": VERSION,
        "misses": [hit_json(h) for h in hits if h.record.outcome is Outcome.MISS],
        "saved": [hit_json(h) for h in hits if h.record.outcome is Outcome.SAVED],
    }
