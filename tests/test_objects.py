"""Display-list replay (makeobj(3G), callobj(3G); vgx_emulator/objects.py).

A compiled object carries only the attributes its own calls set; what it
leaves unset (colour, normal, texture coordinate before its first such
call) comes from the window state at callobj time, and after the call the
state is what the calls would have left.  Replay keeps the records of its
last replay for the same state (GeometryRun.memo): these tests replay the
same object in changing states and compare with immediate mode.
"""
import numpy as np

from irisgl import (bgnpolygon, callobj, clear, closeobj, cpack, endpolygon, genobj,
                    lrectread, makeobj, ortho2, translate, v2f)

W, H = 24, 8


def _square(x0):
    bgnpolygon()
    for dx, dy in ((0, 0), (4, 0), (4, 4), (0, 4)):
        v2f((x0 + dx, 2 + dy))
    endpolygon()


def _scene(with_object):
    """Squares drawn by objects: in the current colour (twice at the same
    place and transform in two colours, then under another transform), one
    whose object sets its own colour, one in the colour that object left."""
    ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    cpack(0)
    clear()
    plain = coloured = None
    if with_object:
        plain = genobj()
        makeobj(plain)
        _square(0)
        closeobj()
        coloured = genobj()
        makeobj(coloured)
        cpack(0xFF00FF00)
        _square(12)
        closeobj()
    # the object without colour calls, or its immediate-mode twin
    square = (lambda: callobj(plain)) if with_object else (lambda: _square(0))
    cpack(0xFF0000FF)
    square()
    cpack(0xFFFF0000)                       # the same object, another colour
    square()
    translate(6, 0, 0)                      # and another transform
    square()
    translate(-6, 0, 0)
    if with_object:
        callobj(coloured)
    else:
        cpack(0xFF00FF00)
        _square(12)
    translate(18, 0, 0)
    square()                                # in the colour the last one left
    return lrectread(0, 0, W - 1, H - 1).astype(np.int64)


def test_replay_takes_the_state_at_each_call(open_window, vgx):
    open_window(W, H)
    immediate = _scene(False)
    vgx.reset()
    open_window(W, H)
    replayed = _scene(True)
    np.testing.assert_array_equal(replayed, immediate)
    # the squares are where and what the calls say
    row = replayed[4]
    assert row[2] == 0xFFFF0000 and row[8] == 0xFFFF0000
    assert row[14] == 0xFF00FF00 and row[20] == 0xFF00FF00


def test_replay_again_in_the_same_state(open_window, vgx):
    open_window(W, H)
    first = _scene(True)
    again = _scene(True)           # new objects, same states: same pixels
    np.testing.assert_array_equal(first, again)


def test_assembled_triangles_are_kept_by_the_machine_and_dropped_by_reset(open_window, vgx):
    """An object replayed twice is assembled once (the machine's
    AssemblyCache holds its primitive table); reset() forgets it with the
    other program state."""
    open_window(W, H)
    ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    obj = genobj()
    makeobj(obj)
    _square(0)
    _square(8)
    closeobj()
    callobj(obj)
    lrectread(0, 0, 0, 0)                   # flushes the batch
    kept = len(vgx.assembled.entries)
    assert kept == 1
    cached = next(iter(vgx.assembled.entries.values()))
    assert len(cached[0]) == 4              # two squares, two triangles each
    callobj(obj)
    lrectread(0, 0, 0, 0)
    assert len(vgx.assembled.entries) == 1 and \
        next(iter(vgx.assembled.entries.values())) is cached
    vgx.reset()
    assert len(vgx.assembled.entries) == 0
