"""Recordings of the window: GIF with Pillow, MP4 with imageio + imageio-ffmpeg.

Both are written to a temporary file next to the target and renamed into place when complete,
so an interrupted run never leaves a half-written recording under the requested name. Both stream:
MP4 frames go to ffmpeg as they come, GIF frames are encoded and appended to the file as they come
(:class:`robokin.gif.GifWriter` on the fixed palette :data:`GIF_PALETTE`), so a run's memory does
not grow with its length.

The time base is the simulation's: the loop offers one frame per simulation step (none while
paused) and ``fps`` is the number of steps per simulated second, so a recording of N steps of
``1 / fps`` seconds lasts N / fps seconds whatever rate the window ran at. With ``every = k`` one
frame in k is kept and shown for k steps (MP4 at fps / k frames per second; GIF frames of
k / fps seconds, rounded to GIF's 10 ms ticks without drifting).
"""

from __future__ import annotations

import os
import signal
from typing import Optional

import numpy as np
from robokin.files import AtomicPath
from robokin.gif import GifWriter

from .outputs import OutputError, reason_of
from .theme import COLOURS

#: The recordings' GIF palette, 63 RGB colours at most: the theme's flat colours exactly, then greys
#: for the antialiased text. With the writer's transparent entry it fills a 64-entry table. Few
#: colours and no dithering keep the frames small: the edges of the scaled-down drawing snap to the
#: nearest flat colour.
GIF_PALETTE = (list(dict.fromkeys(COLOURS))
               + [(g, g, g) for g in range(0, 256, 17) if (g, g, g) not in COLOURS])[:63]


class Recorder:
    """Collects frames (H, W, 3) uint8 RGB and writes them when closed.

    Args:
        path: Target file, ``.gif`` or ``.mp4``.
        fps: Frames offered per second of simulated time (simulation steps per second).
        every: Keep one frame in ``every`` (the others are skipped).
        width: Width of the written frames in pixels (None: as given); even for MP4.
    """

    def __init__(self, path: str, fps: float = 60.0, every: int = 1, width: Optional[int] = None) -> None:
        self.path = path
        self.kind = os.path.splitext(path)[1].lower()
        if self.kind not in (".gif", ".mp4"):
            raise ValueError(f"record: expected a .gif or .mp4 path, got {path!r}")
        self.fps = float(fps)
        self.every = max(1, int(every))
        self.width = width
        self.frames_written = 0
        self._count = 0
        self._shape = None
        self._out = AtomicPath(path)
        # GIF frames stream to a GifWriter, MP4 frames to ffmpeg: at most one frame is held.
        self._gif: Optional[GifWriter] = None
        self._writer = None

    def wants(self) -> bool:
        """True when the next frame offered to :meth:`add` will be kept (lets callers skip the copy)."""
        return self._count % self.every == 0

    def skip(self) -> None:
        """Counts a frame that is not kept (see :meth:`wants`)."""
        self._count += 1

    def add(self, rgb: np.ndarray) -> None:
        """Offers one frame, (H, W, 3) uint8; keeps one in ``every``."""
        keep = self.wants()
        self._count += 1
        if not keep:
            return
        from PIL import Image

        image = Image.fromarray(np.ascontiguousarray(rgb, dtype=np.uint8), "RGB")
        if self._shape is None:
            w, h = image.size
            if self.width:
                w, h = self.width, max(2, round(h * self.width / w))
            if self.kind == ".mp4":
                w, h = w - w % 2, h - h % 2  # yuv420p wants even sizes
            self._shape = (w, h)
        if image.size != self._shape:  # first frame fixes the size; a resized window is rescaled
            image = image.resize(self._shape, Image.Resampling.BOX)
        if self.kind == ".gif":
            try:
                if self._gif is None:
                    self._gif = GifWriter(self._out.tmp, self._shape, self.every / self.fps, palette=GIF_PALETTE)
                self._gif.add(np.asarray(image))
            except OSError as exc:  # a full disk, a file too large
                raise OutputError(self.path, reason_of(exc)) from None
        else:
            try:
                if self._writer is None:
                    import imageio.v2 as imageio

                    self._writer = imageio.get_writer(
                        self._out.tmp, format="FFMPEG", mode="I", fps=self.fps / self.every, codec="libx264",
                        quality=7, pixelformat="yuv420p", macro_block_size=2, ffmpeg_log_level="error",
                    )
                self._writer.append_data(np.asarray(image))
            except Exception as exc:  # ffmpeg stopped: a full disk, a file too large
                self._abandon_writer()
                raise OutputError(self.path, reason_of(exc)) from None
        self.frames_written += 1

    @property
    def seconds(self) -> float:
        """Playing time of the frames kept so far (simulated seconds)."""
        return self.frames_written * self.every / self.fps

    def close(self) -> Optional[str]:
        """Writes the file and renames it into place; returns its path (None if no frame was kept)."""
        try:
            if self.frames_written == 0:
                return None
            try:
                if self.kind == ".gif":
                    self._gif.close()
                else:
                    process = _ffmpeg_process(self._writer)
                    self._writer.close()
                    self._writer = None
                    # ffmpeg may end with status 0 after failed writes (a full disk): the file
                    # itself says whether it is whole.
                    if process is not None and process.wait() != 0:
                        status = process.returncode
                        raise OSError("ffmpeg " + (f"was stopped: {signal.strsignal(-status)}" if status < 0
                                                   else f"ended with status {status}"))
                    if not mp4_complete(self._out.tmp):
                        raise OSError(28, "the video file came out truncated (is the disk full?)")
                return self._out.commit()
            except Exception as exc:  # the disk is full, the file too large, the directory gone
                raise OutputError(self.path, reason_of(exc)) from None
        finally:
            self.discard()

    def discard(self) -> None:
        """Drops the recording (an interrupted run): nothing is left under the path, nor a temporary file."""
        gif, self._gif = self._gif, None
        try:
            if gif is not None:
                gif.abandon()
            self._abandon_writer()
        finally:
            self._out.discard()

    def _abandon_writer(self) -> None:
        """Stops ffmpeg without waiting for it to finish a video nobody will keep."""
        writer, self._writer = self._writer, None
        if writer is None:
            return
        process = _ffmpeg_process(writer)
        if process is not None:
            try:
                process.kill()
            except OSError:
                pass
        try:
            writer.close()
        except Exception:
            pass


def _ffmpeg_process(writer):
    """The ffmpeg subprocess behind an imageio FFMPEG writer (None if it cannot be found)."""
    gen = getattr(writer, "_write_gen", None)
    frame = getattr(gen, "gi_frame", None)
    process = frame.f_locals.get("p") if frame is not None else None
    return process if hasattr(process, "wait") and hasattr(process, "kill") else None


def mp4_complete(path: str) -> bool:
    """Whether the MP4 file's top-level boxes tile it exactly and include the index ('moov'): a file
    cut short by a full disk fails this."""
    import struct

    size = os.path.getsize(path)
    seen, offset = set(), 0
    with open(path, "rb") as f:
        while offset < size:
            f.seek(offset)
            head = f.read(16)
            if len(head) < 8:
                return False
            length, kind = struct.unpack(">I4s", head[:8])
            if length == 1:
                if len(head) < 16:
                    return False
                length = struct.unpack(">Q", head[8:16])[0]
            elif length == 0:
                length = size - offset
            if length < 8 or offset + length > size:
                return False
            seen.add(kind)
            offset += length
    return offset == size and b"moov" in seen and b"mdat" in seen
