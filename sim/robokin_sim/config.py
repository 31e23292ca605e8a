"""The command line (DESIGN.md, "Simulator") and the settings it produces."""

from __future__ import annotations

import argparse
import dataclasses
import os
import sys
from typing import Optional, Sequence, Tuple

from .keys import KeyScript, parse_script
from .scenes import ROBOTS, SCENES, canonical

#: Modes each robot offers; the first is the default (from the table of scenes).
MODES = {name: entry.modes for name, entry in SCENES.items()}


@dataclasses.dataclass(frozen=True)
class Config:
    """Everything a run needs, validated.

    Attributes:
        robot: A name of :data:`robokin_sim.scenes.SCENES` (``"urdf"`` with ``urdf`` set).
        mode: The mode the scene starts in (and returns to on ``r``).
        headless: SDL's dummy video driver, no window, no sleeping.
        frames: Stop after this many frames (None: run until ``esc`` or the window closes).
        record: Path of a ``.gif`` or ``.mp4`` recording, or None.
        record_every: Keep one frame in this many for the recording.
        record_width: Width in pixels of the recorded frames (height keeps the window's aspect).
        log: Path of the CSV log, or None.
        screenshot: Path of a PNG of the last frame drawn, or None.
        keys: Scripted key presses (empty: none).
        avoid: 3-RRR singularity avoidance / RPR null-space joint-limit avoidance at the start.
        size: Window size in pixels (width, height).
        fps: Frames per second of the window (one simulation step per frame).
        urdf: The URDF file of ``--urdf`` (robot ``"urdf"``), or None.
        base: Its base link (None: the root link).
        tip: Its tip link (None: the end of the longest branch).
    """

    robot: str = "rrr3"
    mode: str = "free"
    headless: bool = False
    frames: Optional[int] = None
    record: Optional[str] = None
    record_every: int = 1
    record_width: Optional[int] = None
    log: Optional[str] = None
    screenshot: Optional[str] = None
    keys: KeyScript = KeyScript(())
    avoid: bool = True
    size: Tuple[int, int] = (800, 800)
    fps: int = 60
    urdf: Optional[str] = None
    base: Optional[str] = None
    tip: Optional[str] = None


#: Default width of GIF recordings (pixels).
GIF_WIDTH = 480

#: Frames of the headless demo: the approach to the clover and one full turn (39 + 628).
DEMO_FRAMES = 667


def has_display() -> bool:
    """Whether a window can be opened: on Linux and other X11/Wayland systems, DISPLAY or
    WAYLAND_DISPLAY must be set; other systems always have one."""
    if sys.platform.startswith(("win", "darwin")):
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


#: Largest --frames (about 190 days of a window at 60 frames/s): a typo cannot run for ever.
MAX_FRAMES = 1_000_000_000
#: Bounds of --record-width (pixels) and --fps.
RECORD_WIDTHS = (100, 4096)
MAX_FPS = 1000
MAX_RECORD_EVERY = 10_000


def _bounded_int(lower: int, upper: int):
    def convert(text: str) -> int:
        digits = text.strip()
        if not (digits.isdigit() or (digits[:1] in "+-" and digits[1:].isdigit())):
            raise argparse.ArgumentTypeError(f"expected a whole number in [{lower}, {upper}], got {text!r}")
        if len(digits.lstrip("+-0")) > len(str(upper)) or not lower <= int(digits) <= upper:
            raise argparse.ArgumentTypeError(f"must be a whole number in [{lower}, {upper}], got {text!r}")
        return int(digits)

    return convert


def _positive_int(text: str) -> int:
    return _bounded_int(1, MAX_FRAMES)(text)


def _output(suffixes):
    """An output path: not empty, not a directory, ending in one of ``suffixes`` (when given)."""

    def convert(text: str) -> str:
        if not text.strip():
            raise argparse.ArgumentTypeError("expected a file name, got an empty one")
        if os.path.isdir(text):
            raise argparse.ArgumentTypeError(f"{text!r} is a directory; expected a file name")
        if suffixes and os.path.splitext(text)[1].lower() not in suffixes:
            raise argparse.ArgumentTypeError(f"must end in {' or '.join(suffixes)}, got {text!r}")
        return text

    return convert


class _Parser(argparse.ArgumentParser):
    """argparse, with bad input reported on one line (and exit status 2, as argparse does)."""

    def error(self, message: str):
        # Control characters of the user's input are shown escaped: the message stays one line.
        message = "".join(c if c.isprintable() else repr(c)[1:-1] for c in message)
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def _size(text: str) -> Tuple[int, int]:
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected WIDTHxHEIGHT, e.g. 800x800, got {text!r}") from None
    if not (100 <= w <= 4096 and 100 <= h <= 4096):
        raise argparse.ArgumentTypeError(f"window size must be between 100 and 4096 pixels, got {text!r}")
    return w, h


def _keys(text: str) -> KeyScript:
    try:
        return parse_script(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _recording(text: str) -> str:
    return _output((".gif", ".mp4"))(text)


def _robot(text: str) -> str:
    return canonical(text)


def _modes_help() -> str:
    """``--mode``'s help: each distinct set of modes with the robots offering it."""
    groups: dict = {}
    for name in ROBOTS:
        groups.setdefault(SCENES[name].modes, []).append(name)
    parts = []
    for modes, names in groups.items():
        who = ", ".join(names) if len(names) <= 3 else "the serial arms"
        parts.append(f"{who}: {'|'.join(modes)} (default {modes[0]})")
    return "starting mode; " + "; ".join(parts)


def build_parser() -> argparse.ArgumentParser:
    serial = [n for n in ROBOTS if SCENES[n].renderer is SCENES["urdf"].renderer]
    parser = _Parser(
        prog="robokin-sim",
        description="pygame simulator of the 3-RRR planar parallel robot, the RPR arm and the serial arms of "
        "robokin.robots (or a URDF file).",
        epilog="Keys: h in the window lists them. 3-RRR: m free mode, o circle, p clover, arrows move, k/l rotate, "
        "s avoidance on/off. Serial arms: 1-9/tab select a joint, +/- jog it, arrows and pageup/pagedown move the "
        "tool (with shift: turn it), n next posture, e ellipsoid, f1-f4 views, mouse drag orbits, wheel zooms. "
        "All: space pause, r reset, h help, esc quit.",
    )
    parser.add_argument("--robot", type=_robot, choices=ROBOTS, metavar="ROBOT",
                        help=f"robot to simulate (default rrr3): rrr3, rpr, or a serial arm: {', '.join(serial)}")
    parser.add_argument("--urdf", metavar="FILE", help="a serial arm from a URDF file (instead of --robot)")
    parser.add_argument("--base", metavar="LINK", help="with --urdf: the chain's base link (default: the root link)")
    parser.add_argument("--tip", metavar="LINK",
                        help="with --urdf: the chain's tip link (default: the end of the longest branch)")
    parser.add_argument(
        "--mode",
        choices=sorted({m for modes in MODES.values() for m in modes}),
        help=_modes_help(),
    )
    parser.add_argument("--headless", action="store_true", help="no window (SDL dummy driver), run flat out")
    parser.add_argument(
        "--demo", action="store_true",
        help="what `make run` does: the window when a display exists; without one, one headless turn of "
        "the clover with a recording and a log under out/",
    )
    parser.add_argument("--frames", type=_positive_int, metavar="N", help="stop after N frames")
    parser.add_argument("--record", type=_recording, metavar="OUT", help="write a recording (.gif or .mp4)")
    parser.add_argument(
        "--record-every", type=_bounded_int(1, MAX_RECORD_EVERY), metavar="K", help="record one frame in K (default 1 for .mp4, 2 for .gif)"
    )
    parser.add_argument(
        "--record-width", type=_bounded_int(*RECORD_WIDTHS), metavar="PX",
        help="width of recorded frames, 100-4096 (default: the window's; .gif 480); the frame is drawn at that size"
    )
    parser.add_argument("--log", type=_output(()), metavar="OUT.csv", help="write one CSV row per simulation step")
    parser.add_argument("--screenshot", type=_output(()), metavar="OUT.png", help="save the last frame drawn as a PNG")
    parser.add_argument("--keys", type=_keys, default=KeyScript(()), metavar="SCRIPT",
                        help="scripted key presses, e.g. right*20,down*10,l*10 (hold KEY for N steps; "
                        "shift+up*5 holds two keys)")
    parser.add_argument("--no-avoid", dest="avoid", action="store_false",
                        help="3-RRR: singularity avoidance off; RPR and redundant arms: minimum-norm (no "
                        "null-space joint-limit avoidance)")
    parser.add_argument("--size", type=_size, default=(800, 800), metavar="WxH", help="window size (default 800x800)")
    parser.add_argument("--fps", type=_bounded_int(1, MAX_FPS), default=60,
                        help="frames per second of the window (default 60); one simulation step per frame")
    return parser


def parse_args(argv: Optional[Sequence[str]] = None) -> Config:
    """Parses the command line; exits with a usage message on bad input (argparse's behaviour)."""
    parser = build_parser()
    ns = parser.parse_args(argv)
    if ns.urdf is not None:
        if ns.robot is not None:
            parser.error("--urdf and --robot: choose one")
        ns.robot = "urdf"
        from .urdf import load

        try:
            load(ns.urdf, ns.base, ns.tip)
        except ValueError as exc:
            parser.error(f"--urdf {ns.urdf}: {exc}")
    elif ns.base is not None or ns.tip is not None:
        parser.error("--base and --tip go with --urdf FILE")
    ns.robot = ns.robot or "rrr3"
    if ns.demo and (ns.headless or not has_display()):
        ns.headless = True
        ns.mode = ns.mode or SCENES[ns.robot].demo_mode
        ns.frames = ns.frames or DEMO_FRAMES
        stem = os.path.join("out", f"robokin-sim-{ns.robot}-{ns.mode}")
        ns.record = ns.record or stem + ".gif"
        ns.log = ns.log or stem + ".csv"
        ns.record_every = ns.record_every or 4
    mode = ns.mode or MODES[ns.robot][0]
    if mode not in MODES[ns.robot]:
        parser.error(f"--mode {mode} is not a mode of --robot {ns.robot} (choose from {', '.join(MODES[ns.robot])})")
    gif = bool(ns.record) and ns.record.lower().endswith(".gif")
    every = ns.record_every or (2 if gif else 1)
    if gif and every < 2:
        # Browsers stretch GIF frames below their minimum delay (two hundredths of a second):
        # one step (1/60 s) per frame would play far slower than the run.
        parser.error("--record-every: a GIF keeps one frame in 2 steps or more (frames of at least 1/30 s)")
    width = ns.record_width or (min(GIF_WIDTH, ns.size[0]) if gif else None)
    return Config(
        robot=ns.robot,
        mode=mode,
        headless=ns.headless,
        frames=ns.frames,
        record=ns.record,
        record_every=every,
        record_width=width,
        log=ns.log,
        screenshot=ns.screenshot,
        keys=ns.keys,
        avoid=ns.avoid,
        size=ns.size,
        fps=ns.fps,
        urdf=ns.urdf,
        base=ns.base,
        tip=ns.tip,
    )
