"""Animations: vgx-run --frames N --out anim.gif (display/anim.py), and the
accumulation frames of the gallery (AccumulationFrames)."""
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from vgx_emulator.display.anim import (AccumulationFrames, AnimationError, save_animation,
                                       write_gif)
from vgx_emulator.runner import main as vgx_run
from vgx_emulator.runner import run_program

ROOT = Path(__file__).resolve().parent.parent
TESSMAN = ROOT / "programs" / "tessman_flat_shadows.py"


def _gif_frames(path):
    im = Image.open(path)
    out = []
    for k in range(im.n_frames):
        im.seek(k)
        out.append(np.asarray(im.convert("RGB")))
    return out


def _still(k):
    """Tessman's moving light started at frame k, one frame drawn."""
    return run_program(TESSMAN, 1, ["--figure", "moving", "--frame", str(k)])


def test_gif_has_one_frame_per_program_frame_moving_as_the_program_says(tmp_path):
    frames = []
    run_program(TESSMAN, 4, ["--figure", "moving"], collect=frames)
    assert len(frames) == 4
    # frame k of the run is what the program draws for moving_light(k)
    for k, f in enumerate(frames):
        assert np.array_equal(f, _still(k))
    # the light moves: every frame differs from the one before
    for a, b in zip(frames, frames[1:]):
        assert (a != b).any(-1).sum() > 100
    gif = _gif_frames(write_gif(tmp_path / "m.gif", frames))
    assert len(gif) == 4
    for g, f in zip(gif, frames):
        assert g.shape == f.shape
        assert np.abs(g.astype(int) - f).mean() < 3.0      # 256-colour palette per frame
    for a, b in zip(gif, gif[1:]):
        assert (a != b).any(-1).sum() > 100


def test_every_k_keeps_frames_1_1_plus_k(tmp_path):
    frames = []
    run_program(TESSMAN, 7, ["--figure", "moving"], collect=frames, every=3)
    assert len(frames) == 3                       # frames 1, 4, 7
    for j, f in enumerate(frames):
        assert np.array_equal(f, _still(3 * j))


def test_vgx_run_writes_a_gif_at_the_program_pace(tmp_path, capsys):
    out = tmp_path / "anim.gif"
    assert vgx_run([str(TESSMAN), "--frames", "6", "--every", "2", "--out", str(out),
                    "--", "--figure", "moving"]) == 0
    im = Image.open(out)
    assert im.n_frames == 3
    # every 2nd frame at 30 frames a second: each shown 2/30 s (GIF: 10 ms steps)
    assert abs(im.info["duration"] - 2000 / 30) <= 10


def test_mp4_without_writer_says_how_to_get_one(tmp_path):
    try:
        import imageio_ffmpeg  # noqa: F401
        pytest.skip("imageio-ffmpeg is installed")
    except ImportError:
        pass
    frame = np.zeros((10, 10, 3), np.uint8)
    with pytest.raises(AnimationError, match=r"imageio-ffmpeg.*\[video\]"):
        save_animation(tmp_path / "a.mp4", [frame])
    assert not (tmp_path / "a.mp4").exists()
    assert vgx_run([str(TESSMAN), "--out", str(tmp_path / "b.mp4"), "--",
                    "--figure", "moving"]) == 2


def test_bad_suffix_and_no_frames(tmp_path):
    with pytest.raises(AnimationError):
        save_animation(tmp_path / "a.avi", [np.zeros((4, 4, 3), np.uint8)])
    with pytest.raises(AnimationError):
        write_gif(tmp_path / "a.gif", [])


def test_accumulation_frames_are_the_running_average(vgx):
    """After each AC_ACCUMULATE the frame is what AC_RETURN 1/sum would show."""
    from irisgl import (AC_ACCUMULATE, AC_CLEAR_ACCUMULATE, AC_RETURN, RGBmode, acbuf, acsize,
                        clear, cpack, gconfig, lrectread, prefsize, winopen)
    prefsize(8, 6)
    winopen("acc")
    RGBmode()
    acsize(16)
    gconfig()
    acc = AccumulationFrames()
    acc.install(vgx)
    reds = [200, 100, 51]
    for j, r in enumerate(reds):
        cpack(r)
        clear()
        acbuf(AC_CLEAR_ACCUMULATE if j == 0 else AC_ACCUMULATE, 1.0)
    acbuf(AC_RETURN, 1.0 / 3)
    acc.uninstall()
    assert vgx.trace_hook is None
    assert len(acc.frames) == 3
    for j, f in enumerate(acc.frames):
        want = int(np.floor(sum(reds[:j + 1]) / (j + 1) + 0.5))
        assert f.shape == (6, 8, 3)
        assert (f[..., 0] == want).all() and (f[..., 1:] == 0).all()
    # the last one is the picture AC_RETURN 1/3 gave
    assert (lrectread(0, 0, 7, 5) & 0xFF == acc.frames[-1][0, 0, 0]).all()


def test_heidmann_jittered_lights_accumulating():
    """Fig. 6 with 4 jittered lights: one animation frame per AC_ACCUMULATE;
    the last is the picture AC_RETURN 1/4 leaves on the screen; the soft
    shadow changes as images are added."""
    acc = AccumulationFrames()
    img = run_program(ROOT / "programs" / "heidmann_shadow_volumes.py", 1,
                      ["--figure", "6", "--jitter", "4", "--size", "96x72"], trace=acc)
    assert len(acc.frames) == 4
    assert np.array_equal(acc.frames[-1], img)
    for a, b in zip(acc.frames, acc.frames[1:]):
        assert (a != b).any()


def test_gallery_writes_the_animation_next_to_the_png(tmp_path):
    from vgx_emulator import gallery
    rows = gallery.render(tmp_path, ROOT / "programs", only=["tessman_flat_shadows/moving"])
    assert len(rows) == 1 and rows[0][4] is None
    gif = tmp_path / "tessman_flat_shadows__moving.gif"
    assert Image.open(gif).n_frames == 18
    assert (tmp_path / "tessman_flat_shadows__moving.png").is_file()
    assert "tessman_flat_shadows__moving.gif" in (tmp_path / "index.html").read_text()


def test_mp4_has_one_frame_per_program_frame(tmp_path):
    """With the [video] extra: the MP4 holds every frame, close to the PNG
    of that frame (H.264 is lossy: mean error a few levels of 255)."""
    imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg")
    frames = []
    run_program(TESSMAN, 3, ["--figure", "moving"], collect=frames)
    path = save_animation(tmp_path / "a.mp4", frames, fps=30.0)
    reader = imageio_ffmpeg.read_frames(str(path))
    meta = reader.__next__()
    w, h = meta["size"]
    got = [np.frombuffer(b, np.uint8).reshape(h, w, 3) for b in reader]
    assert len(got) == 3
    for g, f in zip(got, frames):
        err = np.abs(g[:f.shape[0], :f.shape[1]].astype(int) - f.astype(int)).mean()
        assert err < 6
    assert np.abs(got[0].astype(int) - got[2].astype(int)).mean() > 0.5   # the light moved


RESIZING = """\
from irisgl import *
prefsize(20, 10); winopen("grow"); RGBmode(); doublebuffer(); gconfig()
cpack(0xFF0000FF); clear(); swapbuffers()                  # 20 x 10, red
winposition(0, 39, 0, 29); reshapeviewport()
cpack(0xFFFF0000); clear(); swapbuffers()                  # 40 x 30, blue
winposition(0, 9, 0, 4); reshapeviewport()
cpack(0xFF00FF00); clear(); swapbuffers()                  # 10 x 5, green
"""


@pytest.mark.parametrize("suffix", [".gif", ".mp4"])
def test_a_window_that_changes_size_is_animated_whole(tmp_path, suffix):
    """Frames of several sizes (winposition between frames): each is placed
    at the top left of a canvas as large as the largest, none cropped (the
    GIF kept the first frame's size; the MP4 cropped a growing window and
    failed on a shrinking one)."""
    if suffix == ".mp4":
        imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg")
    prog = tmp_path / "grow.py"
    prog.write_text(RESIZING)
    frames = []
    run_program(prog, 3, collect=frames)
    assert [f.shape for f in frames] == [(10, 20, 3), (30, 40, 3), (5, 10, 3)]
    path = save_animation(tmp_path / ("a" + suffix), frames)
    if suffix == ".gif":
        got = _gif_frames(path)
        tol = 0
    else:
        reader = imageio_ffmpeg.read_frames(str(path))
        w, h = reader.__next__()["size"]
        got = [np.frombuffer(b, np.uint8).reshape(h, w, 3) for b in reader]
        tol = 40                                   # H.264 blurs colour edges
    assert len(got) == 3 and all(g.shape == (30, 40, 3) for g in got)
    for g, f in zip(got, frames):
        h, w = f.shape[:2]
        inner = g[1:h - 1, 1:w - 1].astype(int)
        assert np.abs(inner - f[1:h - 1, 1:w - 1]).max() <= tol      # the frame, whole
        outside = g.copy()
        outside[:h + 1, :w + 1] = 0
        assert outside.max() <= tol                                 # black around it
