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
                    lrectread, makeobj, n3f, ortho2, translate, v2f)

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


def _frame(objs, colours):
    """Each colour in turn: every object drawn in it, then a flush (one
    pass per colour, as a multipass frame draws its scene in each pass)."""
    cpack(0)
    clear()
    for c in colours:
        cpack(c)
        for o in objs:
            callobj(o)
        lrectread(0, 0, 0, 0)
    return lrectread(0, 0, W - 1, H - 1).astype(np.int64)


def _two_objects():
    ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    objs = []
    for x0 in (0, 8):
        o = genobj()
        makeobj(o)
        _square(x0)
        closeobj()
        objs.append(o)
    return objs


def test_a_scene_redrawn_in_each_pass_keeps_its_vertex_arrays(open_window, vgx):
    """A frame of two passes (the same two objects in two colours), drawn
    twice: the second frame finds each pass's records (GeometryRun.memo,
    one per state) and concatenated vertex arrays (AssemblyCache.vertices)
    again, and draws what the first drew; the immediate-mode twin draws the
    same pixels and keeps no vertex arrays."""
    open_window(W, H)
    objs = _two_objects()
    colours = (0xFF0000FF, 0xFF00FF00)
    first = _frame(objs, colours)
    kept = {k: v[1] for k, v in vgx.assembled.vertex_entries.items()}
    assert len(kept) == 2                           # one batch per pass
    runs = [op[1] for o in objs for op in vgx.objects[o].ops if op[0] == "run"]
    assert runs and all(len(r.memo) == 2 for r in runs)
    recs = [list(r.memo.values()) for r in runs]
    again = _frame(objs, colours)
    np.testing.assert_array_equal(again, first)
    assert {k: v[1] for k, v in vgx.assembled.vertex_entries.items()} == kept
    assert all(a is b for k in kept for a, b in zip(vgx.assembled.vertex_entries[k][1],
                                                     kept[k]))
    assert [list(r.memo.values()) for r in runs] == recs
    # the same frame sent call by call
    vgx.reset()
    open_window(W, H)
    ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    cpack(0)
    clear()
    for c in colours:
        cpack(c)
        _square(0)
        _square(8)
        lrectread(0, 0, 0, 0)
    np.testing.assert_array_equal(lrectread(0, 0, W - 1, H - 1).astype(np.int64), first)
    assert not vgx.assembled.vertex_entries


def test_a_kept_batch_still_drops_its_non_finite_vertex(open_window, vgx):
    """The non-finite marks are kept with the arrays: every replay of an
    object with a NaN normal (unlit: only the input check sees it) drops
    that polygon with a warning and draws the others (docs/semantics.md:
    a primitive touching a non-finite normal is dropped)."""
    import pytest

    from vgx_emulator import VGXWarning
    open_window(W, H)
    ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    o = genobj()
    makeobj(o)
    _square(0)
    bgnpolygon()
    n3f((float("nan"), 0.0, 1.0))
    for v in ((8, 2), (12, 2), (12, 6), (8, 6)):
        v2f(v)
    endpolygon()
    n3f((0.0, 0.0, 1.0))
    _square(16)
    closeobj()
    for _ in range(3):
        cpack(0)
        clear()
        cpack(0xFFFFFFFF)
        callobj(o)
        with pytest.warns(VGXWarning, match="2 triangle"):
            row = lrectread(0, 0, W - 1, H - 1).astype(np.int64)[4]
        assert row[2] == row[18] == 0xFFFFFFFF and not row[8:13].any()
    assert len(vgx.assembled.vertex_entries) == 1


def test_kept_vertex_arrays_stay_within_their_budget(open_window, vgx, monkeypatch):
    """AssemblyCache.vertices drops the oldest batches beyond VERTEX_BYTES,
    and counts exactly the bytes it holds."""
    from vgx_emulator.geometry import AssemblyCache
    open_window(W, H)
    objs = _two_objects()
    colours = [0xFF000000 | c for c in range(1, 7)]
    _frame(objs, colours[:1])
    one = vgx.assembled.vertex_bytes
    monkeypatch.setattr(AssemblyCache, "VERTEX_BYTES", 3 * one)
    _frame(objs, colours)                       # six batches of the same size
    entries = vgx.assembled.vertex_entries
    assert len(entries) == 3
    assert vgx.assembled.vertex_bytes == sum(a.nbytes for _, out in entries.values()
                                             for a in out) == 3 * one
