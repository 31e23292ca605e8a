"""robokin.gif.GifWriter, the GIF writer of robokin.plots.animate and the simulator's recordings.

Frames stream: each reaches the file as it is added and memory does not grow with their number.
What a viewer shows is checked against independent truths: on a fixed palette, the GIF that
Pillow's own ``save_all`` writes from the whole list of frames (same frame count, every frame shown
equal, same display times); with a palette per frame, each frame as Pillow quantises it alone, close
to the picture given. Display times are GIF's 10 ms ticks without drift, from exact fractions."""

import io
import math
import os
import tracemalloc
from fractions import Fraction

import numpy as np
import pytest
from PIL import GifImagePlugin, Image, ImageSequence

from robokin.gif import GifWriter, durations
from robokin_sim.recording import GIF_PALETTE, Recorder
from robokin_sim.theme import COLOURS

W, H = 160, 120


def picture(j):
    """Picture j: flat theme colours, a block moving a pixel a picture, a bar growing."""
    rgb = np.empty((H, W, 3), dtype=np.uint8)
    rgb[:] = COLOURS[0]
    x = j % (W - 20)
    rgb[40:70, x:x + 20] = COLOURS[1]
    rgb[5:9, 5:5 + (j % 50)] = COLOURS[2 % len(COLOURS)]
    return rgb


def scene(k):
    """Frame k: picture k, except that every third frame repeats the one before."""
    return picture(k - (k + 1) // 3)


def smooth(k, width=W, height=H):
    """Anti-aliased-like frame k: a gradient (more colours than a palette holds) and a moving disc."""
    y, x = np.mgrid[0:height, 0:width]
    rgb = np.empty((height, width, 3), dtype=np.uint8)
    rgb[..., 0] = 255 * x // (width - 1)
    rgb[..., 1] = 255 * y // (height - 1)
    rgb[..., 2] = 128
    disc = np.hypot(x - 20 - 3 * k, y - height / 2) < 15
    rgb[disc] = (250, 250, 250)
    return rgb


def quantiser(colours):
    image = Image.new("P", (1, 1))
    image.putpalette([c for rgb in colours for c in rgb])
    return image


def pillow_gif(path, frames, seconds, colours):
    """The reference: every frame quantised to ``colours``, the pixels unchanged since the frame
    before transparent (the index after the colours), one save_all at the end."""
    palette = quantiser(colours)
    transparent = len(colours)
    images, previous = [], None
    for rgb in frames:
        full = np.asarray(Image.fromarray(rgb, "RGB").quantize(palette=palette, dither=Image.Dither.NONE))
        delta = full.copy()
        if previous is not None:
            delta[full == previous] = transparent
        previous = full
        image = Image.fromarray(delta, "P")
        image.putpalette(palette.getpalette() + [0, 0, 0])
        images.append(image)
    ms = [int(1000 * (exact_end(k + 1, seconds) - exact_end(k, seconds))) for k in range(len(frames))]
    images[0].save(path, format="GIF", save_all=True, append_images=images[1:], loop=0, optimize=False,
                   disposal=1, transparency=transparent, duration=ms)


def exact_end(k, seconds):
    """When frame k starts (s): k frames of ``seconds`` (at least 20 ms), rounded to 10 ms ticks."""
    per = max(Fraction(seconds), Fraction(1, 50))
    return Fraction(round(k * per * 100), 100)


def shown(source):
    """Every frame as a viewer shows it (RGB) and its display time."""
    with Image.open(source) as im:
        return [(np.asarray(f.convert("RGB")), f.info.get("duration")) for f in ImageSequence.Iterator(im)]


def write(frames, seconds=0.1, size=(W, H), **kwargs):
    out = io.BytesIO()
    with GifWriter(out, size, seconds, **kwargs) as gif:
        for rgb in frames:
            gif.add(rgb)
    assert gif.frames == len(frames)
    out.seek(0)
    return out


def test_on_a_fixed_palette_the_gif_is_the_one_pillow_wrote_from_all_frames(tmp_path):
    frames = [scene(k) for k in range(60)]
    for colours, name in ((GIF_PALETTE, "theme"), (COLOURS[:3], "three")):  # a palette without most colours too
        out = write(frames, 1 / 30.0, palette=[c for rgb in colours for c in rgb])
        pillow_gif(tmp_path / f"{name}.gif", frames, 1 / 30.0, colours)
        got, want = shown(out), shown(tmp_path / f"{name}.gif")
        assert len(got) == len(want) == len(frames)  # a repeated frame is a frame too, as Pillow keeps it
        for k, ((a, da), (b, db)) in enumerate(zip(got, want)):
            np.testing.assert_array_equal(a, b, err_msg=f"{name}: frame {k}")
            assert da == db, (name, k)
        with Image.open(out) as im:
            assert im.info.get("loop") == 0 and im.size == (W, H)
    # One global table of 64 entries (the theme's colours, then the transparent one): 6-bit codes.
    assert len(GIF_PALETTE) <= 63 and write(frames[:1], palette=GIF_PALETTE).getvalue()[10] == 0x80 | 5


def test_the_recorder_writes_what_pillow_wrote_from_all_frames(tmp_path):
    frames = [scene(k) for k in range(30)]
    rec = Recorder(str(tmp_path / "a.gif"), fps=30.0, every=1)
    for rgb in frames:
        rec.add(rgb)
    assert rec.close() == str(tmp_path / "a.gif")
    pillow_gif(tmp_path / "b.gif", frames, 1 / 30.0, GIF_PALETTE)
    got, want = shown(tmp_path / "a.gif"), shown(tmp_path / "b.gif")
    assert len(got) == len(want) == len(frames)
    for k, ((a, da), (b, db)) in enumerate(zip(got, want)):
        np.testing.assert_array_equal(a, b, err_msg=f"frame {k}")
        assert da == db, k


def test_no_pixel_takes_the_transparent_index():
    """Colours far from every palette entry (black, magenta) show as their nearest entry, never as
    the frame before showing through."""
    colours = [(250, 250, 250), (90, 90, 90), (200, 40, 40)]
    first = np.full((H, W, 3), 250, np.uint8)
    second = first.copy()
    second[10:50, 10:50] = (0, 0, 0)
    second[60:90, 60:90] = (255, 0, 255)
    (_, _), (shown_second, _) = shown(write([first, second], palette=colours))
    assert (shown_second[10:50, 10:50] == (90, 90, 90)).all()
    assert (shown_second[60:90, 60:90] == (200, 40, 40)).all()


def test_a_palette_per_frame_shows_each_frame_as_pillow_quantises_it(tmp_path):
    frames = [smooth(k) for k in range(12)] + [smooth(11)]
    got = shown(write(frames, 0.05))
    assert len(got) == len(frames)
    for k, (rgb, duration) in enumerate(got):
        alone = Image.fromarray(frames[k]).quantize(colors=255, method=Image.Quantize.MEDIANCUT,
                                                    dither=Image.Dither.NONE)
        np.testing.assert_array_equal(rgb, np.asarray(alone.convert("RGB")), err_msg=f"frame {k}")
        error = np.abs(rgb.astype(int) - frames[k])
        assert error.max() <= 24 and error.mean() < 4, (k, error.max(), error.mean())
        assert duration == 50


def test_a_palette_per_frame_keeps_a_few_colours_exact():
    rng = np.random.default_rng(1)
    colours = rng.integers(0, 256, (5, 3))
    frames = []
    for k in range(5):
        frame = np.zeros((48, 64, 3), np.uint8)
        frame[:, : 10 * (k + 1)] = colours[k]
        frames.append(frame)
    for k, (rgb, duration) in enumerate(shown(write(frames, 0.04, size=(64, 48)))):
        np.testing.assert_array_equal(rgb, frames[k])
        assert duration == 40


def test_display_times_are_ticks_that_do_not_drift():
    for seconds in (1 / 30, 1 / 60, 2 / 60, 1 / 7, 0.1, 0.5, 655.35):  # no tick falls on a half
        ms = durations(100, seconds)
        ends = [exact_end(k + 1, seconds) for k in range(100)]
        assert np.cumsum(ms).tolist() == [int(1000 * e) for e in ends], seconds
        assert all(m % 10 == 0 and m >= 20 for m in ms)
    assert durations(6, 1 / 30) == [30, 40, 30, 30, 40, 30] and durations(0, 1.0) == []
    got = shown(write([scene(k) for k in range(7)], 1 / 30))
    assert [d for _, d in got] == durations(7, 1 / 30)


@pytest.mark.parametrize("palette", [None, GIF_PALETTE])
def test_frames_reach_the_file_as_they_are_added(tmp_path, palette):
    path = tmp_path / "a.gif"
    gif = GifWriter(path, (W, H), 0.1, palette=palette)
    sizes = []
    for k in range(20):
        gif.add(picture(k))
        sizes.append(os.path.getsize(path))
    assert all(b > a > 0 for a, b in zip(sizes, sizes[1:]))  # every frame in the file once added
    gif.close()
    assert len(shown(path)) == 20 and os.path.getsize(path) == sizes[-1] + 1  # then the trailer


class Sink:
    """An output that keeps nothing: what grows is the writer's own memory."""

    def write(self, data):
        return len(data)

    def flush(self):
        pass


def _peak(count, palette):
    rng = np.random.default_rng(0)
    noise = rng.integers(0, len(COLOURS), (count, H, W))  # frames that do not compress away
    colours = np.array(COLOURS, dtype=np.uint8)
    gif = GifWriter(Sink(), (W, H), 0.1, palette=palette)
    gif.add(scene(0))
    gif.add(colours[noise[0]])
    tracemalloc.start()
    try:
        for k in range(count):
            gif.add(colours[noise[k]])
        gif.close()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("palette", [None, GIF_PALETTE])
def test_memory_does_not_grow_with_the_number_of_frames(palette):
    small, large = _peak(10, palette), _peak(80, palette)
    assert large < 1.3 * small + 200_000, (small, large)


def test_the_recorder_streams_frames_to_its_temporary_file(tmp_path):
    rec = Recorder(str(tmp_path / "a.gif"))
    tmp = [os.path.join(tmp_path, n) for n in os.listdir(tmp_path)][0]
    sizes = []
    for k in range(20):
        rec.add(picture(k))
        sizes.append(os.path.getsize(tmp))
    assert all(b > a > 0 for a, b in zip(sizes, sizes[1:]))
    rec.close()
    assert os.listdir(tmp_path) == ["a.gif"]


def _interrupt(*args, **kwargs):
    raise KeyboardInterrupt


def test_an_interrupted_writer_closes_its_file_unfinished(tmp_path, monkeypatch):
    path = tmp_path / "a.gif"
    with pytest.raises(KeyboardInterrupt):
        with GifWriter(path, (W, H), 0.1) as gif:
            gif.add(picture(0))
            monkeypatch.setattr(GifImagePlugin, "getdata", _interrupt)
            gif.add(picture(1))
    with pytest.raises(ValueError, match="close"):  # the writer is done
        gif.add(picture(2))
    data = path.read_bytes()
    assert data.startswith(b"GIF89a") and not data.endswith(b";")  # the file, closed unfinished


def test_arguments_are_checked_by_name(tmp_path):
    out = io.BytesIO()
    for size in ((0, 10), (10, 70000), (10,), (10, 20, 30), "ab"):
        with pytest.raises(ValueError, match="size"):
            GifWriter(out, size, 0.1)
    for size in ((10.5, 20), [1, [2]]):  # a side that is not an int
        with pytest.raises(TypeError, match="size"):
            GifWriter(out, size, 0.1)
    for seconds in (0, -0.1, math.nan, math.inf):
        with pytest.raises(ValueError, match="seconds"):
            GifWriter(out, (W, H), seconds)
    with pytest.raises(ValueError, match=r"^seconds: must be a finite number <= 655.35, got 655.36$"):
        GifWriter(out, (W, H), 655.36)
    with pytest.raises(TypeError, match="seconds"):
        GifWriter(out, (W, H), "0.1")
    rgb = Image.new("RGB", (4, 4))
    bad_palettes = ([], list(range(256)) * 3, [0, 0, 0, 255, 255], [[0, 0, 0, 0]], [0, 0, 300], [0, 0, -1],
                    [0.5, 0, 0], rgb, Image.new("P", (1, 1)))  # an RGB image; a "P" image without colours
    for palette in bad_palettes:
        with pytest.raises(ValueError, match="palette"):
            GifWriter(out, (W, H), 0.1, palette=palette)
    for palette in ("red", [None, 0, 0]):
        with pytest.raises(TypeError, match="palette"):
            GifWriter(out, (W, H), 0.1, palette=palette)
    with pytest.raises(TypeError, match="file"):
        GifWriter(12, (W, H), 0.1)
    gif = GifWriter(out, (W, H), 0.1, palette=quantiser(COLOURS[:4]))  # a "P" image's palette is taken
    for frame in (np.zeros((W, H, 3), np.uint8), np.zeros((H, W), np.uint8), np.zeros((H, W, 4), np.uint8)):
        with pytest.raises(ValueError, match="rgb"):
            gif.add(frame)
    with pytest.raises(TypeError, match="rgb"):
        gif.add(np.zeros((H, W, 3)))
    assert gif.frames == 0
    gif.add(picture(0))
    gif.close()
    assert len(shown(io.BytesIO(out.getvalue()))) == 1
    for count, seconds, error in ((-1, 0.1, ValueError), (1.5, 0.1, TypeError), (3, 0, ValueError)):
        with pytest.raises(error, match="count" if seconds else "seconds"):
            durations(count, seconds)
