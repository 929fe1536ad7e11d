"""``broadsword balance``'s report: runs summed up per stage, difficulty and player, as rows
and as a Markdown table.

A run is the dict :func:`broadsword.balance.play` returns. Per (stage, difficulty, player):

* ``clears``: runs that reached the stage's end without a continue; ``clears_continuing``:
  with any continues (the naive players use theirs; the autopilot never continues, so its
  two counts are equal);
* ``first_miss_s``, ``game_over_s``: mean seconds to the first life lost and to the first
  game over (all lives lost, before any continue); a run without one counts its whole length,
  so both are at most the stage's length;
* ``phases_beaten``: mean boss phases whose hit points ran out (not timed out), of ``phases``;
* ``deaths``, ``bombs``: mean lives lost and bombs used; ``peak_bullets``: the most enemy
  bullets at once over the seeds; ``length_s``: mean seconds of play; ``cleared_length_s``:
  the longest cleared run's.
"""

from __future__ import annotations

from .data.difficulty import Difficulty

#: The players, in the table's order: the autopilot, then the naive scripts.
PLAYERS = ("autopilot", "stand", "weave", "stream")


def _mean(values: list[float], ndigits: int) -> float:
    return round(sum(values) / len(values), ndigits)


def summarise(runs: list[dict]) -> list[dict]:
    """One row per (stage, difficulty, player), in stage, difficulty and player order."""

    def order(key: tuple[str, str, str]) -> tuple:
        level, diff, player = key
        return level, list(Difficulty).index(Difficulty(diff)), PLAYERS.index(player) if player in PLAYERS else 99

    rows = []
    for level, diff, player in sorted({(r["level"], r["difficulty"], r["player"]) for r in runs}, key=order):
        mine = [r for r in runs if (r["level"], r["difficulty"], r["player"]) == (level, diff, player)]
        secs = [r["frames"] / 60.0 for r in mine]
        rows.append(
            {
                "stage": level,
                "difficulty": diff,
                "player": player,
                "seeds": len(mine),
                "clears": sum(r["cleared"] and not r["continues"] for r in mine),
                "clears_continuing": sum(r["cleared"] for r in mine),
                "first_miss_s": _mean(
                    [r["first_miss"] / 60.0 if r["first_miss"] is not None else s for r, s in zip(mine, secs)], 1
                ),
                "game_over_s": _mean(
                    [r["game_over"] / 60.0 if r["game_over"] is not None else s for r, s in zip(mine, secs)], 1
                ),
                "phases_beaten": _mean([r["phases_beaten"] for r in mine], 1),
                "phases": max(r["phases"] for r in mine),
                "deaths": _mean([r["deaths"] for r in mine], 2),
                "bombs": _mean([r["bombs"] for r in mine], 2),
                "peak_bullets": max(r["peak_bullets"] for r in mine),
                "length_s": _mean(secs, 1),
                "cleared_length_s": round(max((r["frames"] for r in mine if r["cleared"]), default=0) / 60.0, 1),
            }
        )
    return rows


def table(rows: list[dict]) -> str:
    """The rows as a Markdown table."""
    head = (
        "| stage | difficulty | player | clears | clears with continues | first miss s | game over s "
        "| phases beaten | deaths | bombs | peak bullets | mean length s |"
    )
    lines = [head, "|" + "---|" * 12]
    for r in rows:
        lines.append(
            f"| {r['stage']} | {r['difficulty']} | {r['player']} | {r['clears']}/{r['seeds']} "
            f"| {r['clears_continuing']}/{r['seeds']} | {r['first_miss_s']} | {r['game_over_s']} "
            f"| {r['phases_beaten']}/{r['phases']} | {r['deaths']} | {r['bombs']} | {r['peak_bullets']:,} "
            f"| {r['length_s']} |"
        )
    return "\n".join(lines)
