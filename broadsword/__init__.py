"""Broadsword: a polygon-armature shoot-'em-up and a tiered, exact 2D collision toolkit.

After Phelps & Cloutier, "Methodologies for Quick Approximation of 2D Collision Detection
Using Polygon Armatures" (RIT, 2003). ``broadsword.collision`` stands alone (numpy only).
"""

__version__ = "0.2.0"  # the one version source: pyproject.toml reads it (tool.setuptools.dynamic)
