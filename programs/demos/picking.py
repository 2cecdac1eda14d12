"""Picking and selecting three named blocks in perspective.

Three blocks stand in a row; each is drawn under its own name (loadname).
LEFTMOUSE picks at the cursor (pick(3G): the projection is restated after
pick, which loads it times the picking matrix, and again after endpick)
and the block under the cursor is drawn yellow; MIDDLEMOUSE selects (gselect(3G)) every block
that reaches into the world box x in [SEL_X0, SEL_X1] and draws those cyan.
The names hit are printed, one line per hit record, as the records come
back in the buffer (depth, then the names).

Headless, the arguments stand in for the mouse: ``-- pick X Y`` queues the
cursor position (screen coordinates) and a LEFTMOUSE press, ``-- select``
a MIDDLEMOUSE press.
"""
import sys

import numpy as np

from irisgl import *

FIGURES = [
    {"name": "pick", "args": ["pick", "200", "150"], "frames": 2,
     "caption": "pick(3G) at the cursor: the middle block, under the cursor, is drawn yellow."},
    {"name": "select", "args": ["select"], "frames": 2,
     "caption": "gselect(3G) of the box x in [-4, 0.5]: the two blocks that reach into it "
                "are drawn cyan."},
]

WIDTH, HEIGHT = 400, 300
FOVY, NEAR, FAR = 400, 1.0, 20.0            # tenths of degrees
EYE = (0.0, 0.0, 8.0)
BLOCKS = [(-2.5, 0x0000C0), (0.0, 0x00C000), (2.5, 0xC00000)]     # x, cpack colour
HALF = 0.8                                  # half the edge of a block
BUFSIZE = 64
SEL_X0, SEL_X1 = -4.0, 0.5
PICKED, SELECTED = 0x00FFFF, 0xFFFF00       # yellow, cyan (0xBBGGRR)
# the six faces of a cube as corner indices, and a shade for each
# (corner i = 4 [x > 0] + 2 [y > 0] + [z < 0]): front, back, left, right, bottom, top
FACES = [((0, 4, 6, 2), 1.0), ((1, 3, 7, 5), 0.55), ((0, 2, 3, 1), 0.7),
         ((4, 5, 7, 6), 0.75), ((0, 1, 5, 4), 0.6), ((2, 6, 7, 3), 0.85)]


def shade(col, k):
    r, g, b = col & 0xFF, (col >> 8) & 0xFF, (col >> 16) & 0xFF
    return int(r * k) | (int(g * k) << 8) | (int(b * k) << 16)


def block(x, col):
    """A cube of edge 2 HALF centred on (x, 0, 0); the front face (+z) is
    drawn in the full colour."""
    c = [(x + sx * HALF, sy * HALF, sz * HALF)
         for sx in (-1, 1) for sy in (-1, 1) for sz in (1, -1)]
    for face, k in FACES:
        cpack(shade(col, k))
        bgnpolygon()
        for i in face:
            v3f(c[i])
        endpolygon()


def viewing():
    perspective(FOVY, WIDTH / HEIGHT, NEAR, FAR)
    loadmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    lookat(EYE[0], EYE[1], EYE[2], 0.0, 0.0, 0.0, 0)


def blocks(marked, mark):
    """The scene, each block under its name (1, 2, 3)."""
    initnames()
    for i, (x, col) in enumerate(BLOCKS):
        loadname(i + 1)
        block(x, mark if i + 1 in marked else col)


def redraw(marked, mark):
    czclear(0x303030, getgdesc(GD_ZMAX))
    viewing()
    blocks(marked, mark)
    swapbuffers()


def hit_names(n, buffer):
    """The name lists of the n hit records (depth, then the names)."""
    out, i = [], 0
    for _ in range(abs(n)):
        depth = int(buffer[i])
        out.append([int(v) for v in buffer[i + 1:i + 1 + depth]])
        i += 1 + depth
    return out


def pick_at_cursor():
    buffer = np.zeros(BUFSIZE, np.int16)
    pick(buffer, BUFSIZE)
    viewing()                        # restated: times the picking matrix
    blocks((), 0)
    n = endpick(buffer)
    names = hit_names(n, buffer)
    for h in names:
        print("picked:", " ".join(str(v) for v in h) or "(no names)")
    if not names:
        print("picked: nothing")
    return {h[-1] for h in names if h}


def select_box():
    buffer = np.zeros(BUFSIZE, np.int16)
    gselect(buffer, BUFSIZE)
    ortho(SEL_X0, SEL_X1, -HALF * 4, HALF * 4, 0.0, 2.0 * FAR)   # the selecting volume
    loadmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    lookat(EYE[0], EYE[1], EYE[2], 0.0, 0.0, 0.0, 0)
    blocks((), 0)
    n = endselect(buffer)
    names = hit_names(n, buffer)
    for h in names:
        print("selected:", " ".join(str(v) for v in h))
    return {h[-1] for h in names if h}


def main():
    prefsize(WIDTH, HEIGHT)
    winopen("picking")
    RGBmode()
    doublebuffer()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    qdevice(ESCKEY)
    qdevice(LEFTMOUSE)
    qdevice(MIDDLEMOUSE)
    qdevice(MOUSEX)
    qdevice(MOUSEY)
    args = sys.argv[1:]
    if args[:1] == ["pick"] and len(args) >= 3:         # headless: a click at X Y
        qenter(MOUSEX, int(args[1]))
        qenter(MOUSEY, int(args[2]))
        qenter(LEFTMOUSE, 1)
        qenter(LEFTMOUSE, 0)
    elif args[:1] == ["select"]:
        qenter(MIDDLEMOUSE, 1)
        qenter(MIDDLEMOUSE, 0)
    marked, mark = set(), PICKED
    while True:
        dev, val = qread()
        if dev == REDRAW:
            reshapeviewport()
            redraw(marked, mark)
        elif dev == LEFTMOUSE and val == 1:
            marked, mark = pick_at_cursor(), PICKED
            redraw(marked, mark)
        elif dev == MIDDLEMOUSE and val == 1:
            marked, mark = select_box(), SELECTED
            redraw(marked, mark)
        elif dev == ESCKEY and val == 0:
            break
    gexit()


if __name__ == "__main__":
    main()
