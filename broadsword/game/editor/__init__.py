"""``broadsword edit PATH``: the armature editor (a pygame view and controller over
:mod:`broadsword.authoring.editing`, which holds the editing rules without pygame).

::

    broadsword edit assets/sprites/scout.armature.toml     edit an armature file
    broadsword edit my_ship.png [--frames N]               edit (or start) the file beside a sprite

``PATH`` is an armature file (its sprite is the PNG it names, beside it), or a sprite PNG:
then the editor opens ``<stem>.armature.toml`` beside it, or, if there is none, starts a new
one whose ``hit`` shape (one per frame of a strip of ``--frames N``) is traced from the
sprite's alpha (:func:`broadsword.authoring.generate_armature`, at most 8 vertices,
no inset; an 8 px box around the centre for a sprite with no opaque pixel). Nothing is written
until Ctrl+S.

The window shows the sprite zoomed (integer zoom) with every shape of the current frame drawn
over it, the active one bright with vertex handles, and a panel with the active shape's
vertex count, area, the share of it over opaque pixels, the share of the sprite's opaque
pixels it covers, and its IoU (:func:`broadsword.authoring.fit_of`).

Mouse: left-drag a vertex to move it; left-click an edge to insert a vertex there (and drag
it); left-drag inside the shape, or Shift+left-drag anywhere, to move the whole shape;
left-drag on empty space to pan; right-click a vertex to delete it; the wheel zooms about the
pointer; hold the middle button for the probe. Keys: Delete/Backspace delete the vertex under
the pointer (else the selected one); arrows nudge the selected vertex by exactly 1 px (Shift:
the whole shape); Ctrl+Z undo, Ctrl+Y or Ctrl+Shift+Z redo; Tab / Shift+Tab next / previous
shape; N / P (PageDown / PageUp) next / previous frame; G snap on/off; B probe on/off; + / -
zoom, 0 fit; Ctrl+S save; Esc quit (with unsaved changes the first Esc only warns; Esc during
a drag cancels the drag). Closing the window behaves like Esc.

Snap to pixel (on by default): a dragged or inserted vertex lands on the nearest pixel
corner of the image (whole image pixels, so whole armature coordinates when the frame's width
and height are even, and .5 ones along an odd dimension); a shape moves by whole pixels, so
its vertices keep their offsets from the grid. With snap off, positions are kept to 1/100 px
so the file stays readable.

An edit that would make a shape invalid (self-crossing or touching edges, zero area, fewer
than 3 vertices: :class:`broadsword.collision.Armature` says why) is refused: the shape keeps
its last valid form (a dragged vertex stays at its last valid position, the rejected outline is
drawn red) and the message line shows the reason.

The probe is a real bullet armature (the shipped ``pellet``, or a 6 px box if that file
cannot be read) placed at the pointer in sprite coordinates and tested against the active
shape with a two-layer :class:`broadsword.collision.Pipeline` (the game's default tiers)
whenever it moves or the shape changes; it is drawn red on contact, green otherwise.

Saving writes every frame's shapes, the frame time and the file's header comment with
:func:`broadsword.data.armatures.save_armature_file` (validated first, written atomically,
four vertices to a line).

Layout: ``editor`` (the :class:`Editor` object: ``handle_event`` / ``update`` / ``draw``, or
``run`` in its own window), ``controller`` (events to edits), ``viewport`` (zoom, pan and the
screen mapping), ``drawing`` and ``panel`` (what is drawn), ``theme`` (sizes and colours),
``command`` (``main``). A sprite frame larger than 4096 px a side, or a broken, empty or
huge PNG, is refused with one line naming the file.
"""

from .command import main
from .documents import open_document
from .editor import Editor
from .theme import HANDLE_FILL, PROBE_CLEAR, PROBE_HIT, WINDOW_SIZE

__all__ = ["HANDLE_FILL", "PROBE_CLEAR", "PROBE_HIT", "WINDOW_SIZE", "Editor", "main", "open_document"]
