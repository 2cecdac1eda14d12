"""vgx-run's command line (vgx_emulator/runner.py): its own options are
checked, the program's go after ``--``, and a program that raises shows its
own traceback without the runner's frames."""
import sys

import pytest

from vgx_emulator.runner import main as vgx_run

PROGRAM = """\
import sys
from irisgl import *
open(sys.argv[0] + ".args", "w").write(repr(sys.argv[1:]))
prefsize(8, 8); winopen("cli"); RGBmode(); gconfig()
cpack(0xFF0000FF); clear(); swapbuffers()
"""


def _write(tmp_path, text, name="prog.py"):
    p = tmp_path / name
    p.write_text(text)
    return p


def _args(prog):
    return eval(open(str(prog) + ".args").read())


def test_an_unknown_option_is_an_error_naming_it(tmp_path, capsys):
    prog = _write(tmp_path, PROGRAM)
    with pytest.raises(SystemExit) as e:
        vgx_run([str(prog), "--fames", "3", "--out", str(tmp_path / "x.png")])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert "unrecognized option --fames" in err and "after --" in err
    assert not (tmp_path / "x.png").exists()          # nothing ran


def test_program_options_go_after_the_double_dash(tmp_path):
    prog = _write(tmp_path, PROGRAM)
    assert vgx_run([str(prog), "--out", str(tmp_path / "x.png"), "--",
                    "--fames", "3", "--out", "y"]) == 0
    assert _args(prog) == ["--fames", "3", "--out", "y"]
    assert (tmp_path / "x.png").is_file()


def test_bare_words_reach_the_program(tmp_path):
    prog = _write(tmp_path, PROGRAM)
    assert vgx_run([str(prog), "exp2", "--out", str(tmp_path / "x.png")]) == 0
    assert _args(prog) == ["exp2"]


def test_a_program_error_shows_the_program_traceback_only(tmp_path, capsys):
    helper = _write(tmp_path, "def boom(n):\n    return 1 // n\n", "helper.py")
    prog = _write(tmp_path, "import sys\nsys.path.insert(0, %r)\nimport helper\n\n"
                            "def draw():\n    helper.boom(0)\n\ndraw()\n" % str(helper.parent))
    assert vgx_run([str(prog), "--out", str(tmp_path / "x.png")]) == 1
    err = capsys.readouterr().err
    assert err.startswith("Traceback (most recent call last):")
    assert "ZeroDivisionError: integer division or modulo by zero" in err
    assert f'File "{prog}", line 8, in <module>' in err
    assert "in draw" in err and "helper.py" in err and "in boom" in err
    assert "runner.py" not in err and "runpy" not in err


def test_a_glerror_traceback_ends_at_the_program_call(tmp_path, capsys):
    prog = _write(tmp_path, "from irisgl import *\nprefsize(8, 8); winopen('e')\n"
                            "RGBmode(); gconfig()\npopmatrix()\n")
    assert vgx_run([str(prog), "--out", str(tmp_path / "x.png")]) == 1
    err = capsys.readouterr().err
    lines = err.splitlines()
    assert f'File "{prog}", line 4, in <module>' in err
    assert "popmatrix()" in err
    assert any(s.startswith("vgx_emulator.errors.GLError: popmatrix:")
               or s.startswith("GLError: popmatrix:") for s in lines), err
    assert "irisgl" + "/" not in err.replace(str(prog), "") and "runner.py" not in err


def test_the_runner_runs_as_a_module_without_runpys_warning(tmp_path):
    """``python -m vgx_emulator.runner prog.py`` works like vgx-run, and the
    package's import has not loaded the runner before runpy runs it (runpy's
    RuntimeWarning, made an error here)."""
    import subprocess
    prog = _write(tmp_path, PROGRAM)
    out = tmp_path / "m.png"
    r = subprocess.run([sys.executable, "-W", "error::RuntimeWarning", "-m",
                        "vgx_emulator.runner", str(prog), "--out", str(out)],
                       capture_output=True, text=True, timeout=600, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "found in sys.modules" not in r.stderr and out.is_file()


TWO_WINDOWS = """\
from irisgl import *
prefposition(100, 119, 200, 209); a = winopen("a"); RGBmode(); gconfig()
cpack(0xFF0000FF); clear()
prefposition(130, 139, 205, 224); b = winopen("b"); RGBmode(); gconfig()
cpack(0xFF00FF00); clear(); gflush()
"""


def test_screen_pictures_every_window_where_it_is(tmp_path):
    """``vgx-run --screen``: the smallest screen rectangle holding every
    open window (x 100..139, y 200..224), each window at its place, the
    rest black; without it, the current window alone."""
    from PIL import Image
    import numpy as np
    prog = _write(tmp_path, TWO_WINDOWS)
    assert vgx_run([str(prog), "--screen", "--out", str(tmp_path / "s.png")]) == 0
    assert vgx_run([str(prog), "--out", str(tmp_path / "w.png")]) == 0
    s = np.asarray(Image.open(tmp_path / "s.png").convert("RGB"))
    w = np.asarray(Image.open(tmp_path / "w.png").convert("RGB"))
    assert s.shape == (25, 40, 3) and w.shape == (20, 10, 3)
    top = 224                                        # row 0 of the picture is screen y 224
    red, green, black = (255, 0, 0), (0, 255, 0), (0, 0, 0)
    assert tuple(s[top - 205, 5]) == red             # window a: x 100..119, y 200..209
    assert tuple(s[top - 215, 35]) == green          # window b: x 130..139, y 205..224
    assert tuple(s[top - 220, 5]) == black           # above a, left of b
    assert np.array_equal(s[0:20, 30:40], w)         # b whole, as it shows alone


def test_a_loop_that_waits_on_a_button_ends_cleanly(tmp_path):
    """alias_back.c: ``while (!getbutton(ESCKEY)) { ...mapcolor... }`` with no
    frame point waits for a key no one presses headless: after POLLS reads
    of a device's state the runner ends it cleanly and saves its picture
    (it hung); getvaluator and getdev count the same way."""
    from PIL import Image
    import numpy as np
    for read in ("getbutton(ESCKEY)", "getvaluator(MOUSEX) > 5000", "getdev(1, [ESCKEY])[0]"):
        prog = _write(tmp_path, "from irisgl import *\n"
                                "prefsize(8, 8); winopen('poll'); color(RED); clear()\n"
                                f"while not ({read}):\n"
                                "    mapcolor(RED, 0, 255, 0)\n", name="poll.py")
        out = tmp_path / "p.png"
        assert vgx_run([str(prog), "--out", str(out)]) == 0
        assert tuple(np.asarray(Image.open(out).convert("RGB"))[4, 4]) == (0, 255, 0)


def test_gsync_is_a_frame_point_single_buffered(tmp_path):
    """gsync(3G) paces a single-buffered GL2-era program (stars.c): each is
    a frame point, so --frames 3 stops after the third, and an animation
    gets a frame each; double-buffered, swapbuffers is the frame point."""
    from vgx_emulator.runner import run_program
    prog = _write(tmp_path, "from irisgl import *\n"
                            "prefsize(8, 8); winopen('s'); RGBmode(); gconfig()\n"
                            "for k in range(100):\n"
                            "    cpack(0xFF000000 | k); clear(); gsync()\n", name="s.py")
    frames = []
    img = run_program(prog, 3, collect=frames)
    assert len(frames) == 3 and [int(f[0, 0, 0]) for f in frames] == [0, 1, 2]
    assert int(img[0, 0, 0]) == 2


SCRIPTED = """\
import sys
from irisgl import *
prefsize(8, 8); winopen("in"); RGBmode(); doublebuffer(); gconfig()
qdevice(KEYBD); qdevice(LEFTMOUSE); tie(LEFTMOUSE, MOUSEX, MOUSEY)
got = []
while True:
    cpack(0xFF000000 | len(got)); clear(); swapbuffers()
    dev, val = qread()
    got.append((dev, val))
    open(sys.argv[0] + ".got", "w").write(repr(got))
"""


def test_input_scripts_keys_and_buttons_by_frame(tmp_path):
    """``vgx-run --input N:DEV=VAL,...``: after the N-th frame point (0: at
    the first wait) the devices change as the window system reports them,
    a tied button bringing its valuators; a bad spec is a usage error."""
    prog = _write(tmp_path, SCRIPTED)
    assert vgx_run([str(prog), "--frames", "8", "--out", str(tmp_path / "i.png"),
                    "--input", "0:KEYBD=a", "--input", "2:MOUSEX=30,MOUSEY=40,LEFTMOUSE=1"]) == 0
    got = eval(open(str(prog) + ".got").read())
    events = [e for e in got if e[0] not in (REDRAW_DEV, INPUTCHANGE_DEV)]
    assert events[:4] == [(513, ord("a")), (103, 1), (266, 30), (267, 40)]
    with pytest.raises(SystemExit) as e:
        vgx_run([str(prog), "--input", "x:KEYBD=a"])
    assert e.value.code == 2
    with pytest.raises(SystemExit):
        vgx_run([str(prog), "--input", "1:NOSUCHKEY=1"])


REDRAW_DEV, INPUTCHANGE_DEV = 528, 534


def test_a_program_that_starts_graphics_again_after_gexit_keeps_its_input(tmp_path):
    """gexit then ginit again (a GL2-era habit): the runner's hooks stay, so
    a later qtest-only loop ends cleanly headless (it hung) and scripted
    input still arrives."""
    prog = _write(tmp_path, "import sys\n"
                            "from irisgl import *\n"
                            "ginit(); color(RED); clear(); gexit()\n"
                            "ginit(); qdevice(KEYBD); qreset(); color(GREEN); clear(); gflush()\n"
                            "while qtest() == 0:\n"
                            "    pass\n"
                            "open(sys.argv[0] + '.got', 'w').write(repr(qread()))\n",
                  name="again.py")
    assert vgx_run([str(prog), "--frames", "3", "--input", "1:KEYBD=k",
                    "--out", str(tmp_path / "a.png")]) == 0
    assert eval(open(str(prog) + ".got").read()) == (KEYBD_DEV, ord("k"))
    prog.with_name("again.py.got").unlink()
    assert vgx_run([str(prog), "--out", str(tmp_path / "b.png")]) == 0     # ends, no hang


KEYBD_DEV = 513


def test_frame_zero_input_waits_for_the_program_to_queue_its_devices(tmp_path):
    """input.c reads getdev before its qdevice calls: a device read is not
    when frame-0 input is given (the LEFTMOUSE entries were lost), the
    first wait is; a getbutton loop still gets its scripted key."""
    prog = _write(tmp_path, "import sys\n"
                            "from irisgl import *\n"
                            "winopen('a'); getvaluator(MOUSEX); qdevice(LEFTMOUSE); qreset()\n"
                            "got = [qread(), qread()]\n"
                            "while not getbutton(ESCKEY):\n"
                            "    pass\n"
                            "open(sys.argv[0] + '.got', 'w').write(repr(got))\n", name="first.py")
    assert vgx_run([str(prog), "--input", "0:LEFTMOUSE=1,LEFTMOUSE=0,ESCKEY=1",
                    "--out", str(tmp_path / "f.png")]) == 0
    assert eval(open(str(prog) + ".got").read()) == [(103, 1), (103, 0)]
