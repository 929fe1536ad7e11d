"""A stage for practice tests: all boss, quick to play to every phase."""

from __future__ import annotations

from pathlib import Path

#: A stage that is all boss: it arrives after 1 s, three short phases (the autopilot reaches
#: every one within some 200 frames).
LEVEL = """
[level]
title = "Practice test"

[player]
lives = 3

[boss]
name = "Test Warden"
at = 1.0
score = 1000
y = 130
sway = 40

[[boss.part]]
sprite = "frigate"
offset = [0, 0]
spin = 0
fire = "aimed"
bullet = "pellet"
bullet_speed = 150
fire_every = 0.5

[[boss.phase]]
name = "First"
hp = 30
time = 5

[[boss.phase]]
name = "Second"
hp = 30
time = 5

[[boss.phase]]
hp = 30
time = 5
"""


def write_level(folder: Path) -> Path:
    """Write the stage as ``folder / "warden.toml"`` (its level name: ``warden``); returns the path."""
    path = folder / "warden.toml"
    path.write_text(LEVEL, encoding="utf-8")
    return path
