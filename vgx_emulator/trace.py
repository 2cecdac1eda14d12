"""The bitplanes pass by pass: a trace of one frame (docs/trace.md).

A :class:`Trace` installed on the machine is told of every pass boundary
(``VGX.trace_hook``): each clear, sclear, zclear, czclear and acbuf, each
flush of the batch that drew (a change of state that ends a batch, a read),
and the frame end (swapbuffers, gflush, finish).  At each boundary of the
traced frame it snapshots every bank that exists (planes.py) into a
:class:`Step` together with the IRIS GL calls issued since the previous
boundary (``VGX.call_hook``: the program's top-level calls, not the calls
they make inside) and a summary of the per-fragment state the pass drew
with.  ``Trace.write(DIR)`` (``vgx-run --trace DIR``) saves a false-colour
picture of every bank after every step and an ``index.html`` stepping
through the frame.

A draw step that happens inside a call (the state change that flushed the
batch) lists that call as what ended it; the call opens the next pass.
A bank that did not change keeps the picture of the step before.
"""
import html
from pathlib import Path

import numpy as np

from .planes import _side_by_side, banks, picture, stencil_key

__all__ = ["Trace", "Step", "trace_program"]

EVENTS = {"draw": "drawing pass", "clear": "clear", "sclear": "sclear", "zclear": "zclear",
          "czclear": "czclear", "acbuf": "acbuf", "frame": "frame end"}
AC_NAMES = ("AC_CLEAR", "AC_ACCUMULATE", "AC_CLEAR_ACCUMULATE", "AC_RETURN", "AC_MULT",
            "AC_ADD")
MAX_CALLS = 400                 # call lines kept per step (runs of one name count once)


def _names(prefix):
    from irisgl import constants as K
    return {v: n for n, v in vars(K).items() if n.startswith(prefix) and isinstance(v, int)}


def _arg(a):
    r = repr(a) if not isinstance(a, float) else f"{a:g}"
    return r if len(r) <= 40 else r[:37] + "..."


def _state(win):
    """A line saying how the pass drew: z, writemasks, stencil, blending."""
    st = win.st
    zf, sf, so, bf = _names("ZF_"), _names("SF_"), _names("ST_"), _names("BF_")
    out = [f"zbuffer {'on ' + zf.get(st.zfunc, str(st.zfunc)) if st.zbuffer else 'off'}",
           f"zwritemask {st.zwritemask & 0xFFFFFF:#x}", f"wmpack {st.cmask:#x}"]
    if st.stencil_on:
        ref, func, mask, fail_, pass_, zpass = st.stencil
        out.append(f"stencil(ref {ref}, {sf.get(func, func)}, mask {mask:#x}, "
                   f"fail {so.get(fail_, fail_)}, zfail {so.get(pass_, pass_)}, "
                   f"zpass {so.get(zpass, zpass)})")
    else:
        out.append("stencil off")
    s, d = st.blendfunc
    out.append(f"blendfunction({bf.get(s, s)}, {bf.get(d, d)})")
    return ", ".join(out)


def _draw_label(win):
    """What kind of drawing pass the state makes it."""
    st = win.st
    sf, so = _names("SF_"), _names("ST_")
    colour = (st.cmask != 0) and st.drawmode == 0x10 or st.drawmode != 0x10
    zw = st.zbuffer and (st.zwritemask & 0xFFFFFF) != 0
    sten = st.stencil_on and win.fb.has("stencil")
    ref, func, _, f1, f2, f3 = st.stencil
    writes_s = sten and (f1, f2, f3) != (0, 0, 0)
    if not colour and not zw:
        what = "stencil-only pass" if writes_s else "pass writing no colour and no z"
    elif not colour:
        what = "depth-only pass"
    else:
        what = "drawing pass"
    extra = []
    if writes_s:
        ops = [f"{k} {so.get(v, v)}" for k, v in (("fail", f1), ("zfail", f2), ("zpass", f3))
               if v != 0]
        extra.append("stencil " + ", ".join(ops))
    if sten and func not in (0, 7):
        extra.append(f"gated by stencil {sf.get(func, func)} {ref}")
    if colour and tuple(st.blendfunc) != (1, 0):
        extra.append("blended")
    return what + (f" ({'; '.join(extra)})" if extra else "")


class Step:
    """One pass boundary of the traced frame: ``event`` (a key of EVENTS),
    ``label``, the ``calls`` of the pass [(name, first args, count)],
    ``ended_by`` (the call that flushed a drawing pass), ``state`` (a
    drawing pass's z/stencil/blend summary), ``key`` (the stencil pictures'
    reference), ``arrays`` (bank -> numpy copy, when the trace keeps them)
    and ``files`` (bank -> picture file, once written)."""

    def __init__(self, index, event, label, gid, calls, ended_by, state, key, arrays):
        self.index = index
        self.event = event
        self.label = label
        self.gid = gid
        self.calls = calls
        self.ended_by = ended_by
        self.state = state
        self.key = key
        self.arrays = arrays
        self.files = {}
        self.win = None

    def picture(self, name):
        return picture(name, self.arrays[name], self.win, self.key)

    def pictures(self):
        return {n: self.picture(n) for n in self.arrays}

    def _repr_png_(self):
        return _side_by_side([self.picture(n) for n in self.arrays])

    def __repr__(self):
        return f"<Step {self.index} {self.label} ({len(self.calls)} call lines)>"


class _Run:
    """A run of top-level calls of one name, listed as one line: ``v3f(1, 2,
    3) ×24`` when every call had those arguments, ``pdr(3, 3, -3) … (3, -3,
    3) ×3`` (the first and the last) when they differed."""
    __slots__ = ("name", "first", "count", "last", "prev", "varied", "varied_prev")

    def __init__(self, name, args):
        self.name, self.first, self.count, self.last = name, args, 1, args
        self.prev, self.varied, self.varied_prev = None, False, False

    def add(self, args):
        self.prev, self.varied_prev = self.last, self.varied
        self.varied = self.varied or args != self.last
        self.last = args
        self.count += 1

    def drop_last(self):
        """Takes the run's last call off (it opens the next pass); once only."""
        self.last, self.varied = self.prev, self.varied_prev
        self.count -= 1

    def line(self):
        """(name, arguments, count) as Step.calls lists them."""
        args = f"{self.first}) … ({self.last}" if self.varied else self.first
        return (self.name, args, self.count)


class Trace:
    """Records the passes of frame ``frame`` (1 = the first frame drawn).
    ``keep``: keep every bank of every step in memory (Step.arrays; a bank
    unchanged since the step before shares its array); ``outdir``: write
    the pictures as the steps happen (then nothing need be kept)."""

    def __init__(self, frame=1, keep=True, outdir=None):
        self.frame = frame
        self.keep = keep
        self.outdir = Path(outdir) if outdir is not None else None
        self.steps = []
        self.frame_no = 1
        self.pending = []           # _Run: the runs of calls of this pass
        self.dropped = 0            # calls beyond MAX_CALLS in this pass
        self.last = None            # (name, args, listed) of the last top-level call
        self.active = None          # the top-level call running now
        self.depth = 0
        self.sclear_value = {}      # gid -> the last sclear value (the stencil key)
        self.acc_weight = {}        # gid -> sum of the AC_ACCUMULATE values so far
        self._prev = {}             # (gid, bank) -> (array, file, key)
        self.machine = None

    # -- installation --------------------------------------------------
    def install(self, machine):
        self.machine = machine
        machine.trace_hook = self._hook
        machine.call_hook = self._call
        return self

    def uninstall(self):
        if self.machine is not None:
            self.machine.trace_hook = None
            self.machine.call_hook = None

    @property
    def recording(self):
        return self.frame_no == self.frame

    # -- hooks ---------------------------------------------------------
    def _call(self, name, f, args):
        """Run one IRIS GL call, noting it when it is a top-level call."""
        if self.depth == 0 and self.recording:
            args_s = ", ".join(_arg(a) for a in args)
            p = self.pending
            if self.dropped or (len(p) >= MAX_CALLS and p[-1].name != name):
                self.dropped += 1
            elif p and p[-1].name == name:
                p[-1].add(args_s)
            else:
                p.append(_Run(name, args_s))
            self.active = name
            self.last = (name, args_s, p[-1].name == name and p[-1].last is args_s)
        self.depth += 1
        try:
            return f(*args)
        finally:
            self.depth -= 1
            if self.depth == 0:
                self.active = None

    def _hook(self, m, win, event, *detail):
        if event == "sclear":
            self.sclear_value[win.gid] = detail[0]
        if event == "acbuf":
            op, value = detail
            w = self.acc_weight.get(win.gid, 0.0)
            if op == 2:                      # AC_CLEAR_ACCUMULATE
                w = value
            elif op == 1:                    # AC_ACCUMULATE
                w += value
            elif op == 0:                    # AC_CLEAR
                w = 0.0
            self.acc_weight[win.gid] = w
        if self.recording:
            self._step(m, win, event, detail)
        if event == "frame":
            self.frame_no += 1
            self.pending = []
            self.dropped = 0

    def _step(self, m, win, event, detail):
        runs = list(self.pending)
        ended_by = None
        if event == "draw" and self.active is not None and self.last is not None:
            name, args_s, listed = self.last
            ended_by = f"{name}({args_s})"         # it opens the next pass
            if listed:
                if runs[-1].count > 1:
                    runs[-1].drop_last()
                else:
                    runs.pop()
            elif self.dropped:
                self.dropped -= 1
            self.pending = [_Run(name, args_s)]
        else:
            self.pending = []
        calls = [r.line() for r in runs]
        if self.dropped:
            calls.append(("...", f"{self.dropped} more calls", 1))
        self.dropped = 0
        label = EVENTS[event]
        if event == "acbuf":
            label = f"acbuf({AC_NAMES[detail[0]]}, {detail[1]:g})"
        elif event == "sclear":
            label = f"sclear({detail[0]})"
        elif event == "frame" and calls:
            label = f"frame end ({calls[-1][0]})"
        state = _state(win) if event == "draw" else None
        if event == "draw":
            label = _draw_label(win)
        key = stencil_key(win, self.sclear_value.get(win.gid, 0))
        arrays = {}
        step = Step(len(self.steps) + 1, event, label, win.gid, calls, ended_by,
                    state, key, arrays)
        step.win = win
        for name, a in banks(win).items():
            prev = self._prev.get((win.gid, name))
            kkey = key if name == "stencil" else None
            if prev is not None and prev[2] == kkey and prev[0].shape == a.shape \
                    and np.array_equal(prev[0], a):
                snap, fname = prev[0], prev[1]
            else:
                snap, fname = a.copy(), None
                if self.outdir is not None:
                    fname = f"step{step.index:04d}_{name}.png"
                    self.outdir.mkdir(parents=True, exist_ok=True)
                    picture(name, snap, win, key, m).save(self.outdir / fname)
            self._prev[(win.gid, name)] = (snap, fname, kkey)
            if self.keep:
                arrays[name] = snap
            if fname:
                step.files[name] = fname
        self.steps.append(step)

    # -- output --------------------------------------------------------
    def write(self, outdir=None, title="trace"):
        """index.html (and, for steps recorded without an outdir, their
        pictures) into ``outdir``; returns its path."""
        out = Path(outdir) if outdir is not None else self.outdir
        out.mkdir(parents=True, exist_ok=True)
        for s in self.steps:
            for name, a in s.arrays.items():
                if name not in s.files:
                    s.files[name] = f"step{s.index:04d}_{name}.png"
                    if not (out / s.files[name]).exists():
                        s.picture(name).save(out / s.files[name])
        (out / "index.html").write_text(_index(self, title))
        return out / "index.html"


def _index(tr, title):
    e = html.escape
    parts = ["<!doctype html><html><head><meta charset='utf-8'>",
             f"<title>{e(title)}</title><style>"
             "body{font-family:sans-serif;background:#1b1b1b;color:#ddd;margin:16px}"
             ".step{display:none}.step.on{display:block}img{border:1px solid #555;"
             "margin:4px;vertical-align:top}code{color:#fc9}ol{font-family:monospace;"
             "font-size:13px}nav button{font-size:16px;margin-right:8px}"
             "#toc a{color:#9cf;margin-right:6px;font-size:12px}</style></head><body>",
             f"<h1>{e(title)}</h1><p>Frame {tr.frame}: {len(tr.steps)} passes. "
             "Left/right arrow keys or the buttons step through them; each picture "
             "is a bank after the pass (docs/trace.md).</p>",
             "<nav><button onclick='go(-1)'>&larr; previous</button>"
             "<button onclick='go(1)'>next &rarr;</button><span id='pos'></span></nav>",
             "<p id='toc'>" + " ".join(
                 f"<a href='#' onclick='show({i});return false'>{s.index}&nbsp;{e(s.label)}</a>"
                 for i, s in enumerate(tr.steps)) + "</p>"]
    for i, s in enumerate(tr.steps):
        parts.append(f"<div class='step' id='s{i}'><h2>Pass {s.index}: {e(s.label)}"
                     f" (window {s.gid})</h2>")
        if s.state:
            parts.append(f"<p>drawn with: <code>{e(s.state)}</code></p>")
        if s.ended_by:
            parts.append(f"<p>ended by <code>{e(s.ended_by)}</code> (a change of state "
                         "that ends the batch; it opens the next pass)</p>")
        parts.append("<ol>" + "".join(
            f"<li><code>{e(n)}({e(a)})</code>{f' &times;{c}' if c > 1 else ''}</li>"
            for n, a, c in s.calls) + "</ol>")
        parts.append("".join(f"<img src='{e(f)}' alt='{e(n)}' title='{e(n)}'>"
                             for n, f in s.files.items()))
        parts.append("</div>")
    parts.append("<script>var n=%d,i=0;function show(k){if(!n)return;"
                 "document.getElementById('s'+i).className='step';i=(k+n)%%n;"
                 "document.getElementById('s'+i).className='step on';"
                 "document.getElementById('pos').textContent=' pass '+(i+1)+' of '+n;}"
                 "function go(d){show(i+d);}"
                 "document.onkeydown=function(ev){if(ev.key=='ArrowLeft')go(-1);"
                 "if(ev.key=='ArrowRight')go(1);};show(0);</script>" % len(tr.steps))
    parts.append("</body></html>")
    return "\n".join(parts)


def trace_program(path, argv=None, frame=1, keep=True, outdir=None):
    """Run a program headless (runner.run_program) up to frame ``frame``
    and return the Trace of that frame."""
    from .runner import run_program
    tr = Trace(frame, keep, outdir)
    run_program(path, frame, argv, trace=tr)
    return tr
