"""gl2_ginit: a GL2-style program (IRIS 2000/3000 era) that never opens a
window: ginit() makes the whole screen its window, in colour-map mode,
single-buffered, with the default colour map.

It draws with the old calls only (color, clear, rectfi, circfi, pmv2i/
pdr2i/pclos, move2i/draw2i, mapcolor, cmov2i/charstr), gflush()es, and
waits for a key (qdevice(KEYBD)) before gexit(), as such programs did.
The picture: a colour-index ramp in a band across the bottom, a filled
circle, a filled triangle and a grid of lines on a blue screen.
"""
from irisgl import *

FIGURES = [
    {"name": "screen", "args": [],
     "caption": "ginit() with no winopen: the whole 1280x1024 screen in colour-map "
                "mode, drawn with GL2 calls (color, rectfi, circfi, pmv2i/pdr2i, "
                "move2i/draw2i, charstr)"},
]

RAMP = 64                 # colour indices 64..95: a grey ramp made with mapcolor
STEPS = 32


def ramp():
    for i in range(STEPS):
        v = i * 255 // (STEPS - 1)
        mapcolor(RAMP + i, v, v, v)
    w = (XMAXSCREEN + 1) // STEPS
    for i in range(STEPS):
        color(RAMP + i)
        rectfi(i * w, 0, (i + 1) * w, 99)


def picture():
    color(BLUE)
    clear()
    ramp()
    color(YELLOW)
    circfi(400, 550, 200)
    color(RED)
    pmv2i(750, 350)
    pdr2i(1150, 350)
    pdr2i(950, 750)
    pclos()
    color(WHITE)
    for x in range(100, 1200, 100):
        move2i(x, 850)
        draw2i(x, 1000)
    for y in range(850, 1001, 50):
        move2i(100, y)
        draw2i(1100, y)
    color(GREEN)
    cmov2i(100, 120)
    charstr("ginit: the whole screen is the window")


def main():
    ginit()
    picture()
    gflush()
    qdevice(KEYBD)
    while True:
        dev, val = qread()
        if dev == KEYBD:
            break
    gexit()


if __name__ == "__main__":
    main()
