"""Where Broadsword keeps the user's data (the high scores): one function, every platform.

=========================  ===============================================================
``$BROADSWORD_DATA_DIR``    used as given (``~`` expanded), on every platform
``$XDG_DATA_HOME``          ``$XDG_DATA_HOME/broadsword``, when set to an absolute path
                            (the XDG Base Directory rule; honoured on every platform, since
                            whoever sets it asks for it)
Windows                     ``%APPDATA%\\broadsword``, else ``~\\AppData\\Roaming\\broadsword``
macOS                       ``~/Library/Application Support/broadsword``
Linux and other systems     ``~/.local/share/broadsword`` (the XDG default)
=========================  ===============================================================

A variable that is set but empty counts as unset.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from pathlib import Path, PurePath

__all__ = ["APP", "user_data_dir"]

#: The folder name under each platform's data directory.
APP = "broadsword"


def user_data_dir(
    platform: str | None = None, environ: Mapping[str, str] | None = None, home: Path | None = None
) -> Path:
    """The directory for Broadsword's saved data (see the module docstring for the rules).

    ``platform`` (a :data:`sys.platform` value), ``environ`` and ``home`` default to this
    process's; tests pass them to check every platform on any machine.
    """
    platform = sys.platform if platform is None else platform
    environ = os.environ if environ is None else environ
    override = environ.get("BROADSWORD_DATA_DIR")
    if override:
        return Path(override).expanduser()
    xdg = environ.get("XDG_DATA_HOME")
    if xdg and PurePath(xdg).is_absolute():
        return Path(xdg) / APP
    home = Path.home() if home is None else home
    if platform == "win32":
        appdata = environ.get("APPDATA")
        return (Path(appdata) if appdata else home / "AppData" / "Roaming") / APP
    if platform == "darwin":
        return home / "Library" / "Application Support" / APP
    return home / ".local" / "share" / APP
