"""The command line (DESIGN.md, "Simulator") and the settings it produces."""

from __future__ import annotations

import argparse
import dataclasses
import os
import sys
from typing import Optional, Sequence, Tuple

from .keys import KeyScript, parse_script

#: Modes each robot offers; the first is the default.
MODES = {"rrr3": ("free", "circle", "clover"), "rpr": ("line", "free")}


@dataclasses.dataclass(frozen=True)
class Config:
    """Everything a run needs, validated.

    Attributes:
        robot: ``"rrr3"`` or ``"rpr"``.
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


#: Frames of the headless demo: the approach to the clover and one full turn (39 + 628).
DEMO_FRAMES = 667


def has_display() -> bool:
    """Whether a window can be opened: on Linux and other X11/Wayland systems, DISPLAY or
    WAYLAND_DISPLAY must be set; other systems always have one."""
    if sys.platform.startswith(("win", "darwin")):
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    return value


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
    if os.path.splitext(text)[1].lower() not in (".gif", ".mp4"):
        raise argparse.ArgumentTypeError(f"recording must end in .gif or .mp4, got {text!r}")
    return text


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="robokin-sim",
        description="pygame simulator of the 3-RRR planar parallel robot and the RPR arm (robokin).",
        epilog="Keys: m free mode, o circle, p clover (RPR: o/p the line), arrows move, k/l rotate, "
        "s avoidance on/off, space pause, r reset, h help, esc quit.",
    )
    parser.add_argument("--robot", choices=sorted(MODES), default="rrr3", help="robot to simulate (default rrr3)")
    parser.add_argument(
        "--mode",
        choices=sorted({m for modes in MODES.values() for m in modes}),
        help="starting mode: rrr3 free|circle|clover (default free), rpr line|free (default line)",
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
        "--record-every", type=_positive_int, metavar="K", help="record one frame in K (default 1 for .mp4, 2 for .gif)"
    )
    parser.add_argument(
        "--record-width", type=_positive_int, metavar="PX", help="width of recorded frames (default: window; .gif 400)"
    )
    parser.add_argument("--log", metavar="OUT.csv", help="write one CSV row per simulation step")
    parser.add_argument("--screenshot", metavar="OUT.png", help="save the last frame drawn as a PNG")
    parser.add_argument("--keys", type=_keys, default=KeyScript(()), metavar="SCRIPT",
                        help="scripted key presses, e.g. right*20,down*10,l*10 (hold KEY for N steps)")
    parser.add_argument("--no-avoid", dest="avoid", action="store_false",
                        help="3-RRR: singularity avoidance off; RPR: minimum-norm (no joint-limit avoidance)")
    parser.add_argument("--size", type=_size, default=(800, 800), metavar="WxH", help="window size (default 800x800)")
    parser.add_argument("--fps", type=_positive_int, default=60, help="frames per second with a window (default 60)")
    return parser


def parse_args(argv: Optional[Sequence[str]] = None) -> Config:
    """Parses the command line; exits with a usage message on bad input (argparse's behaviour)."""
    parser = build_parser()
    ns = parser.parse_args(argv)
    if ns.demo and (ns.headless or not has_display()):
        ns.headless = True
        ns.mode = ns.mode or ("clover" if ns.robot == "rrr3" else "line")
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
    width = ns.record_width or (min(400, ns.size[0]) if gif else None)
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
    )
