"""Where the shipped levels and assets live, installed or in a source checkout.

A wheel carries the repository's top-level ``levels/`` and ``assets/`` folders as the
packages ``broadsword.levels`` and ``broadsword.assets`` (see pyproject.toml), found with
:mod:`importlib.resources`. An editable install or a plain checkout has no such folders in
the package, so the ones beside the ``broadsword`` package are used instead.

:func:`read_text` and :func:`read_toml` are how every data file is read: bytes, checked
for size and UTF-8, then parsed by :mod:`tomllib` (or :mod:`json`, for recordings).
Nothing read is ever executed.
"""

from __future__ import annotations

import importlib.resources
import re
import tomllib
from pathlib import Path

from ..fileio import FileTooLarge, NotRegularFile, read_capped
from .errors import DataError

_ROOT = Path(__file__).resolve().parents[2]  # the repository, in a source checkout


def data_dir(kind: str) -> Path:
    """The folder of shipped ``"levels"`` or ``"assets"``.

    Installed (a wheel), it is found through :mod:`importlib.resources` inside the
    ``broadsword`` package; in a source checkout or an editable install, beside the package.
    The installed package must be on a file system (not zipped): levels and sprites are
    opened as files.
    """
    if kind not in ("levels", "assets"):
        raise ValueError(f"kind must be 'levels' or 'assets', got {kind!r}")
    shipped = importlib.resources.files("broadsword").joinpath(kind)
    for path in (shipped, _ROOT / kind):
        if isinstance(path, Path) and path.is_dir():
            return path
    raise FileNotFoundError(f"shipped {kind} not found in {shipped} or {_ROOT / kind}")


def read_bytes(path: str | Path, max_bytes: int, kind: str) -> bytes:
    """The bytes of the data file ``path`` (``kind`` names it in errors: "a level file"),
    read by :func:`broadsword.fileio.read_capped`.

    Refused, with a :class:`DataError` naming the file: anything but a regular file (a FIFO
    or a device never blocks or floods the read); a file over ``max_bytes`` bytes, by its
    size before reading and by reading at most ``max_bytes + 1`` bytes in case the size
    lies; a file that cannot be read (missing, no permission, a symlink loop).
    """
    path = Path(path)
    try:
        return read_capped(path, max_bytes)
    except NotRegularFile as exc:
        raise DataError(path, "", f"{exc.strerror}; {kind} is a file") from None
    except FileTooLarge as exc:
        plus = "" if exc.exact else "+"
        raise DataError(path, "", f"is {exc.size:,}{plus} bytes; {kind} is at most {max_bytes:,}") from None
    except OSError as exc:
        raise DataError(path, "", f"cannot read: {exc.strerror or exc}") from None
    except ValueError as exc:  # a path the system cannot take (an embedded NUL)
        raise DataError(path, "", f"cannot read: {exc}") from None


def read_text(path: str | Path, max_bytes: int, kind: str) -> str:
    """The UTF-8 text of the data file ``path``: :func:`read_bytes`, and a
    :class:`DataError` naming the file for bytes that are not UTF-8."""
    data = read_bytes(path, max_bytes, kind)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise DataError(
            path, "", f"not UTF-8 text (byte 0x{data[exc.start]:02x} at offset {exc.start}); {kind} is a text file"
        ) from None


#: Keys of this many dotted parts or more (``a.b.c...``) are refused before parsing:
#: :mod:`tomllib` takes time quadratic in a key's parts (100,000 parts: seconds).
KEY_PARTS_MAX = 32
_PART = r"""(?:[A-Za-z0-9_-]++|"[^"\\\n]*+"|'[^'\n]*+')"""
_DOTTED_CHAIN = re.compile(rf"(?<![A-Za-z0-9_.-])(?:{_PART}[ \t]*+\.[ \t]*+){{{KEY_PARTS_MAX - 1}}}{_PART}")


def read_toml(path: str | Path, max_bytes: int, kind: str) -> dict:
    """:func:`read_text`, parsed by :mod:`tomllib` into a table. Text that is not TOML,
    is nested too deeply for the parser (arrays or tables, or a key of ``KEY_PARTS_MAX``
    dotted parts: checked first, as a pattern, so even text in a string that looks like
    one is refused), or holds an integer of over 4,300 digits is refused with a
    :class:`DataError` naming the file (and the line, where known)."""
    text = read_text(path, max_bytes, kind)
    deep = _DOTTED_CHAIN.search(text)
    if deep:
        line = text.count("\n", 0, deep.start()) + 1
        raise DataError(
            path,
            "",
            f"not valid TOML: nested too deeply (a key of {KEY_PARTS_MAX} or more dotted parts, at line {line})",
        )
    try:
        return tomllib.loads(text)
    except RecursionError:
        raise DataError(path, "", "not valid TOML: nested too deeply") from None
    except ValueError as exc:  # TOMLDecodeError, or an integer too long to convert
        raise DataError(path, "", f"not valid TOML: {exc}") from None


def list_levels() -> list[str]:
    """Names of the shipped levels, in play order (file names sort by their number prefix)."""
    return [p.stem for p in sorted(data_dir("levels").glob("*.toml"))]


def resolve_level(name_or_path: str) -> Path:
    """A shipped level's name (as :func:`list_levels` gives) or a path to a level file.

    A name is only ever looked up among the shipped levels: ``../x`` is not a name. A path
    is anything ending ``.toml`` or naming something that exists; it must be a file.
    """
    path = Path(name_or_path)
    try:
        is_path = path.suffix == ".toml" or path.exists()
        is_file = is_path and path.is_file()
    except (OSError, ValueError):  # a name too long for the system, an embedded NUL
        is_path, is_file = True, False
    if is_path:
        if not is_file:
            raise DataError(path, "", "no such level file")
        return path
    shipped = list_levels()
    if name_or_path not in shipped:
        raise DataError(name_or_path, "", f"no such level; shipped levels are {', '.join(shipped)}")
    return data_dir("levels") / f"{name_or_path}.toml"
