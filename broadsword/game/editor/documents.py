"""Opening an armature document with pygame reading the sprite: the one piece the editor
window (:mod:`.editor`) and its command (:mod:`.command`) share, kept apart so the two do
not import each other."""

from __future__ import annotations

from pathlib import Path

from ...authoring import document
from ..images import read_alpha


def open_document(path: str | Path, frames: int = 1) -> document.ArmatureDocument:
    """:func:`broadsword.authoring.document.open_document`, reading the sprite with pygame."""
    return document.open_document(path, read_alpha, frames)
