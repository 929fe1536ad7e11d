"""The scenes, each driven directly or through App.frame with posted events (dummy drivers)."""

from __future__ import annotations

import dataclasses
import warnings

import pygame
import pytest
from support.events import frames
from support.events import post_key as key

from broadsword.data import load_level, resolve_level
from broadsword.data.difficulty import Difficulty
from broadsword.game.app import App
from broadsword.game.controls import Action
from broadsword.game.run import Run, Stage
from broadsword.game.scenes import (
    Continue,
    GameOver,
    HighScoresScene,
    NameEntry,
    OptionsScene,
    Pause,
    Play,
    Results,
    SceneStack,
    Title,
)
from broadsword.game.scenes.options_screen import ROWS
from broadsword.game.scores import Entry, HighScores
from broadsword.sim import World


def post(kind):
    pygame.event.post(pygame.event.Event(kind))


def empty_stage(app, run=None, waves=()) -> World:
    """Play an emptied first stage (no waves, no boss): it clears on its first step."""
    level = dataclasses.replace(load_level(resolve_level("1-picket")), waves=tuple(waves), boss=None)
    world = World(level, app.ctx.bank.armatures, seed=1)
    app.play_stage(Stage(world, "1-picket", ""), run or Run(0))
    return world


def lose_every_life(world: World) -> None:
    world.player.lives = 1
    world.player.bombs = 0  # no death-bomb to save it
    world.player.invulnerable = 0.0
    world.player.stricken = 1  # struck: the life goes on the next step


class Flat:
    def __init__(self, opaque, log, name):
        self.opaque, self.log, self.name = opaque, log, name

    def draw(self, surf):
        self.log.append(self.name)


# --------------------------------------------------------------------------- the stack
def test_stack__draws_from_the_highest_opaque_scene_up():
    log: list[str] = []
    s = SceneStack()
    for name, opaque in (("title", True), ("play", True), ("pause", False), ("veil", False)):
        s.push(Flat(opaque, log, name))
    s.draw(None)
    assert log == ["play", "pause", "veil"]
    s.pop()
    s.replace(Flat(True, log, "scores"))
    log.clear()
    s.draw(None)
    assert log == ["scores"] and s.find(Flat).name == "scores"
    s.reset(Flat(False, log, "only"))
    assert len(s.scenes) == 1 and s.top.name == "only"


# --------------------------------------------------------------------------- defects (issue 12, item 10)
def test_name_entry__m_types_m_and_does_not_mute(app):
    app.stack.push(NameEntry(app.ctx, 1234, "1-picket"))
    for ch in "mammoth":
        key(getattr(pygame, f"K_{ch}"), ch)
    frames(app)
    assert app.scene.name == "MAMMOTH" and not app.ctx.audio.muted
    key(pygame.K_RETURN, "\r")
    frames(app)
    assert isinstance(app.scene, HighScoresScene) and app.ctx.scores.entries[0].name == "MAMMOTH"


def test_m_mutes_elsewhere(app):
    key(pygame.K_m, "m")
    frames(app)
    assert app.ctx.audio.muted and isinstance(app.scene, Title)


@pytest.mark.parametrize("kind", [pygame.WINDOWFOCUSLOST, pygame.WINDOWMINIMIZED, pygame.WINDOWHIDDEN])
def test_autopilot__never_pauses_by_itself(tmp_path, kind):
    a = App(seed=1, audio=False, demo=True, scores=HighScores(tmp_path / "s.json"))
    a.start_run()
    post(pygame.WINDOWFOCUSGAINED)
    frames(a, 2)
    post(kind)
    frames(a, 3)
    assert isinstance(a.scene, Play) and a.world.frame >= 3
    pygame.quit()


def test_level_run__a_window_opened_without_focus_does_not_start_paused(app):
    frames(app)  # the window's own start-up events
    app.presence.focused = False  # opened behind the terminal that launched it
    app.start_run()
    post(pygame.WINDOWFOCUSLOST)  # what the window manager may send to a window that never had focus
    frames(app, 3)
    assert isinstance(app.scene, Play) and app.world.frame > 0
    post(pygame.WINDOWFOCUSGAINED)
    post(pygame.WINDOWFOCUSLOST)  # now it had the focus, and lost it: a player's game pauses
    frames(app)
    assert isinstance(app.scene, Pause)


def test_autopilot__never_asks_for_a_name_nor_enters_the_table(tmp_path):
    a = App(seed=1, audio=False, demo=True, scores=HighScores(tmp_path / "s.json"))
    world = empty_stage(a, waves=load_level(resolve_level("1-picket")).waves[:1])
    world.score.points = 40_000  # below the first extend
    lose_every_life(world)
    frames(a, 2)
    assert isinstance(a.scene, GameOver) and not a.scene.qualifies  # no continue offered either
    key(pygame.K_RETURN)
    frames(a)
    assert isinstance(a.scene, Title) and a.ctx.scores.entries == []
    assert not (tmp_path / "s.json").exists()
    pygame.quit()


def fits(app) -> None:
    """Every line drawn this frame lies inside the field, and no text colour touches its edges."""
    w, h = app.ctx.display.screen.get_size()
    assert app.ctx.painter.drawn
    for r in app.ctx.painter.drawn:
        assert 0 <= r.left and r.right <= w, r
    img = pygame.surfarray.array3d(app.ctx.display.screen)
    for column in (img[0], img[w - 1]):
        bright = (column.max(axis=1) > 140).sum()
        assert bright <= 6, "text at the field's edge"  # a star or two may sit there, never a line of text


def test_text__never_clipped_at_the_right_edge(app):
    frames(app)
    fits(app)
    assert "shows your hit shape" in "".join(
        r
        for _, r in __import__("broadsword.game.scenes.title", fromlist=["controls_list"]).controls_list(
            app.ctx.controls.bindings
        )
    )
    # the widest strings each screen can draw, fitted
    app.ctx.choice.custom = "/a/very/long/path/" * 8 + "level.toml"
    frames(app)
    fits(app)
    app.ctx.choice.custom = None
    world = empty_stage(app, waves=load_level(resolve_level("1-picket")).waves[:1])
    app.ctx.overlay.visible = True
    key(pygame.K_ESCAPE)
    frames(app)
    assert isinstance(app.scene, Pause)
    fits(app)
    for scene in (
        Results(app.ctx, app.play),
        Continue(app.ctx, app.play),
        GameOver(app.ctx, app.play, True),
        NameEntry(app.ctx, 123456789, "x"),
        OptionsScene(app.ctx),
        HighScoresScene(app.ctx),
    ):
        app.stack.push(scene)
        app.ctx.scores.entries = [Entry("W" * 12, 10**12, "w" * 40, "2024-01-01")]
        app.render()
        fits(app)
        app.stack.pop()
    assert world is app.world


# --------------------------------------------------------------------------- title and difficulty
def test_title__up_down_choose_the_difficulty_it_plays_and_remembers(app, tmp_path):
    assert app.ctx.difficulty is Difficulty.NORMAL
    key(pygame.K_DOWN)
    key(pygame.K_DOWN)
    frames(app)
    assert app.ctx.difficulty is Difficulty.LUNATIC
    assert '"difficulty": "lunatic"' in (tmp_path / "options.json").read_text()
    key(pygame.K_UP)
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, Play) and app.world.settings.difficulty is Difficulty.HARD
    assert app.recording().first.settings["difficulty"] == "hard"


def test_title__o_opens_options_and_h_the_high_scores(app):
    key(pygame.K_o)
    frames(app)
    assert isinstance(app.scene, OptionsScene)
    key(pygame.K_ESCAPE)
    key(pygame.K_h)
    frames(app)
    assert isinstance(app.scene, HighScoresScene)
    key(pygame.K_ESCAPE)
    frames(app)
    assert isinstance(app.scene, Title)


# --------------------------------------------------------------------------- results
def test_results__after_a_stage_then_the_next_stage_with_the_score_carried(app):
    world = empty_stage(app)
    frames(app, 2)
    results = app.scene
    assert isinstance(results, Results) and world.complete and not results.final
    rows = dict((label, value) for label, value, _ in results.rows())
    assert rows["No-miss bonus"] == "+30,000" and rows["No-bomb bonus"] == "+20,000"
    assert rows["Stage clear bonus"] == "+10,000" and rows["Score"] == f"{world.score.points:,}"
    score = world.score.points
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, Play) and app.world is not world
    assert app.world.level.name == app.ctx.levels[1] and app.world.score.points == score


def test_results__the_next_stage_keeps_the_power_won(app):
    """A stage cleared at power 2.60 starts the next at 2.60, not back at the base power
    (and its recording carries it, so the stage replays on its own)."""
    world = empty_stage(app)
    world.player.power = 260
    frames(app, 2)
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, Play) and app.world is not world
    rec = app.recording()  # one run: both stages, the second starting with the power won
    assert app.world.player.power == 260 and len(rec.stages) == 2 and rec.stages[1].carry["power"] == 260


def test_results__a_missed_bonus_says_why(app):
    world = empty_stage(app)
    world.player.misses, world.progress.bombs_used = 2, 1
    frames(app, 2)
    rows = dict((label, value) for label, value, _ in app.scene.rows())
    assert rows["No-miss bonus"].startswith("-- (2 misses") and rows["No-bomb bonus"].startswith("-- (1 bomb;")


def test_results__the_last_stage_leads_to_the_final_results_and_the_name(app):
    world = empty_stage(app, Run(len(app.ctx.levels) - 1))
    frames(app, 2)
    assert isinstance(app.scene, Results) and app.scene.final
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, GameOver) and app.scene.victory and app.scene.score == world.score.points
    app.render()  # a one-stage run (started at the last stage) cleared only that stage
    assert "STAGE CLEARED" in app.ctx.painter.said and not any("Every stage" in line for line in app.ctx.painter.said)
    key(pygame.K_RETURN)
    frames(app)
    assert isinstance(app.scene, NameEntry) and app.scene.score == world.score.points


def test_final_results__every_stage_cleared_only_when_the_run_cleared_them_all(app):
    empty_stage(app, Run(len(app.ctx.levels) - 1))
    frames(app, 2)
    key(pygame.K_RETURN)
    frames(app)
    over = app.scene
    assert over.victory_lines()[0] == "STAGE CLEARED"
    over.totals = dataclasses.replace(over.totals, stages=2)
    assert over.victory_lines() == (
        "STAGES CLEARED",
        f"2 of {len(app.ctx.levels)} stages, to I. Outer Picket, on Normal",
    )
    over.totals = dataclasses.replace(over.totals, stages=len(app.ctx.levels))
    assert over.victory_lines() == ("BROADSWORD FALLS", "Every stage cleared on Normal")


def test_final_results__the_runs_totals_add_every_stage_cleared(app):
    """Two emptied stages cleared one after the other: the final screen adds both stages'
    misses, bombs, grazes, items and time (the run's totals, not the last stage's)."""
    first = empty_stage(app, Run(len(app.ctx.levels) - 2))
    first.player.misses, first.progress.bombs_used, first.score.grazes, first.score.items = 1, 2, 30, 4
    frames(app, 2)
    key(pygame.K_RETURN)  # results -> the last stage
    frames(app)
    run = app.play.run
    assert app.world is not first and run.totals.stages == 1
    last = empty_stage(app, run)  # the last stage, emptied the same way
    last.player.misses, last.progress.bombs_used, last.score.grazes, last.score.items = 2, 1, 12, 6
    frames(app, 2)
    key(pygame.K_RETURN)
    frames(app)
    over = app.scene
    assert isinstance(over, GameOver) and over.victory
    t = over.totals
    assert (t.stages, t.misses, t.bombs, t.grazes, t.items) == (2, 3, 3, 42, 10)
    assert t.seconds == first.time + last.time
    rows = dict(over.rows())
    assert rows["Stages cleared"] == "2" and rows["Misses"] == "3" and rows["Grazes"] == "42"
    assert over.victory_lines()[0] == "STAGES CLEARED"  # two of five, not every stage


# --------------------------------------------------------------------------- continues
def test_continue__play_on_with_the_score_counting_continues(app):
    world = empty_stage(app, waves=load_level(resolve_level("1-picket")).waves[:1])
    world.score.points = 5000
    lose_every_life(world)
    frames(app, 2)
    assert isinstance(app.scene, Continue) and world.over
    key(pygame.K_z)
    frames(app, 3)
    assert isinstance(app.scene, Play) and not world.over and world.score.points % 10 == 1
    assert world.toggles[-1].toggle.value == "continue"


def test_continue__names_the_fire_keys_bound_now(app):
    """After Fire is rebound to J, the continue screen says J, not Z (issue 22)."""
    app.ctx.controls.bindings.bind_key(Action.FIRE, pygame.K_j, replace=True)
    world = empty_stage(app, waves=load_level(resolve_level("1-picket")).waves[:1])
    lose_every_life(world)
    frames(app, 2)
    assert isinstance(app.scene, Continue)
    assert "Enter or J: continue   Esc: end the run" in app.ctx.painter.said
    key(pygame.K_j)
    frames(app, 3)
    assert isinstance(app.scene, Play) and not world.over


def test_launch__a_custom_binding_says_nothing_on_stderr(tmp_path, capfd):
    """controls.json naming keys was read before pygame.init(): pygame warned ("pygame.init()
    has not been called") on stderr at every launch."""
    pygame.quit()
    (tmp_path / "controls.json").write_text('{"version": 1, "keys": {"slow": ["c"], "fire": ["j"]}}')
    capfd.readouterr()
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        a = App(audio=False, scores=HighScores(tmp_path / "scores.json"), data=tmp_path)
    try:
        assert a.ctx.controls.bindings.keys[Action.SLOW] == (pygame.K_c,) and a.ctx.message is None
        assert [str(w.message) for w in said] == [] and capfd.readouterr().err == ""
    finally:
        pygame.quit()


def test_continue__declined_or_timed_out_ends_the_run(app):
    world = empty_stage(app, waves=load_level(resolve_level("1-picket")).waves[:1])
    world.score.points = 5000
    lose_every_life(world)
    frames(app, 2)
    assert isinstance(app.scene, Continue)
    app.frame(11.0)  # ten seconds to decide
    assert isinstance(app.scene, GameOver) and not app.scene.victory and app.scene.qualifies
    t = app.scene.totals  # the stage lost counts in the totals, not as cleared
    assert t.stages == 0 and t.misses == world.player.misses >= 1 and t.seconds == world.time > 0


def test_continue__none_left_goes_straight_to_game_over(app):
    world = empty_stage(app, waves=load_level(resolve_level("1-picket")).waves[:1])
    world.progress.continues_used = 3
    lose_every_life(world)
    frames(app, 2)
    assert isinstance(app.scene, GameOver)


# --------------------------------------------------------------------------- options
def row(name: str) -> int:
    return next(i for i, r in enumerate(ROWS) if r.label == name)


def test_options__rebind_fire_by_pressing_a_key_and_it_is_saved(app, tmp_path):
    app.stack.push(OptionsScene(app.ctx))
    for _ in range(row("Fire")):
        key(pygame.K_DOWN)
    key(pygame.K_RETURN)
    frames(app)
    assert app.scene.waiting is Action.FIRE
    key(pygame.K_F1)  # a fixed key is refused, and it still waits
    frames(app)
    assert app.scene.waiting is Action.FIRE and "fixed" in app.scene.note
    key(pygame.K_c, "c")
    frames(app)
    assert app.scene.waiting is None and app.ctx.controls.bindings.keys[Action.FIRE] == (
        pygame.K_z,
        pygame.K_SPACE,
        pygame.K_c,
    )
    assert '"fire": [\n   "z",\n   "space",\n   "c"\n  ]' in (tmp_path / "controls.json").read_text()
    key(pygame.K_BACKSPACE)  # Backspace, then a key: that key alone
    key(pygame.K_j, "j")
    frames(app)
    assert app.scene.waiting is None and app.ctx.controls.bindings.keys[Action.FIRE] == (pygame.K_j,)
    assert '"fire": [\n   "j"\n  ]' in (tmp_path / "controls.json").read_text()
    key(pygame.K_ESCAPE)
    frames(app)
    assert isinstance(app.scene, Title)
    app.render()
    assert any(line.startswith("Enter or J play") for line in app.ctx.painter.said)  # the real Fire key


def test_options__volumes_hitbox_and_difficulty_change_and_are_saved(app, tmp_path):
    scene = OptionsScene(app.ctx)
    app.stack.push(scene)
    before = app.ctx.options.music
    scene.row = row("Music volume")
    key(pygame.K_LEFT)
    scene_row_hitbox = row("Always show hit shape")
    frames(app)
    assert app.ctx.options.music == before - 1
    scene.row = scene_row_hitbox
    key(pygame.K_RETURN)
    frames(app)
    assert app.ctx.options.always_hitbox
    text = (tmp_path / "options.json").read_text()
    assert f'"music": {before - 1}' in text and '"always_hitbox": true' in text


def test_options__no_two_lines_overlap(app):
    """Every row (the bullet palette's too) and the help line below them stand apart."""
    app.stack.push(OptionsScene(app.ctx))
    frames(app)
    drawn = list(app.ctx.painter.drawn)
    assert len(drawn) >= 2 * len(ROWS)
    for i, a in enumerate(drawn):
        for b in drawn[i + 1 :]:
            assert not a.colliderect(b), (a, b)


def test_options__always_show_hitbox_draws_the_hit_shape(app):
    world = empty_stage(app, waves=load_level(resolve_level("1-picket")).waves[:1])
    world.player.invulnerable = 0.0
    frames(app)
    outline = (255, 60, 90)
    has = lambda: (pygame.surfarray.array3d(app.ctx.display.screen) == outline).all(axis=2).any()  # noqa: E731
    assert not has()
    app.ctx.set_options(always_hitbox=True)
    frames(app)
    assert has()


# --------------------------------------------------------------------------- pause
def test_pause__q_quits_to_the_title(app):
    empty_stage(app, waves=load_level(resolve_level("1-picket")).waves[:1])
    key(pygame.K_p)
    key(pygame.K_q)
    frames(app)
    assert isinstance(app.scene, Title) and app.play is None


# --------------------------------------------------------------------------- the stage's title card
class _Fonts:
    """A font that notes every text it renders (and renders it)."""

    def __init__(self, font):
        self.font, self.rendered = font, []

    def render(self, text, *args):
        self.rendered.append(text)
        return self.font.render(text, *args)


def test_title_card__shown_in_play_not_under_the_pause_screen(app):
    """The stage's title fades in over its first seconds; under the pause screen (whose
    PAUSED heading sits where the card does) it is not drawn."""
    app.start_run()
    frames(app, 30)
    fonts = app.ctx.renderer.big = _Fonts(app.ctx.renderer.big)
    frames(app)
    assert app.world.level.title in fonts.rendered and app.world.time < 3.0
    key(pygame.K_p)
    frames(app)
    assert isinstance(app.scene, Pause)
    fonts.rendered.clear()
    frames(app, 2)
    assert app.world.level.title not in fonts.rendered


# --------------------------------------------------------------------------- a tap between two steps
def tap(k):
    """A key pressed and let go within one frame's events (a quick tap, or a slow frame)."""
    key(k)
    pygame.event.post(pygame.event.Event(pygame.KEYUP, key=k, mod=0, unicode="", scancode=0))


def test_bomb__a_tap_shorter_than_a_step_still_bombs_once(app):
    app.start_run()
    frames(app, 90)
    bombs = app.world.player.bombs
    tap(pygame.K_x)
    frames(app, 5)
    assert app.world.progress.bombs_used == 1 and app.world.player.bombs == bombs - 1


def test_bomb__a_tap_on_the_pause_screen_does_not_go_off_on_resuming(app):
    app.start_run()
    frames(app, 90)
    key(pygame.K_p)
    frames(app)
    assert isinstance(app.scene, Pause)
    tap(pygame.K_x)
    frames(app)
    key(pygame.K_p)
    frames(app, 5)
    assert isinstance(app.scene, Play) and app.world.progress.bombs_used == 0


# --------------------------------------------------------------------------- the high-score table
def test_high_scores__columns_one_long_custom_level_does_not_shrink_its_row(app):
    """A score made on a level file shows the file's name, not its directories, and a long
    one is fitted in its own column: every row's score is drawn at the same size, right-aligned
    on one edge (a whole row used to be one string, shrunk to a tiny font by a long path)."""
    long_path = "/home/someone/levels/" + "a-very-long-custom-level-name" * 2 + ".toml"
    for i, level in enumerate(["1-picket", long_path, "2-gauntlet"]):
        app.ctx.scores.add(Entry("MAMMOTH", 900_000 - i * 1000, level, "2026-11-27"))
    drawn = []
    real = app.ctx.painter.text

    def text(s, y, *args, **kwargs):
        rect = real(s, y, *args, **kwargs)
        drawn.append((s, rect))
        return rect

    app.ctx.painter.text = text
    app.stack.reset(HighScoresScene(app.ctx))
    frames(app)
    scores = [r for s, r in drawn if s in {f"{e.score:,}" for e in app.ctx.scores.entries}]
    assert len(scores) == 3
    assert len({r.right for r in scores}) == 1 and len({r.height for r in scores}) == 1
    assert not any("/" in s for s, _ in drawn) and any(s.startswith("a-very-long") for s, _ in drawn)
    field = app.ctx.display.screen.get_rect()
    assert all(field.contains(r) for _, r in drawn)


def test_title__both_unusable_settings_files_are_said_in_full(tmp_path, capsys):
    """A broken options file and a broken controls file: the title names both (by file name;
    the first used to take both lines and end in "..."), and stderr has each in full."""
    data = tmp_path / "a-data-directory-with-a-rather-long-name"
    data.mkdir()
    (data / "options.json").write_text("garbage")
    (data / "controls.json").write_text('["not", "a", "table"]')  # unusable whole (one bad value keeps the rest)
    a = App(seed=1, audio=False, scores=HighScores(data / "scores.json"), data=data)
    drawn = []
    real = a.ctx.painter.text
    a.ctx.painter.text = lambda s, y, *args, **kw: drawn.append(s) or real(s, y, *args, **kw)
    frames(a)
    shown = " ".join(drawn)
    assert "options.json not used" in shown and "controls.json not used" in shown
    assert "default keys" in shown and not shown.endswith("...")
    err = capsys.readouterr().err
    assert str(data / "options.json") in err and str(data / "controls.json") in err
    pygame.quit()


def test_options__a_session_difficulty_is_not_saved_with_other_options(tmp_path):
    """``--difficulty lunatic`` plays this session on Lunatic; changing the music volume saves
    the options without it (the file kept "lunatic" once any option changed); choosing a
    difficulty saves that."""
    import json

    a = App(seed=1, audio=False, scores=HighScores(tmp_path / "s.json"), data=tmp_path, difficulty=Difficulty.LUNATIC)
    a.ctx.set_options(music=3)
    saved = json.loads((tmp_path / "options.json").read_text())
    assert saved["music"] == 3 and saved["difficulty"] == "normal" and a.ctx.difficulty is Difficulty.LUNATIC
    a.ctx.set_options(difficulty=Difficulty.HARD)
    assert json.loads((tmp_path / "options.json").read_text())["difficulty"] == "hard"
    assert a.ctx.difficulty is Difficulty.HARD
    pygame.quit()


def test_play__slow_motion_and_a_rotation_switch_are_said_on_screen(app):
    """F3 slows the game and F4 switches the rotation mode: the HUD says so while they are on
    (nothing on screen used to tell a player why the game had slowed)."""
    app.start_run()
    drawn = []
    real = app.ctx.painter.text
    app.ctx.painter.text = lambda s, y, *args, **kw: drawn.append(s) or real(s, y, *args, **kw)
    frames(app, 2)
    assert not any("SLOW" in s or "rotation" in s for s in drawn)
    key(pygame.K_F3)
    key(pygame.K_F4)
    frames(app)
    drawn.clear()
    frames(app)
    shown = " ".join(drawn)
    assert "SLOW MOTION (F3)" in shown and f"rotation {app.world.rotation} (F4)" in shown
    key(pygame.K_F3)
    key(pygame.K_F4)
    frames(app)
    drawn.clear()
    frames(app)
    assert not any("SLOW" in s or "rotation" in s for s in drawn)


# --------------------------------------------------------------------------- how to play, first run
def test_how_to_play__from_the_title_three_pages_naming_the_keys_bound(app):
    from broadsword.game.scenes.how_to_play import PAGES, HowToPlay

    app.ctx.controls.bindings.bind_key(Action.BOMB, pygame.K_v, replace=True)
    key(pygame.K_i)
    frames(app)
    assert isinstance(app.scene, HowToPlay)
    text = []
    for _ in PAGES:
        app.render()
        text.append(" ".join(app.ctx.painter.said))
        key(pygame.K_RIGHT)
        frames(app)
    body = " ".join(text)
    for topic in ("precise mode", "hit shape", "Graze", "Death-save", "P (red)", "Point", "Star", "continues", "bonus"):
        assert topic in body, topic
    assert "press V within" in body and "press X" not in body  # the bomb key bound now
    key(pygame.K_ESCAPE)
    frames(app)
    assert isinstance(app.scene, Title)


def test_first_run__the_title_and_the_first_stage_hint_then_never_again(app, tmp_path):
    assert not app.ctx.options.played
    app.render()
    assert any("how to play" in line for line in app.ctx.painter.said)
    app.start_run()
    frames(app)
    assert app.hint and app.ctx.options.played and '"played": true' in (tmp_path / "options.json").read_text()
    assert any(line.startswith("Hold Z / Space: fire") for line in app.ctx.painter.said)
    app.to_title()
    app.start_run()  # the second run: no hint
    frames(app)
    assert not app.hint and not any(line.startswith("Hold Z") for line in app.ctx.painter.said)


def test_title__names_the_stage_by_its_title(app):
    app.render()
    assert any(line.startswith("Stage: I. Outer Picket") for line in app.ctx.painter.said)
    assert not any("1-picket" in line for line in app.ctx.painter.said)


def test_high_scores__one_table_a_difficulty_with_the_stages_title(app):
    app.ctx.scores.add(Entry("EASY", 5000, "I. Outer Picket", "2026-11-27", Difficulty.EASY))
    app.ctx.scores.add(Entry("HARD", 900, "IV. Ion Storm", "2026-11-27", Difficulty.HARD))
    app.stack.reset(HighScoresScene(app.ctx, Difficulty.EASY))
    frames(app)
    app.render()
    assert (
        "EASY" in app.ctx.painter.said
        and "I. Outer Picket" in app.ctx.painter.said
        and "HARD" not in app.ctx.painter.said
    )
    key(pygame.K_RIGHT)  # Normal: empty
    frames(app)
    assert "none yet" in app.ctx.painter.said
    key(pygame.K_RIGHT)
    frames(app)
    assert (
        "HARD" in app.ctx.painter.said
        and "IV. Ion Storm" in app.ctx.painter.said
        and "EASY" not in app.ctx.painter.said
    )


def test_game_over__a_score_enters_its_difficultys_table_with_the_stages_title(app):
    app.ctx.set_options(difficulty=Difficulty.HARD)
    world = empty_stage(app, Run(0, Difficulty.HARD), waves=load_level(resolve_level("1-picket")).waves[:1])
    world.progress.continues_used = 3
    world.score.points = 12_340
    lose_every_life(world)
    frames(app, 2)
    assert isinstance(app.scene, GameOver) and app.scene.qualifies
    key(pygame.K_RETURN)
    frames(app)
    key(pygame.K_a, "a")
    key(pygame.K_RETURN)
    frames(app)
    (entry,) = app.ctx.scores.entries
    assert (entry.name, entry.level, entry.difficulty) == ("A", "I. Outer Picket", Difficulty.HARD)
