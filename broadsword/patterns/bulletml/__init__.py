"""BulletML: load, validate and run bullet patterns (numpy + standard library only).

    >>> from broadsword.patterns import bulletml
    >>> p = bulletml.loads('<bulletml><action label="top"><fire><direction type="absolute">180</direction>'
    ...                    '<speed>2</speed><bullet/></fire></action></bulletml>')
    >>> [f.round(9).tolist() for f in bulletml.trace(p, 3, origin=(0, 0), target=(0, 100))]
    [[[0.0, 0.0]], [[0.0, 2.0]], [[0.0, 4.0]]]

See docs/PATTERNS.md for the conventions and every choice where the specification is silent.
"""

from . import limits
from .engine import Engine, trace
from .load import load, loads
from .model import Orientation, Pattern

__all__ = ["Engine", "Orientation", "Pattern", "limits", "load", "loads", "trace"]
