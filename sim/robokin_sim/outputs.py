"""What the simulator writes goes wrong in one way: :class:`OutputError`, one line naming the file.

A full disk, a file too large for the file system or a directory that cannot be written turns
into ``robokin-sim: error: cannot write FILE: REASON`` and exit status 1 (see ``__main__``). The
file is written under a temporary name first (:class:`robokin.files.AtomicPath`), so a file
that was there before keeps its content.
"""

from __future__ import annotations

class OutputError(OSError):
    """An output file (log, recording, screenshot) that could not be written."""

    def __init__(self, path: str, reason: str) -> None:
        super().__init__(f"cannot write {path}: {reason}")
        self.path = path
        self.reason = reason

    def __str__(self) -> str:
        return self.args[0]


def reason_of(exc: BaseException) -> str:
    """A one-line reason for a failed write: the OS's message when there is one, else the last
    line of the tool's (ffmpeg's) complaint, never a command line or a traceback."""
    if isinstance(exc, OSError) and exc.strerror and exc.errno not in (None, 32):  # 32: broken pipe
        return exc.strerror
    lines = [line.strip() for line in str(exc).splitlines() if line.strip()]
    for line in reversed(lines):
        low = line.lower()
        if any(word in low for word in ("no space", "too large", "quota", "permission", "read-only", "error")):
            return line[:200]
    if isinstance(exc, OSError) and exc.errno == 32:
        return "the encoder stopped (is the disk full?)"
    return (lines[0] if lines else type(exc).__name__)[:200]


def surface_rgb(pygame, surface):
    """The surface's pixels as a new (H, W, 3) uint8 RGB array, rows top to bottom. SDL copies its
    rows as they are; surfarray's (W, H) view would need a transposing copy per frame."""
    import numpy as np

    w, h = surface.get_size()
    return np.frombuffer(pygame.image.tobytes(surface, "RGB"), dtype=np.uint8).reshape(h, w, 3)


def save_png(pygame, surface, path: str) -> str:
    """Saves ``surface`` as a PNG at ``path`` (atomically); OutputError when it cannot. (Pillow
    writes it: SDL's libpng would also print its complaint on stderr.)"""
    from PIL import Image
    from robokin.files import AtomicPath

    rgb = surface_rgb(pygame, surface)
    try:
        with AtomicPath(path) as tmp:
            Image.fromarray(rgb, "RGB").save(tmp, format="PNG")
    except OSError as exc:
        raise OutputError(path, reason_of(exc)) from None
    return path
