"""drawing2d: the old 2-D drawing calls of IRIS GL in one ortho2 window.

A program of our own in the style of a 1990 C listing ported line by line:
circles, an outlined arc, a pie slice, a dashed and a wide line, a
polygon built with pmv/pdr/pclos, an outlined rectf (polymode PYM_LINE)
and a screen-aligned box.  It redraws on REDRAW and exits on ESC.
"""
from irisgl import *

FIGURES = [
    {"name": "drawing2d", "args": [],
     "caption": "Old-style 2-D drawing: circf, circ, arc, arcf (a pie slice), a "
                "linestyle 0x0F0F with lsrepeat 2, a 5-pixel linewidth, a "
                "pmv/pdr/pclos triangle, rectf under polymode(PYM_LINE) and sboxf."},
]

WIDTH, HEIGHT = 400, 300
DASHED = 1


def draw_scene():
    cpack(0x00000000)
    clear()

    cpack(0xFF0000FF)                       # red disc
    circfi(70, 230, 36)
    cpack(0xFF00FF00)                       # green circle, blue arc inside it
    circi(200, 230, 40)
    cpack(0xFFFF0000)
    arci(200, 230, 30, 450, 1350)
    cpack(0xFF00FFFF)                       # yellow pie slice, first quadrant
    arcfi(330, 230, 36, 0, 900)

    setlinestyle(DASHED)                    # 8 pixels on, 8 off
    lsrepeat(2)
    cpack(0xFFFFFFFF)
    move2i(20, 150)
    draw2i(380, 150)
    setlinestyle(0)
    lsrepeat(1)

    linewidth(5)                            # a 5-pixel wide cyan line
    cpack(0xFFFFFF00)
    move2i(20, 120)
    draw2i(380, 120)
    linewidth(1)

    cpack(0xFFFF00FF)                       # magenta triangle, point by point
    pmv2i(40, 30)
    pdr2i(140, 30)
    pdr2i(90, 100)
    pclos()

    polymode(PYM_LINE)                      # a rectf drawn as its outline
    cpack(0xFF808080)
    rectfi(160, 20, 240, 90)
    polymode(PYM_FILL)

    cpack(0xFFFFFFFF)                       # a screen-aligned box
    sboxfi(260, 30, 340, 80)
    gflush()


def main():
    prefsize(WIDTH, HEIGHT)
    winopen("drawing2d")
    RGBmode()
    gconfig()
    ortho2(-0.5, WIDTH - 0.5, -0.5, HEIGHT - 0.5)
    deflinestyle(DASHED, 0x0F0F)
    qdevice(ESCKEY)
    qdevice(REDRAW)
    while True:
        dev, val = qread()
        if dev == REDRAW:
            reshapeviewport()
            draw_scene()
        elif dev == ESCKEY and val == 0:
            break
    gexit()


if __name__ == "__main__":
    main()
