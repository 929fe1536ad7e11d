"""The tracks the game can ask for: ``Track.TITLE``, ``Track.stage(n)``, ``Track.BOSS`` ..."""

from __future__ import annotations

from enum import Enum

__all__ = ["Track", "STAGES", "PLAY_ORDER"]

STAGES = 5  # stage loops; Track.stage(n) wraps past this


class Track(Enum):
    """One piece of music. Loops (title, stages, bosses) repeat until another track starts;
    jingles (``CLEAR``, ``GAME_OVER``) play once."""

    TITLE = "title"
    STAGE_1 = "stage_1"
    STAGE_2 = "stage_2"
    STAGE_3 = "stage_3"
    STAGE_4 = "stage_4"
    STAGE_5 = "stage_5"
    BOSS = "boss"
    FINAL_BOSS = "final_boss"
    CLEAR = "clear"
    GAME_OVER = "game_over"

    @classmethod
    def stage(cls, n: int) -> Track:
        """The loop for stage ``n`` (1-based). Past stage 5 it wraps: 6 -> 1, 7 -> 2 ...

        ValueError for ``n < 1`` or a non-integer, naming the argument.
        """
        if isinstance(n, bool) or not isinstance(n, int) or n < 1:
            raise ValueError(f"Track.stage(n): n must be a whole number >= 1, got {n!r}")
        return cls[f"STAGE_{(n - 1) % STAGES + 1}"]

    @property
    def loops(self) -> bool:
        """True for a loop, False for a jingle that plays once."""
        return self not in (Track.CLEAR, Track.GAME_OVER)


#: The order a game meets the tracks in: the order to render them ahead of need.
PLAY_ORDER: tuple[Track, ...] = (
    Track.TITLE,
    Track.STAGE_1,
    Track.BOSS,
    Track.CLEAR,
    Track.GAME_OVER,
    Track.STAGE_2,
    Track.STAGE_3,
    Track.STAGE_4,
    Track.STAGE_5,
    Track.FINAL_BOSS,
)
