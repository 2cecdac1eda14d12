"""text_menus: raster text and a pop-up menu, as a 1990 IRIS GL demo.

A title line drawn with charstr, a shape in the middle and a caption that
names the current choice.  The right mouse button pops up a menu: its
"Colour" submenu has a menu function (%F) that sets the colour, the shape
items have item functions (%f) that set the shape, and "Quit" (%n) ends
the program.  Headless, the menu choices come from ``vgx-run --menu``:
``--menu 1.2,3`` picks Colour -> green, then Circle.
"""
import math

from irisgl import *

FIGURES = [
    {"name": "start", "args": [],
     "caption": "charstr title and caption in the 9x15 font; the starting choice, "
                "a red square"},
    {"name": "menu-green-circle", "args": ["--menu", "1.2,3"],
     "caption": "after two scripted pop-up menu choices: Colour > green (%m submenu, "
                "%F function), then Circle (%f function)"},
]

WIDTH, HEIGHT = 320, 240
TITLE = "IRIS GL text and pop-up menus"

COLOURS = (("red", 0x0000FF), ("green", 0x00FF00), ("blue", 0xFF0000),
           ("yellow", 0x00FFFF))
SHAPES = ("square", "circle", "triangle")

colour = 1              # COLOURS index + 1 (the submenu's item values)
shape = 1               # SHAPES index + 1
done = False


def setcolour(n):
    """The colour submenu's %F function: item n chosen."""
    global colour
    colour = n
    return n


def setsquare(n):
    global shape
    shape = 1
    return n


def setcircle(n):
    global shape
    shape = 2
    return n


def settriangle(n):
    global shape
    shape = 3
    return n


def quit_(n):
    global done
    done = True
    return n


def drawshape():
    cx, cy, r = WIDTH // 2, HEIGHT // 2, 60
    cpack(0xFF000000 | COLOURS[colour - 1][1])
    if shape == 1:
        rectfi(cx - r, cy - r, cx + r, cy + r)
    elif shape == 2:
        pts = [(cx + r * math.cos(2 * math.pi * i / 64), cy + r * math.sin(2 * math.pi * i / 64))
               for i in range(64)]
        polf2(64, pts)
    else:
        bgnpolygon()
        v2i((cx - r, cy - r))
        v2i((cx + r, cy - r))
        v2i((cx, cy + r))
        endpolygon()


def draw():
    cpack(0xFF402010)
    clear()
    drawshape()
    cpack(0xFFFFFFFF)
    cmov2i((WIDTH - strwidth(TITLE)) // 2, HEIGHT - 5 - getheight() + getdescender())
    charstr(TITLE)
    caption = f"shape: {SHAPES[shape - 1]}   colour: {COLOURS[colour - 1][0]}"
    cpack(0xFF00FFFF)
    cmov2i(10, 10 + getdescender())
    charstr(caption)
    swapbuffers()


def main():
    prefsize(WIDTH, HEIGHT)
    winopen("text_menus")
    RGBmode()
    doublebuffer()
    gconfig()
    qdevice(RIGHTMOUSE)
    qdevice(ESCKEY)
    qdevice(REDRAW)

    colours = defpup("Colour %t %F|red|green|blue|yellow", setcolour)
    menu = defpup("Text demo %t|Colour %m|Square %f|Circle %f|Triangle %f %l|Quit %n",
                  colours, setsquare, setcircle, settriangle, quit_)

    while not done:
        dev, val = qread()
        if dev == REDRAW:
            reshapeviewport()
            draw()
        elif dev == RIGHTMOUSE and val:
            if dopup(menu) != -1 and not done:
                draw()
        elif dev == ESCKEY and val == 0:
            break
    gexit()


if __name__ == "__main__":
    main()
