"""vgx-gallery (vgx_emulator/gallery.py): a section per paper with its
reference, a table of contents, every figure once, at its own size beside
its caption, a page per figure with the command that reproduces it, and a
figure that fails or cannot be written reported while the rest goes on.
The page is opened in headless Chromium, where every picture must load."""
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from PIL import Image

from vgx_emulator import gallery
from vgx_emulator.runner import main as vgx_run

ROOT = Path(__file__).resolve().parent.parent

PROGRAM = """\
import sys
from irisgl import *
FIGURES = [{{"name": "red", "args": [], "caption": "Tiny fig. 1: a red square."}},
           {{"name": "blue", "args": ["--blue"], "caption": "Tiny fig. 2: a blue square."}}]
prefsize({w}, {h}); winopen("tiny"); RGBmode(); gconfig()
cpack(0xFFFF0000 if "--blue" in sys.argv else 0xFF0000FF); clear(); swapbuffers()
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
    """A programs folder: a 'paper' program, a broken one, a demo."""
    d = tmp_path / "programs"
    (d / "demos").mkdir(parents=True)
    (d / "tiny.py").write_text(PROGRAM.format(w=40, h=30))
    (d / "broken.py").write_text(BROKEN)
    (d / "demos" / "demo.py").write_text(DEMO)
    monkeypatch.setattr(gallery, "PAPERS", [
        {"key": "tiny", "title": "Tiny 2024: squares", "reference": "A. Author, \"Squares\", "
         "Journal of Tiny Things 1(1), 1-2, 2024.", "contribution": "Coloured squares.",
         "programs": ["tiny", "broken"]}])
    monkeypatch.setattr(gallery, "PROGRAMS", ["tiny", "broken"])
    return d


def test_seed_figures_appear_once():
    """No figure twice: Williams fig. 1 comes from its own program only."""
    items = gallery.collect(ROOT / "programs")
    stems = [gallery._stem(p, f) for p, f, _ in items]
    captions = [f["caption"] for _, f, _ in items]
    assert len(set(stems)) == len(stems) and len(set(captions)) == len(captions)
    assert sum("four spheres" in c and "observer" in c for c in captions) == 1
    assert {s for _, _, s in items} >= {p["key"] for p in gallery.PAPERS if p["key"] != "newell"}


def test_every_paper_has_its_full_reference():
    for p in gallery.PAPERS:
        assert p["reference"].count('"') == 2 and re.search(r"19\d\d|20\d\d|Illinois",
                                                              p["reference"]), p["key"]
        assert len(p["contribution"]) > 80 and p["programs"]


def test_page_sections_contents_and_figure_pages(programs, tmp_path):
    out = tmp_path / "gallery"
    rows = gallery.render(out, programs)
    assert [(r.prog.stem, r.fig["name"]) for r in rows] == [
        ("tiny", "red"), ("tiny", "blue"), ("broken", "boom"), ("demo", "green")]
    assert [r.error is None for r in rows] == [True, True, False, True]
    assert "RuntimeError: no picture today" in rows[2].error
    page = (out / "index.html").read_text()
    # a section per paper, with its reference and contribution, then the demos
    assert page.index("id='tiny'") < page.index("id='demos'")
    assert "Journal of Tiny Things 1(1), 1-2, 2024." in page and "Coloured squares." in page
    # the table of contents links every section and every figure
    toc = page[page.index("<nav"):page.index("</nav>")]
    links = re.findall(r"href='#([^']+)'", toc)
    assert set(links) == {"tiny", "demos"} | {gallery._stem(r.prog, r.fig) for r in rows}
    assert all(f"id='{a}'" in page for a in links)
    # figures at their own size, caption beside (one figure element each)
    assert "<img src='tiny__red.png' alt='red' width='40' height='30'>" in page
    assert page.count("<figure") == 4 and "failed: RuntimeError" in page
    assert "display:grid" in page
    # a page per figure, with the command that reproduces it
    fig_page = (out / "tiny__blue.html").read_text()
    cmd = re.search(r"<pre>(vgx-run [^<]+)</pre>", fig_page).group(1)
    assert cmd == "vgx-run programs/tiny.py --out tiny__blue.png -- --blue"
    assert "Journal of Tiny Things" in fig_page


def test_the_command_of_a_figure_page_reproduces_it(programs, tmp_path, monkeypatch):
    out = tmp_path / "gallery"
    rows = gallery.render(out, programs, only=["tiny/blue"])
    monkeypatch.chdir(programs.parent)
    cmd = gallery.command(rows[0].prog, rows[0].fig).split()
    assert cmd[0] == "vgx-run" and vgx_run(cmd[1:]) == 0
    a = Image.open(programs.parent / "tiny__blue.png").convert("RGB")
    b = Image.open(out / "tiny__blue.png").convert("RGB")
    assert a.tobytes() == b.tobytes() and a.getpixel((0, 0)) == (0, 0, 255)


def test_render_time_is_shown_apart_from_compile_time(programs, tmp_path):
    rows = gallery.render(tmp_path / "g", programs, only=["tiny/red"])
    r = rows[0]
    assert r.seconds >= 0 and r.compile >= 0
    page = (tmp_path / "g" / "index.html").read_text()
    assert f"rendered in {r.seconds:.2f} s" in page
    assert "compiling the kernels (or loading them from numba's disk cache) took" in page


def test_a_figure_that_cannot_be_written_is_reported_and_the_rest_goes_on(
        programs, tmp_path, capsys):
    out = tmp_path / "gallery"
    (out / "tiny__red.png").mkdir(parents=True)      # a folder where the PNG should go
    assert gallery.main(["--out", str(out), "--programs", str(programs)]) == 1
    err = capsys.readouterr().err
    assert "failed: tiny/red: cannot write" in err and "failed: broken/boom" in err
    assert (out / "tiny__blue.png").is_file() and (out / "demos__demo__green.png").is_file()
    page = (out / "index.html").read_text()
    assert "failed: cannot write" in page and "tiny__blue.png" in page


CHROMIUM = next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome")
                 if shutil.which(n)), None)

#: appended to a copy of the page: after load, the body lists every picture
#: that did not load (complete and with a natural width)
CHECK = """<script>
window.addEventListener('load', function () {
  var bad = [], imgs = document.images;
  for (var i = 0; i < imgs.length; i++)
    if (!(imgs[i].complete && imgs[i].naturalWidth > 0)) bad.push(imgs[i].getAttribute('src'));
  document.body.setAttribute('data-images', String(imgs.length));
  document.body.setAttribute('data-broken', bad.join(' ') || 'none');
});
</script>"""


def _images_in_chromium(page):
    probe = page.with_name("_probe_" + page.name)
    probe.write_text(page.read_text().replace("</body>", CHECK + "</body>"))
    r = subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu",
                        "--allow-file-access-from-files", "--virtual-time-budget=5000",
                        "--dump-dom", probe.as_uri()],
                       capture_output=True, text=True, timeout=120)
    probe.unlink()
    m = re.search(r"data-images=\"(\d+)\" data-broken=\"([^\"]*)\"", r.stdout)
    assert m, r.stdout[-2000:] + r.stderr[-2000:]
    return int(m.group(1)), m.group(2)


@pytest.mark.skipif(CHROMIUM is None, reason="needs chromium (apt-get install chromium)")
def test_every_picture_loads_in_headless_chromium(programs, tmp_path):
    out = tmp_path / "gallery"
    gallery.render(out, programs)
    n, broken = _images_in_chromium(out / "index.html")
    assert n == 3 and broken == "none"
    n, broken = _images_in_chromium(out / "tiny__red.html")
    assert n == 1 and broken == "none"
