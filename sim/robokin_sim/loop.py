"""The fixed-timestep game loop: input, one simulation step, drawing, recording, logging.

Each frame advances the scene by exactly one step of ``DT`` seconds. With a window the loop is
paced at ``fps`` frames per second; headless it runs as fast as it can and never sleeps. Nothing
is printed inside the loop; :func:`run` returns what it wrote and :func:`robokin_sim.__main__.main`
reports it.

A recording gets one frame per simulation step (none while paused), drawn by a renderer of its
own at the recording's size: its text is as large as the window's, and it carries neither the
window's frames-per-second row nor the REC mark the window shows while recording.
"""

from __future__ import annotations

import dataclasses
import os
import sys
import time
from typing import Iterator, Optional

from .config import Config
from .keys import HELD_KEYS, NO_INPUT, Input
from .outputs import save_png, surface_rgb
from .scene import DT
from .scenes import entry
from .signals import deferred, requested

#: Frames a headless run lasts when neither --frames nor --keys says: about one clover turn
#: (628 steps) with its approach.
DEFAULT_HEADLESS_FRAMES = 700


@dataclasses.dataclass
class RunResult:
    """What a run did."""

    frames: int
    steps: int
    record: Optional[str]
    log: Optional[str]
    screenshot: Optional[str]
    seconds: float
    scene: object
    stopped: Optional[int] = None  # the signal that stopped the run (its files are whole), or None


def make_scene(config: Config):
    """The scene for ``config.robot`` in ``config.mode`` (from the table of scenes)."""
    return entry(config.robot).scene(config)


def record_size(config: Config, window) -> tuple:
    """Size (w, h) of the recorded frames: ``record_width`` wide (the window's width when None)
    with the window's aspect; even for MP4 (yuv420p)."""
    w, h = window
    if config.record_width:
        w, h = config.record_width, max(2, round(h * config.record_width / w))
    if config.record and config.record.lower().endswith(".mp4"):
        w, h = max(2, w - w % 2), max(2, h - h % 2)
    return int(w), int(h)


def make_renderer(robot: str, size):
    """The renderer drawing ``robot``'s scene states on a surface of ``size`` pixels."""
    return entry(robot).renderer(size)


def _frame_budget(config: Config) -> Optional[int]:
    if config.frames is not None:
        return config.frames
    if config.headless:
        return config.keys.frames if config.keys else DEFAULT_HEADLESS_FRAMES
    return None


class _Keyboard:
    """Turns pygame's events into :class:`Input`; also reports quit requests, mouse drags (pixels
    moved with a button down) and wheel turns."""

    def __init__(self, pygame) -> None:
        self.pg = pygame
        k = pygame
        self.names = {
            k.K_m: "m", k.K_o: "o", k.K_p: "p", k.K_LEFT: "left", k.K_RIGHT: "right", k.K_UP: "up",
            k.K_DOWN: "down", k.K_k: "k", k.K_l: "l", k.K_s: "s", k.K_SPACE: "space", k.K_r: "r",
            k.K_h: "h", k.K_ESCAPE: "esc", k.K_TAB: "tab", k.K_PAGEUP: "pageup", k.K_PAGEDOWN: "pagedown",
            k.K_n: "n", k.K_e: "e", k.K_v: "v", k.K_F1: "f1", k.K_F2: "f2", k.K_F3: "f3", k.K_F4: "f4",
            k.K_PLUS: "plus", k.K_EQUALS: "plus", k.K_KP_PLUS: "plus", k.K_MINUS: "minus", k.K_KP_MINUS: "minus",
        }
        for digit in range(1, 10):
            self.names[getattr(k, f"K_{digit}")] = str(digit)
            self.names[getattr(k, f"K_KP{digit}")] = str(digit)
        self.codes: dict = {}
        for code, name in self.names.items():
            self.codes.setdefault(name, []).append(code)
        self.quit = False

    def poll(self) -> Input:
        pressed = set()
        drag_x = drag_y = 0
        wheel = 0
        for event in self.pg.event.get():
            if event.type == self.pg.QUIT:
                self.quit = True
            elif event.type == self.pg.KEYDOWN and event.key in self.names:
                pressed.add(self.names[event.key])
            elif event.type == self.pg.MOUSEMOTION and any(event.buttons):
                drag_x += event.rel[0]
                drag_y += event.rel[1]
            elif event.type == self.pg.MOUSEWHEEL:
                wheel += event.y
        down = self.pg.key.get_pressed()
        held = {name for name in HELD_KEYS if any(down[c] for c in self.codes.get(name, ()))} | pressed
        if self.pg.key.get_mods() & self.pg.KMOD_SHIFT:
            held.add("shift")
        return Input(pressed=frozenset(pressed), held=frozenset(held), drag=(drag_x, drag_y), wheel=wheel)


def _start_pygame(config: Config):
    """pygame with its display and fonts up: the dummy video driver headless, and SDL kept off the
    signals (SDL would turn SIGINT and SIGTERM into a quit event that a headless run never reads:
    signals are Python's, robokin_sim.signals)."""
    if config.headless:
        # Must be set before pygame initialises its display.
        os.environ["SDL_VIDEODRIVER"] = "dummy"
        os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    os.environ["SDL_NO_SIGNAL_HANDLERS"] = "1"
    import pygame

    pygame.display.init()
    pygame.font.init()
    return pygame


def _open_screen(pygame, config: Config, scene):
    """The window, or headless an off-screen surface of the same size."""
    if config.headless:
        return pygame.Surface(config.size)
    screen = pygame.display.set_mode(config.size, pygame.RESIZABLE)
    pygame.display.set_caption(f"robokin-sim: {getattr(scene, 'title', config.robot)}")
    return screen


def _apply(inp: Input, scene, hud) -> bool:
    """The frame's keys and pointer: to the HUD (pause, help) and the scene. False on Esc (quit)."""
    if "esc" in inp.pressed:
        return False
    if "space" in inp.pressed:
        hud.paused = not hud.paused
    if "h" in inp.pressed:
        hud.help = not hud.help
    for key in sorted(inp.pressed):
        scene.press(key, inp.held)
    if inp.drag != (0, 0) or inp.wheel:
        scene.pointer(inp.drag, inp.wheel)
    return True


class _Outputs:
    """The recording and the log of a run: each written under its name when the run ends (its
    frame budget, esc, the window's close button or a signal: close); a run cut short by an error
    discards both, leaving no temporary file."""

    def __init__(self) -> None:
        self.recorder = self.log = None
        self.surface = self.renderer = None

    def open(self, pygame, config: Config, scene, screen_size) -> None:
        from .csvlog import CsvLog
        from .recording import Recorder

        if config.record:
            size = record_size(config, screen_size)
            self.recorder = Recorder(config.record, fps=1.0 / DT, every=config.record_every, width=size[0])
            self.surface = pygame.Surface(size)
            self.renderer = make_renderer(config.robot, size)
        self.log = CsvLog(config.log, scene.columns, flush=not config.headless) if config.log else None
        for kept in self.log.kept if self.log is not None else ():
            # Before the loop starts (nothing is printed inside it): one line per file kept.
            try:
                print(f"robokin-sim: kept the rows a killed run had written for {config.log} in {kept}",
                      file=sys.stderr, flush=True)
            except OSError:  # no terminal to say it on: the file is kept all the same
                pass

    def log_step(self, scene) -> None:
        if self.log is not None:
            self.log.write(scene.row())

    def record_step(self, pygame, scene, hud, state) -> None:
        """One recording frame per simulation step, when the recording wants it (state: the scene's
        state if already taken this frame)."""
        if self.recorder is None:
            return
        if not self.recorder.wants():
            self.recorder.skip()
            return
        state = state or scene.state()
        self.renderer.draw(self.surface, state, dataclasses.replace(hud, fps=None, recording=False))
        self.recorder.add(surface_rgb(pygame, self.surface))

    def discard(self) -> None:
        if self.recorder is not None:
            self.recorder.discard()
        if self.log is not None:
            self.log.discard()

    def close(self) -> tuple:
        """(recording, log) written, or None for each not asked for."""
        record = log = None
        try:
            if self.recorder is not None:
                record = self.recorder.close()
        finally:
            if self.log is not None:
                log = self.log.close()
        return record, log


def run(config: Config, render: bool = True) -> RunResult:
    """Runs the simulator.

    Args:
        config: The parsed command line.
        render: Draw every frame (always true with a window or a recording; headless runs may
            turn it off to measure or log the kinematics alone).

    Returns:
        RunResult with the frames and steps run, the files written and the signal that stopped the
        run, if one did (under :func:`robokin_sim.signals.stop_on_signals`; its files are whole).
    """
    pygame = _start_pygame(config)
    try:
        scene = make_scene(config)
        screen = _open_screen(pygame, config, scene)
        # From here a signal only asks the loop to stop after the frame it comes in: the log, the
        # recording and the screenshot are then finished whole, as by esc (robokin_sim.signals).
        with deferred():
            return _Session(pygame, config, scene, screen, render).run()
    finally:
        pygame.display.quit()


class _Session:
    """One run's loop over frames: input, one simulation step, drawing, recording, logging."""

    def __init__(self, pygame, config: Config, scene, screen, render: bool) -> None:
        from .render_common import Hud

        self.pg, self.config, self.scene, self.screen = pygame, config, scene, screen
        # The window is drawn every frame; headless, the screen only when asked (render) and not
        # recording (the recording has its own frames), and once at the end for a screenshot.
        self.draw_screen = not config.headless or (render and not config.record)
        wanted = self.draw_screen or config.screenshot
        self.renderer = make_renderer(config.robot, screen.get_size()) if wanted else None
        self.keyboard = None if config.headless else _Keyboard(pygame)
        self.script: Iterator[Input] = config.keys.inputs()
        self.clock = pygame.time.Clock()
        self.hud = Hud(recording=bool(config.record))
        self.outputs = _Outputs()
        self.frames = 0
        self.drawn = False

    def run(self) -> RunResult:
        started = time.perf_counter()
        try:
            self.outputs.open(self.pg, self.config, self.scene, self.screen.get_size())
            stopped = self._loop()
            shot = self._screenshot()
        except BaseException:
            # An error (or Ctrl-C outside robokin-sim's handlers): the recording and the log would be
            # cut short, so neither is written under its name.
            self.outputs.discard()
            raise
        record, log = self.outputs.close()
        return RunResult(frames=self.frames, steps=self.scene.steps, record=record, log=log, screenshot=shot,
                         seconds=time.perf_counter() - started, scene=self.scene, stopped=stopped)

    def _loop(self) -> Optional[int]:
        """Frames until the budget, esc, the window's close or a signal (returned, else None)."""
        budget = _frame_budget(self.config)
        last = time.perf_counter()
        while budget is None or self.frames < budget:
            if requested() is not None:
                return requested()
            inp = next(self.script, NO_INPUT)
            if self.keyboard is not None:
                live = self.keyboard.poll()
                inp = Input(inp.pressed | live.pressed, inp.held | live.held, live.drag, live.wheel)
                if self.keyboard.quit:
                    break
            if not _apply(inp, self.scene, self.hud):
                break
            self._frame(inp)
            if self.keyboard is not None:
                self.pg.display.flip()
                self.clock.tick(self.config.fps)
                self.hud.fps = self.clock.get_fps()
            elif self.frames % 30 == 0:
                now = time.perf_counter()
                self.hud.fps = 30.0 / max(now - last, 1e-9)
                last = now
        return None

    def _frame(self, inp: Input) -> None:
        """One frame: a step (unless paused) logged, the screen drawn, a recording frame."""
        scene, hud = self.scene, self.hud
        stepped = not hud.paused
        if stepped:
            scene.step(inp.held)
            self.outputs.log_step(scene)
        state = None
        if self.draw_screen:
            if self.keyboard is not None and self.screen.get_size() != self.pg.display.get_surface().get_size():
                self.screen = self.pg.display.get_surface()
            state = scene.state()
            self.renderer.draw(self.screen, state, hud)
            self.drawn = True
        if stepped:
            self.outputs.record_step(self.pg, scene, hud, state)
        self.frames += 1

    def _screenshot(self) -> Optional[str]:
        """The PNG of the last frame drawn (drawn now if none was), when asked for."""
        if not (self.config.screenshot and self.renderer is not None):
            return None
        if not self.drawn:
            self.renderer.draw(self.screen, self.scene.state(), dataclasses.replace(self.hud, recording=False))
        return save_png(self.pg, self.screen, self.config.screenshot)
