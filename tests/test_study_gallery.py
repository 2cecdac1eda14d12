"""vgx-gallery --workers N (the study-at-scale issue's gallery part): the
figures rendered in worker processes are the serial run's, in gallery
order, and a figure that fails or cannot be written is still reported
while the rest goes on."""
import pytest

from vgx_emulator import gallery

PROGRAM = """\
import sys
from irisgl import *
FIGURES = [{"name": "red", "args": [], "caption": "Tiny fig. 1: a red square."},
           {"name": "blue", "args": ["--blue"], "caption": "Tiny fig. 2: a blue square."}]
prefsize(40, 30); winopen("tiny"); RGBmode(); gconfig()
cpack(0xFFFF0000 if "--blue" in sys.argv else 0xFF0000FF); clear()
cpack(0xFFFFFFFF); rectf(5, 5, 20, 12); swapbuffers()
"""

BROKEN = """\
FIGURES = [{"name": "boom", "args": [], "caption": "Broken fig. 1: raises."}]
raise RuntimeError("no picture today")
"""

DEMO = """\
from irisgl import *
FIGURES = [{"name": "green", "args": [], "caption": "A green demo."}]
prefsize(24, 16); winopen("demo"); RGBmode(); gconfig()
cpack(0xFF00FF00); clear(); swapbuffers()
"""


@pytest.fixture
def programs(tmp_path, monkeypatch):
    d = tmp_path / "programs"
    (d / "demos").mkdir(parents=True)
    (d / "tiny.py").write_text(PROGRAM)
    (d / "broken.py").write_text(BROKEN)
    (d / "demos" / "demo.py").write_text(DEMO)
    monkeypatch.setattr(gallery, "PAPERS", [
        {"key": "tiny", "title": "Tiny: squares", "reference": "", "contribution": "",
         "programs": ["tiny", "broken"]}])
    monkeypatch.setattr(gallery, "PROGRAMS", ["tiny", "broken"])
    return d


def test_the_parallel_gallery_is_the_serial_one(programs, tmp_path):
    one = gallery.render(tmp_path / "one", programs)
    two = gallery.render(tmp_path / "two", programs, workers=2)
    assert [(r.prog.stem, r.fig["name"], r.png, r.error) for r in two] == \
        [(r.prog.stem, r.fig["name"], r.png, r.error) for r in one]
    assert [r.error is None for r in two] == [True, True, False, True]
    assert "RuntimeError: no picture today" in two[2].error
    for r in one:
        if r.png:
            assert (tmp_path / "two" / r.png).read_bytes() == \
                (tmp_path / "one" / r.png).read_bytes()
    assert (tmp_path / "two" / "index.html").exists()


def test_a_figure_it_cannot_write_is_reported_and_the_rest_goes_on(programs, tmp_path,
                                                                    capsys):
    out = tmp_path / "gallery"
    (out / "tiny__red.png").mkdir(parents=True)      # a folder where the PNG should go
    assert gallery.main(["--out", str(out), "--programs", str(programs),
                         "--workers", "2"]) == 1
    err = capsys.readouterr().err
    assert "failed: tiny/red: cannot write" in err and "failed: broken/boom" in err
    assert (out / "tiny__blue.png").is_file() and (out / "demos__demo__green.png").is_file()
    assert "failed: cannot write" in (out / "index.html").read_text()
