"""broadsword.authoring: the tools that make armatures, numpy and the standard library only.

Never imports pygame (a test holds it to that); it stands above ``collision`` and ``data``
and below ``game``. Modules, one idea each:

* ``masks``     opaque pixels, the largest solid region, disk erosion and dilation
* ``outline``   tracing a region's pixel outline, simplifying it, generating an armature
* ``fit``       how well a shape sits on its sprite (coverage, on-opaque share, IoU)
"""

from .fit import ShapeFit, fit_of, shape_fit
from .masks import ALPHA_THRESHOLD, dilate, erode, largest_region, opaque_mask
from .outline import generate_armature, simplify_polygon, trace_outline

__all__ = [
    "ALPHA_THRESHOLD",
    "ShapeFit",
    "dilate",
    "erode",
    "fit_of",
    "generate_armature",
    "largest_region",
    "opaque_mask",
    "shape_fit",
    "simplify_polygon",
    "trace_outline",
]
