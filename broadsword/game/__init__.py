"""broadsword.game: everything pygame -- window, loop, scenes, input, rendering, audio, overlay."""
