"""The simulator in a real X window: an Xvfb server of its own, key events sent through X (XTEST,
by xdotool), the window manager's close message, a resize and signals. Each key's effect is read
from the log (which a window run flushes row by row to its temporary file) or from the pixels of
the X server's framebuffer (Xvfb -fbdir: an XWD image kept current).

Xvfb and xdotool are Debian packages that `make setup` installs (scripts/install-system-deps.sh).
Everything polls with generous time limits, so a loaded machine only makes the tests slower.
"""

import csv
import ctypes
import glob
import os
import select
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from robokin_sim import theme

LIMIT = 60.0  # seconds any one awaited effect may take on a loaded machine


@pytest.fixture(scope="module")
def xserver(tmp_path_factory):
    """An Xvfb on a free display number (Xvfb picks it: -displayfd); yields (env, framebuffer)."""
    for tool in ("Xvfb", "xdotool"):
        assert shutil.which(tool), f"{tool} is missing: `make setup` installs it (scripts/install-system-deps.sh)"
    fbdir = tmp_path_factory.mktemp("xvfb")
    read_fd, write_fd = os.pipe()
    server = subprocess.Popen(
        ["Xvfb", "-displayfd", str(write_fd), "-screen", "0", "1024x768x24", "-nolisten", "tcp", "-fbdir",
         str(fbdir), "-noreset"],
        pass_fds=(write_fd,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    os.close(write_fd)
    try:
        number = b""
        deadline = time.monotonic() + LIMIT
        while not number.endswith(b"\n") and time.monotonic() < deadline:
            ready, _, _ = select.select([read_fd], [], [], 0.5)
            if ready:
                chunk = os.read(read_fd, 16)
                if not chunk:
                    break
                number += chunk
        assert number.strip().isdigit(), f"Xvfb did not start (exit status {server.poll()})"
        env = {k: v for k, v in os.environ.items() if not k.startswith("SDL_")}
        env.update(DISPLAY=":" + number.decode().strip(), SDL_AUDIODRIVER="dummy", PYGAME_HIDE_SUPPORT_PROMPT="1")
        yield env, fbdir / "Xvfb_screen0"
    finally:
        os.close(read_fd)
        server.terminate()
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()


def wait_for(what, predicate, limit=LIMIT):
    deadline = time.monotonic() + limit
    while True:
        value = predicate()
        if value:
            return value
        assert time.monotonic() < deadline, f"waited {limit:.0f} s for {what}"
        time.sleep(0.05)


class Sim:
    """A windowed robokin-sim under the test's X server, its log followed as it is written."""

    def __init__(self, env, directory, *args):
        self.env, self.dir = env, directory
        self.log = os.path.join(directory, "run.csv")
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "robokin_sim", "--log", self.log, "--size", "480x480", *args],
            env=env, cwd=directory, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.window = wait_for("the window", self.find_window)
        self.xdo("windowfocus", "--sync", self.window)
        wait_for("the first logged step", lambda: len(self.rows()) > 0)

    def find_window(self):
        """The visible window titled robokin-sim (xdotool's --name misses SDL's UTF-8 titles:
        windows are listed by class and their names asked one by one)."""
        assert self.proc.poll() is None, f"robokin-sim exited: {self.proc.communicate()[1]}"
        for wid in self.xdo_out("search", "--onlyvisible", "--classname", ".").split():
            if self.xdo_out("getwindowname", wid).startswith("robokin-sim"):
                return wid
        return None

    def xdo(self, *args):
        subprocess.run(["xdotool", *args], env=self.env, check=True, timeout=LIMIT, capture_output=True)

    def xdo_out(self, *args):
        out = subprocess.run(["xdotool", *args], env=self.env, timeout=LIMIT, capture_output=True, text=True)
        return out.stdout.strip() if out.returncode == 0 else ""

    def rows(self):
        """Rows logged so far (the run's temporary log; complete lines only)."""
        parts = glob.glob(os.path.join(self.dir, f".run.{self.proc.pid}.*.part.csv"))
        if not parts:
            return []
        with open(parts[0], newline="") as f:
            text = f.read()
        lines = text.splitlines(keepends=True)
        if lines and not lines[-1].endswith("\n"):
            lines.pop()
        return list(csv.DictReader(lines))

    def last(self):
        rows = self.rows()
        return rows[-1] if rows else None

    def hold(self, key, what, predicate):
        """Holds ``key`` down until ``predicate(last row)`` holds."""
        self.xdo("keydown", key)
        try:
            return wait_for(what, lambda: (r := self.last()) is not None and predicate(r) and r)
        finally:
            self.xdo("keyup", key)

    def press(self, key):
        self.xdo("key", key)

    def geometry(self):
        out = self.xdo_out("getwindowgeometry", "--shell", self.window)
        values = dict(line.split("=", 1) for line in out.splitlines() if "=" in line)
        return int(values["X"]), int(values["Y"]), int(values["WIDTH"]), int(values["HEIGHT"])

    def finish(self, limit=LIMIT):
        try:
            out, err = self.proc.communicate(timeout=limit)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            out, err = self.proc.communicate()
            raise AssertionError(f"robokin-sim did not exit within {limit} s: {err}")
        return self.proc.returncode, out, err

    def kill(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.communicate()


def framebuffer(path):
    """The X screen as an (H, W, 3) uint8 array, from Xvfb's XWD framebuffer file."""
    data = np.fromfile(path, dtype=np.uint8)
    head = data[:100].view(">u4")
    header_size, width, height = int(head[0]), int(head[4]), int(head[5])
    byte_order, bits, bytes_per_line = int(head[7]), int(head[11]), int(head[12])
    masks, ncolors = [int(m) for m in head[14:17]], int(head[19])
    assert bits == 32, f"expected a 32-bit framebuffer, got {bits}"
    start = header_size + 12 * ncolors
    rows = data[start:start + height * bytes_per_line].reshape(height, bytes_per_line)[:, : 4 * width]
    pixels = rows.copy().view("<u4" if byte_order == 0 else ">u4").reshape(height, width)
    channels = [(pixels & m) >> (int(m) & -int(m)).bit_length() - 1 for m in masks]
    return np.stack(channels, axis=-1).astype(np.uint8)


def window_pixels(sim, fb):
    x, y, w, h = sim.geometry()
    return framebuffer(fb)[y:y + h, x:x + w]


def near(pixel, colour, tol=12):
    return bool(np.all(np.abs(pixel.astype(int) - np.array(colour)) <= tol))


def test_keys_resize_and_esc_in_a_real_window(xserver, tmp_path):
    env, fb = xserver
    sim = Sim(env, str(tmp_path))
    try:
        start = sim.last()
        assert start["mode"] == "free" and float(start["x"]) == 0.0

        # Arrows held move the effector 1 mm per step, and stop when released.
        r = sim.hold("Right", "x to grow", lambda r: float(r["x"]) >= 0.01)
        assert float(r["y"]) == 0.0 and float(r["phi"]) == 0.0
        x_released = float(wait_for("a step after the release", lambda: sim.last())["x"])
        n = len(sim.rows())
        wait_for("ten more steps", lambda: len(sim.rows()) >= n + 10)
        assert float(sim.last()["x"]) <= x_released + 0.005  # a few frames at most (the key-up's way to the sim)
        sim.hold("Up", "y to grow", lambda r: float(r["y"]) >= 0.005)
        # l turns counter-clockwise, k clockwise, 0.01 rad per step.
        sim.hold("l", "phi to grow", lambda r: float(r["phi"]) >= 0.05)
        phi = float(sim.last()["phi"])
        sim.hold("k", "phi to come down", lambda r: float(r["phi"]) <= phi - 0.03)

        # h shows the key list in a dark panel down the right side, the robot drawn beside it (its
        # links in sight left of the panel); h again hides it.
        def links_left_of(pixels, right):
            return np.count_nonzero(np.all(np.abs(pixels[:, :right].astype(int) - theme.LINK_1) <= 12, axis=2))

        assert links_left_of(window_pixels(sim, fb), 480) > 100
        sim.press("h")
        wait_for("the help panel", lambda: near((p := window_pixels(sim, fb))[240, 470], theme.OVERLAY)
                 and near(p[5, 285], theme.OVERLAY) and links_left_of(p, 275) > 100)
        sim.press("h")
        wait_for("the help panel to go", lambda: not near(window_pixels(sim, fb)[240, 470], theme.OVERLAY))
        # The window shows REC only when recording: not here.
        assert not near(window_pixels(sim, fb)[20:40, 440:470].min(axis=(0, 1)), theme.SINGULAR, tol=40)

        # space pauses (no step, no row) and resumes.
        sim.press("space")

        def settled():
            n = len(sim.rows())
            time.sleep(0.3)
            return len(sim.rows()) == n

        wait_for("the pause", settled)
        n = len(sim.rows())
        time.sleep(0.5)
        assert len(sim.rows()) == n
        sim.press("space")
        wait_for("steps after the pause", lambda: len(sim.rows()) > n + 5)

        # o: approach, then the circle; s: avoidance off then on; p: the clover; m: free mode.
        sim.press("o")
        wait_for("the circle", lambda: sim.last()["mode"] == "circle")
        sim.press("s")
        wait_for("avoidance off", lambda: sim.last()["avoid"] == "0")
        sim.press("s")
        wait_for("avoidance on", lambda: sim.last()["avoid"] == "1")
        sim.press("p")
        wait_for("the clover", lambda: sim.last()["mode"] == "clover")
        sim.press("m")
        wait_for("free mode", lambda: sim.last()["mode"] == "free")
        # r: back home along a singularity-free route.
        sim.press("r")
        wait_for("home", lambda: (r := sim.last())["mode"] == "free" and (float(r["x"]), float(r["y"]), float(r["phi"]))
                 == (0.0, 0.0, 0.0) and len(sim.rows()) > 0)
        rows = sim.rows()
        det = np.array([float(r["det_a"]) for r in rows])
        assert np.all(det < 0) and "parallel" not in {r["state"] for r in rows}

        # Resizing: the drawing fills the new size (background, not black, beyond the old 480 px).
        sim.xdo("windowsize", sim.window, "640", "420")
        wait_for("the new size", lambda: sim.geometry()[2:] == (640, 420))
        wait_for("the drawing at the new size",
                 lambda: near(window_pixels(sim, fb)[410, 630], theme.BACKGROUND, tol=30))

        sim.press("Escape")
        status, out, err = sim.finish()
        assert status == 0, err
        assert f"log: {sim.log}" in out
        assert sorted(os.listdir(tmp_path)) == ["run.csv"]  # renamed into place, no temporary left
    finally:
        sim.kill()


def _close_window(display: str, window: int) -> None:
    """Sends WM_DELETE_WINDOW, the message a window manager's close button sends."""
    x11 = ctypes.CDLL("libX11.so.6")
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XInternAtom.restype = ctypes.c_ulong
    x11.XInternAtom.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int]
    x11.XSendEvent.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_long, ctypes.c_void_p]
    x11.XFlush.argtypes = [ctypes.c_void_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]

    class ClientMessage(ctypes.Structure):
        _fields_ = [("type", ctypes.c_int), ("serial", ctypes.c_ulong), ("send_event", ctypes.c_int),
                    ("display", ctypes.c_void_p), ("window", ctypes.c_ulong), ("message_type", ctypes.c_ulong),
                    ("format", ctypes.c_int), ("data", ctypes.c_long * 5)]

    class Event(ctypes.Union):
        _fields_ = [("xclient", ClientMessage), ("pad", ctypes.c_long * 24)]

    dpy = x11.XOpenDisplay(display.encode())
    assert dpy, f"cannot open display {display}"
    try:
        event = Event()
        event.xclient.type = 33  # ClientMessage
        event.xclient.window = window
        event.xclient.message_type = x11.XInternAtom(dpy, b"WM_PROTOCOLS", 0)
        event.xclient.format = 32
        event.xclient.data[0] = x11.XInternAtom(dpy, b"WM_DELETE_WINDOW", 0)
        assert x11.XSendEvent(dpy, window, 0, 0, ctypes.byref(event))
        x11.XFlush(dpy)
    finally:
        x11.XCloseDisplay(dpy)


def test_the_close_message_ends_the_run_and_keeps_the_log(xserver, tmp_path):
    env, fb = xserver
    sim = Sim(env, str(tmp_path), "--mode", "circle", "--record", str(tmp_path / "run.gif"))
    try:
        wait_for("a few steps", lambda: len(sim.rows()) >= 20)
        # The REC mark at the top right of the window while recording.
        wait_for("the REC mark", lambda: np.sum(np.all(np.abs(
            window_pixels(sim, fb)[5:35, 400:475].astype(int) - np.array(theme.SINGULAR)) < 30, axis=2)) > 30)
        _close_window(env["DISPLAY"], int(sim.window))
        status, out, err = sim.finish()
        assert status == 0, err
        assert sorted(os.listdir(tmp_path)) == ["run.csv", "run.gif"]
    finally:
        sim.kill()


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP])
def test_a_signal_stops_a_window_run_and_keeps_its_files(xserver, tmp_path, sig):
    env, _ = xserver
    sim = Sim(env, str(tmp_path), "--record", str(tmp_path / "run.mp4"))
    try:
        wait_for("a few steps", lambda: len(sim.rows()) >= 10)
        sim.proc.send_signal(sig)
        status, out, err = sim.finish()
        assert status == 128 + sig, err
        assert sorted(os.listdir(tmp_path)) == ["run.csv", "run.mp4"]  # no temporary left
        with open(sim.log, newline="") as f:
            steps = [int(r["step"]) for r in csv.DictReader(f)]
        assert steps == list(range(1, len(steps) + 1)) and len(steps) >= 10
        import imageio.v3 as iio

        assert len(iio.imread(tmp_path / "run.mp4")) == len(steps)
        assert err.strip().splitlines() == [
            f"robokin-sim: stopped by {signal.Signals(sig).name} after {len(steps)} steps; log: {sim.log}, "
            f"recording: {tmp_path / 'run.mp4'}"]
    finally:
        sim.kill()


def test_n_pressed_during_a_move_in_a_real_window_is_applied_after_it(xserver, tmp_path):
    """Nine presses of n in quick succession show nine postures of the UR5, one after the other."""
    env, _ = xserver
    sim = Sim(env, str(tmp_path), "--robot", "ur5")
    try:
        n0 = len(sim.rows())
        sim.xdo("key", "--delay", "40", *["n"] * 9)

        def runs():
            modes = [r["mode"] for r in sim.rows()[n0:]]
            starts = [k for k in range(len(modes)) if modes[k] == "posture" and (k == 0 or modes[k - 1] != "posture")]
            return len(starts) if modes and modes[-1] == "joint" else 0

        wait_for("nine posture moves", lambda: runs() >= 9)
        time.sleep(0.5)
        assert runs() == 9
        sim.press("Escape")
        status, out, err = sim.finish()
        assert status == 0, err
    finally:
        sim.kill()


def test_a_serial_arm_jogs_and_orbits_by_a_mouse_drag_in_a_real_window(xserver, tmp_path):
    env, fb = xserver
    sim = Sim(env, str(tmp_path), "--robot", "ur5")
    try:
        start = sim.last()
        assert start["mode"] == "joint"
        q = [float(start[f"q_{i}"]) for i in range(6)]
        # 2 selects joint 2, keypad + moves it (0.01 rad per step), the others stay.
        sim.press("2")
        r = sim.hold("KP_Add", "q_1 to grow", lambda r: float(r["q_1"]) >= q[1] + 0.05)
        assert [float(r[f"q_{i}"]) for i in (0, 2, 3, 4, 5)] == [q[i] for i in (0, 2, 3, 4, 5)]
        # Right moves the tool along base x, its orientation kept.
        r0 = sim.last()
        r = sim.hold("Right", "x to grow", lambda r: float(r["x"]) >= float(r0["x"]) + 0.01)
        assert r["mode"] == "cartesian" and abs(float(r["y"]) - float(r0["y"])) < 1e-9
        assert all(abs(float(r[c]) - float(r0[c])) < 1e-9 for c in ("roll", "pitch", "yaw"))
        # Shift + Up turns the tool about base y: the position stays.
        r0 = sim.last()
        sim.xdo("keydown", "shift")
        try:
            r = sim.hold("Up", "the tool to turn", lambda r: max(abs(float(r[f"q_{i}"]) - float(r0[f"q_{i}"]))
                                                                 for i in range(6)) > 0.02)
        finally:
            sim.xdo("keyup", "shift")
        assert all(abs(float(r[c]) - float(r0[c])) < 1e-9 for c in "xyz")

        # A mouse drag orbits the camera: the picture changes, the arm does not move.
        def settled():
            n = len(sim.rows())
            time.sleep(0.3)
            return len(sim.rows()) > n and sim.rows()[-1]["q_0"] == sim.rows()[n]["q_0"]

        wait_for("the arm at rest", settled)
        resting = sim.last()
        before = window_pixels(sim, fb).astype(int)
        x, y, w, h = sim.geometry()
        sim.xdo("mousemove", str(x + w // 2), str(y + h // 2))
        sim.xdo("mousedown", "1")
        for _ in range(6):
            sim.xdo("mousemove_relative", "--", "25", "8")
            time.sleep(0.05)
        sim.xdo("mouseup", "1")
        wait_for("the orbit", lambda: np.mean(np.any(np.abs(window_pixels(sim, fb).astype(int) - before) > 30,
                                                       axis=2)) > 0.01)
        after = sim.last()
        assert all(after[f"q_{i}"] == resting[f"q_{i}"] for i in range(6))

        # Resizing: the scene is drawn at the new size (background beyond the old 480 px).
        sim.xdo("windowsize", sim.window, "640", "420")
        wait_for("the new size", lambda: sim.geometry()[2:] == (640, 420))
        wait_for("the drawing at the new size",
                 lambda: near(window_pixels(sim, fb)[415, 635], theme.BACKGROUND, tol=30))
        # n moves to the next closed-form posture, animated ("posture" rows), then stops there.
        sim.press("n")
        wait_for("the posture change", lambda: sim.last()["mode"] == "posture")
        wait_for("the new posture", lambda: sim.last()["mode"] in ("joint", "cartesian"))
        sim.press("Escape")
        status, out, err = sim.finish()
        assert status == 0, err
    finally:
        sim.kill()
