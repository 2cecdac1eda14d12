"""Animations of what a window showed, frame by frame (``vgx-run --frames N
--out anim.gif``).

A frame is shown for ``every / fps`` seconds, so saving every K-th frame
keeps the program's pace (the frame points of a headless run are taken at
``fps`` a second, 30 by default).  GIF is written with Pillow, each frame
with its own 256-colour palette, looping forever; consecutive identical
frames become one longer frame (same timing).  Frames of a window that
changed size are placed at the top left of a canvas of the largest.  MP4 needs the optional extra
``pip install 'iris-vgx[video]'`` (imageio-ffmpeg, its own ffmpeg binary);
without it writing an .mp4 raises AnimationError saying so.
"""
from pathlib import Path

import numpy as np
from PIL import Image

__all__ = ["AnimationError", "AccumulationFrames", "save_animation", "write_gif",
           "write_mp4", "FORMATS"]

FORMATS = (".gif", ".mp4")


class AnimationError(RuntimeError):
    """An animation cannot be written (no frames, no video writer)."""


def _check(frames):
    """The frames as (h, w, 3) uint8 arrays of one size.  A window that
    changed size during the run (winposition, a full-screen toggle) gives
    frames of several sizes: each is placed at the top left of a black
    canvas as large as the largest, so no frame is cropped."""
    frames = [np.asarray(f, np.uint8) for f in frames]
    if not frames:
        raise AnimationError("no frame was drawn: nothing to animate")
    h = max(f.shape[0] for f in frames)
    w = max(f.shape[1] for f in frames)
    for i, f in enumerate(frames):
        if f.shape[:2] != (h, w):
            canvas = np.zeros((h, w, 3), np.uint8)
            canvas[:f.shape[0], :f.shape[1]] = f
            frames[i] = canvas
    return frames


def write_gif(path, frames, fps=30.0, every=1):
    """Save (h, w, 3) uint8 frames (top row first) as a looping GIF."""
    frames = _check(frames)
    ims = [Image.fromarray(f, "RGB").quantize(256, method=Image.Quantize.MEDIANCUT,
                                              dither=Image.Dither.NONE) for f in frames]
    ms = max(int(round(1000.0 * every / fps)), 20) if fps > 0 else 100
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    ims[0].save(path, save_all=True, append_images=ims[1:], duration=ms, loop=0,
                disposal=1)
    return path


def write_mp4(path, frames, fps=30.0, every=1):
    """Save frames as an H.264 MP4 through imageio-ffmpeg (the ``video``
    extra); odd sizes are padded by one black row/column (yuv420p)."""
    try:
        import imageio_ffmpeg
    except ImportError:
        raise AnimationError("writing .mp4 needs imageio-ffmpeg: pip install "
                             "'iris-vgx[video]' (or save a .gif)") from None
    frames = _check(frames)
    h, w = frames[0].shape[:2]
    H, W = h + h % 2, w + w % 2
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    rate = fps / every if fps > 0 else 30.0
    gen = imageio_ffmpeg.write_frames(str(path), (W, H), fps=rate, codec="libx264",
                                      pix_fmt_out="yuv420p", macro_block_size=1)
    gen.send(None)
    for f in frames:
        pad = np.zeros((H, W, 3), np.uint8)
        pad[:h, :w] = f
        gen.send(np.ascontiguousarray(pad))
    gen.close()
    return path


def save_animation(path, frames, fps=30.0, every=1):
    """Write frames as a .gif or .mp4 (by the name's suffix)."""
    suffix = Path(path).suffix.lower()
    if suffix == ".gif":
        return write_gif(path, frames, fps, every)
    if suffix == ".mp4":
        return write_mp4(path, frames, fps, every)
    raise AnimationError(f"{path}: an animation is a .gif or an .mp4")


class AccumulationFrames:
    """Frames of the accumulation buffer filling up inside one frame
    (acbuf(3G)): after each AC_ACCUMULATE (or AC_CLEAR_ACCUMULATE) the
    accumulated R G B divided by the sum of the values accumulated so far,
    i.e. what AC_RETURN with 1/that sum would show.  Install it as
    ``run_program(..., trace=AccumulationFrames())``; ``frames`` holds the
    (h, w, 3) images, top row first."""

    def __init__(self):
        self.frames = []
        self.weight = {}
        self.machine = None

    def install(self, machine):
        self.machine = machine
        machine.trace_hook = self._hook

    def uninstall(self):
        if self.machine is not None:
            self.machine.trace_hook = None

    def _hook(self, m, win, event, *detail):
        if event != "acbuf" or win.fb.accum is None:
            return
        op, value = detail
        if op == 0:                                  # AC_CLEAR
            self.weight[win.gid] = 0.0
        elif op in (1, 2):                           # AC_ACCUMULATE, AC_CLEAR_ACCUMULATE
            w = value + (self.weight.get(win.gid, 0.0) if op == 1 else 0.0)
            self.weight[win.gid] = w
            if w > 0:
                rgb = win.fb.accum[..., :3].astype(np.float64) * (1.0 / w)
                self.frames.append(np.clip(np.floor(rgb + 0.5), 0, 255)
                                   .astype(np.uint8)[::-1].copy())
