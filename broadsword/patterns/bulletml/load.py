"""``load(path) -> Pattern``: read, validate and compile a BulletML file.

Every element of BulletML is checked against the specification's DTD (which children, how
many, which ``type`` values); every number is compiled by :mod:`.expr`; every reference must
name a labelled element of its kind; chains of references may neither loop nor run deeper
than ``MAX_REF_CHAIN`` hops (or ``MAX_RUN_DEPTH`` nested actions). A bad file raises
``ValueError("FILE: ELEMENT-PATH (line N): what is wrong")``.

Where libBulletML is lenient the loader is too, and says so in ``Pattern.warnings`` (one line
per kind of leniency and element, with how often): an attribute BulletML does not define is
ignored, an empty expression reads 0, a file with no top action loads and fires nothing; a
reference that passes fewer parameters than its target reads is warned of too.
"""

from __future__ import annotations

import os
from typing import Any, Literal, NoReturn, overload

from .expr import Expr, compile_expression
from .limits import MAX_PARAMS, MAX_REF_CHAIN, MAX_REPEAT
from .model import (
    Accel,
    Action,
    ActionRef,
    Bullet,
    BulletRef,
    ChangeDirection,
    ChangeSpeed,
    Direction,
    DirKind,
    Fire,
    FireRef,
    Orientation,
    Pattern,
    Repeat,
    Speed,
    SpeedKind,
    Vanish,
    Wait,
)
from .xmlread import Element, read_elements

#: Most actions nested inside one another at run time, counting through references.
MAX_RUN_DEPTH = 160

_COMMANDS = (
    "changeDirection",
    "accel",
    "vanish",
    "changeSpeed",
    "repeat",
    "wait",
    "fire",
    "fireRef",
    "action",
    "actionRef",
)
_LABELLED = {"action": "actions", "bullet": "bullets", "fire": "fires"}


class _Builder:
    def __init__(self, name: str):
        self.name = name
        self.labels: dict[str, dict[str, Element]] = {"actions": {}, "bullets": {}, "fires": {}}
        # leniencies: what (one kind, one element tag) -> [times, where first]
        self.notes: dict[str, list] = {}

    def fail(self, el: Element, what: str) -> NoReturn:
        raise ValueError(f"{self.name}: {el.where()}: {what}")

    def warn(self, el: Element, what: str) -> None:
        """Note a leniency (counted once per distinct ``what``, located at its first place)."""
        note = self.notes.setdefault(what, [0, el.where()])
        note[0] += 1

    def warnings(self) -> tuple[str, ...]:
        return tuple(
            f"{where}: {what}" + (f" ({times} times)" if times > 1 else "")
            for what, (times, where) in self.notes.items()
        )

    # -- shape checks -------------------------------------------------------------------
    def check(
        self,
        el: Element,
        attrs: tuple[str, ...],
        allowed: tuple[str, ...] = (),
        text: bool = False,
        required: tuple[str, ...] = (),
    ) -> None:
        for key in el.attrs:
            if key not in attrs and not key.startswith("xmlns"):
                # libBulletML ignores attributes it does not know; so do we, with a warning
                self.warn(
                    el, f"unknown attribute {key[:30]!r} on <{el.tag}> ignored (allowed: {', '.join(attrs) or 'none'})"
                )
        for key in required:
            if not el.attrs.get(key, "").strip():
                self.fail(el, f"<{el.tag}> needs a {key} attribute")
        for child in el.children:
            if child.tag not in allowed:
                what = f"<{child.tag[:30]}> is not allowed inside <{el.tag}>"
                self.fail(child, what + (f" (allowed: {', '.join(allowed)})" if allowed else " (it holds no elements)"))
        if not text and el.text.strip():
            self.fail(el, f"text {el.text.strip()[:20]!r} is not allowed inside <{el.tag}>")

    @overload
    def one(self, el: Element, tags: tuple[str, ...], required: Literal[True]) -> Element: ...

    @overload
    def one(self, el: Element, tags: tuple[str, ...], required: bool) -> Element | None: ...

    def one(self, el: Element, tags: tuple[str, ...], required: bool) -> Element | None:
        found = [c for c in el.children if c.tag in tags]
        if len(found) > 1:
            self.fail(found[1], f"<{el.tag}> holds more than one <{'> or <'.join(tags)}>")
        if required and not found:
            self.fail(el, f"<{el.tag}> needs a <{'> or <'.join(tags)}>")
        return found[0] if found else None

    def expr(self, el: Element) -> Expr:
        self.check(el, ("type",) if el.tag in ("direction", "speed", "horizontal", "vertical") else (), text=True)
        if not el.text.strip():  # libBulletML reads an empty expression as 0
            self.warn(el, f"empty <{el.tag}> read as 0")
            return compile_expression("0")
        try:
            return compile_expression(el.text)
        except ValueError as exc:
            self.fail(el, str(exc))

    def kind(self, el: Element, enum, default):
        value = el.attrs.get("type")
        if value is None:
            return default
        try:
            return enum(value.strip())
        except ValueError:
            self.fail(el, f"type {value[:30]!r} is not one of {', '.join(k.value for k in enum)}")

    # -- elements -----------------------------------------------------------------------
    @overload
    def direction(self, el: Element) -> Direction: ...

    @overload
    def direction(self, el: Element | None) -> Direction | None: ...

    def direction(self, el: Element | None) -> Direction | None:
        if el is None:
            return None
        return Direction(self.kind(el, DirKind, DirKind.AIM), self.expr(el))

    @overload
    def speed(self, el: Element) -> Speed: ...

    @overload
    def speed(self, el: Element | None) -> Speed | None: ...

    def speed(self, el: Element | None) -> Speed | None:
        if el is None:
            return None
        return Speed(self.kind(el, SpeedKind, SpeedKind.ABSOLUTE), self.expr(el))

    def ref(self, el: Element, cls, table: str):
        self.check(el, ("label",), ("param",), required=("label",))
        label = el.attrs["label"]
        if label not in self.labels[table]:
            self.fail(el, f"no {table[:-1]} labelled {label[:40]!r}")
        params = [c for c in el.children if c.tag == "param"]
        if len(params) > MAX_PARAMS:
            self.fail(params[MAX_PARAMS], f"more than {MAX_PARAMS} params")
        return cls(label, tuple(self.expr(p) for p in params))

    def action(self, el: Element) -> Action:
        self.check(el, ("label",), _COMMANDS)
        return Action(el.attrs.get("label"), tuple(self.command(c) for c in el.children))

    def bullet(self, el: Element) -> Bullet:
        self.check(el, ("label",), ("direction", "speed", "action", "actionRef"))
        acts = [self.action(c) for c in el.children if c.tag == "action"]
        refs = [self.ref(c, ActionRef, "actions") for c in el.children if c.tag == "actionRef"]
        return Bullet(
            el.attrs.get("label"),
            self.direction(self.one(el, ("direction",), False)),
            self.speed(self.one(el, ("speed",), False)),
            tuple(acts + refs),
        )

    def fire(self, el: Element) -> Fire:
        self.check(el, ("label",), ("direction", "speed", "bullet", "bulletRef"))
        b = self.one(el, ("bullet", "bulletRef"), True)
        bullet = self.bullet(b) if b.tag == "bullet" else self.ref(b, BulletRef, "bullets")
        return Fire(
            el.attrs.get("label"),
            self.direction(self.one(el, ("direction",), False)),
            self.speed(self.one(el, ("speed",), False)),
            bullet,
        )

    def command(self, el: Element):
        tag = el.tag
        if tag == "action":
            return self.action(el)
        if tag == "actionRef":
            return self.ref(el, ActionRef, "actions")
        if tag == "fire":
            return self.fire(el)
        if tag == "fireRef":
            return self.ref(el, FireRef, "fires")
        if tag == "wait":
            self.check(el, (), text=True)
            return Wait(self.expr(el))
        if tag == "vanish":
            self.check(el, ())
            return Vanish()
        if tag == "changeDirection":
            self.check(el, (), ("direction", "term"))
            return ChangeDirection(self.direction(self.one(el, ("direction",), True)), self.term(el))
        if tag == "changeSpeed":
            self.check(el, (), ("speed", "term"))
            return ChangeSpeed(self.speed(self.one(el, ("speed",), True)), self.term(el))
        if tag == "accel":
            self.check(el, (), ("horizontal", "vertical", "term"))
            return Accel(
                self.speed(self.one(el, ("horizontal",), False)),
                self.speed(self.one(el, ("vertical",), False)),
                self.term(el),
            )
        # repeat (check() allowed nothing else)
        self.check(el, (), ("times", "action", "actionRef"))
        times_el = self.one(el, ("times",), True)
        times = self.expr(times_el)
        if times.const is not None and times.const > MAX_REPEAT:
            self.fail(times_el, f"times is {times.const:g} (at most {MAX_REPEAT})")
        body = self.one(el, ("action", "actionRef"), True)
        return Repeat(times, self.action(body) if body.tag == "action" else self.ref(body, ActionRef, "actions"))

    def term(self, el: Element) -> Expr:
        return self.expr(self.one(el, ("term",), True))

    # -- the whole file -----------------------------------------------------------------
    def collect_labels(self, root: Element) -> None:
        todo = [root]
        while todo:
            el = todo.pop()
            todo.extend(reversed(el.children))
            table = _LABELLED.get(el.tag)
            if table and "label" in el.attrs:
                label = el.attrs["label"]
                if not label.strip():
                    self.fail(el, "label is empty")
                seen = self.labels[table]
                if label in seen:
                    self.fail(el, f"label {label[:40]!r} is already used by the {el.tag} at line {seen[label].line}")
                seen[label] = el

    def pattern(self, root: Element) -> Pattern:
        if root.tag != "bulletml":
            self.fail(root, f"the root element is <{root.tag[:30]}>, expected <bulletml>")
        self.check(root, ("type",), ("bullet", "action", "fire"))
        orientation = self.kind(root, Orientation, Orientation.NONE)
        self.collect_labels(root)
        built: dict[str, dict[str, Any]] = {"actions": {}, "bullets": {}, "fires": {}}
        top: list[Action] = []
        for el in root.children:
            obj: Any = {"action": self.action, "bullet": self.bullet, "fire": self.fire}[el.tag](el)
            if obj.label is not None:
                built[_LABELLED[el.tag]][obj.label] = obj
            if el.tag == "action" and obj.label is not None and obj.label.startswith("top"):
                top.append(obj)
        for table, els in self.labels.items():  # labelled elements nested inside others
            for label, el in els.items():
                if label not in built[table]:
                    built[table][label] = {"actions": self.action, "bullets": self.bullet, "fires": self.fire}[table](
                        el
                    )
        if not top:  # libBulletML loads it, and it fires nothing
            self.warn(
                root, "no top action (an <action> labelled 'top', or 'top1', 'top2', ...): the file fires nothing"
            )
        pattern = Pattern(self.name, orientation, tuple(top), built["actions"], built["bullets"], built["fires"])
        _RefCheck(self, pattern).run(root)
        params = _ParamCheck(self, pattern)
        top_params = max((params.scope(t) for t in top), default=0)  # top actions are labelled
        return Pattern(
            self.name,
            orientation,
            tuple(top),
            built["actions"],
            built["bullets"],
            built["fires"],
            self.warnings(),
            top_params,
        )


class _RefCheck:
    """Refuses reference loops and chains past the limits. A bullet's own actions run in a
    new runner, so a bullet that fires itself (through bulletRef) is not a loop; actionRef
    and fireRef chains run inside one runner and are followed."""

    def __init__(self, builder: _Builder, pattern: Pattern):
        self.b, self.p = builder, pattern
        self.depth: dict[str, tuple[int, int]] = {}  # action label -> (ref hops, nesting)

    def run(self, root: Element) -> None:
        for label in self.p.actions:
            self.action_ref(label, (), root)
        for bullet in self.p.bullets.values():
            for act in bullet.actions:
                self.body(act, (), root)

    def action_ref(self, label: str, chain: tuple[str, ...], root: Element) -> tuple[int, int]:
        if label in chain:
            loop = " -> ".join(chain[chain.index(label) :] + (label,))
            self.b.fail(self.b.labels["actions"][label], f"actionRef loop: {loop[:200]}")
        if label not in self.depth:
            chain = chain + (label,)
            if len(chain) > MAX_REF_CHAIN:
                self.b.fail(self.b.labels["actions"][label], f"references chain deeper than {MAX_REF_CHAIN}")
            hops, nest = self.commands(self.p.actions[label].commands, chain, root)
            self.depth[label] = (hops + 1, nest + 1)
            if hops + 1 > MAX_REF_CHAIN or nest + 1 > MAX_RUN_DEPTH:
                self.b.fail(
                    self.b.labels["actions"][label],
                    f"actions nest (through references) deeper than {MAX_REF_CHAIN} references or "
                    f"{MAX_RUN_DEPTH} levels",
                )
        return self.depth[label]

    def body(self, node, chain, root) -> tuple[int, int]:
        if isinstance(node, ActionRef):
            return self.action_ref(node.label, chain, root)
        hops, nest = self.commands(node.commands, chain, root)
        return hops, nest + 1

    def commands(self, commands, chain, root) -> tuple[int, int]:
        hops = nest = 0
        for c in commands:
            if isinstance(c, (Action, ActionRef)):
                h, n = self.body(c, chain, root)
            elif isinstance(c, Repeat):
                h, n = self.body(c.body, chain, root)
                n += 1
            elif isinstance(c, FireRef):
                h, n = 1, 1
            else:
                continue
            hops, nest = max(hops, h), max(nest, n)
        return hops, nest


class _ParamCheck:
    """Which ``$n`` each scope reads. A scope is a top action (given the emitter's
    parameters) or the target of a reference (given the reference's ``<param>``s); an inline
    ``<bullet>`` and nested actions share their scope, and a reference's target is a scope of
    its own, so a label's needs never depend on what it references (no recursion).
    ``needs[(table, label)]`` is the highest ``$n`` a labelled element reads; a reference
    passing fewer parameters than its target reads is warned of."""

    _TABLES = {ActionRef: "actions", FireRef: "fires", BulletRef: "bullets"}

    def __init__(self, builder: _Builder, pattern: Pattern):
        self.b, self.p = builder, pattern
        refs: list = []
        self.needs = {
            (table, label): self.scope(node, refs)
            for table in ("actions", "bullets", "fires")
            for label, node in getattr(pattern, table).items()
        }
        for ref in refs:
            table = self._TABLES[type(ref)]
            need, given = self.needs[(table, ref.label)], len(ref.params)
            if need > given:
                name = type(ref).__name__
                self.b.warn(
                    self.b.labels[table][ref.label],
                    f"reads ${need} but a <{name[0].lower()}{name[1:]}> to it passes {given} "
                    f"parameter{'s' if given != 1 else ''} (the rest read 0)",
                )

    def scope(self, node, refs: list | None = None) -> int:
        """Highest ``$n`` read by ``node`` (an Action, Bullet, Fire or command) in its own
        scope; the references met are appended to ``refs``."""
        most = 0
        todo = [node]
        while todo:
            n = todo.pop()
            kind = type(n)
            if kind in self._TABLES:
                most = max([most] + [e.max_param for e in n.params])
                if refs is not None:
                    refs.append(n)
            elif kind is Action:
                todo.extend(n.commands)
            elif kind is Bullet or kind is Fire:
                for part in (n.direction, n.speed):
                    if part is not None:
                        most = max(most, part.expr.max_param)
                todo.extend(n.actions if kind is Bullet else (n.bullet,))
            elif kind is ChangeDirection or kind is ChangeSpeed:
                part = n.direction if kind is ChangeDirection else n.speed
                most = max(most, part.expr.max_param, n.term.max_param)
            elif kind is Accel:
                for part in (n.horizontal, n.vertical):
                    if part is not None:
                        most = max(most, part.expr.max_param)
                most = max(most, n.term.max_param)
            elif kind is Wait:
                most = max(most, n.frames.max_param)
            elif kind is Repeat:
                most = max(most, n.times.max_param)
                todo.append(n.body)
        return most


def load(path: str | os.PathLike) -> Pattern:
    """Read, validate and compile the BulletML file at ``path``.

    Raises ``ValueError`` whose message starts with the file name, then the element path
    (and line), then what is wrong.
    """
    name = os.fspath(path)
    return _Builder(name).pattern(read_elements(name))


def loads(data: bytes | str, name: str = "<string>") -> Pattern:
    """Like :func:`load`, from the file's contents (``name`` heads error messages)."""
    raw = data.encode("utf-8") if isinstance(data, str) else data
    return _Builder(name).pattern(read_elements(name, raw))
