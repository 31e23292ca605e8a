"""An animated GIF written a frame at a time: each frame is encoded by Pillow as it comes and its
image block appended to the open file, so memory does not grow with the number of frames.

Every frame is quantised to a palette of its own (up to 255 colours, median cut, without
dithering: flat colours stay flat) carried as its local colour table; frames are not disposed. The
file is GIF89a, looping forever, each frame shown ``delay`` hundredths of a second.
"""

from __future__ import annotations

import io
import struct

import numpy as np

# A GIF's blocks: an extension (0x21), an image descriptor (0x2C), the trailer (0x3B).
_EXTENSION, _IMAGE, _TRAILER = 0x21, 0x2C, 0x3B


def _skip_sub_blocks(data: bytes, at: int) -> int:
    """The offset after the data sub-blocks starting at ``at`` (a zero length ends them)."""
    while data[at]:
        at += data[at] + 1
    return at + 1


def _image_block(gif: bytes) -> bytes:
    """The first image of a one-frame GIF (as Pillow writes it) as an image descriptor carrying the
    file's global colour table as its local one, then the image's compressed data."""
    packed = gif[10]
    table_size = 3 * 2 ** ((packed & 7) + 1) if packed & 0x80 else 0
    table = gif[13:13 + table_size]
    at = 13 + table_size
    while gif[at] != _IMAGE:
        if gif[at] != _EXTENSION:
            raise ValueError("unexpected GIF block")  # never for Pillow's output
        at = _skip_sub_blocks(gif, at + 2)
    flags = gif[at + 9]
    if flags & 0x80:  # a local table of its own: kept
        bits = flags & 7
        table = gif[at + 10:at + 10 + 3 * 2 ** (bits + 1)]
    else:
        bits = packed & 7
    start = at + 10 + (len(table) if flags & 0x80 else 0)
    end = _skip_sub_blocks(gif, start + 1)  # after the LZW minimum code size
    descriptor = bytearray(gif[at:at + 10])
    descriptor[9] = (0x80 | bits if table else 0) | (flags & 0x40)  # the interlace bit as Pillow set it
    return bytes(descriptor) + table + gif[start:end]


class GifWriter:
    """Writes (H, W, 3) uint8 RGB frames of one size to an open binary file."""

    def __init__(self, file, size, delay: int) -> None:
        self._file = file
        self._size = (int(size[0]), int(size[1]))
        self._delay = int(delay)
        width, height = self._size
        # The header, a logical screen without a global table, and the loop-forever extension.
        file.write(b"GIF89a" + struct.pack("<HHBBB", width, height, 0, 0, 0))
        file.write(b"!\xff\x0bNETSCAPE2.0\x03\x01" + struct.pack("<H", 0) + b"\x00")
        self.frames = 0

    def add(self, rgb: np.ndarray) -> None:
        from PIL import Image

        image = Image.fromarray(np.ascontiguousarray(rgb, dtype=np.uint8), "RGB")
        if image.size != self._size:
            raise ValueError(f"frame: expected {self._size} pixels, got {image.size}")
        paletted = image.quantize(colors=255, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
        one = io.BytesIO()
        paletted.save(one, format="GIF", optimize=False)
        # The graphic control extension: no disposal (1), the delay, no transparency.
        self._file.write(b"!\xf9\x04" + struct.pack("<BHB", 1 << 2, self._delay, 0) + b"\x00")
        self._file.write(_image_block(one.getvalue()))
        self.frames += 1

    def close(self) -> None:
        self._file.write(bytes((_TRAILER,)))
