"""``python -m broadsword``: the same as the ``broadsword`` command."""

from .cli import main

raise SystemExit(main())
