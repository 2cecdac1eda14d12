"""Every tunable of the emulated machine, in one table.

Kernels read these only through :mod:`vgx_emulator.jit` and the stage modules;
no other module hard-codes a compiler flag or a fixed-point width.
"""
import os

#: Fractional bits of window coordinates handed to the rasterizer (docs/semantics.md §1
#: asks for at least 4).  8 bits keep sub-pixel vertices close to their float
#: position while edge functions stay far inside int64 (see scan/fixed.py).
SUBPIXEL_BITS = 8

#: Guard band: primitives are clipped against x/y only where they leave a
#: window-coordinate square of this half-size (pixels) around the viewport
#: centre.  Inside it the rasterizer's scissor does the work; the bound keeps
#: fixed-point edge functions exact (|coord| * 2**SUBPIXEL_BITS < 2**23).
GUARD_BAND_PIXELS = 8192

#: Rows per band of the parallel triangle walker.  Each band is owned by one
#: thread, so triangles are drawn in submission order within every pixel and
#: the picture does not depend on the number of threads.
BAND_ROWS = 32

#: Fractional bits of the z DDA along a triangle span (scan/triangles.py):
#: with |window z| < 2**30 (viewport.Z_LIMIT) the planes stay inside int64
#: over any box of the guard band, and the error of a pixel's z is below
#: 2**-16 of a z unit.
ZFRAC = 30

#: Fractional bits of the Gouraud colour DDAs: 16 keeps 0xFFF << 16 inside
#: int32, so that colours step in 32-bit vector lanes (fill-z 50 -> 43 ms at
#: 1280x1024 against 24 bits).
CFRAC = 16

#: The bound of a triangle's fixed-point plane (scan/triangles.py,
#: plane_fixed): |start| + |step x| * width + |step y| * height below 2**62
#: keeps every value of the plane in its box inside int64; a sliver beyond
#: it evaluates each span start exactly instead.
PLANE_LIMIT = float(1 << 62)

#: Pixels per vector of the span loop (8 int32 lanes of AVX2): spans shorter
#: than PAD_SPAN are padded to a multiple of it, and to at least two vectors
#: (LLVM runs the vectorised loop only from 16 iterations, its threshold for
#: a loop with run-time checks; Heidmann's colour passes 34.6 -> 31.1 ms on
#: one thread).
VEC = 8

#: Spans shorter than this many pixels run over whole vectors in the
#: triangle walker (scan/triangles.py): the loop starts early or ends late
#: inside the row, and the extra pixels fail like a 0 pattern bit.  A short
#: span's scalar remainder otherwise costs as much as its vector part
#: (Heidmann's lit passes, spans of about 25 pixels: 6.8 -> 5.7 ms on one
#: thread).  0 turns it off; the pixels are the same either way.
PAD_SPAN = 64

#: ... but spans shorter than this many pixels run as they are: the scalar
#: loop over a few pixels costs less than two padded vectors (the walker
#: of a 40k-triangle tmesh of 7.7-pixel triangles, spans of 1-8 pixels,
#: one thread: 4.7 -> 3.6 ms; 4, 12 and 16 measured alike, the Heidmann and
#: spheres frames unchanged).
PAD_MIN = 8

#: Batches whose triangle boxes cover fewer pixels than this run on one
#: thread (scan.triangles.run_bands): below it waking the other threads
#: costs more than it saves, and on a busy machine much more.
PARALLEL_MIN_PIXELS = 1 << 18

#: Shares of the band list per thread (scan.triangles.run_bands): a thread
#: takes the next share when it finishes one, so one whose bands hold less
#: work takes more of them (shadow map frame 9.7 -> 9.3 ms against one
#: contiguous share per thread).
SHARES_PER_THREAD = 4

#: triangle setup (scan.triangles.setup_triangles) of a batch of at least
#: twice this many triangles is cut into shares of at least this many,
#: set up on the walker's threads while the raster thread has nothing queued
SETUP_SHARE = 4096

#: numba flags.  fastmath stays off: the NaN/inf guards and exact integer
#: edge tests must not be compiled away (docs/architecture.md, Kernels).
JIT_OPTIONS = dict(nogil=True, cache=True, fastmath=False,
                   boundscheck=False)

#: work in shares on Python threads (the triangle walker's bands, setup,
#: lighting, the accumulation buffer's rows: pipeline.in_shares; no kernel
#: uses numba's parallel lowering); NUMBA_NUM_THREADS (or
#: numba.set_num_threads) chooses how many threads; VGX_PARALLEL=0 runs
#: everything on one.
PARALLEL = os.environ.get("VGX_PARALLEL", "1") != "0"

#: the raster subsystem on its own thread, pipelined with the geometry
#: (pipeline.py): on with PARALLEL on a machine of more than one core;
#: VGX_PIPELINE=0 runs scan conversion on the calling thread.
PIPELINE = PARALLEL and (os.cpu_count() or 1) > 1 and \
    os.environ.get("VGX_PIPELINE", "1") != "0"

#: Virtual screen of the VGX (docs/porting.md §5).
SCREEN_WIDTH = 1280
SCREEN_HEIGHT = 1024

#: Default size of a window opened without prefsize/prefposition.
DEFAULT_WINDOW_SIZE = (640, 480)

#: Event queue length (qdevice(3G): the queue holds 101 entries).
QUEUE_LENGTH = 101

#: The largest polygon (bgnpolygon(3G), GD_NVERTEX_POLY).
MAX_POLYGON_VERTICES = 256

#: a pass of at most this many triangles over a box of at most this many
#: pixels is drawn at once on the program's thread when the raster thread
#: is idle (pipeline.submit ``now``): waking that thread and trading the
#: GIL with it cost more than such a pass (a one-triangle lit pass at
#: 640x480: 424-443 -> 300-320 us a flush, docs/performance.md)
INLINE_TRIANGLES = 256
INLINE_PIXELS = 1 << 14

#: An immediate-mode batch is flushed at the end* that brings it to this
#: many vertices: the raster thread then draws it while the program sends
#: the next ones, as the VGX's Geometry Pipeline drew while the host ran
#: (a 40k-vertex immediate tmesh at 640x480: 31 -> 26 ms a frame; 8192 and
#: 16384 measured alike, 32768 lost half the gain).  A flush changes no pixel:
#: a batch holds only primitives drawn under the current state.
FLUSH_VERTICES = 16384

#: Error mode: "strict" raises GLError, "lenient" prints "GL: ..." on stderr
#: and ignores the call (docs/semantics.md §14).  VGX_ERRORS=lenient selects it.
ERROR_MODE = os.environ.get("VGX_ERRORS", "strict")

#: passes of a raster state drawn on its family's general variant before a
#: second process is asked to compile the state's own (specialise.py): a
#: state used once (a figure, a title) is not worth the compile, one drawn
#: every frame is
SPECIALISE_AFTER = 3
