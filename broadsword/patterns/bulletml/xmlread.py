"""Reading a BulletML file's XML safely into plain element nodes.

Hostile files are data: the size is checked before parsing; expat runs with parameter
entities off, and any entity declaration, internal DTD subset, external entity reference or
undeclared entity stops the parse. A ``<!DOCTYPE bulletml SYSTEM "bulletml.dtd">`` line with
no internal subset (as the public patterns carry) is accepted and never fetched. Nesting
depth and element count are capped while parsing, before any tree grows past them.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from xml.parsers import expat

from ...fileio import FileTooLarge, read_capped
from .limits import MAX_DEPTH, MAX_ELEMENTS, MAX_FILE_BYTES


@dataclass
class Element:
    """One XML element: ``tag`` without namespace prefix, attributes, the text it holds
    directly, its child elements, its source line and its path (``bulletml/action[2]``,
    indices 1-based among siblings of the same tag, shown only when there are several)."""

    tag: str
    attrs: dict[str, str]
    line: int
    path: str = ""
    text: str = ""
    children: list[Element] = field(default_factory=list)
    parts: list[str] = field(default_factory=list, repr=False)  # text while parsing
    seen: dict[str, int] = field(default_factory=dict, repr=False)  # children per tag while parsing

    def where(self) -> str:
        """``path`` plus the source line, for error messages."""
        return f"{self.path} (line {self.line})"


class _Refused(Exception):
    """Raised from an expat handler to stop the parse at once."""


def _local(name: str) -> str:
    return name.rsplit(":", 1)[-1].rsplit("}", 1)[-1]


def read_elements(path: str | os.PathLike, data: bytes | None = None) -> Element:
    """The root element of the XML file at ``path`` (or of ``data``, its bytes, if given).

    Raises ``ValueError("FILE: where: what")`` for a missing, unreadable, too large,
    malformed, too deep or too big file, or one that declares entities or a DTD subset.
    """
    name = os.fspath(path)
    if data is None:
        try:
            data = read_capped(name, MAX_FILE_BYTES)
        except FileTooLarge as exc:
            raise ValueError(
                f"{name}: file is {exc.size}{'' if exc.exact else '+'} bytes (at most {MAX_FILE_BYTES})"
            ) from None
        except OSError as exc:
            raise ValueError(f"{name}: cannot read the file ({exc.strerror or exc})") from None
    if len(data) > MAX_FILE_BYTES:
        raise ValueError(f"{name}: file is over {MAX_FILE_BYTES} bytes")

    parser = expat.ParserCreate()
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    stack: list[Element] = []
    root: list[Element] = []
    count = 0
    problem: list[str] = []

    def refuse(where: str, what: str):
        problem.append(f"{where}: {what}")
        raise _Refused

    def here() -> str:
        where = stack[-1].path if stack else "(document)"
        if len(where) > 80:
            where = "..." + where[-77:]
        return f"{where} (line {parser.CurrentLineNumber})"

    def start(tag, attrs):
        nonlocal count
        count += 1
        if count > MAX_ELEMENTS:
            refuse(here(), f"more than {MAX_ELEMENTS} elements")
        if len(stack) >= MAX_DEPTH:
            refuse(here(), f"elements nested deeper than {MAX_DEPTH}")
        local = _local(tag)
        if stack:
            parent = stack[-1]
            same = parent.seen.get(local, 0)
            parent.seen[local] = same + 1
            path = f"{parent.path}/{local}" + (f"[{same + 1}]" if same else "")
        elif root:
            refuse(here(), "more than one root element")
        else:
            path = local
        el = Element(local, dict(attrs), parser.CurrentLineNumber, path)
        (stack[-1].children if stack else root).append(el)
        stack.append(el)

    def end(tag):
        el = stack.pop()
        el.text, el.parts, el.seen = "".join(el.parts), [], {}

    def chars(text):
        if stack:
            stack[-1].parts.append(text)  # joined once at the end tag: never quadratic

    def doctype(name_, sysid, pubid, has_internal_subset):
        if has_internal_subset:
            refuse(
                f"(line {parser.CurrentLineNumber})",
                "a DOCTYPE with an internal subset is refused (entities are never expanded)",
            )

    def entity_decl(*args):
        refuse(f"(line {parser.CurrentLineNumber})", "entity declarations are refused")

    def external_ref(*args):
        refuse(here(), "external entities are refused")
        return 0

    def skipped(name_, is_param):
        refuse(
            here(),
            f"entity reference &{name_[:20]}; is refused (only &lt; &gt; &amp; &quot; &apos; and character references)",
        )

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = chars
    parser.StartDoctypeDeclHandler = doctype
    parser.EntityDeclHandler = entity_decl
    parser.UnparsedEntityDeclHandler = entity_decl
    parser.ExternalEntityRefHandler = external_ref
    parser.SkippedEntityHandler = skipped
    try:
        parser.Parse(data, True)
    except _Refused:
        raise ValueError(f"{name}: {problem[0]}") from None
    except expat.ExpatError as exc:
        raise ValueError(f"{name}: (line {exc.lineno}): not well-formed XML ({expat.ErrorString(exc.code)})") from None
    except RecursionError:  # pragma: no cover - depth is capped above
        raise ValueError(f"{name}: nested too deeply") from None
    if not root:
        raise ValueError(f"{name}: no root element")
    return root[0]
