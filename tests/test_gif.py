"""GIF recordings stream: each frame reaches the file as it is added (none is held in memory),
so a run's memory does not grow with its length; and the GIF shows what the one Pillow's
``save_all`` wrote from the whole list of frames showed (same frame count, every frame as a viewer
shows it equal, same display times)."""

import os
import tracemalloc

import numpy as np
from PIL import Image, ImageSequence

from robokin_sim import recording
from robokin_sim.recording import Recorder
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


def pillow_gif(path, frames, seconds):
    """The reference: every frame quantised, unchanged pixels transparent, one save_all at the end."""
    palette = recording._gif_palette()
    images, previous = [], None
    for rgb in frames:
        full = np.asarray(Image.fromarray(rgb, "RGB").quantize(palette=palette, dither=Image.Dither.NONE))
        delta = full.copy()
        if previous is not None:
            delta[full == previous] = recording._TRANSPARENT
        previous = full
        image = Image.fromarray(delta, "P")
        image.putpalette(palette.getpalette())
        images.append(image)
    images[0].save(path, format="GIF", save_all=True, append_images=images[1:],
                   duration=recording.gif_durations(len(images), seconds), loop=0, optimize=False, disposal=1,
                   transparency=recording._TRANSPARENT)


def shown(path):
    """Every frame as a viewer shows it (RGB) and its display time."""
    with Image.open(path) as im:
        return [(np.asarray(f.convert("RGB")), f.info.get("duration")) for f in ImageSequence.Iterator(im)]


def test_the_streamed_gif_is_the_one_pillow_wrote_from_all_frames(tmp_path):
    frames = [scene(k) for k in range(60)]
    rec = Recorder(str(tmp_path / "a.gif"), fps=30.0, every=1)
    for rgb in frames:
        rec.add(rgb)
    assert rec.close() == str(tmp_path / "a.gif")
    pillow_gif(tmp_path / "b.gif", frames, 1 / 30.0)
    got, want = shown(tmp_path / "a.gif"), shown(tmp_path / "b.gif")
    assert len(got) == len(want) == len(frames)  # a repeated frame is a frame too, as Pillow keeps it
    np.testing.assert_array_equal(got[0][0], want[0][0])
    for k, ((a, da), (b, db)) in enumerate(zip(got, want)):
        np.testing.assert_array_equal(a, b, err_msg=f"frame {k}")
        assert da == db, k
    with Image.open(tmp_path / "a.gif") as im:
        assert im.info.get("loop") == 0 and im.size == (W, H)


def test_frames_reach_the_file_as_they_come(tmp_path):
    rec = Recorder(str(tmp_path / "a.gif"))
    tmp = [os.path.join(tmp_path, n) for n in os.listdir(tmp_path)][0]
    sizes = []
    for k in range(40):
        rec.add(picture(k))
        sizes.append(os.path.getsize(tmp))
    assert all(b > a > 0 for a, b in zip(sizes, sizes[1:]))  # every frame in the file once added
    rec.close()
    assert os.listdir(tmp_path) == ["a.gif"]


def _peak(tmp_path, count):
    rec = Recorder(str(tmp_path / f"p{count}.gif"))
    rng = np.random.default_rng(0)
    noise = rng.integers(0, len(COLOURS), (count, H, W))  # frames that do not compress away
    palette = np.array(COLOURS, dtype=np.uint8)
    rec.add(scene(0))
    tracemalloc.start()
    try:
        for k in range(count):
            rec.add(palette[noise[k]])
        rec.close()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_memory_does_not_grow_with_the_number_of_frames(tmp_path):
    small, large = _peak(tmp_path, 20), _peak(tmp_path, 160)
    assert large < 1.3 * small + 200_000, (small, large)
