"""lit_valuators: a lit cube turned with the mouse, as a 1990 IRIS GL demo.

The left button is tied to MOUSEX and MOUSEY (tie), so each press and
release arrives as one group: the button, then the two positions.  The
drag between press and release turns the cube: one tenth of a degree of
azimuth per pixel in x, of elevation per pixel in y.  The right button
pops up a menu (defpup/dopup) to change the material or reset the view.

Headless the program can replay a drag of its own: ``-drag X0 Y0 X1 Y1``
sets the mouse (setvaluator) and enters the press and the release with
qenter, as a window system would.  ``vgx-run --menu 2.3`` picks
Material > blue plastic.
"""
import sys

from irisgl import *

FIGURES = [
    {"name": "start", "args": [],
     "caption": "a lit cube (lmdef/lmbind), 20 degrees of azimuth, 25 of elevation"},
    {"name": "dragged", "args": ["-drag", "400", "500", "650", "500"], "frames": 2,
     "caption": "after a left-button drag of 250 pixels (MOUSEX/MOUSEY tied to "
                "LEFTMOUSE): 45 degrees of azimuth"},
    {"name": "menu-blue", "args": ["--menu", "2.3"],
     "caption": "right-button menu: Material > blue plastic"},
]

WIDTH, HEIGHT = 300, 300
START_AZIM, START_ELEV = 200, 250          # tenths of a degree
MATERIALS = ((0.8, 0.6, 0.2), (0.7, 0.1, 0.1), (0.1, 0.2, 0.8))   # brass, red, blue
SUN, SCENE = 1, 1

FACES = (((1, 0, 0), ((1, -1, -1), (1, 1, -1), (1, 1, 1), (1, -1, 1))),
         ((-1, 0, 0), ((-1, -1, 1), (-1, 1, 1), (-1, 1, -1), (-1, -1, -1))),
         ((0, 1, 0), ((-1, 1, 1), (1, 1, 1), (1, 1, -1), (-1, 1, -1))),
         ((0, -1, 0), ((-1, -1, -1), (1, -1, -1), (1, -1, 1), (-1, -1, 1))),
         ((0, 0, 1), ((-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1))),
         ((0, 0, -1), ((-1, 1, -1), (1, 1, -1), (1, -1, -1), (-1, -1, -1))))

azim, elev = START_AZIM, START_ELEV
material = 1


def define_lighting():
    for i, (r, g, b) in enumerate(MATERIALS):
        lmdef(DEFMATERIAL, i + 1, 0, [AMBIENT, 0.2 * r, 0.2 * g, 0.2 * b,
                                      DIFFUSE, r, g, b,
                                      SPECULAR, 0.6, 0.6, 0.6,
                                      SHININESS, 40.0, LMNULL])
    lmdef(DEFLIGHT, SUN, 0, [LCOLOR, 1.0, 1.0, 1.0,
                               POSITION, 0.4, 0.6, 1.0, 0.0, LMNULL])
    lmdef(DEFLMODEL, SCENE, 0, [AMBIENT, 0.2, 0.2, 0.2, LMNULL])


def drawcube():
    for normal, corners in FACES:
        bgnpolygon()
        n3f(normal)
        for c in corners:
            v3f(c)
        endpolygon()


def draw():
    czclear(0xFF302020, getgdesc(GD_ZMAX))
    pushmatrix()
    rotate(elev, 'x')
    rotate(azim, 'y')
    lmbind(MATERIAL, material)
    drawcube()
    popmatrix()
    swapbuffers()


def tied_values():
    """The MOUSEX and MOUSEY entries that follow a tied LEFTMOUSE entry."""
    pos = {}
    for _ in range(2):
        dev, val = qread()
        pos[dev] = val
    return pos.get(MOUSEX, getvaluator(MOUSEX)), pos.get(MOUSEY, getvaluator(MOUSEY))


def replay_drag(x0, y0, x1, y1):
    """Enter a left-button drag as the window system queues it: each button
    entry followed by its tied MOUSEX and MOUSEY (qenter enters exactly one
    entry, so the program enters all three)."""
    for button, x, y in ((1, x0, y0), (0, x1, y1)):
        setvaluator(MOUSEX, x, 0, XMAXSCREEN)
        setvaluator(MOUSEY, y, 0, YMAXSCREEN)
        qenter(LEFTMOUSE, button)
        qenter(MOUSEX, x)
        qenter(MOUSEY, y)


def main():
    global azim, elev, material
    prefsize(WIDTH, HEIGHT)
    winopen("lit_valuators")
    RGBmode()
    doublebuffer()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    ortho(-2.0, 2.0, -2.0, 2.0, -10.0, 10.0)
    loadmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    define_lighting()
    lmbind(LIGHT0, SUN)
    lmbind(LMODEL, SCENE)

    qdevice(LEFTMOUSE)
    qdevice(RIGHTMOUSE)
    qdevice(ESCKEY)
    qdevice(REDRAW)
    tie(LEFTMOUSE, MOUSEX, MOUSEY)
    materials = defpup("Material %t|brass %x11|red plastic %x12|blue plastic %x13")
    menu = defpup("Lit cube %t|Reset view %x1|Material %m|Quit %x99", materials)

    args = sys.argv[1:]
    if len(args) == 5 and args[0] == "-drag":
        replay_drag(*(int(a) for a in args[1:]))

    start = None
    while True:
        dev, val = qread()
        if dev == REDRAW:
            reshapeviewport()
            draw()
        elif dev == LEFTMOUSE:
            mx, my = tied_values()
            if val:
                start = (mx, my)
            elif start is not None:
                azim += mx - start[0]
                elev += my - start[1]
                start = None
                draw()
        elif dev == RIGHTMOUSE and val:
            choice = dopup(menu)
            if choice == 99:
                break
            if choice == 1:
                azim, elev = START_AZIM, START_ELEV
            elif 11 <= choice <= 13:
                material = choice - 10
            if choice != -1:
                draw()
        elif dev == ESCKEY and val == 0:
            break
    gexit()


if __name__ == "__main__":
    main()
