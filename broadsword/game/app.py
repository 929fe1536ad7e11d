"""The game application: window, scenes, input, the fixed-step loop.

Loop (Game Programming Patterns, "Game Loop"): real time accumulates; the world steps in
fixed 1/60 s increments while enough has accumulated, at most ``MAX_CATCH_UP`` steps a
frame (a slow machine slows the game down instead of spiralling); then one render,
interpolated by the leftover fraction. :meth:`App.frame` takes the elapsed time as an
argument, so tests drive the real loop frame by frame with injected events.

Robustness: a level that fails to load (a broken file, a missing file, a ship with no
armature) never ends the game: its one-line error is shown on the title, where another
level can be picked. Minimising, hiding or leaving the window pauses play; the stall when
it comes back costs at most ``MAX_CATCH_UP`` steps; a tiny or missing window is not an error.
"""

from __future__ import annotations

import datetime
import sys
from dataclasses import dataclass
from pathlib import Path

import pygame

from ..data import DataError, check_level_sprites, list_levels, load_level, resolve_level
from ..data.recordings import file_sha256
from ..sim import DT, FIELD, Carry, Input, Pilot, World
from ..sim.replay import Recorder
from .audio import Audio
from .overlay import Overlay
from .render import Renderer
from .scores import Entry, HighScores
from .sprites import SpriteBank
from .text import wrap_text

MAX_CATCH_UP = 5
DEFAULT_SCALE = 1.25
SLOW_MOTION = 0.25
TITLE = "Broadsword"
HIDDEN_FPS = 20  # frame rate while the window is minimised or hidden (nothing to see, save the CPU)
ERROR_LINES = 7  # at most this many wrapped lines of a load error on the title (the rest: "...")
ERROR_TEXT = (255, 214, 200)
ERROR_WRAP = int(FIELD[0]) - 64  # px: the width of a load error's lines in its panel

#: Window events that pause play (as focus loss does) and that mean the window is out of sight.
PAUSE_EVENTS = {pygame.WINDOWFOCUSLOST, pygame.WINDOWMINIMIZED, pygame.WINDOWHIDDEN}
HIDE_EVENTS = {pygame.WINDOWMINIMIZED, pygame.WINDOWHIDDEN}
SHOW_EVENTS = {pygame.WINDOWRESTORED, pygame.WINDOWSHOWN, pygame.WINDOWEXPOSED, pygame.WINDOWMAXIMIZED,
               pygame.WINDOWFOCUSGAINED}

CONTROLS = [
    ("Arrows / WASD", "move"),
    ("Z / Space", "fire"),
    ("Shift", "precise mode: slow, shows your hit shape"),
    ("Esc / P", "pause"),
    ("M", "mute"),
    ("F1", "collision overlay"),
    ("F2", "step one frame (paused)"),
    ("F3", "slow motion"),
    ("F4", "rotation: lut / exact"),
    ("Gamepad", "stick / d-pad, A fire, B slow, Start pause"),
]

MOVE_KEYS = {
    pygame.K_LEFT: (-1, 0), pygame.K_a: (-1, 0), pygame.K_RIGHT: (1, 0), pygame.K_d: (1, 0),
    pygame.K_UP: (0, -1), pygame.K_w: (0, -1), pygame.K_DOWN: (0, 1), pygame.K_s: (0, 1),
}
FIRE_KEYS = {pygame.K_z, pygame.K_SPACE}
SLOW_KEYS = {pygame.K_LSHIFT, pygame.K_RSHIFT}
BOMB_KEYS = {pygame.K_x}


@dataclass
class Run:
    """A play-through: the level being played, and what carries to the next one."""

    level_index: int
    score: int = 0
    lives: int | None = None


class App:
    """Broadsword. ``App().run()`` plays until the window closes.

    Parameters
    ----------
    start_level : str, optional
        A shipped level's name or a level file to start from (default: the first). A file
        that is missing or broken is reported on the title (``error``), not raised.
    seed : int
    demo : bool
        Let the autopilot play (the title's attract mode, and ``broadsword --autopilot``).
    audio : bool
    scores : HighScores, optional
        Where high scores live (default: the user's data directory).
    """

    def __init__(self, start_level: str | None = None, seed: int = 0, demo: bool = False,
                 audio: bool = True, scores: HighScores | None = None, scale: float = DEFAULT_SCALE,
                 lab: tuple[int, int] | None = None):
        pygame.init()
        pygame.display.set_caption(TITLE)
        self.window = pygame.display.set_mode((int(FIELD[0] * scale), int(FIELD[1] * scale)), pygame.RESIZABLE)
        self.screen = pygame.Surface((int(FIELD[0]), int(FIELD[1])))
        self.bank = SpriteBank()
        self.bank.convert()
        self.renderer = Renderer(self.bank, seed)
        self.overlay = Overlay()
        self.audio = Audio(enabled=audio)
        self.scores = (scores or HighScores()).load()
        self.levels = list_levels()
        self.error: str | None = None  # the last level load failure, one line, shown on the title
        self.custom_level = None
        if start_level is not None and start_level not in self.levels:
            self.custom_level = start_level  # resolved again at each start, so a fixed file just works
            try:
                self.custom_level = str(resolve_level(start_level))
            except DataError as exc:
                self._report(exc)
        self.start_index = self.levels.index(start_level) if start_level in self.levels else 0
        self.seed, self.demo = seed, demo
        self.scene = "title"
        self.world: World | None = None
        self.run_state: Run | None = None
        self.keys: set[int] = set()
        self.pad = None
        self._init_pad()
        self.accumulator = 0.0
        self.slow_motion = False
        self.step_once = False
        self.fps = 60.0
        self.running = True
        self.hidden = False  # minimised or hidden: nothing to see
        self.name = ""
        self.message = self.scores.warning  # a set-aside scores file is reported on the title
        self.font = pygame.font.Font(None, 24)
        self.big = pygame.font.Font(None, 72)
        self.recorder: Recorder | None = None  # the level in play, as a recording
        self.lab = None
        if lab is not None:  # the benchmark's scene, live (broadsword --lab)
            from .lab import Lab

            self.lab = Lab(*lab, seed=seed)
            self.screen = pygame.Surface(Lab.size)
            self.overlay.visible = True
            self.scene = "lab"
            self.lab_paused = False

    # ------------------------------------------------------------------ the loop
    def run(self) -> None:
        clock = pygame.time.Clock()
        while self.running:
            dt = clock.tick(HIDDEN_FPS if self.hidden else 120) / 1000.0
            self.fps = clock.get_fps() or self.fps
            self.frame(dt)
        pygame.quit()

    def frame(self, dt: float) -> int:
        """Handle events, step the world by the elapsed ``dt`` seconds, render. Returns steps taken.

        At most ``MAX_CATCH_UP`` steps whatever ``dt`` is (a 30 s stall after the window
        comes back costs five steps, and the backlog beyond one step is dropped); a
        negative or nan ``dt`` counts as 0. Always renders once.
        """
        if not dt >= 0.0:
            dt = 0.0
        for event in pygame.event.get():
            self.handle(event)
        steps = 0
        if self.scene == "lab":
            if not self.lab_paused:
                self.lab.step()
                steps = 1
        elif self.scene == "play" and self.world is not None:
            self.accumulator += dt * (SLOW_MOTION if self.slow_motion else 1.0)
            while self.accumulator >= DT and steps < MAX_CATCH_UP:
                self._step()
                steps += 1
                self.accumulator -= DT
                if self.scene != "play":
                    break
            if steps == MAX_CATCH_UP:
                self.accumulator = min(self.accumulator, DT)  # drop the backlog: slow down, don't spiral
        elif self.scene == "paused" and self.step_once:
            self.step_once = False
            self._step(paused=True)
            steps = 1
        self.render()
        return steps

    def _step(self, paused: bool = False) -> None:
        world = self.world
        inp = self.pilot(world) if self.demo else self.current_input()
        ev = world.step(inp)
        self.recorder.stepped(inp)
        self.renderer.on_events(ev)
        if ev.shots:
            self.audio.play("shot")
        if ev.grazes:
            self.audio.play("graze")
        if ev.damaged:
            self.audio.play("hit")
        if ev.kills:
            self.audio.play("big_explosion" if ev.boss_killed else "explosion")
        if ev.player_hit:
            self.audio.play("player_hit")
        if ev.game_over:
            self._end_run()
        elif ev.level_complete and not paused:
            self.scene = "complete"

    # ------------------------------------------------------------------ input
    def _init_pad(self) -> None:
        try:
            pygame.joystick.init()
            if pygame.joystick.get_count():
                self.pad = pygame.joystick.Joystick(0)
        except pygame.error:
            self.pad = None

    def current_input(self) -> Input:
        dx = sum(MOVE_KEYS[k][0] for k in self.keys if k in MOVE_KEYS)
        dy = sum(MOVE_KEYS[k][1] for k in self.keys if k in MOVE_KEYS)
        fire = bool(self.keys & FIRE_KEYS)
        slow = bool(self.keys & SLOW_KEYS)
        if self.pad is not None:
            try:
                ax, ay = self.pad.get_axis(0), self.pad.get_axis(1)
                hx, hy = self.pad.get_hat(0) if self.pad.get_numhats() else (0, 0)
                dx += (ax > 0.35) - (ax < -0.35) + hx
                dy += (ay > 0.35) - (ay < -0.35) - hy
                fire |= bool(self.pad.get_button(0))
                slow |= self.pad.get_numbuttons() > 1 and bool(self.pad.get_button(1))
            except pygame.error:
                self.pad = None
        clamp = lambda v: max(-1, min(1, v))  # noqa: E731
        bomb = bool(self.keys & BOMB_KEYS)
        if self.pad is not None:
            try:
                bomb |= self.pad.get_numbuttons() > 2 and bool(self.pad.get_button(2))
            except pygame.error:
                self.pad = None
        return Input(clamp(dx), clamp(dy), fire, slow, bomb)

    def handle(self, event: pygame.event.Event) -> None:
        if event.type == pygame.QUIT:
            self.running = False
        elif event.type == pygame.KEYDOWN:
            self.keys.add(event.key)
            self._key(event)
        elif event.type == pygame.KEYUP:
            self.keys.discard(event.key)
        elif event.type == pygame.JOYBUTTONDOWN and event.button == 7:  # Start
            self._toggle_pause()
        elif event.type == pygame.JOYDEVICEADDED:
            self._init_pad()
        elif event.type in PAUSE_EVENTS:
            self.keys.clear()  # keys released while away never send their KEYUP to us
            self.hidden |= event.type in HIDE_EVENTS
            if self.scene == "play":
                self._toggle_pause()
        elif event.type in SHOW_EVENTS:
            self.hidden = False

    def _key(self, event) -> None:
        k = event.key
        if k == pygame.K_m:
            self.audio.toggle_mute()
            return
        if self.scene == "name":
            self._name_key(event)
            return
        if self.scene == "lab":
            self._lab_key(k)
            return
        if k == pygame.K_F1:
            self.overlay.visible = not self.overlay.visible
        elif k == pygame.K_F3:
            self.slow_motion = not self.slow_motion
        elif k == pygame.K_F4 and self.world is not None:
            self.world.set_rotation("exact" if self.world.rotation == "lut" else "lut")
        if self.scene == "title":
            if k in (pygame.K_RETURN, pygame.K_z, pygame.K_SPACE):
                self.audio.play("select")
                self.start_run()
            elif k in (pygame.K_LEFT, pygame.K_RIGHT):
                if self.custom_level is not None:
                    self.custom_level = None  # back to the shipped levels
                else:
                    self.start_index = (self.start_index + (1 if k == pygame.K_RIGHT else -1)) % len(self.levels)
            elif k == pygame.K_h:
                self.scene = "scores"
            elif k == pygame.K_ESCAPE:
                self.running = False
        elif self.scene == "play":
            if k in (pygame.K_ESCAPE, pygame.K_p):
                self._toggle_pause()
        elif self.scene == "paused":
            if k in (pygame.K_ESCAPE, pygame.K_p):
                self._toggle_pause()
            elif k == pygame.K_F2:
                self.step_once = True
            elif k == pygame.K_q:
                self.scene = "title"
        elif self.scene == "complete":
            if k in (pygame.K_RETURN, pygame.K_z, pygame.K_SPACE):
                self.next_level()
        elif self.scene in ("gameover", "scores", "victory"):
            if k in (pygame.K_RETURN, pygame.K_z, pygame.K_SPACE, pygame.K_ESCAPE):
                self.scene = "title"

    def _lab_key(self, k) -> None:
        from .lab import SCALES

        lab = self.lab
        if k == pygame.K_F1:
            self.overlay.visible = not self.overlay.visible
        elif k == pygame.K_F4:
            lab.toggle_rotation()
        elif k == pygame.K_t:
            lab.next_mix()
        elif k in (pygame.K_LEFT, pygame.K_RIGHT):
            now = (lab.scene.enemies, lab.scene.bullets)
            i = SCALES.index(now) if now in SCALES else 0
            lab.reset(*SCALES[(i + (1 if k == pygame.K_RIGHT else -1)) % len(SCALES)])
        elif k == pygame.K_SPACE:
            self.lab_paused = not self.lab_paused
        elif k == pygame.K_ESCAPE:
            self.running = False

    def _toggle_pause(self) -> None:
        if self.scene == "play":
            self.scene = "paused"
            self.audio.play("pause")
        elif self.scene == "paused":
            self.scene = "play"
            self.accumulator = 0.0

    def _name_key(self, event) -> None:
        if event.key == pygame.K_RETURN:
            self._save_score(self.name.strip() or "PILOT")
        elif event.key == pygame.K_BACKSPACE:
            self.name = self.name[:-1]
        elif event.unicode and event.unicode.isprintable() and len(self.name) < 12:
            self.name += event.unicode.upper()

    # ------------------------------------------------------------------ runs and levels
    def start_run(self, index: int | None = None) -> bool:
        """Start playing (the custom level, else shipped level ``index``, default the chosen one).

        Returns False, and stays on the title showing the error, if the level fails to load.
        """
        self.run_state = Run(self.start_index if index is None else index)
        return self._load_level()

    def _load_level(self) -> bool:
        """Load the run's level into a new world and play it; on failure, back to the title."""
        run = self.run_state
        try:
            path = resolve_level(self.custom_level or self.levels[run.level_index])
            level = load_level(path)
            check_level_sprites(level, self.bank.armatures)  # names the field of an unknown sprite
            carry = Carry(run.score, run.lives)
            world = World(level, self.bank.armatures, seed=self.seed + run.level_index, carry=carry)
        except DataError as exc:
            self._report(exc)
            self.world, self.run_state = None, None
            self.accumulator = 0.0
            self.scene = "title"
            return False
        self.world = world
        self.pilot = Pilot()  # the demo's player, fresh for each level
        self.recorder = Recorder(world, self.custom_level or self.levels[run.level_index], file_sha256(path))
        self.error = None
        self.accumulator = 0.0
        self.scene = "play"
        return True

    def _report(self, exc: DataError) -> None:
        """A level failed to load: keep its one-line error for the title, and say it on stderr."""
        self.error = str(exc)
        print(f"broadsword: {exc}", file=sys.stderr)

    def next_level(self) -> None:
        run, w = self.run_state, self.world
        run.score, run.lives = w.score.points, w.player.lives
        if self.custom_level is None and run.level_index + 1 < len(self.levels):
            run.level_index += 1
            self._load_level()
        else:
            self._end_run(victory=True)

    def _end_run(self, victory: bool = False) -> None:
        score = self.world.score.points if self.world else 0
        self.final = (score, victory)
        if self.scores.qualifies(score) and score > 0:
            self.name = ""
            self.scene = "name"
        else:
            self.scene = "victory" if victory else "gameover"

    def _save_score(self, name: str) -> None:
        level = self.world.level.name if self.world else ""
        self.scores.add(Entry(name, self.final[0], level, datetime.date.today().isoformat()))
        try:
            warning = self.scores.save()
            if warning:
                self.message = warning
        except OSError as exc:
            self.message = f"could not save high scores: {exc}"
        self.scene = "scores"

    # ------------------------------------------------------------------ drawing
    def render(self) -> None:
        s = self.screen
        if self.scene == "lab":
            self.lab.draw(s)
            if self.overlay.visible and self.lab.last is not None:
                self.overlay.draw(s, self.lab.last, self.fps, paused=self.lab_paused)
            sc = self.lab.scene
            self._text(f"LAB: {sc.enemies} ships, {sc.bullets} bullets, {'+'.join(self.lab.pipeline.tiers)}",
                       s.get_height() - 34, x=s.get_width() / 2, colour=(255, 230, 170))
            self._text("T tiers   Left/Right scale   F1 overlay   F4 rotation   Space pause   Esc quit",
                       s.get_height() - 14, x=s.get_width() / 2, colour=(200, 210, 240))
            self._present()
            return
        if self.world is not None and self.scene in ("play", "paused", "complete", "gameover", "name", "victory"):
            alpha = self.accumulator / DT if self.scene == "play" else 1.0
            slow = (bool(self.keys & SLOW_KEYS) or self.current_input().slow) and not self.demo
            self.renderer.draw(s, self.world, min(alpha, 1.0), show_armature=slow)
            if self.overlay.visible:
                self.overlay.draw(s, self.world.collision and self.world.collision.result, self.fps,
                                  paused=self.scene == "paused")
        else:
            self.renderer.tick += 1
            self.renderer.background(s, self.renderer.tick)
        getattr(self, f"_draw_{self.scene}", lambda: None)()
        self._present()

    def _present(self) -> None:
        """Scale the playfield into the window, keeping its aspect (black bars, never stretched).

        A window of any size down to 1 x 1 gets the field scaled to at least 1 x 1 pixel; no
        window at all (or a zero-sized one) skips presenting, the frame is still drawn.
        """
        win = pygame.display.get_surface()
        if win is None:
            return
        ww, wh = win.get_size()
        if ww <= 0 or wh <= 0:
            return
        fw, fh = self.screen.get_size()
        k = min(ww / fw, wh / fh)
        size = (max(1, int(fw * k)), max(1, int(fh * k)))
        win.fill((0, 0, 0))
        win.blit(pygame.transform.scale(self.screen, size), ((ww - size[0]) // 2, (wh - size[1]) // 2))
        pygame.display.flip()

    def _text(self, text, y, font=None, colour=(230, 236, 255), x=None):
        img = (font or self.font).render(text, True, colour)
        rect = img.get_rect(center=(FIELD[0] / 2 if x is None else x, y))
        self.screen.blit(img, rect)

    def _lines(self, text: str, width: int, limit: int) -> list[str]:
        """``text`` wrapped to ``width`` px in the small font, at most ``limit`` lines; cut text ends in "..."."""
        lines = wrap_text(text, self.font, width)
        if len(lines) > limit:
            lines = lines[:limit]
            while lines[-1] and self.font.size(lines[-1] + "...")[0] > width:
                lines[-1] = lines[-1][:-1]
            lines[-1] += "..."
        return lines

    def _veil(self, a=150):
        v = pygame.Surface(self.screen.get_size(), pygame.SRCALPHA)
        v.fill((0, 0, 0, a))
        self.screen.blit(v, (0, 0))

    def _draw_title(self) -> None:
        self._text("BROADSWORD", 120, self.big, (255, 220, 140))
        self._text("polygon-armature shoot-'em-up", 162, colour=(160, 180, 220))
        ship = pygame.transform.scale_by(self.bank.images["player"], 2)
        self.screen.blit(ship, ship.get_rect(center=(FIELD[0] / 2, 222)))
        if self.custom_level:
            name, hint = Path(self.custom_level).name, "   (Left/Right: shipped levels)"
        else:
            name, hint = self.levels[self.start_index], "   (Left/Right to choose)"
        while len(name) > 8 and self.font.size(f"Start: {name}{hint}")[0] > FIELD[0] - 20:
            name = "..." + name[4:]  # a long file name loses its start, keeps its end
        self._text(f"Start: {name}{hint}", 282, colour=(255, 240, 200))
        self._text("Enter or Z to play   H high scores   Esc quit", 306, colour=(200, 210, 240))
        if self.error:
            self._draw_error()
        else:
            self._draw_controls()
        if self.scores.entries:
            best = self.scores.entries[0]
            self._text(f"High score {best.score:,}  {best.name}", 570, colour=(150, 255, 200))
        if self.message:
            for i, line in enumerate(self._lines(self.message, int(FIELD[0]) - 20, 2)):
                self._text(line, 600 + 20 * i, colour=(255, 140, 120))

    def _draw_controls(self) -> None:
        for i, (key, what) in enumerate(CONTROLS):
            y = 350 + 20 * i
            k = self.font.render(key, True, (255, 220, 140))
            self.screen.blit(k, k.get_rect(midright=(150, y)))
            d = self.font.render(what, True, (200, 210, 240))
            self.screen.blit(d, d.get_rect(midleft=(166, y)))

    def _draw_error(self) -> None:
        """The level load error, wrapped, in a panel where the controls list goes (y 334 to at most 546).

        At most ``ERROR_LINES`` lines of ``ERROR_WRAP`` px; a longer error ends in "...".
        """
        lines = self._lines(self.error, ERROR_WRAP, ERROR_LINES)
        panel = pygame.Rect(20, 334, ERROR_WRAP + 24, 72 + 20 * len(lines))
        pygame.draw.rect(self.screen, (44, 12, 18), panel)
        pygame.draw.rect(self.screen, (255, 110, 110), panel, 1)
        self._text("The level could not be loaded", panel.y + 18, colour=(255, 140, 120))
        for i, line in enumerate(lines):
            img = self.font.render(line, True, ERROR_TEXT)
            self.screen.blit(img, img.get_rect(midleft=(panel.x + 12, panel.y + 42 + 20 * i)))
        self._text("Enter: try again   Left/Right: another level", panel.bottom - 16, colour=(200, 210, 240))

    def _draw_paused(self) -> None:
        self._veil(110)
        self._text("PAUSED", 280, self.big)
        self._text("Esc / P resume   F2 step a frame   Q quit to title", 330)

    def _draw_complete(self) -> None:
        self._veil()
        self._text("LEVEL COMPLETE", 260, self.big, (150, 255, 200))
        self._text(f"Score {self.world.score.points:,}   Grazes {self.world.score.grazes}", 315)
        self._text("Enter to continue", 350)

    def _draw_gameover(self) -> None:
        self._veil()
        self._text("GAME OVER", 270, self.big, (255, 110, 110))
        self._text(f"Score {self.final[0]:,}", 320)
        self._text("Enter for the title", 350)

    def _draw_victory(self) -> None:
        self._veil()
        self._text("BROADSWORD FALLS", 270, self.big, (255, 220, 140))
        self._text(f"Final score {self.final[0]:,}", 320)

    def _draw_name(self) -> None:
        self._veil()
        self._text("NEW HIGH SCORE", 240, self.big, (255, 220, 140))
        self._text(f"{self.final[0]:,}", 290)
        self._text(f"Name: {self.name}_", 330, colour=(255, 240, 200))
        self._text("type, then Enter", 360)

    def _draw_scores(self) -> None:
        self._veil()
        self._text("HIGH SCORES", 110, self.big, (255, 220, 140))
        for i, e in enumerate(self.scores.entries):
            self._text(f"{i + 1:>2}. {e.name:<12} {e.score:>10,}  {e.level}", 170 + 28 * i)
        if not self.scores.entries:
            self._text("none yet", 200)
        if self.message:  # e.g. a save that failed: say so here, where the player is looking
            for i, line in enumerate(self._lines(self.message, ERROR_WRAP, 3)):
                self._text(line, 540 + 20 * i, colour=(255, 140, 120))
        self._text("Enter for the title", 500)
