"""colormap_cycle: colour-map animation, drawn once, animated by mapcolor.

Written in the style of a 1990 IRIS GL C program: vertical bands are drawn
once with color(BASE + i); every frame the program only rewrites the map
entries BASE..BASE+NBANDS-1, so the colours march across the screen while
the bitplanes keep the same indices (mapcolor(3G) acts at scan-out).

    vgx-run programs/demos/colormap_cycle.py --out /tmp/x.png --frames 5
"""
import sys

from irisgl import *

FIGURES = [{"name": "colormap_cycle", "args": [],
            "caption": "Colour-map cycling: bands drawn once with color(i), animated "
                       "by rewriting their mapcolor entries every frame."}]

BASE = 32                       # first colour-map entry of the bands
WIDTH, HEIGHT = 320, 240
PALETTE = [(255, 0, 0), (255, 128, 0), (255, 255, 0), (0, 255, 0),
           (0, 255, 255), (0, 0, 255), (128, 0, 255), (255, 0, 255)]
NBANDS = len(PALETTE)
BANDW = WIDTH // NBANDS


def setramp(phase):
    """Entry BASE + i shows palette colour (i + phase) mod NBANDS."""
    for i in range(NBANDS):
        r, g, b = PALETTE[(i + phase) % NBANDS]
        mapcolor(BASE + i, r, g, b)


def drawbands():
    color(BLACK)
    clear()
    for i in range(NBANDS):
        color(BASE + i)
        rectfi(i * BANDW, 20, (i + 1) * BANDW, HEIGHT - 20)


def main():
    prefsize(WIDTH, HEIGHT)
    winopen("cycle")
    cmode()
    gconfig()
    qdevice(ESCKEY)
    qdevice(REDRAW)
    setramp(0)
    phase = 0
    while True:
        while qtest():
            dev, val = qread()
            if dev == ESCKEY:
                gexit()
                sys.exit(0)
            if dev == REDRAW:
                drawbands()
        phase = (phase + 1) % NBANDS
        setramp(phase)
        gflush()


if __name__ == "__main__":
    main()
