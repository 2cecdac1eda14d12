"""The notebook live view (vgx_emulator/notebook.py): a program runs in its
own thread, its window reaches an image widget, DOM events over the image
reach its queue.  Skipped without the [notebook] extra."""
import io
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("ipywidgets")
pytest.importorskip("ipyevents")

from PIL import Image                                      # noqa: E402

from vgx_emulator.notebook import LiveView                 # noqa: E402
from vgx_emulator.runner import run_program                # noqa: E402

CUBE = Path(__file__).resolve().parent.parent / "programs" / "demos" / "lit_valuators.py"


def _picture(view, previous=None, timeout=30.0):
    """The widget's picture once it is there (and differs from ``previous``)."""
    t0 = time.time()
    while time.time() - t0 < timeout:
        v = bytes(view.widget.value)
        if v:
            img = np.asarray(Image.open(io.BytesIO(v)).convert("RGB"))
            if previous is None or not np.array_equal(img, previous):
                time.sleep(0.2)             # let a frame in progress finish
                return np.asarray(Image.open(io.BytesIO(bytes(view.widget.value)))
                                  .convert("RGB"))
        time.sleep(0.05)
    raise AssertionError("no new picture")


def test_live_view_shows_the_frame_and_takes_a_drag():
    # the headless pictures first: the live program then has the machine alone
    start = run_program(CUBE, frames=1)
    dragged = run_program(CUBE, frames=2, argv=["-drag", "100", "149", "160", "149"])
    view = LiveView(CUBE, fps=0)
    try:
        first = _picture(view)
        assert np.array_equal(first, start)
        # a drag over the image from (100, 150) to (160, 150): screen y = 299 - 150
        for e in ({"type": "mousemove", "dataX": 100, "dataY": 150},
                  {"type": "mousedown", "dataX": 100, "dataY": 150, "button": 0},
                  {"type": "mousemove", "dataX": 160, "dataY": 150},
                  {"type": "mouseup", "dataX": 160, "dataY": 150, "button": 0}):
            view.on_event(e)
        after = _picture(view, previous=first)
        assert np.array_equal(after, dragged)
        view.on_event({"type": "keyup", "key": "Escape"})
        view.on_event({"type": "keydown", "key": "Escape"})
        view.on_event({"type": "keyup", "key": "Escape"})
        assert view.wait(10) is None and not view.thread.is_alive()
    finally:
        view.stop()


def test_stop_ends_a_waiting_program():
    view = LiveView(CUBE, fps=0)
    _picture(view)
    view.stop()
    assert not view.thread.is_alive()
