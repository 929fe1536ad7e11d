"""The contract between the app and its scenes (issue 24, part 2): no import loop in the game
package; no scene imports the app, even for types; every scene is made with a typed
:class:`SceneContext`; every hub parameter in the game is typed; the transitions a scene
returns are what the app does."""

from __future__ import annotations

import ast
import inspect
from pathlib import Path

import pygame
from support.events import key_event as key
from support.imports import find_cycle, import_graph

import broadsword.game
from broadsword.game.scenes import base
from broadsword.game.scenes.base import Go, Push, Replace, Reset
from broadsword.game.scenes.high_scores import HighScoresScene
from broadsword.game.scenes.how_to_play import HowToPlay
from broadsword.game.scenes.options_screen import OptionsScene
from broadsword.game.scenes.title import Title
from broadsword.sim import DT

GAME = Path(broadsword.game.__file__).parent
HUB_NAMES = {"app", "world", "ctx", "context"}


def test_the_game_package_has_no_import_loop():
    graph = import_graph(broadsword.game)
    assert len(graph) > 60 and "broadsword.game.scenes.context" in graph["broadsword.game.scenes.title"]
    assert find_cycle(graph) is None, " -> ".join(find_cycle(graph) or [])


def test_no_scene_imports_the_app():
    graph = import_graph(broadsword.game)
    scenes = {m for m in graph if m.startswith("broadsword.game.scenes")}
    assert len(scenes) > 20
    assert [m for m in sorted(scenes) if "broadsword.game.app" in graph[m]] == []


def _scene_classes() -> list[type]:
    import importlib
    import pkgutil

    import broadsword.game.scenes as package

    found = []
    for info in pkgutil.iter_modules(package.__path__):
        module = importlib.import_module(f"{package.__name__}.{info.name}")
        for _, cls in inspect.getmembers(module, inspect.isclass):
            is_protocol = getattr(cls, "_is_protocol", False)
            if (
                cls.__module__ == module.__name__
                and not is_protocol
                and all(hasattr(cls, m) for m in ("handle", "update", "draw"))
            ):
                found.append(cls)
    return found


def test_every_scene_takes_a_typed_scene_context_and_returns_transitions():
    classes = _scene_classes()
    assert len(classes) >= 20
    for cls in classes:
        params = list(inspect.signature(cls.__init__).parameters.values())
        assert params[1].name == "ctx" and params[1].annotation == "SceneContext", cls
        assert inspect.signature(cls.update).return_annotation == "Tick", cls
        assert inspect.signature(cls.handle).return_annotation in ("Handled", "bool"), cls


def test_every_hub_parameter_in_the_game_is_typed():
    untyped = []
    for path in sorted(GAME.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda):
                args = node.args
                for a in [*args.posonlyargs, *args.args, *args.kwonlyargs]:
                    if a.arg in HUB_NAMES and (isinstance(node, ast.Lambda) or a.annotation is None):
                        untyped.append(f"{path.relative_to(GAME)}:{node.lineno} {a.arg}")
    assert untyped == []


def test_scenes_return_transitions_and_leave_the_stack_to_the_app(app):
    """A scene's handle says what comes next; the stack changes only when the app applies it."""
    title = app.scene
    assert isinstance(title, Title)
    step = title.handle(key(pygame.K_o))
    assert isinstance(step, Push) and isinstance(step.scene, OptionsScene) and app.scene is title
    app.apply(step)
    assert app.scene is step.scene and app.stack.scenes == [title, step.scene]
    assert step.scene.handle(key(pygame.K_ESCAPE)) is Go.POP and app.scene is step.scene
    assert title.handle(key(pygame.K_ESCAPE)) is Go.QUIT and app.running
    app.apply(Go.POP)
    assert app.scene is title
    app.apply(Replace(HowToPlay(app.ctx)))
    assert isinstance(app.scene, HowToPlay) and len(app.stack.scenes) == 1
    app.apply(Go.POP)  # nothing under it: the title, never an empty stack
    assert isinstance(app.scene, Title)
    app.apply(Reset(HighScoresScene(app.ctx)))
    app.apply(Go.TO_TITLE)
    assert isinstance(app.scene, Title) and len(app.stack.scenes) == 1
    app.apply(Go.QUIT)
    assert not app.running and app.frame(DT) == 0


def test_the_transition_union_names_every_kind():
    assert set(base.Transition.__args__) == {Go, Push, Replace, Reset, base.NextStage, base.PlayStage}
