"""Text layout shared by the game's screens and the editor."""

from __future__ import annotations

import pygame


def wrap_text(text: str, font: pygame.font.Font, width: int) -> list[str]:
    """``text`` broken into lines no wider than ``width`` pixels in ``font``.

    Greedy: words (split on whitespace) fill each line in order; a word wider than a whole
    line (a long path) is broken between characters. Every character of every word appears
    once, in order. Always at least one line (``[""]`` for empty text); a single character
    wider than ``width`` gets a line of its own rather than being dropped.
    """
    lines: list[str] = []
    line = ""
    for word in text.split():
        candidate = f"{line} {word}" if line else word
        if font.size(candidate)[0] <= width:
            line = candidate
            continue
        if line:
            lines.append(line)
        line = ""
        for ch in word:  # the word starts a new line; break it if it is too long for one
            if line and font.size(line + ch)[0] > width:
                lines.append(line)
                line = ""
            line += ch
    lines.append(line)
    return lines
