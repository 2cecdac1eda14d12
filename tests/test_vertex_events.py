"""geometry.batch.per_vertex: the attributes each vertex takes from the
event stream of the immediate-mode calls (docs/semantics.md §3: a vertex
takes the current normal, colour and texture coordinate; lmcolor(3G): the
later of the last normal and colour decides LAST_WAS_NORMAL, a colour sent
while a material is bound sets COLOUR_SINCE_BIND).  Checked against the
stream replayed event by event, on random streams and on the cases the
vectorised code treats apart (one record, kinds never sent)."""
import numpy as np
import pytest

from vgx_emulator.geometry.batch import (COLOUR_SINCE_BIND, EV_BYTE, EV_COLOUR, EV_CPACK,
                                         EV_NORMAL, EV_REC, EV_TEX, EV_UNIT, LAST_WAS_NORMAL,
                                         R_COLOUR, R_FLAGS, R_MATERIAL, R_NORMAL, R_STRQ,
                                         RECORD, _events, _packed, colour_value,
                                         per_vertex)


def _replayed(ev, recs, n, mats):
    """The attributes of vertices 0..n-1, applying the events in order."""
    out = np.zeros((n, RECORD))
    cur, j = None, 0
    for i in range(n):
        while j < len(ev) and ev[j, 0] <= 4 * i:
            at, kind, a, b, c, d = ev[j]
            kind = int(kind)
            if kind == EV_REC:
                cur = recs[int(a)].copy()
            elif kind == EV_NORMAL:
                cur[R_NORMAL] = (a, b, c)
                cur[R_FLAGS] = (int(cur[R_FLAGS]) & COLOUR_SINCE_BIND) | LAST_WAS_NORMAL
            elif kind == EV_TEX:
                cur[R_STRQ] = (a, b, c, d)
            else:
                cur[R_COLOUR] = colour_value(kind, a, b, c, d)
                bound = mats[int(cur[R_MATERIAL])][0] != 0
                cur[R_FLAGS] = (int(cur[R_FLAGS]) & COLOUR_SINCE_BIND) | \
                    (COLOUR_SINCE_BIND if bound else 0)
            j += 1
        out[i] = cur
    return out


def _stream(rng, n, nrecs, kinds):
    recs = rng.uniform(0, 1, (nrecs, RECORD))
    recs[:, R_FLAGS] = rng.integers(0, 4, nrecs)
    recs[:, R_MATERIAL] = rng.integers(0, 3, nrecs)
    ev = [(0, EV_REC, 0, 0, 0, 0)]
    for i in range(n):
        for _ in range(rng.integers(0, 3)):
            k = int(rng.choice(kinds))
            if k == EV_REC:
                ev.append((4 * i, EV_REC, int(rng.integers(0, nrecs)), 0, 0, 0))
            elif k == EV_CPACK:
                ev.append((4 * i, k, int(rng.integers(0, 1 << 32)), 0, 0, 0))
            else:
                ev.append((4 * i, k, *rng.uniform(-0.5, 300, 4)))
    return np.array(ev, np.float64), recs


MATS = [(0, 0, None, 0), (1, 0, None, 0), (2, 0, None, 0)]   # material 0: none bound


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("nrecs, kinds", [
    (1, [EV_NORMAL]),                                   # n3f only, one record
    (1, [EV_NORMAL, EV_UNIT]),
    (3, [EV_REC, EV_NORMAL, EV_TEX, EV_COLOUR, EV_UNIT, EV_BYTE, EV_CPACK]),
    (2, [EV_REC, EV_TEX]),                              # no normal or colour events
    (4, [EV_REC]),                                      # records only
])
def test_per_vertex_matches_the_stream_replayed(seed, nrecs, kinds):
    rng = np.random.default_rng(seed)
    n = 40
    ev, recs = _stream(rng, n, nrecs, kinds)
    got, last = per_vertex(ev, recs, n, MATS)
    want = _replayed(ev, recs, n, MATS)
    assert np.array_equal(got, want)
    # the newest event of each group (VertexBatch.sync), -1 where none came
    groups = ([EV_NORMAL], [EV_TEX], [EV_COLOUR, EV_UNIT, EV_BYTE, EV_CPACK])
    want_last = [max([j for j in range(len(ev)) if ev[j, 1] in g], default=-1) for g in groups]
    assert last.tolist() == want_last


NAN, INF = float("nan"), float("inf")


@pytest.mark.parametrize("kind, values, want", [
    # c3f/c4f (3G): 0.0-1.0 components, clamped, times 255 (huge finite ones too)
    (EV_UNIT, (0.5, 2.0, -1.0, 1e301), (127.5, 255.0, 0.0, 255.0)),
    # c3i/c3s/RGBcolor (3G): 0-255 components, clamped
    (EV_BYTE, (12.0, 300.0, -4.0, 255.0), (12.0, 255.0, 0.0, 255.0)),
    # cpack(3G): 0xAABBGGRR
    (EV_CPACK, (float(0x80FF1002), 0, 0, 0), (2.0, 16.0, 255.0, 128.0)),
    # an index or a final colour passes as it is
    (EV_COLOUR, (7.0, 300.0, -1.0, 0.25), (7.0, 300.0, -1.0, 0.25)),
    # non-finite components pass (the flush drops the primitive with a warning)
    (EV_UNIT, (NAN, INF, -INF, 0.0), (NAN, INF, -INF, 0.0)),
    (EV_BYTE, (NAN, INF, -INF, 1.0), (NAN, INF, -INF, 1.0)),
])
def test_colour_events_convert_as_the_man_pages_say(kind, values, want):
    """colour_value (the state a flush leaves) and per_vertex's compiled
    pass (each vertex's colour) give the same 0..255 components, as the
    colour calls' man pages define them."""
    assert np.array_equal(colour_value(kind, *values), want, equal_nan=True)
    ev = np.array([(0, EV_REC, 0, 0, 0, 0), (0, kind, *values)], np.float64)
    got = per_vertex(ev, np.zeros((1, RECORD)), 1, MATS)[0][0, R_COLOUR]
    assert np.array_equal(got, want, equal_nan=True)


@pytest.mark.parametrize("m", [0, 1, 255, 256, 257, 700])
def test_events_convert_every_value_as_fromiter_does(m):
    """_events (struct, chunks of 256 events) gives the (m, 6) array that
    np.fromiter gives, at the chunk edges too, for the values the calls
    append: int at and kind, floats, a cpack word, NaN and infinities; a
    chunk with a float at or kind (events made from an array) included."""
    rng = np.random.default_rng(m)
    ev = []
    for j in range(m):
        kind = int(rng.integers(0, 7))
        vals = [float(v) for v in rng.uniform(-1e3, 1e3, 4)]
        if j % 97 == 5:
            vals[1:3] = [NAN, -INF]
        if kind == EV_CPACK:
            vals = [int(rng.integers(0, 1 << 32)), 0, 0, 0]
        at = 4 * j if j % 300 != 299 else float(4 * j)      # a float at, now and then
        ev += [at, kind, *vals]
    want = np.fromiter(ev, np.float64, len(ev)).reshape(-1, 6)
    got = _events(ev)
    assert got.shape == (m, 6)
    assert np.array_equal(got, want, equal_nan=True)


def test_packed_converts_as_fromiter_and_raises_as_it_does():
    vals = [1.5, 2, -0.0, NAN, INF, np.float64(3.25), True]
    assert np.array_equal(_packed(vals, np.float64), np.fromiter(vals, np.float64),
                          equal_nan=True)
    assert _packed(vals, np.float64).flags.writeable
    assert _packed([], np.float64).shape == (0,)
    with pytest.raises(OverflowError):
        _packed([1.0, 10 ** 400], np.float64)
    with pytest.raises((TypeError, ValueError)):
        _packed([1.0, "x"], np.float64)
    ints = [3, 0, 2 ** 40, -7, True, np.int64(5)]        # the primitive table's values
    got = _packed(ints, np.int64)
    assert got.dtype == np.int64 and got.tolist() == [3, 0, 2 ** 40, -7, 1, 5]
    with pytest.raises(OverflowError):                  # (never a silent cut)
        _packed([1, 2 ** 70], np.int64)
