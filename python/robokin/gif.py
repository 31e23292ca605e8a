"""Animated GIFs written a frame at a time: each RGB frame is quantised, encoded (Pillow's LZW) and
appended to the file as it comes, and only the picture shown after the last frame is kept (to tell
what the next one changes), so memory does not grow with the number of frames.

Two kinds of palette:

- none given: every frame is quantised to a palette of its own (median cut, up to 255 colours,
  without dithering), written as the frame's local colour table. For anti-aliased pictures such as
  matplotlib figures (:func:`robokin.plots_arm.animate`).
- a fixed palette of up to 255 colours: every frame is quantised to it (the nearest colour, without
  dithering: flat colours stay flat), written once as the file's global colour table. For flat
  drawings such as the simulator's, where few colours make small files.

Either way a frame after the first holds only the box around the pixels whose shown colour changed,
its unchanged pixels set to the transparent index (the entry after the palette's colours, which no
pixel is quantised to); frames are not disposed, so the previous picture shows through. A frame
equal to the one before is still written (one transparent pixel), so the display times stay those
asked for. The file is GIF89a and loops forever.

Display times are whole ticks of 10 ms that do not drift: the first k frames end at
``round(k * seconds / 10 ms)`` ticks, so the total is right to one tick whatever the number of
frames. Viewers show frames shorter
than 20 ms slower (browsers at 100 ms), so frames are shown at least 20 ms. :func:`durations` gives
the times a writer uses.
"""

from __future__ import annotations

import os
import struct

import numpy as np

from . import _checks

__all__ = ["GifWriter", "durations"]

# GIF's clock ticks in hundredths of a second; a delay is a 16-bit count of them.
_TICK = 0.01
_SHORTEST = 0.02  # viewers stretch shorter frames
_LONGEST = 0xFFFF * _TICK
_MAX_SIDE = 0xFFFF  # a logical screen's sides are 16-bit
_MAX_COLOURS = 255  # of 256 indices, one is kept for transparency
_TRAILER = b";"
_LOOP_FOREVER = b"!\xff\x0bNETSCAPE2.0\x03\x01\x00\x00\x00"
_NOT_DISPOSED = 1  # the graphic control block's disposal method: leave the frame in place


class GifWriter:
    """Writes an animated GIF one (H, W, 3) uint8 RGB frame at a time (see the module's text for the
    palettes, the delta frames and the display times). Call :meth:`close` when the last frame is
    added, or :meth:`abandon` to stop without finishing the file; as a context manager it closes
    when the block ends normally and abandons when it raises::

        with AtomicPath("out/run.gif") as tmp, GifWriter(tmp, (480, 360), 1 / 30) as gif:
            for rgb in pictures:
                gif.add(rgb)

    Args:
        file: A path (the file is created, or truncated, and closed by :meth:`close` or
            :meth:`abandon`) or a binary file object open for writing (written to and left open).
        size: (width, height) of every frame in pixels, each 1 to 65535.
        seconds: How long each frame is shown, above 0 and at most 655.35 (GIF's 16-bit delay);
            shown on 10 ms ticks, at least 20 ms (display times per :func:`durations`).
        palette: None: each frame quantised to a palette of its own. Or a fixed palette of 1 to 255
            colours: a Pillow ``"P"`` image (its palette), or RGB values 0 to 255, flat
            ``[r, g, b, r, g, b, ...]`` or (N, 3).

    Attributes:
        size: (width, height) of the frames.
        seconds: ``seconds`` as given (a float).
        frames: The number of frames written so far.
    """

    def __init__(self, file, size, seconds, palette=None) -> None:
        self.size = _frame_size(size)
        self.seconds = _seconds(seconds)
        self.frames = 0
        self._colours = None if palette is None else _colours(palette)
        self._quantiser = None if palette is None else _quantiser(self._colours)
        self._shown: np.ndarray | None = None  # the picture after the last frame, (H, W, 3)
        self._owned = isinstance(file, (str, os.PathLike))
        if not self._owned and not callable(getattr(file, "write", None)):
            raise TypeError(f"file: expected a path or a binary file object, got {type(file).__name__}")
        self._file = open(file, "wb") if self._owned else file
        try:
            table = b"" if self._colours is None else _table(self._colours)
            flags = 0x80 | _table_code(table) if table else 0  # a global colour table, or none
            self._file.write(b"GIF89a" + struct.pack("<HHBBB", *self.size, flags, 0, 0) + table + _LOOP_FOREVER)
        except BaseException:
            self.abandon()
            raise

    def add(self, rgb) -> None:
        """Quantises one frame and appends it to the file.

        Args:
            rgb: (height, width, 3) uint8 RGB picture of the writer's ``size``.
        """
        from PIL import Image

        if self._file is None:
            raise ValueError("GifWriter: add after close or abandon")
        picture = _picture(rgb, self.size)
        image = Image.fromarray(picture, "RGB")
        if self._quantiser is None:
            paletted = image.quantize(colors=_MAX_COLOURS, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
            colours = np.asarray(paletted.getpalette(), dtype=np.uint8).reshape(-1, 3)
        else:
            paletted = image.quantize(palette=self._quantiser, dither=Image.Dither.NONE)
            colours = self._colours
        indices = np.asarray(paletted)
        shown = colours[indices]
        offset, pixels = _changed_box(indices, shown, self._shown, transparent=len(colours))
        local = colours if self._quantiser is None else None
        self._write(pixels, offset, _duration(self.frames, self.seconds), local, len(colours))
        self._shown = shown
        self.frames += 1

    def close(self) -> None:
        """Writes the trailer, which ends the file; closes the file if the writer opened it."""
        if self._file is None:
            return
        try:
            self._file.write(_TRAILER)
            self._file.flush()
        finally:
            self.abandon()

    def abandon(self) -> None:
        """Stops without ending the file (an interrupted run: the caller removes it); closes the
        file if the writer opened it."""
        file, self._file, self._shown = self._file, None, None
        if file is not None and self._owned:
            file.close()

    def __enter__(self) -> GifWriter:
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        if exc_type is None:
            self.close()
        else:
            self.abandon()

    def _write(self, pixels: np.ndarray, offset, duration: int, local, transparent: int) -> None:
        """Encodes and writes one frame: its graphic control block (display time, not disposed, the
        transparent index), its image descriptor (with ``local`` as its colour table unless None)
        and its LZW data."""
        from PIL import GifImagePlugin, Image

        image = Image.fromarray(pixels, "P")
        params = {"duration": duration, "disposal": _NOT_DISPOSED, "transparency": transparent}
        if local is not None:
            image.putpalette(_table(local))
            params["include_color_table"] = True
        chunks = GifImagePlugin.getdata(image, offset, **params)
        for chunk in chunks:
            self._file.write(chunk)
        # The list belongs to a class getdata makes per call, freed only by the cycle collector:
        # emptied now, the encoded frames do not pile up until it runs.
        chunks.clear()
        self._file.flush()  # the frame is in the file, not in a buffer


def durations(count, seconds) -> list:
    """The display times (ms, multiples of GIF's 10 ms tick) a :class:`GifWriter` gives ``count``
    frames of ``seconds`` each: the first k frames end at round(k * seconds / 10 ms) ticks (frames
    of at least 20 ms), so the total is right to one tick and never drifts.

    Args:
        count: The number of frames, 0 or more.
        seconds: How long each frame is shown, as :class:`GifWriter` takes it.
    """
    count = _checks.whole(count, "count", 0, 2**31 - 1, "frames")
    seconds = _seconds(seconds)
    return [_duration(k, seconds) for k in range(count)]


def _duration(k: int, seconds: float) -> int:
    """Display time (ms) of frame k of frames of ``seconds`` each: entry k of :func:`durations`."""
    per = max(seconds, _SHORTEST)
    return 10 * (int(round((k + 1) * per / _TICK)) - int(round(k * per / _TICK)))


def _changed_box(indices: np.ndarray, shown: np.ndarray, previous, transparent: int):
    """What to write of a frame: ((x, y) offset, indices) of the box around the pixels whose shown
    colour differs from ``previous`` (the whole frame when there is none), unchanged pixels in it
    set to ``transparent``; a frame showing no change is one transparent pixel."""
    if previous is None:
        return (0, 0), indices
    changed = (shown != previous).any(axis=2)
    rows, cols = np.flatnonzero(changed.any(axis=1)), np.flatnonzero(changed.any(axis=0))
    if rows.size == 0:
        rows = cols = np.zeros(1, dtype=np.intp)
    box = (slice(rows[0], rows[-1] + 1), slice(cols[0], cols[-1] + 1))
    pixels = indices[box].copy()
    pixels[~changed[box]] = transparent
    return (int(cols[0]), int(rows[0])), pixels


def _table(colours: np.ndarray) -> bytes:
    """A colour table: ``colours``, then the transparent entry and black up to a power of two
    entries (2 to 256), as GIF stores it."""
    entries = max(2, 1 << int(len(colours)).bit_length())  # room for one entry after the colours
    return colours.tobytes() + bytes(3 * (entries - len(colours)))


def _table_code(table: bytes) -> int:
    """The 3-bit size code of a colour table of 2 ** (code + 1) entries."""
    return (len(table) // 3).bit_length() - 2


def _frame_size(size) -> tuple:
    return _checks.pixels(size, "size", 1, _MAX_SIDE)


def _seconds(seconds) -> float:
    return _checks.number(seconds, "seconds", positive=True, maximum=_LONGEST)  # GIF's longest delay


def _colours(palette) -> np.ndarray:
    """A fixed palette as (N, 3) uint8 RGB, 1 <= N <= 255."""
    values = palette
    if callable(getattr(palette, "getpalette", None)):  # a Pillow image
        if palette.mode != "P":
            raise ValueError(f"palette: expected a \"P\" image, got mode {palette.mode!r}")
        values = palette.getpalette()
    a = _checks.real_array(values, "palette")
    if not (a.ndim == 1 and a.size % 3 == 0 or a.ndim == 2 and a.shape[1] == 3):
        raise ValueError(f"palette: expected RGB values, flat (3 N,) or (N, 3), got shape {a.shape}")
    if not 1 <= a.size // 3 <= _MAX_COLOURS:
        raise ValueError(f"palette: expected 1 to {_MAX_COLOURS} colours (one index is kept for "
                         f"transparency), got {a.size // 3}")
    if not np.all((a >= 0) & (a <= 255) & (a == np.round(a))):
        raise ValueError("palette: expected whole RGB values 0 to 255")
    return a.reshape(-1, 3).astype(np.uint8)


def _quantiser(colours: np.ndarray):
    """A Pillow "P" image holding exactly ``colours``, for Image.quantize (which picks among them only)."""
    from PIL import Image

    image = Image.new("P", (1, 1))
    image.putpalette(colours.tobytes())
    return image


def _picture(rgb, size) -> np.ndarray:
    """``rgb`` as a contiguous (height, width, 3) uint8 array of ``size`` = (width, height)."""
    a = np.asarray(rgb)
    if a.dtype != np.uint8:
        raise TypeError(f"rgb: expected uint8 values, got {a.dtype}")
    if a.shape != (size[1], size[0], 3):
        raise ValueError(f"rgb: expected shape {(size[1], size[0], 3)} (height, width, RGB), got {a.shape}")
    return np.ascontiguousarray(a)
