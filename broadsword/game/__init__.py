"""broadsword.game: everything pygame -- window, loop, scenes, input, rendering, audio, overlay."""

import os

os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")  # no banner in the game's or the bench's output
