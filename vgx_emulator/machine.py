"""The VGX: windows, the current window, batching and flush.

The machine knows no C names: :mod:`irisgl` validates every argument, then
calls one method here.  Methods change state only after their own checks
passed, so a call that raises leaves everything as it was.

Batching: vertices and primitives accumulate in the current window's
:class:`VertexBatch`; any call that changes how already-issued primitives
must be drawn (lighting, z-buffer, viewport, shading, buffers ...) first
flushes the batch through the geometry subsystem and the scan converter.
Matrix changes do not flush: each vertex run remembers its transform.
Reads (lrectread, PNG output) flush too.
"""
import numpy as np

from . import config, display, geometry, pipeline, scan
from .errors import fail, warn
from .events import INPUTCHANGE, REDRAW, EventQueue
from .framebuffer import ZMAX, ZMIN, Framebuffer
from .framebuffer import layers
from .geometry import lighting, scrbox, stack
from .geometry.assemble import CLOSEDLINE, LINE, POINT, POLYGON, QSTRIP, TMESH
from .geometry.batch import CLASS_OF, EV_COLOUR, EV_NORMAL, EV_TEX, FILLED, POINTS, VertexBatch
from .raster import fragment, variants
from .raster import depth as _depth
from .raster import stencil as _stencil
from .scan.spans import fill, fill_pattern, fill_z
from .scan.triangles import CULL_BACK, CULL_FRONT, CULL_NONE
from .state import WindowState

SRC_AUTO, SRC_FRONT, SRC_BACK, SRC_ZBUFFER = 0, 1, 2, 3
_SRC_LAYER = {4: layers.PUPDRAW, 5: layers.OVERDRAW, 6: layers.UNDERDRAW}   # SRC_PUP/OVER/UNDER

_DUMMY_C = np.zeros((1, 1), np.uint32)


def _closed(p):
    """``VGX.V`` outside bgn/end: the per-vertex call takes its checked path."""
    raise LookupError("vertex outside bgn/end")


class Window:
    """One IRIS GL window: its bitplanes, its graphics state, its batch."""

    def __init__(self, gid, name, x, y, width, height):
        self.gid = gid
        self.name = name
        self.origin = (x, y)
        self.width = width
        self.height = height
        self.fb = Framebuffer(width, height)
        self.st = WindowState(width, height)
        self.batch = VertexBatch()
        self.st.events, self.batch.owner = self.batch, self.st
        self.readsource = SRC_AUTO
        self.frames = 0
        # window-manager state (irisgl.window): title, constraints, border...
        self.wm = {"title": name}
        self.parent = None             # swinopen: the parent window's gid
        self.offset = (0, 0)           # swinopen: origin relative to the parent
        self.saved_geometry = None     # fullscrn: (x, y, w, h) to restore
        self.attrib_stack = []         # pushattributes(3G)

    def _repr_png_(self):
        """Jupyter: what the screen shows of the window (planes.py)."""
        from .planes import window_picture
        return window_picture(self).to_png()

    def resize(self, x, y, width, height):
        """Move and reshape (winposition, fullscrn): the banks are rebuilt at
        the new size in the same configuration, keeping the overlapping
        pixels anchored at the lower-left corner (what is outside is 0, the
        man pages leave it undefined).  Viewport and matrices are kept: a
        program reissues them (reshapeviewport) on the REDRAW that follows."""
        self.origin = (x, y)
        if (width, height) == (self.width, self.height):
            return
        old = self.fb
        fb = Framebuffer(width, height)
        fb.configure(old.back is not None, old.stencil_planes, old.accum is not None)
        if old.z is not None:
            fb.ensure_z()
        h, w = min(height, self.height), min(width, self.width)
        for name in ("front", "back", "z", "stencil", "accum"):
            a, b = getattr(old, name), getattr(fb, name)
            if a is not None and b is not None:
                b[:h, :w] = a[:h, :w]
        fb.layer_planes = dict(old.layer_planes)       # pop-up/overlay/underlay (layers.py)
        for mode, a in old.layers.items():
            fb.layer(mode)[:h, :w] = a[:h, :w]
        fb.z_written()
        self.fb = fb
        self.width, self.height = width, height


class VGX:
    """The emulated IRIS-4D VGX: a virtual 1280x1024 screen with windows."""

    def __init__(self):
        self._current = self._recording = self._call_hook = None
        self.reset()

    # -- the handles of the per-vertex calls --------------------------------
    # irisgl's v*/n3f/c*/t* calls append to the current window's lists
    # through these attributes, with no check of their own: every change of
    # the current window, of recording, of bgn/end or of the colour mode
    # rebinds them, and a handle that does not apply (None, or _closed for V)
    # sends the call down its checked path.
    @property
    def current(self):
        """The current window (winset(3G)), or None."""
        return self._current

    @current.setter
    def current(self, win):
        self._current = win
        self.rebind()

    @property
    def recording(self):
        """The object being recorded (makeobj(3G)), or None."""
        return self._recording

    @recording.setter
    def recording(self, ob):
        self._recording = ob
        self.rebind()

    @property
    def call_hook(self):
        """trace.py: ``(name, f, args)`` runs each top-level call, or None."""
        return self._call_hook

    @call_hook.setter
    def call_hook(self, hook):
        self._call_hook = hook
        self.rebind()

    def rebind(self):
        """Point the per-vertex handles at the current window's batch:
        ``B`` the batch, ``st`` its state, ``P`` its position list, ``E`` its
        event list (``EC`` the same in RGB mode only), ``V`` the extend of
        ``P`` inside bgn/end.  None (``_closed``) where the calls must take
        their checked path: no window, an object being recorded, a trace
        naming every call.  ``W`` is the window itself for bgn*/end*."""
        win = self._current
        if win is None or self._recording is not None or self._call_hook is not None:
            self.W = self.B = self.st = self.P = self.E = self.EC = None
            self.V = _closed
            return
        b = win.batch
        self.W, self.B, self.st, self.P, self.E = win, b, win.st, b.pos, b.ev
        self.EC = b.ev if win.st.rgb else None
        self.V = b.extend if b.open is not None else _closed

    def reset(self):
        """Power-on state: no windows, default colour map, empty definitions
        (after the raster work queued for the old windows)."""
        pipeline.sync()
        self.windows = {}
        self.current = None
        self.next_gid = 1
        self.events = EventQueue()
        self.colormap = display.default_colormap()
        self.defs = {lighting.DEFMATERIAL: {}, lighting.DEFLIGHT: {}, lighting.DEFLMODEL: {}}
        self.pref = {}
        self.objects = {}              # display lists: Object -> irisgl.objects._Object
        self.recording = None          # the Object being recorded, or None
        self.generated = {"obj": 0, "tag": 0}   # genobj/gentag: the last number handed out
        self.textures = {}             # texdef2d: index -> vgx_emulator.texture.Texture
        self.environments = {}         # tevdef: index -> Environment
        self.curve_state = None        # defbasis/curvebasis/patch* settings (irisgl.curves)
        self.patterns = {}             # defpattern: index -> (size, bits (size, size) uint8)
        self.fonts = {}                # defrasterfont/deflfont/loadXfont: n -> RasterFont
        from .menus import MenuTable
        self.menus = MenuTable()       # defpup/newpup menus and scripted dopup answers
        self.linestyles = {0: 0xFFFF}  # deflinestyle: index -> 16-bit pattern (all windows)
        self.frame_hook = None         # runner: called at each frame end
        self.trace_hook = None         # trace.py: (machine, win, event, *detail) at pass ends
        self.display_hook = None       # display/tkwindow.py: called after each drawn batch
        self.call_hook = None          # trace.py: (name, f, args) runs each top-level call
        self.last_image = None         # what the last closed window showed
        self.picking = None            # pick/gselect session (vgx_emulator/picking.py)
        self.picksize = (10, 10)       # picksize(3G)
        self.stacking = []             # gids, back to front (winpop/winpush)
        self.system = {}               # irisgl.system / cursor state (bell, lamps, video ...)
        self.gamma = None              # gammaramp(3G): (256, 3) uint8 LUT, None = identity
        self.maps = display.MapState()  # pop-up/overlay/underlay/cursor maps, setmap, blink
        self.assembled = geometry.AssemblyCache()   # triangles of replayed primitive tables

    # ------------------------------------------------------------------
    # windows and configuration (docs/semantics.md §4, §13)
    def window(self, call):
        """The current window, or GLError for a call before winopen."""
        if self.current is None:
            fail(call, "no window is open", "call winopen first")
        return self.current

    def winopen(self, name):
        x, y = self.pref.get("origin", (0, 0))
        w, h = self.pref["size"] if "size" in self.pref else self._swept_size()
        win = Window(self.next_gid, name, x, y, w, h)
        self.next_gid += 1
        # the default projection maps window pixels: ortho2(-0.5, w-0.5, -0.5, h-0.5)
        win.st.matrices.single[-1] = stack.ortho(-0.5, w - 0.5, -0.5, h - 0.5, -1.0,
                                                 1.0).astype(np.float32)
        # constraints and window-manager requests bind to the new window
        win.wm.update((k, v) for k, v in self.pref.items() if k not in ("origin", "size"))
        self.windows[win.gid] = win
        self.stacking.append(win.gid)
        self.current = win
        self.pref = {}
        # winopen queues INPUTCHANGE and REDRAW for the new window
        self.events.qdevice(INPUTCHANGE)
        self.events.qdevice(REDRAW)
        self.events.post(INPUTCHANGE, win.gid)
        self.events.post(REDRAW, win.gid, coalesce=True)
        return win.gid

    def _swept_size(self):
        """No prefsize: the size a user could sweep out, the default size
        shaped by keepaspect and bounded by minsize/maxsize (minsize(3G))."""
        sw, sh = config.SCREEN_WIDTH, config.SCREEN_HEIGHT
        w, h = config.DEFAULT_WINDOW_SIZE
        if "aspect" in self.pref:
            ax, ay = self.pref["aspect"]
            h = max(1, round(w * ay / ax))
            if h > sh:
                w, h = max(1, round(sh * ax / ay)), sh
        lo = self.pref.get("minsize", (1, 1))
        hi = self.pref.get("maxsize", (sw, sh))
        return (min(max(w, lo[0]), hi[0], sw), min(max(h, lo[1]), hi[1], sh))

    def winclose(self, gid):
        win = self.windows[gid]
        self._flush(win)
        self.last_image = self.image(win)
        del self.windows[gid]
        if self._picking(win):
            self.picking = None        # its pick/gselect session ends with it
        if gid in self.stacking:
            self.stacking.remove(gid)
        if self.current is win:
            self.current = next(iter(self.windows.values()), None)

    def winset(self, gid):
        self.flush()
        self.current = self.windows[gid]

    def gexit(self):
        """gexit(3G): every window closed, graphics ended; an object still
        open is closed as closeobj would (it keeps what was recorded)."""
        from . import objects as O
        if self.recording is not None:
            ob = self.objects[self.recording]
            ob.ops = O.compile_items(ob.items)
            self.recording = None
        for gid in list(self.windows):
            self.winclose(gid)
        self.events.reset_all()

    def gconfig(self, win):
        """Apply the configuration requests (gconfig(3G))."""
        self._flush(win)
        st = win.st
        mode = st.drawmode                 # the requests are the normal framebuffer's
        layers.switch(st, layers.NORMALDRAW)
        st.rgb = st.req_rgb
        self.rebind()
        st.double = st.req_double
        st.multimap = st.req_multimap
        win.fb.configure(st.double, st.req_stencil, st.req_accum)
        win.fb.configure_layers(*layers.resolve(st.req_overlay, st.req_underlay))
        layers.reset_layers(st)            # every drawmode: index 0, writemask all ones
        st.colour = (0.0, 0.0, 0.0, 0.0)
        st.zwritemask = 0xFFFFFF
        st.swritemask = 0xFF
        st.cmask = 0xFFFFFFFF
        st.front_enabled = not st.double
        st.back_enabled = st.double
        st.zdraw = False                   # zdraw(3G): FALSE after gconfig
        layers.switch(st, mode)

    def swapbuffers(self, win):
        self._flush(win)
        if layers.normal(win.st, "double"):      # whatever the drawmode (layers.py)
            win.fb.swap()
        self.frame_end(win)

    def frame_end(self, win):
        """A frame point (swapbuffers, gflush, finish): the runner counts it.
        The raster work queued so far is finished first (finish(3G): the
        pipeline drained), so a frame point ends a whole frame."""
        self._finish(win)
        win.frames += 1
        self.maps.tick()                   # cyclemap/blink: retraces per frame point
        if self.trace_hook is not None:
            self.trace_hook(self, win, "frame")
        if self.frame_hook is not None:
            self.frame_hook(self, win)

    # ------------------------------------------------------------------
    # batching
    def state_change(self, win=None):
        """Flush primitives already issued before a state change."""
        win = win or self.current
        if win is not None and len(win.batch):
            self._flush(win)

    def flush(self):
        if self.current is not None:
            self._flush(self.current)

    def _finish(self, win):
        """Flush ``win`` and wait for every queued raster pass
        (pipeline.py): before work that touches pixels on this thread."""
        self._flush(win)
        pipeline.sync()

    def _picking(self, win):
        """Whether win is in picking or selecting mode (nothing is drawn)."""
        return self.picking is not None and self.picking.win is win

    def flush_all(self):
        for win in self.windows.values():
            self._flush(win)

    def _flush(self, win):
        b = win.batch
        if not len(b):
            return
        if self._picking(win):
            # pick/gselect: geometry and clipping only, no pixel (picking.py)
            self.picking.test_batch(b, win.st)
            b.keep_open_primitive(win.st) if b.open is not None else b.reset()
            return
        st = win.st
        vp = _intersect(st.viewport, st.scrmask, (0, win.width - 1, 0, win.height - 1))
        if vp is not None:
            # a pass that writes no colour and tests no alpha (a depth-only
            # or stencil pass) needs neither lighting nor texturing
            shade = self._colour_needed(win)
            tex = self._texturing(win) if (b.klass == FILLED and shade and
                                           st.polymode == 1) else None   # PYM_FILL only
            work = geometry.process_batch(b, st, self.defs, not st.subpixel, st.viewport,
                                          texturing=tex is not None, shade=shade,
                                          linestyles=self.linestyles,
                                          assembled=self.assembled)
            if st.scrbox_mode == 1:           # scrbox(3G) SB_TRACK
                scrbox.track(st, work, vp)
            filled = work.klass == FILLED
            zfar = self._z_maxima_bound(win) if filled else None
            key, planes, ip = self._raster_setup(win, work, filled, defer_z=True)
            key = key._replace(texture=tex is not None)
            if key.gouraud and (not key.color or (work.klass == FILLED and tex is None
                                                  and work.constant_colour())):
                key = key._replace(gouraud=False)   # same pixels, no interpolation
            cull = (CULL_BACK if st.backface else CULL_NONE) | \
                   (CULL_FRONT if st.frontface else CULL_NONE)
            pipeline.submit(_raster_pass, win.fb, work, key, planes, ip, cull,
                            not st.subpixel, tex, zfar, scan.setup_batch(work, key, ip, cull),
                            now=_small_pass(work))
            if self.trace_hook is not None:
                self.trace_hook(self, win, "draw")
        if b.open is not None:
            b.keep_open_primitive(st)
        else:
            b.reset()

    def _z_maxima_bound(self, win):
        """Whether a pass may skip spans against the z bank's per-segment
        maxima (framebuffer/zmax.py): z test LESS, EQUAL or LEQUAL, z
        written in full or not at all (its writes then only lower z), and a
        fragment failing the z test changes nothing (stencil off, or its
        fail and z-fail ops ST_KEEP).  Returns the far end of the depth
        range then (_raster_pass: maxima uniform at or beyond it, just
        cleared, make no span fail), otherwise None."""
        st, fb = win.st, win.fb
        if not st.zbuffer or \
                st.zfunc not in (_depth.ZF_LESS, _depth.ZF_EQUAL, _depth.ZF_LEQUAL):
            return None
        if st.zwritemask & 0xFFFFFF not in (0, 0xFFFFFF):
            return None
        if st.stencil_on and fb.has("stencil") and \
                (st.stencil[3] != _stencil.ST_KEEP or st.stencil[4] != _stencil.ST_KEEP):
            return None
        return max(st.depth_range)

    def _texturing(self, win):
        """(Texture, parameters) when texturing is on: a texture != 0 bound to
        TX_TEXTURE_0 and an environment != 0 to TV_ENV0, in RGB mode
        (docs/semantics.md §16); otherwise None."""
        from . import texture as T
        from .raster import texture as RT
        st = win.st
        if not (st.rgb and st.texture and st.tev):
            return None
        tx = self.textures.get(st.texture)
        env = self.environments.get(st.tev)
        if tx is None or env is None:
            return None
        mode = RT.ENV_MODULATE
        if env.mode == T.TV_DECAL and tx.nc >= 3:
            mode = RT.ENV_DECAL
        elif env.mode == T.TV_BLEND and tx.nc <= 2:
            mode = RT.ENV_BLEND
        p = np.zeros(7)
        p[RT.T_WRAPS] = tx.wrap_s != T.TX_CLAMP
        p[RT.T_WRAPT] = tx.wrap_t != T.TX_CLAMP
        p[RT.T_ENV] = mode
        p[RT.T_CR:RT.T_CA + 1] = env.colour
        return tx, p

    def _colour_needed(self, win):
        """Whether the fragments' colour is used: written to a colour buffer
        or tested by afunction."""
        st = win.st
        full = layers.index_bits(win)
        written = bool(self._targets(win)) and (st.cmask & full) != 0
        return written or (st.rgb and st.afunc[1] != 7)

    def _targets(self, win):
        """The colour banks drawing goes to (frontbuffer/backbuffer(3G))."""
        st, fb = win.st, win.fb
        if st.drawmode != layers.NORMALDRAW:
            # drawmode(3G): the pop-up/overlay/underlay bank (none in
            # CURSORDRAW, or without planes)
            bank = fb.layer(st.drawmode, queued=True) if st.drawmode in layers.LAYERS else None
            return [bank] if bank is not None else []
        zdraw = getattr(st, "zdraw", False)
        if not st.double:
            out = [fb.queued("front")] if (st.front_enabled or not zdraw) else []
        else:
            out = []
            if st.back_enabled:
                out.append(fb.queued("back"))
            if st.front_enabled:
                out.append(fb.queued("front"))
        if zdraw and len(out) < 2:
            # zdraw(3G): colour words also go to the z bank, as a third
            # colour buffer (at most two banks per pass: docs/windows-and-devices.md)
            out.append(fb.ensure_z().view(np.uint32))
            fb.z_written()
        return out

    def _raster_setup(self, win, work, filled=True, defer_z=False):
        """The RasterKey, banks and parameter vector of a pass
        (raster.variants.choose).  A pass that writes z marks the z maxima
        stale, unless ``defer_z`` (the caller marks them after the pass,
        if it changed z)."""
        st, fb = win.st, win.fb
        targets = self._targets(win)
        pat = self.patterns.get(st.pattern) if filled and st.pattern else None
        key, ip = variants.choose(
            st, fb, targets, bits=layers.index_bits(win), pattern=pat,
            scissor=_intersect(st.viewport, st.scrmask, (0, win.width - 1, 0, win.height - 1)),
            origin=win.origin, twoside=bool(work is not None and work.twoside),
            hollow=bool(work is not None and work.hollow))
        if key.zwrite and not defer_z:
            fb.z_written()
        return key, variants.banks(key, fb, targets, pat, win.origin), ip

    # ------------------------------------------------------------------
    # primitives (docs/semantics.md §3)
    def begin(self, win, kind, call):
        """bgnpolygon(3G) and the other bgn* calls: open a primitive of
        ``kind``; the handles of the per-vertex calls now append to it."""
        b = win.batch
        if b.open is not None:
            fail(call, f"already inside {b.open[1]}", f"close it with end{b.open[1][3:]} first")
        klass = CLASS_OF[kind]
        if b.klass != klass:
            if len(b):
                self._flush(win)
            b.klass = klass
        b.open = (kind, call)
        if call not in b.calls:
            b.calls.add(call)
        b.start = b.vbase + (len(b.pos) >> 2)
        if b.dirty:
            b.record_attributes(win.st)
        if win is self.W:
            self.V = b.extend

    def end(self, win, kind, call):
        """endpolygon(3G) and the other end* calls: close the primitive.  A
        polygon of more than GD_NVERTEX_POLY (256) vertices is an error here,
        at its end (docs/decisions.md): it is not drawn, and the pair is
        closed."""
        b = win.batch
        o = b.open
        if o is None or o[0] != kind:
            name = call[3:]
            fail(call, f"inside {o[1]}" if o else "not inside any bgn call",
                 f"end{name} closes bgn{name}")
        nverts = b.vbase + (len(b.pos) >> 2)
        n = nverts - b.start
        if kind == POLYGON:
            if n > config.MAX_POLYGON_VERTICES:
                b.drop_open_primitive()
                self._close(win, b)
                fail(call, f"{n} vertices in a polygon",
                     f"at most {config.MAX_POLYGON_VERTICES} (GD_NVERTEX_POLY); it is not drawn")
            if n:
                b.prims += (kind, b.start, n, win.st.concave)
        else:
            while kind == TMESH and b.swaps and b.swaps[-1] >= nverts:
                b.swaps.pop()             # a swap after the last vertex swaps nothing
            if n:
                b.prims += (kind, b.start, n, False)
        b.open = None
        if win is self.W:
            self.V = _closed
        if nverts >= config.FLUSH_VERTICES:   # (the primitive's end adds no vertex)
            self._flush(win)                # the raster thread draws while the program goes on
        if self.display_hook is not None:
            self.display_hook(win)          # a real window: drawing shows as it happens

    def _close(self, win, b):
        b.open = None
        if win is self.W:
            self.V = _closed

    def vertex(self, win, x, y, z, w, call):
        """A vertex of the open primitive (the checked path of v*)."""
        b = win.batch
        if b.open is None:
            fail(call, "vertex outside bgn/end", "call it between bgn* and end*")
        b.pos += (x, y, z, w)

    def swaptmesh(self, win):
        b = win.batch
        if b.open is None or b.open[0] != TMESH:
            fail("swaptmesh", "not inside bgntmesh", "call it between bgntmesh and endtmesh")
        b.swaps.append(b.nverts)

    def polyline_vertices(self, win, kind, pts, call):
        """A whole primitive from a point list of 4-tuples (rect, poly, polf, ...)."""
        self.begin(win, kind, call)
        pos = win.batch.pos
        for p in pts:
            pos += p
        self.end(win, kind, call)

    def primitive_array(self, win, kind, pts, call, colours=None):
        """A whole primitive from an (n, 4) array (circ, arc, sbox, splf ...)
        with list operations only; ``colours`` (n, 4) gives each vertex its
        own colour (splf), the current colour stays as it was."""
        pts = np.asarray(pts, np.float64).reshape(-1, 4)
        if kind == POLYGON and len(pts) > config.MAX_POLYGON_VERTICES:
            fail(call, f"{len(pts)} vertices in a polygon", "GD_NVERTEX_POLY is 256")
        self.begin(win, kind, call)
        b = win.batch
        if colours is not None:
            # one colour event per vertex, then the current attributes again
            n0 = len(b.pos)
            ev = np.zeros((len(pts), 6))
            ev[:, 0] = np.arange(n0, n0 + 4 * len(pts), 4)
            ev[:, 1] = EV_COLOUR
            ev[:, 2:6] = np.asarray(colours, np.float64).reshape(-1, 4)
            b.ev += ev.ravel().tolist()
            b.synced = len(b.ev)           # the current colour stays as it was
            if win.st.material:
                win.st.colour_since_bind = True
        b.pos += pts.ravel().tolist()
        if colours is not None:
            b.record_attributes(win.st)
        self.end(win, kind, call)

    def polyline_eye_vertices(self, win, kind, projection, pts, call):
        """One primitive whose points (N, 4) are already eye coordinates (the
        ModelView applied), drawn through ``projection`` only (curveit(3G));
        appended as one block, as display-list replay appends."""
        from .geometry.batch import Transform
        b = win.batch
        if b.open is not None:
            fail(call, f"inside {b.open[1]}", "call it outside bgn/end")
        klass = CLASS_OF[kind]
        if len(b) and b.klass != klass:
            self._flush(win)
        b.klass = klass
        b.xforms.append(Transform(np.eye(4), np.asarray(projection, np.float64)))
        b.xf_dirty = False
        rec = b.record_row(win.st)          # the current colour, with that transform
        v0 = b.nverts
        pts = np.ascontiguousarray(pts, np.float64).reshape(-1, 4)
        b.add_vertices(pts, np.repeat(rec[None], len(pts), 0))
        b.add_block(np.array([[kind, v0, len(pts), 0]], np.int64), call)
        b.xf_dirty = True             # the next vertices use the matrices in force again
        b.dirty = True

    def point(self, win, p, call):
        """pnt(3G): one point.  Consecutive pnt calls extend one point
        primitive (the same points, one primitive record)."""
        b = win.batch
        if b.open is not None:
            fail(call, f"not allowed inside {b.open[1]}", f"call end{b.open[1][3:]} first")
        if b.klass != POINTS:
            if len(b):
                self._flush(win)
            b.klass = POINTS
        if b.dirty:
            b.record_attributes(win.st)
        n = b.vbase + (len(b.pos) >> 2)
        pr = b.prims
        if pr and pr[-4] == POINT and pr[-3] + pr[-2] == n:
            pr[-2] += 1
        else:
            pr += (POINT, n, 1, False)
            b.calls.add(call)
        b.pos += p
        if self.display_hook is not None:
            self.display_hook(win)

    def move(self, win, p):
        win.st.gpos = p

    def draw(self, win, p, call):
        st = win.st
        start = st.gpos if st.gpos is not None else p
        self.polyline_vertices(win, LINE, (start, p), call)
        st.gpos = p

    # ------------------------------------------------------------------
    # current attributes: they do not flush; each is an event of the batch
    # (geometry/batch.py), as irisgl's per-vertex calls append it
    def set_colour(self, win, rgba):
        st = win.st
        st.colour = rgba = tuple(rgba)
        st.last_was_normal = False
        if st.material:
            st.colour_since_bind = True
        self._event(win, (EV_COLOUR,) + rgba)

    def set_normal(self, win, n):
        st = win.st
        st.normal = n = tuple(n)
        st.last_was_normal = True
        self._event(win, (EV_NORMAL,) + n + (0.0,))

    def set_texcoord(self, win, strq):
        win.st.texcoord = strq = tuple(strq)
        self._event(win, (EV_TEX,) + strq)

    def _event(self, win, kind_values):
        """Append an attribute event the state already holds (synced)."""
        b = win.batch
        b.ev += (len(b.pos),) + kind_values
        b.synced = len(b.ev)

    def attributes_changed(self, win):
        """Something a vertex carries changed other than its normal, colour
        or texture coordinate (lmbind, lmcolor, drawmode, popattributes): the
        following vertices take a new record."""
        b = win.batch
        b.dirty = True
        if b.open is not None:
            b.record_attributes(win.st)

    def matrices_changed(self, win):
        b = win.batch
        b.dirty = True
        b.xf_dirty = True

    # ------------------------------------------------------------------
    # lighting (docs/semantics.md §9)
    def lmdef(self, deftype, index, props):
        """Store a definition; ``props`` None resets it to the defaults.
        Redefining a bound definition takes effect immediately, so every
        window's pending primitives are drawn with the old one first; a bound
        light's POSITION is re-transformed by the ModelView current now."""
        for win in self.windows.values():
            self._flush(win)
        table = self.defs[deftype]
        new = dict(table.get(index) or lighting.defaults(deftype))
        if props is None:
            new = lighting.defaults(deftype)
        else:
            new.update(props)
        table[index] = new
        if deftype == lighting.DEFLIGHT:
            for win in self.windows.values():
                for bind in win.st.lights.values():
                    if bind.index == index:
                        bind.place(new, win.st.matrices.modelview_matrix())

    def lmbind(self, win, target, index):
        st = win.st
        if target in (lighting.MATERIAL, lighting.BACKMATERIAL):
            idx = index if index in self.defs[lighting.DEFMATERIAL] else 0
            bound = st.material if target == lighting.MATERIAL else st.backmaterial
            if idx == bound and not st.colour_since_bind and not st.mat_override:
                return      # binding the bound material again changes nothing: no flush
            if target == lighting.MATERIAL and (idx == 0) != (bound == 0) and \
                    st.lmodel != 0 and \
                    st.lmodel in self.defs[lighting.DEFLMODEL]:
                # lighting turns on or off: the batch so far is drawn first.
                # Another material (or none without a light model) needs no
                # flush: each vertex record carries its material (batch.mats)
                self.state_change(win)
            if target == lighting.MATERIAL:
                st.material = idx
            else:
                st.backmaterial = idx
            st.colour_since_bind = False
            st.mat_override = {}       # binding a material discards lmcolor changes
            self.attributes_changed(win)
        elif target == lighting.LMODEL:
            self.state_change(win)
            st.lmodel = index if index in self.defs[lighting.DEFLMODEL] else 0
        else:
            self.state_change(win)
            slot = target - lighting.LIGHT0
            table = self.defs[lighting.DEFLIGHT]
            if index == 0 or index not in table:
                st.lights.pop(slot, None)
                return
            for other, bind in list(st.lights.items()):
                if bind.index == index and other != slot:
                    del st.lights[other]       # one light target per definition
            st.lights[slot] = lighting.LightBinding(index, table[index],
                                                    st.matrices.modelview_matrix())

    # ------------------------------------------------------------------
    # clears (docs/semantics.md §3, §5)
    def clear_rect(self, win):
        st = win.st
        return _intersect(st.viewport, st.scrmask, (0, win.width - 1, 0, win.height - 1))

    def clear(self, win):
        """clear(3G): current colour into viewport ∩ scrmask of every enabled
        colour buffer, honouring the pattern and the colour writemask only."""
        self._flush(win)
        r = self.clear_rect(win)
        if self._picking(win):
            return self.picking.clear_hit(r)
        if r is None:
            return
        st = win.st
        if not all(-1e300 < c < 1e300 for c in st.colour):
            warn("clear", "the current colour is not finite (NaN or infinity); "
                 "nothing is cleared")
            return
        word = np.uint32(self.colour_word(st, st.colour))
        mask = np.uint32(st.cmask & layers.index_bits(win))
        pat = self.patterns.get(st.pattern) if st.pattern else None
        rows = None if pat is None else variants.pattern_rows(pat, win.origin[0], win.fb.width)
        pipeline.submit(_kernel_calls, win.fb, [
            (fill, (t, r[0], r[1], r[2], r[3], word, mask)) if pat is None else
            (fill_pattern, (t, r[0], r[1], r[2], r[3], word, mask, rows, pat[0], win.origin[1]))
            for t in self._targets(win)])
        if self.trace_hook is not None:
            self.trace_hook(self, win, "clear")

    def sclear(self, win, sval):
        """sclear(3G): stencil := sval within the planes, under swritemask,
        over viewport ∩ scrmask; the pattern does not apply."""
        self._flush(win)
        r = self.clear_rect(win)
        fb = win.fb
        if r is None or not fb.has("stencil") or self._picking(win):
            return
        smax = (1 << fb.stencil_planes) - 1
        pipeline.submit(_kernel_calls, fb, [(fill, (fb.queued("stencil"), r[0], r[1], r[2], r[3],
                                                  np.uint8(sval & smax),
                                                  np.uint8(win.st.swritemask & smax)))])
        if self.trace_hook is not None:
            self.trace_hook(self, win, "sclear", sval & smax)

    def zclear(self, win):
        self._flush(win)
        r = self.clear_rect(win)
        if r is None or self._picking(win):
            return
        m = win.st.zwritemask & 0xFFFFFF
        pipeline.submit(_kernel_calls, win.fb,
                        [(fill_z, (win.fb.ensure_z(queued=True), r[0], r[1], r[2], r[3], ZMAX, m))],
                        r if m == 0xFFFFFF else None, ZMAX if m else None)
        if self.trace_hook is not None:
            self.trace_hook(self, win, "zclear")

    def czclear(self, win, cval, zval):
        self._flush(win)
        r = self.clear_rect(win)
        if self._picking(win):
            return self.picking.clear_hit(r)
        if r is None:
            return
        word = cval & layers.index_bits(win)
        z = min(max(int(zval), ZMIN), ZMAX)
        pipeline.submit(_kernel_calls, win.fb,
                        [(fill, (t, r[0], r[1], r[2], r[3], np.uint32(word), np.uint32(0xFFFFFFFF)))
                         for t in self._targets(win)] +
                        [(fill_z, (win.fb.ensure_z(queued=True), r[0], r[1], r[2], r[3], z,
                                   0xFFFFFF))], r, z)
        if self.trace_hook is not None:
            self.trace_hook(self, win, "czclear")

    @staticmethod
    def colour_word(st, colour):
        if not st.rgb:
            return int(colour[0]) & 0xFFF
        r, g, b, a = (int(min(max(c, 0.0), 255.0) + 0.5) for c in colour)
        return (a << 24) | (b << 16) | (g << 8) | r

    # ------------------------------------------------------------------
    # accumulation buffer (docs/semantics.md §10)
    def acbuf(self, win, op, value):
        """acbuf(3G), queued on the raster thread like a pass (pipeline.py):
        the accumulation reads the bank readsource names as the passes
        queued before it left it."""
        from .framebuffer import accum as A
        self._flush(win)
        r = self.clear_rect(win)
        if r is None or self._picking(win):
            return
        st, fb = win.st, win.fb
        acc = fb.queued("accum")
        if op == A.AC_RETURN:
            v = min(max(value, 0.0), 1.0)
            mask = st.cmask & (0xFFFFFFFF if st.rgb else 0xFFF)
            pipeline.submit(_kernel_calls, fb, [
                (A.give_back, (acc, t, v, mask, not st.rgb, r[0], r[1], r[2], r[3]))
                for t in self._targets(win)])
            if self.trace_hook is not None:
                self.trace_hook(self, win, "acbuf", op, v)
            return
        if op in (A.AC_ACCUMULATE, A.AC_CLEAR_ACCUMULATE):
            value = min(max(value, -256.0), 256.0)
            src = self.read_bank(win, win.readsource, queued=True)
        else:
            src = _DUMMY_C
        pipeline.submit(_kernel_calls, fb, [
            (A.accumulate, (acc, src, op, float(value), r[0], r[1], r[2], r[3]))])
        if self.trace_hook is not None:
            self.trace_hook(self, win, "acbuf", op, float(value))

    # ------------------------------------------------------------------
    # reading pixels (docs/semantics.md §11)
    def read_bank(self, win, source, queued=False):
        """The bank readsource(3G) ``source`` reads; ``queued``: for work
        queued on the raster thread, without waiting (Framebuffer.queued)."""
        fb = win.fb
        if source == SRC_AUTO and win.st.drawmode in layers.LAYERS:
            source = {v: k for k, v in _SRC_LAYER.items()}[win.st.drawmode]
        if source in _SRC_LAYER:
            # readsource(SRC_PUP/SRC_OVER/SRC_UNDER): a framebuffer without
            # planes reads 0
            bank = fb.layer(_SRC_LAYER[source], queued=queued)
            return bank if bank is not None else np.zeros((win.height, win.width), np.uint32)
        if source == SRC_ZBUFFER:
            return fb.ensure_z(queued=queued)
        back = fb.queued("back") if queued else fb.back
        if source == SRC_BACK:
            return back
        if source == SRC_FRONT or not win.st.double:
            return fb.queued("front") if queued else fb.front
        return back

    def lrectread(self, win, x1, y1, x2, y2, source):
        """The (h, w) block with row 0 at y1.  Pixels outside the window
        read what the screen holds there (_beneath)."""
        self._flush(win)
        bank = self.read_bank(win, source)
        h, w = y2 - y1 + 1, x2 - x1 + 1
        out = np.zeros((h, w), bank.dtype)
        xa, xb = max(x1, 0), min(x2, win.width - 1)
        ya, yb = max(y1, 0), min(y2, win.height - 1)
        if xa <= xb and ya <= yb:
            out[ya - y1:yb - y1 + 1, xa - x1:xb - x1 + 1] = bank[ya:yb + 1, xa:xb + 1]
        if (xa, xb, ya, yb) != (x1, x2, y1, y2) and len(self.windows) > 1 \
                and source != SRC_ZBUFFER:
            self._beneath(win, out, x1, y1, (xa, xb, ya, yb), source)
        return out

    def _beneath(self, win, out, x1, y1, own, source):
        """Fill the pixels of ``out`` (row 0 at y1, window coordinates of
        ``win``) that lie outside ``win`` from the front-most other window
        covering them, its bank of the same kind; 0 where no window is.
        The VGX has one framebuffer, so a read outside the window (after
        screenspace(3G), which "allows pixels ... outside a program's
        graphics window to be read"; a screen magnifier's rectcopy) sees the
        windows there.  [S] The other window's bits are read as they are,
        whatever its mode; the z-buffer is not read beyond the window."""
        h, w = out.shape
        filled = np.zeros((h, w), bool)
        xa, xb, ya, yb = own
        if xa <= xb and ya <= yb:
            filled[ya - y1:yb - y1 + 1, xa - x1:xb - x1 + 1] = True
        if source == SRC_AUTO and win.st.drawmode not in layers.LAYERS:
            source = SRC_BACK if win.st.double else SRC_FRONT
        for gid in reversed(self.stacking):
            o = self.windows[gid]
            if o is win:
                continue
            ax, ay = o.origin[0] - win.origin[0], o.origin[1] - win.origin[1]
            xa, xb = max(x1, ax), min(x1 + w - 1, ax + o.width - 1)
            ya, yb = max(y1, ay), min(y1 + h - 1, ay + o.height - 1)
            if xa > xb or ya > yb:
                continue
            self._flush(o)
            src = self.read_bank(o, source)[ya - ay:yb - ay + 1, xa - ax:xb - ax + 1]
            mark = filled[ya - y1:yb - y1 + 1, xa - x1:xb - x1 + 1]
            dst = out[ya - y1:yb - y1 + 1, xa - x1:xb - x1 + 1]
            dst[~mark] = src[~mark].astype(out.dtype)
            mark[:] = True

    def write_pixels(self, win, x1, y1, words, zoom):
        """lrectwrite/rectwrite: words (h, w), row 0 at y1 (docs/semantics.md §11)."""
        from .scan.spans import pixel_kernel
        self._finish(win)
        if self._picking(win) or self.clear_rect(win) is None:
            return      # picking/selecting, or viewport ∩ scrmask ∩ window is empty
        key, planes, ip = self._raster_setup(win, None, filled=False)
        key = key._replace(ztest=False, zwrite=False, stencil=False, pattern=False,
                           gouraud=False, twoside=False)
        if not key.color:
            return
        words = np.ascontiguousarray(words)
        scan.run(pixel_kernel, "pixel", key, planes, ip,
                 lambda planes, ip: (words, x1, y1, float(zoom[0]), float(zoom[1]), planes, ip))

    def char_pixels(self, win, xs, ys, z):
        """charstr(3G): glyph pixels (window x, y int arrays) at one window z,
        in the current colour, through the per-fragment operations of a point
        (writemasks, z test and write, stencil, blend); clipped to scrmask ∩
        window, never to the viewport; patterns do not apply."""
        from .raster import fragment as F
        self._finish(win)
        st = win.st
        sc = _intersect(st.scrmask, (0, win.width - 1, 0, win.height - 1))
        if sc is None or not len(xs) or self._picking(win):
            return
        key, planes, ip = self._raster_setup(win, None, filled=False)
        if key.gouraud and not key.color:
            key = key._replace(gouraud=False)   # the key a point batch uses
        ip[F.P_SX0], ip[F.P_SX1], ip[F.P_SY0], ip[F.P_SY1] = sc
        pts = np.empty((len(xs), 7))
        pts[:, 0] = xs
        pts[:, 1] = ys
        pts[:, 2] = z
        pts[:, 3:7] = st.colour
        if st.scrbox_mode == 1:               # scrbox(3G) tracks characters too
            scrbox.track_xy(st, pts[:, :2], sc)
        scan.run_points(key, pts, planes, ip)

    # ------------------------------------------------------------------
    # display
    def image(self, win=None):
        """What the screen shows of a window: (h, w, 3) uint8, top row first."""
        win = win or self.current
        self._flush(win)
        st = win.st
        img = display.scanout_window(win.fb, layers.normal(st, "rgb"), st.multimap,
                                     self.colormap, self.maps)
        if self.gamma is not None:           # gammaramp(3G): applied at scan-out
            img = np.stack([self.gamma[img[..., c], c] for c in range(3)], axis=-1)
        return img


def _raster_pass(fb, work, key, planes, ip, cull, closed_lines, tex, zfar, setup):
    """The Raster Subsystem's part of a batch (queued by VGX._flush on the
    raster thread, pipeline.py; its triangle setup, scan.setup_batch, made
    by the thread that queued it): the z maxima when the pass may skip spans
    against them (zfar: VGX._z_maxima_bound), scan conversion, and the
    maxima marked stale when the pass changed a stored z (the walker
    reports it: a redraw with ZF_LEQUAL or ZF_EQUAL of the surfaces already
    in the z bank keeps them), over the triangles' box within the scissor,
    or wrote z as lines or points (anywhere)."""
    zmaxima = None
    if zfar is not None and not (fb.zmax_uniform is not None and fb.zmax_uniform >= zfar):
        zmaxima = fb.z_maxima()     # (uniform at the far end: no span can fail)
    ip[fragment.P_ZMAX] = zmaxima is not None
    scan.scan_batch(work, key, planes, ip, cull, closed_lines, tex, zmaxima, setup)
    if key.zwrite and (work.klass != FILLED or ip[fragment.P_ZCHANGED]):
        b = work.box if work.klass == FILLED else None
        fb.z_written(box=None if b is None else (
            max(b[0], int(ip[fragment.P_SX0])), min(b[1], int(ip[fragment.P_SX1])),
            max(b[2], int(ip[fragment.P_SY0])), min(b[3], int(ip[fragment.P_SY1]))))


def _small_pass(work):
    """Whether a pass is small enough to draw at once rather than hand to
    the raster thread (config.INLINE_TRIANGLES, INLINE_PIXELS): filled,
    with few triangles over a small box."""
    b = work.box
    if work.klass != FILLED or b is None or work.tris is None or \
            len(work.tris) > config.INLINE_TRIANGLES:
        return False
    return (b[1] - b[0] + 1) * (b[3] - b[2] + 1) <= config.INLINE_PIXELS


def _kernel_calls(fb, calls, zrect=None, zvalue=None):
    """Kernel calls queued like a pass (pipeline.py: the fills of a clear,
    acbuf's): each ``(kernel, args)``, then, for a z clear, the z maxima set
    or marked stale (Framebuffer.z_written)."""
    for kernel, args in calls:
        kernel(*args)
    if zvalue is not None:
        fb.z_written(zrect, zvalue)


def _intersect(*rects):
    """Intersection of inclusive (x0, x1, y0, y1) rectangles, or None."""
    x0 = max(r[0] for r in rects)
    x1 = min(r[1] for r in rects)
    y0 = max(r[2] for r in rects)
    y1 = min(r[3] for r in rects)
    if x0 > x1 or y0 > y1:
        return None
    return (x0, x1, y0, y1)
