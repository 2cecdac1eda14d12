"""Window-manager calls, ginit/gbegin, system calls, old pixel calls, zdraw,
gammaramp, readdisplay (docs/windows-and-devices.md and the man pages
cited in each test)."""
import numpy as np
import pytest

import vgx_emulator
from irisgl import *  # noqa: F401,F403
from irisgl import GLError

RED, GREEN, BLUE = 0xFF0000FF, 0xFF00FF00, 0xFFFF0000


def machine():
    from irisgl._current import machine
    return machine


def cur():
    return machine().current


def entries():
    return list(machine().events.entries)


# -- winposition / winmove ------------------------------------------------------------
def test_winposition_moves_reshapes_and_keeps_lower_left_pixels(open_window):
    open_window(20, 10)
    cpack(RED)
    clear()
    qreset()
    winposition(300, 339, 400, 404)          # x1, x2, y1, y2: 40 x 5
    assert getorigin() == (300, 400)
    assert getsize() == (40, 5)
    assert cur().fb.front.shape == (5, 40)
    img = lrectread(0, 0, 39, 4)
    assert (img[:, :20] == RED).all()        # the old 20x5 lower-left part
    assert (img[:, 20:] == 0).all()
    assert entries() == [(REDRAW, winget())]


def test_winposition_corners_in_any_order_and_banks_follow_config(open_window):
    open_window(8, 8, double=True)
    stensize(2)
    acsize(16)
    gconfig()
    zbuffer(TRUE)
    winposition(49, 10, 29, 10)
    assert getsize() == (40, 20) and getorigin() == (10, 10)
    fb = cur().fb
    for bank in (fb.front, fb.back, fb.z, fb.stencil):
        assert bank.shape == (20, 40)
    assert fb.accum.shape == (20, 40, 4)
    assert getgconfig(GC_BITS_STENCIL) == 2


def test_drawing_after_resize_fills_new_size(open_window):
    open_window(8, 8)
    winposition(0, 31, 0, 15)
    reshapeviewport()
    ortho2(-0.5, 31.5, -0.5, 15.5)
    cpack(GREEN)
    clear()
    assert (lrectread(0, 0, 31, 15) == GREEN).all()


def test_winmove_changes_origin_not_size_or_pixels(open_window):
    open_window(10, 10)
    cpack(BLUE)
    clear()
    qreset()
    winmove(123, 456)
    assert getorigin() == (123, 456) and getsize() == (10, 10)
    assert (lrectread(0, 0, 9, 9) == BLUE).all()
    assert entries() == []                   # a move alone needs no REDRAW


def test_winmove_moves_pattern_phase(open_window):
    # defpattern(3G): the pattern is aligned to the screen
    open_window(16, 1)
    defpattern(1, 16, [0x0001] * 16)          # one bit per 16 screen columns
    setpattern(1)
    cpack(RED)
    clear()
    on = list(np.nonzero(lrectread(0, 0, 15, 0)[0])[0])
    assert len(on) == 1
    setpattern(0)
    cpack(0)
    clear()
    winmove(3, 0)
    setpattern(1)
    cpack(RED)
    clear()
    assert list(np.nonzero(lrectread(0, 0, 15, 0)[0])[0]) == [(on[0] - 3) % 16]


def test_window_calls_need_a_window():
    for call, args in ((winposition, (0, 1, 0, 1)), (winmove, (0, 0)), (wintitle, ("x",)),
                       (winpop, ()), (fullscrn, ())):
        with pytest.raises(GLError) as e:
            call(*args)
        assert str(e.value).startswith(call.__name__)


# -- stacking, titles, constraints ----------------------------------------------------
def test_winpop_winpush_windepth(open_window):
    a = open_window(4, 4)
    b = open_window(4, 4)
    assert windepth(b) < windepth(a)         # the newest is in front
    winset(a)
    winpop()
    assert windepth(a) < windepth(b)
    winpush()
    assert windepth(b) < windepth(a)
    with pytest.raises(GLError):
        windepth(99)


def test_title_and_constraints_are_kept(open_window):
    minsize(100, 50)
    maxsize(800, 600)
    keepaspect(4, 3)
    stepunit(8, 8)
    fudge(2, 2)
    noborder()
    iconsize(64, 64)
    prefsize(40, 30)
    winopen("t")
    wm = cur().wm
    assert wm["title"] == "t"
    assert wm["minsize"] == (100, 50) and wm["maxsize"] == (800, 600)
    assert wm["aspect"] == (4, 3) and wm["stepunit"] == (8, 8) and wm["fudge"] == (2, 2)
    assert wm["border"] is False and wm["iconsize"] == (64, 64)
    wintitle("new title")
    icontitle("icon")
    assert wm["title"] == "new title" and wm["icontitle"] == "icon"
    with pytest.raises(GLError):
        minsize(0, 10)


def test_winconstraints_binds_and_reshapes(open_window):
    open_window(10, 10)
    prefposition(100, 149, 100, 119)
    minsize(20, 20)
    winconstraints()
    assert getorigin() == (100, 100) and getsize() == (50, 20)
    assert cur().wm["minsize"] == (20, 20)


def test_imakebackground_opens_the_whole_screen():
    imakebackground()
    winopen("bg")
    assert getsize() == (1280, 1024) and getorigin() == (0, 0)
    assert cur().wm["background"] is True


def test_winattach_returns_previous_focus(open_window):
    a = open_window(4, 4)
    b = open_window(4, 4)
    assert winattach() == b                   # nobody else had it
    winset(a)
    assert winattach() == b
    winset(b)
    assert winattach() == a


# -- subwindows -------------------------------------------------------------------------
def test_swinopen_places_relative_to_parent_and_follows_it(open_window):
    prefposition(200, 299, 100, 179)
    parent = winopen("p")
    sub = swinopen(parent)
    assert winget() == sub and sub != parent
    assert getorigin() == (200, 100)         # before winposition: the parent's rectangle
    winposition(10, 19, 5, 9)                 # relative to the parent's origin
    assert getorigin() == (210, 105) and getsize() == (10, 5)
    assert cur().fb.front.shape == (5, 10)
    winset(parent)
    winmove(500, 600)
    winset(sub)
    assert getorigin() == (510, 605)
    with pytest.raises(GLError):
        swinopen(999)


def test_subwindow_has_own_state_and_banks(open_window):
    parent = open_window(20, 20)
    cpack(RED)
    clear()
    sub = swinopen(parent)
    RGBmode()
    gconfig()
    winposition(0, 4, 0, 4)
    cpack(GREEN)
    clear()
    winset(parent)
    assert (lrectread(0, 0, 4, 4) == RED).all()
    winset(sub)
    assert (lrectread(0, 0, 4, 4) == GREEN).all()


# -- fullscrn, ginit, gbegin, getport ---------------------------------------------------
def test_fullscrn_whole_screen_then_back(open_window):
    prefposition(100, 139, 50, 79)
    winopen("x")
    RGBmode()
    gconfig()
    fullscrn()
    assert getsize() == (1280, 1024) and getorigin() == (0, 0)
    assert tuple(getviewport()) == (0, 1279, 0, 1023)
    cpack(RED)
    bgnpoint()
    v2i((1000, 900))                          # world = screen coordinates (ortho2)
    endpoint()
    assert lrectread(1000, 900, 1000, 900)[0, 0] == RED
    endfullscrn()
    assert getsize() == (40, 30) and getorigin() == (100, 50)


def test_ginit_opens_full_screen_window_and_resets_colormap():
    prefsize(8, 8)
    winopen("before")
    mapcolor(1, 1, 2, 3)                     # mapcolor needs a window (a GLError before)
    ginit()
    assert getsize() == (1280, 1024) and getorigin() == (0, 0)
    assert getdisplaymode() == DMSINGLE      # colour map, single buffer
    assert getmcolor(1) == (255, 0, 0)       # the default map again
    color(GREEN & 7)
    clear()
    assert machine().image().shape == (1024, 1280, 3)


def test_gbegin_keeps_colormap():
    ginit()
    mapcolor(9, 10, 20, 30)
    gbegin()
    assert getsize() == (1280, 1024)
    assert getmcolor(9) == (10, 20, 30)


def test_getport_is_winopen_and_ismex():
    prefsize(30, 20)
    g = getport("old")
    assert winget() == g and getsize() == (30, 20)
    assert ismex() == TRUE


def test_screens():
    assert getgdesc(GD_NSCRNS) == 1
    assert scrnselect(0) == 0 and scrnselect(1) == -1
    assert scrnattach(INFOCUSSCRN) == 0 and scrnattach(3) == -1
    prefsize(4, 4)
    winopen("s")
    assert getwscrn() == 0


# -- system calls ------------------------------------------------------------------------
def test_bell_keyboard_dialbox_state():
    sysd = machine().system
    ringbell()
    ringbell()
    assert sysd["bells"] == 2
    setbell(2)
    assert sysd["bellmode"] == 2
    with pytest.raises(GLError):
        setbell(3)
    lampon(0x5)
    lampoff(0x1)
    assert sysd["lamps"] == 0x4
    with pytest.raises(GLError):
        lampon(0x10)
    assert sysd["lamps"] == 0x4
    dbtext("HELLO")
    with pytest.raises(GLError):
        dbtext("TOO LONG!")
    assert sysd["dbtext"] == "HELLO"
    setdblights(0x1FFFFFFFF)
    assert sysd["dblights"] == 0xFFFFFFFF
    clkoff()
    assert sysd["click"] is False
    blanktime(0)
    with pytest.raises(GLError):
        blanktime(-1)


def test_video_registers():
    assert getvideo(GL_VIDEO_REG) == GLV_UNBLANK
    assert getvideo(0x1234) == -1             # getvideo(3G): -1 for no such register
    blankscreen(TRUE)
    assert getvideo(GL_VIDEO_REG) & GLV_UNBLANK == 0
    setvideo(GL_VIDEO_REG, GLV_UNBLANK | GLV_GENLOCK)
    assert getvideo(GL_VIDEO_REG) == GLV_UNBLANK | GLV_GENLOCK
    with pytest.raises(GLError) as e:
        setvideo(0x1234, 0)
    assert str(e.value).startswith("setvideo")
    with pytest.raises(GLError):
        setvideo(GL_VIDEO_REG, 0x40000)
    assert getvideo(GL_VIDEO_REG) == GLV_UNBLANK | GLV_GENLOCK


def test_monitor_and_version():
    assert getmonitor() == HZ60
    setmonitor(NTSC)
    assert getmonitor() == NTSC
    with pytest.raises(GLError):
        setmonitor(12345)
    assert getothermonitor() == NTSC
    ret, v = gversion()
    assert ret == 0 and v.startswith("GL4DVGX-") and len(v) < 12
    with pytest.raises(GLError) as e:
        videocmd(0)
    assert "not emulated" in str(e.value)


def test_glcompat_kept_and_checked():
    glcompat(GLC_OLDPOLYGON, 1)
    glcompat(GLC_ZRANGEMAP, 0)
    assert machine().system["glcompat"] == {GLC_OLDPOLYGON: 1, GLC_ZRANGEMAP: 0}
    with pytest.raises(GLError):
        glcompat(99, 1)


def test_swap_calls(open_window):
    open_window(4, 4, double=True)
    cpack(RED)
    clear()
    assert (lrectread(0, 0, 3, 3) == RED).all()     # SRC_AUTO: back
    mswapbuffers(NORMALDRAW)
    readsource(SRC_FRONT)
    assert (lrectread(0, 0, 3, 3) == RED).all()
    with pytest.raises(GLError):
        mswapbuffers(0x1)
    swapinterval(2)
    assert cur().wm["swapinterval"] == 2
    with pytest.raises(GLError):
        swapinterval(0)
    gsync()


def test_getbuffer_bits(open_window):
    open_window(4, 4, double=True)
    assert getbuffer() == BCKBUFFER
    frontbuffer(TRUE)
    assert getbuffer() == BCKBUFFER | FRNTBUFFER
    zdraw(TRUE)
    assert getbuffer() == BCKBUFFER | FRNTBUFFER | DRAWZBUFFER
    gconfig()                                  # zdraw is FALSE after gconfig
    assert getbuffer() == BCKBUFFER


def test_multisample_has_no_buffer_on_vgx(open_window):
    open_window(4, 4)
    mssize(4, 32, 1)
    gconfig()
    assert getgdesc(GD_MULTISAMPLE) == 0
    assert getgconfig(GC_MS_SAMPLES) == 0
    assert getmultisample() == TRUE            # multisample(3G): default TRUE
    multisample(FALSE)
    assert getmultisample() == FALSE
    msalpha(MSA_ALPHA)
    msmask(2.0, FALSE)
    assert machine().system["multisample"]["mask"] == (1.0, False)
    mspattern(MSP_DEFAULT)
    mssample(MSS_AREA)
    with pytest.raises(GLError):
        msalpha(7)


def test_rgbsize_pixmode_readcomponent_kept(open_window):
    open_window(4, 4)
    RGBsize(12)
    gconfig()
    assert getgconfig(GC_BITS_RED) == 8        # the VGX has 8
    pixmode(PM_SIZE, 32)                       # the default is accepted
    with pytest.raises(GLError) as e:
        pixmode(PM_SIZE, 8)
    assert "not emulated" in str(e.value)
    assert cur().wm["pixmode"][PM_SIZE] == 32
    with pytest.raises(GLError):
        pixmodef(PM_SHIFT, 2.0)
    with pytest.raises(GLError):
        pixmode(500, 1)
    readcomponent(RC_ABGR)
    with pytest.raises(GLError):
        readcomponent(RC_RED)
    with pytest.raises(GLError):
        readcomponent(9)


def test_pixmode_ttob_rtol(open_window):
    open_window(3, 2)
    pixmode(PM_TTOB, 1)
    lrectwrite(0, 0, 2, 1, [1, 2, 3, 4, 5, 6])  # first row given is the top one
    pixmode(PM_TTOB, 0)
    assert lrectread(0, 0, 2, 1).tolist() == [[4, 5, 6], [1, 2, 3]]
    pixmode(PM_RTOL, 1)
    assert lrectread(0, 0, 2, 1).tolist() == [[6, 5, 4], [3, 2, 1]]
    pixmode(PM_TTOB, 1)
    assert lrectread(0, 0, 2, 1).reshape(-1).tolist() == [3, 2, 1, 6, 5, 4]


def test_textport_and_object_memory(open_window):
    open_window(4, 4)
    textport(0, 500, 0, 300)
    tpoff()
    textcolor(3)
    pagecolor(4)
    tp = machine().system["textport"]
    assert tp == {"on": False, "rect": (0, 500, 0, 300), "textcolor": 3, "pagecolor": 4}
    textinit()
    assert machine().system["textport"]["on"] is True
    with pytest.raises(GLError):
        textport(10, 0, 0, 10)
    chunksize(1024)
    makeobj(5)
    closeobj()
    compactify(5)
    with pytest.raises(GLError):
        compactify(6)


# -- zdraw, zsource ------------------------------------------------------------------------
def test_zdraw_writes_colours_into_z(open_window):
    open_window(8, 8)
    zclear()
    zdraw(TRUE)
    frontbuffer(FALSE)                          # allowed single-buffered while zdraw
    cpack(0x00123456)
    clear()
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, 7, 7)
    assert (z.view(np.uint32) == 0x00123456).all()
    readsource(SRC_FRONT)
    assert (lrectread(0, 0, 7, 7) == 0).all()  # the front buffer was off
    zdraw(FALSE)
    cpack(RED)
    clear()
    assert (lrectread(0, 0, 7, 7) == RED).all()


def test_zsource_color_not_emulated(open_window):
    open_window(4, 4)
    zsource(ZSRC_DEPTH)
    with pytest.raises(GLError) as e:
        zsource(ZSRC_COLOR)
    assert "not emulated" in str(e.value)
    assert cur().st.zsource == ZSRC_DEPTH


# -- gammaramp --------------------------------------------------------------------------------
def test_gammaramp_applies_at_scanout_only(open_window):
    open_window(4, 4)
    cpack(0xFF204080)                          # r 0x80, g 0x40, b 0x20
    clear()
    inv = [255 - i for i in range(256)]
    half = [i // 2 for i in range(256)]
    gammaramp(inv, half, list(range(256)))
    img = vgx_emulator.window_image() if hasattr(vgx_emulator, "window_image") else \
        machine().image()
    assert tuple(img[0, 0]) == (255 - 0x80, 0x40 // 2, 0x20)
    assert lrectread(0, 0, 0, 0)[0, 0] == 0xFF204080   # bitplanes keep the true values
    ident = list(range(256))
    gammaramp(ident, ident, ident)
    assert tuple(machine().image()[0, 0]) == (0x80, 0x40, 0x20)
    with pytest.raises(GLError):
        gammaramp(ident[:10], ident, ident)


# -- old pixel calls ---------------------------------------------------------------------------
def test_writeRGB_readRGB_at_character_position(open_window):
    open_window(8, 4)
    cur().st.cpos = (2, 1)                     # as cmov2i(2, 1) leaves it
    writeRGB(3, [10, 20, 30], [1, 2, 3], [7, 8, 9])
    assert cur().st.cpos == (5, 1)
    row = lrectread(0, 1, 7, 1)[0]
    assert list(row[2:5]) == [0xFF07010A, 0xFF080214, 0xFF09031E]
    assert row[1] == 0 and row[5] == 0
    cur().st.cpos = (2, 1)
    n, r, g, b = readRGB(3)
    assert n == 3 and list(r) == [10, 20, 30] and list(g) == [1, 2, 3] and list(b) == [7, 8, 9]
    cur().st.cpos = (100, 1)                   # outside the viewport
    assert readRGB(2)[0] == 0
    with pytest.raises(GLError):
        writeRGB(3, [1], [1], [1])             # arrays shorter than n


def test_writepixels_readpixels_colour_map(open_window):
    open_window(8, 2, rgb=False)
    cur().st.cpos = (0, 0)
    writepixels(4, [1, 2, 3, 4])
    assert list(rectread(0, 0, 3, 0)[0]) == [1, 2, 3, 4]
    cur().st.cpos = (1, 0)
    n, c = readpixels(2)
    assert n == 2 and list(c) == [2, 3]
    with pytest.raises(GLError):
        writeRGB(1, [1], [1], [1])             # RGB call in colour-map mode
    open_window(8, 2)
    with pytest.raises(GLError, match="^readpixels: in RGB mode"):
        readpixels(2)                          # colour-map call in RGB mode


def test_readpixels_readRGB_fill_given_arrays_and_return_the_count(open_window):
    """readpixels(3G), readRGB(3G): C fills the caller's arrays and returns
    the count; ported with the arrays given, the call returns the count
    alone (docs/porting.md §3), the arrays hold the values, and a position
    outside the viewport (count 0) leaves them alone.  An array shorter than
    n, a read-only one, or (readRGB) only some of the three is a GLError."""
    open_window(8, 2, rgb=False)
    cur().st.cpos = (0, 0)
    writepixels(4, [1, 2, 3, 4])
    cur().st.cpos = (1, 0)
    buf = np.full(3, 99, np.uint16)
    assert readpixels(2, buf) == 2 and list(buf) == [2, 3, 99]
    cur().st.cpos = (100, 0)
    assert readpixels(2, buf) == 0 and list(buf) == [2, 3, 99]
    with pytest.raises(GLError, match="^readpixels: colors has 1 elements"):
        readpixels(2, [0])
    ro = np.zeros(4, np.uint16)
    ro.flags.writeable = False
    with pytest.raises(GLError, match="^readpixels: colors is a read-only array"):
        readpixels(2, ro)
    open_window(8, 2)
    cur().st.cpos = (0, 0)
    writeRGB(2, [10, 20], [1, 2], [7, 8])
    cur().st.cpos = (0, 0)
    r, g, b = [0] * 2, np.zeros(2, np.uint8), np.zeros(4, np.int32)
    assert readRGB(2, r, g, b) == 2
    assert r == [10, 20] and list(g) == [1, 2] and list(b) == [7, 8, 0, 0]
    with pytest.raises(GLError, match="^readRGB: some of red, green, blue given"):
        readRGB(2, r, None, None)
    with pytest.raises(GLError, match="^readRGB: blue has 1 elements"):
        readRGB(2, r, g, [0])


# -- readdisplay -------------------------------------------------------------------------------
def test_readdisplay_composes_windows_by_stacking(open_window):
    prefposition(10, 19, 10, 19)
    a = winopen("a")
    RGBmode()
    gconfig()
    cpack(RED)
    clear()
    prefposition(15, 24, 15, 24)
    winopen("b")
    RGBmode()
    gconfig()
    cpack(GREEN)
    clear()
    d = readdisplay(25, 25, 5, 5)              # corners in any order
    assert d.shape == (21, 21)
    assert d[0, 0] == 0xFF000000               # screen background (5, 5)
    assert d[7, 7] == RED                      # (12, 12): only a
    assert d[12, 12] == GREEN                  # (17, 17): b in front
    winset(a)
    winpop()
    assert readdisplay(17, 17, 17, 17)[0, 0] == RED
    buf = np.zeros(4, np.uint32)
    assert readdisplay(12, 12, 13, 13, buf) == 4
    assert (buf == RED).all()


# -- demos ------------------------------------------------------------------------------------
DEMOS = __import__("pathlib").Path(__file__).resolve().parent.parent / "programs" / "demos"


def _run(name, frames=1, argv=None):
    from vgx_emulator.runner import run_program
    return run_program(DEMOS / name, frames, argv)


def test_demo_gl2_ginit_draws_on_the_whole_screen():
    img = _run("gl2_ginit.py")
    assert img.shape == (1024, 1280, 3)

    def px(x, y):                               # screen coordinates, y up
        return tuple(int(c) for c in img[1023 - y, x])
    assert px(640, 800) == (0, 0, 255)          # color(BLUE); clear()
    assert px(400, 550) == (255, 255, 0)        # circfi centre, YELLOW
    assert px(400, 740) == (255, 255, 0)        # inside, 190 from the centre
    assert px(400, 760) == (0, 0, 255)          # outside, 210 from the centre
    assert px(950, 500) == (255, 0, 0)          # the pmv2i/pdr2i triangle
    assert px(500, 925) == (255, 255, 255)      # a grid line (move2i/draw2i)
    for i in (0, 16, 31):                       # the mapcolor grey ramp
        v = i * 255 // 31
        assert px(i * 40 + 20, 50) == (v, v, v)


def _columns(img, background=(0x20, 0x20, 0x30)):
    """Number of image columns holding a non-background pixel."""
    return int((img != np.array(background, np.uint8)).any(axis=2).any(axis=0).sum())


def test_demo_lit_valuators_drag_turns_the_cube():
    import math
    still = _run("lit_valuators.py", 2)
    dragged = _run("lit_valuators.py", 2, ["-drag", "400", "500", "650", "500"])
    # orthographic, 75 pixels per unit, cube half-size 1: the silhouette is
    # 150 (|cos a| + |sin a|) wide whatever the elevation (rotate x acts last)
    for img, azim in ((still, 20.0), (dragged, 45.0)):
        a = math.radians(azim)
        expect = 150 * (abs(math.cos(a)) + abs(math.sin(a)))
        assert abs(_columns(img) - expect) <= 2, (azim, _columns(img), expect)
    # a vertical drag changes the elevation only: same width, other picture
    tilted = _run("lit_valuators.py", 2, ["-drag", "400", "500", "400", "650"])
    assert abs(_columns(tilted) - _columns(still)) <= 1
    assert (tilted != still).any()


def test_demo_lit_valuators_menu_changes_material():
    brass = _run("lit_valuators.py", 1)
    blue = _run("lit_valuators.py", 1, ["--menu", "2.3"])
    r, g, b = (int(c) for c in brass[150, 170])        # the lit front face
    assert r > g > b
    r, g, b = (int(c) for c in blue[150, 170])
    assert b > r and b > g


def test_a_read_outside_the_window_sees_the_windows_there(open_window):
    """The VGX has one framebuffer: after screenspace(3G), which "allows
    pixels and locations outside a program's graphics window to be read",
    readpixels (and lrectread, rectcopy) beyond the window read the window
    in front there, and 0 where no window is (GL2's mag, showramp's
    getapixel)."""
    from irisgl import screenspace
    from irisgl._current import machine
    machine.reset()
    prefposition(100, 299, 100, 299)
    winopen("a")
    color(1)
    clear()
    prefposition(500, 699, 500, 699)
    winopen("b")
    color(4)
    clear()
    screenspace()
    cur().st.cpos = (150 - 500, 150 - 500)       # as cmov2i(150, 150) leaves it
    n, under = readpixels(4)
    assert n == 4 and list(under) == [1] * 4
    cur().st.cpos = (400 - 500, 400 - 500)       # no window there
    assert list(readpixels(2)[1]) == [0, 0]
    assert list(rectread(-401, -350, -400, -350)[0]) == [0, 1]   # screen x 99 is not in a
