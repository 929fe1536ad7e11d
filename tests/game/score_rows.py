"""Rows of the high-score table for the score tests."""

from broadsword.game.scores import Entry

DAY = "2024-05-17"


def entry(name="ACE", score=100, level="1-picket", date=DAY) -> Entry:
    return Entry(name, score, level, date)
