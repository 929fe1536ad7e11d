"""Keeping Python's cyclic garbage collector out of the frames of a stage.

The collector runs when allocations outnumber frees by a threshold, and a full collection
walks every container object alive: the level, the sprite and rotation caches, the pattern
trees. A bullet-hell frame allocates thousands of short-lived objects (the blit list is one
tuple per bullet), so full collections came every few seconds of play and took 50-60 ms at
5,000 bullets: a visible hitch (docs/PERFORMANCE.md). :func:`settle` is called when a stage
starts: it collects once, then freezes everything alive into the permanent generation,
which collections skip; the frame's own garbage is still collected, young and cheap.
It then gives the C heap's free pages back to the system
(:func:`broadsword.collision.release_heap`): the last stage's are free now, and under
``retain_heap()`` nothing else ever returns them (docs/RELIABILITY.md).
"""

from __future__ import annotations

import gc

from ..collision import release_heap

__all__ = ["settle"]


def settle() -> None:
    """Collect once, give the freed heap back to the system and freeze every object alive
    now (call when a stage has loaded). The previous stage's frozen objects are unfrozen
    first, so that those that have become garbage since are still reclaimed."""
    gc.unfreeze()
    gc.collect()
    release_heap()
    gc.freeze()
