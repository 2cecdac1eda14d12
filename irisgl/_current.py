"""The one module-level state of irisgl: the machine the calls drive, and the
wrapper every call goes through (strict/lenient errors, bgn/end rule)."""
import functools
import inspect
import math

import numpy as np

from vgx_emulator.errors import GLError, fail, fp_quiet, fp_restore, is_lenient, report, warn
from vgx_emulator.machine import VGX

machine = VGX()

#: calls allowed between bgn* and end* (bgnpolygon(3G)); the rest raise there.
_INSIDE_OK = set()

#: every IRIS GL call irisgl defines: name -> (status, why).  ``status`` is
#: IMPLEMENTED (behaves per its man page), HEADLESS (keeps its state and
#: answers its queries without a display; takes effect in a real window) or
#: NOT_EMULATED (raises GLError saying why).  docs/api.md is generated from it.
IMPLEMENTED, HEADLESS, NOT_EMULATED = "implemented", "headless", "not emulated"
#: the default of a parameter that must be given (the explicit per-vertex
#: calls: ``def v3f(v=NOT_GIVEN, *more)``): a missing or extra argument
#: then reaches the checked path, which reports the arity as a GLError
NOT_GIVEN = object()

API = {}

#: calls run at once even while an object is open (never recorded):
#: queries, window and configuration calls, definitions that objects(3G)
#: says are immediate-only.  Calls join it with ``glcall(immediate=True)``.
IMMEDIATE = set()


def glcall(fn=None, *, inside=False, immediate=False, status=IMPLEMENTED, why=""):
    """Wrap an IRIS GL call: in lenient mode a GLError is printed as
    ``GL: <message>`` and the call ignored; calls not allowed inside bgn/end
    raise there; numpy floating-point warnings are off while it runs.
    ``immediate`` calls are never recorded into an object; ``status``/``why``
    classify the call for docs/api.md (see ``API``)."""
    def wrap(f):
        name = f.__name__
        API[name] = (status, why)
        if immediate or name.startswith(("get", "is")):    # queries: never recorded
            IMMEDIATE.add(name)
        if inside:
            _INSIDE_OK.add(name)

        @functools.wraps(f)
        def call(*args):
            try:
                if machine.recording is not None and name not in IMMEDIATE:
                    return _record(name, call, args)
                if not inside:
                    w = machine.current
                    if w is not None and w.batch.open is not None:
                        fail(name, f"not allowed inside bgn{_kind(w)}",
                             "only v*, n*, c*, color, cpack, RGBcolor, t*, lmdef, "
                             "lmbind, lmcolor and swaptmesh may appear there")
                # non-finite results are the machine's to report (a VGXWarning
                # naming the call); numpy's own warnings never reach the user
                token = fp_quiet()
                try:
                    if machine.call_hook is not None:    # trace.py: names the passes' calls
                        return machine.call_hook(name, f, args)
                    return f(*args)
                finally:
                    fp_restore(token)
            except GLError as e:
                if is_lenient():
                    report(e)
                    return None
                raise
            except TypeError:
                e = _arity_error(name, f, args)
                if e is None:
                    raise
                if is_lenient():
                    report(e)
                    return None
                raise e from None
        call.__wrapped__ = f
        return call
    return wrap(fn) if fn is not None else wrap


def raise_or_report(e):
    """A GLError from a call's fast path: raised, or printed in lenient mode."""
    if is_lenient():
        report(e)
        return None
    raise e


def _arity_error(name, f, args):
    """The GLError for a call given too few or too many arguments (a K&R
    program's ``qenter(REDRAW)``), or None when ``args`` fit ``f`` and the
    TypeError came from inside it."""
    try:
        sig = inspect.signature(f)
        sig.bind(*args)
        return None
    except ValueError:
        return None
    except TypeError:
        pass
    params = [p.name for p in sig.parameters.values()
              if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD, p.VAR_POSITIONAL)]
    n = len(args)
    try:
        fail(name, f"{n} argument{'s' if n != 1 else ''} given",
             f"the call is {name}({', '.join(params)})")
    except GLError as e:
        return e


def not_emulated(name, why):
    """An IRIS GL call the emulated VGX does not provide: it exists, and
    calling it raises GLError naming the call and saying why (porting
    conventions 5: never a NameError, never a silent no-op)."""
    def call(*args, **kwargs):
        fail(name, f"not emulated: {why}")
    call.__name__ = call.__qualname__ = name
    call.__doc__ = f"{name}(3G): not emulated ({why})."
    return glcall(call, immediate=True, status=NOT_EMULATED, why=why)


def _record(name, fn, args):
    from .objects import record
    record(name, fn, args)


def _kind(w):
    return w.batch.open[1][3:]


def win(call):
    """The current window (GLError before winopen)."""
    w = machine.current
    if w is None:
        fail(call, "no window is open", "call winopen first")
    return w


# -- validators ------------------------------------------------------------
def vec(call, v, n, what="array"):
    """A C array argument of n numbers as a tuple of floats.  A longer array
    is read from its first n elements, as C reads a ``float[4]`` row passed
    where ``float[3]`` is expected; fewer than n is an error."""
    try:
        if len(v) < n:
            fail(call, f"{what} has {len(v)} elements", f"it takes {n}")
        if isinstance(v, str):
            raise TypeError
        return tuple(float(v[i]) for i in range(n))
    except TypeError:
        fail(call, f"{what} is not a sequence of {n} numbers", f"pass {n} numbers")
    except ValueError:
        fail(call, f"{what} holds something that is not a number", "numbers only")


def num(call, x, what="argument"):
    try:
        return float(x)
    except (TypeError, ValueError):
        fail(call, f"{what} {x!r} is not a number", "pass a number")


def integer(call, x, what="argument"):
    """An integer argument.  A finite float is truncated toward zero, as a C
    compiler converts it for a ``short``/``long`` parameter (a port of
    ``XMAXSCREEN*3/4`` or ``circfs(x, y, r)`` with ``float r``); NaN and
    infinity have no integer value and are refused."""
    if isinstance(x, int):
        return int(x)                     # exact, however wide (docs/semantics.md §1 masks)
    if isinstance(x, np.integer):
        return int(x)
    if isinstance(x, str):
        fail(call, f"{what} {x!r} is not an integer", "pass an integer")
    try:
        f = float(x)
    except (TypeError, ValueError):
        fail(call, f"{what} {x!r} is not an integer", "pass an integer")
    if not math.isfinite(f):
        fail(call, f"{what} {x!r} is not an integer", "pass a finite integer")
    return int(f)


def angle(call, x, what="angle"):
    """An ``Angle`` argument (a C short, tenths of degrees): a float is
    truncated toward zero and the value reduced to 16 bits, two's complement,
    as C converts it for the parameter (``rotate(900.7, 'z')`` turns 90
    degrees; ``rotate(40000, 'z')`` turns -25536 tenths).  [S] NaN and
    infinity have no C value: they pass as they are, so the matrix they make
    drops the primitives drawn through it with a VGXWarning."""
    f = num(call, x, what)
    if not math.isfinite(f):
        return f
    return signed(int(x) if isinstance(x, (int, np.integer)) else int(f), 16)


def signed(v, bits):
    """The integer v reduced to ``bits`` bits, two's complement: what C gives
    when it converts v to a signed short (16) or long (32) parameter."""
    half = 1 << (bits - 1)
    return (v + half) % (half << 1) - half


def token(call, x, allowed, what="token"):
    """One of the named constants in ``allowed`` (a {value: name} dict)."""
    v = integer(call, x, what)
    if v not in allowed:
        fail(call, f"unknown {what} {x!r}",
             "allowed: " + ", ".join(allowed[k] for k in sorted(allowed)))
    return v


def boolean(call, x):
    return bool(integer(call, x, "Boolean"))


def words(a, mask):
    """An integer array reduced to the bits of ``mask``, as C converts a
    value to an ``unsigned long``/``short`` array element (docs/semantics.md §1);
    an object array of Python integers of any size (2**70) included.
    Raises TypeError/ValueError for elements that are not integers."""
    if a.dtype == object:
        return np.array([int(v) & mask for v in a.reshape(-1)], np.int64).reshape(a.shape)
    return a.astype(np.int64) & mask


def out_array(call, a, n, what, hint=None):
    """An array C fills, ported as an optional trailing argument (porting.md
    §3): None (the call returns a new array), or a writable numeric numpy
    array or a list of at least ``n`` elements (a longer C buffer is filled
    in its first n); anything else is a GLError naming the call."""
    if a is None:
        return
    if isinstance(a, np.ndarray):
        if not a.flags.writeable:
            fail(call, f"{what} is a read-only array", "pass a writable array, or nothing")
        if a.dtype.kind not in "iuf":
            fail(call, f"{what} has dtype {a.dtype}", "pass a numeric array, or nothing")
        size = a.size
    elif isinstance(a, list):
        size = len(a)
    else:
        fail(call, f"{what} {a!r} is not an array", "pass a numpy array or a list, or nothing")
    if size < n:
        fail(call, f"{what} has {size} elements", hint or f"pass at least {n}, or nothing")


def fill(a, values):
    """Store ``values`` (an array or a list) in the first elements of a
    checked out_array, in its own element order whatever its layout (C
    fills the caller's buffer); a list gets Python numbers."""
    values = np.asarray(values)
    if isinstance(a, np.ndarray):
        a.flat[:values.size] = values
    else:
        a[:values.size] = values.tolist()


def ulong(x):
    """unsigned long arguments: reduced modulo 2**32 (docs/semantics.md §1)."""
    return int(x) & 0xFFFFFFFF


def screen_z(call, v, what):
    """A window z argument, a C ``long`` (czclear, lsetdepth, lshaderange,
    lRGBrange): reduced to a 32-bit signed value as C converts it, so
    ``0xff800000`` is -0x800000, GD_ZMIN (docs/semantics.md §1), then
    clamped to the VGX range GD_ZMIN..GD_ZMAX with a VGXWarning (a program
    written for an unsigned z range passes 0xC00000 and would otherwise see
    its depth reversed without a word)."""
    from vgx_emulator.framebuffer import ZMAX, ZMIN
    z = signed(integer(call, v, what), 32)
    if not ZMIN <= z <= ZMAX:
        warn(call, f"{what} {z} is outside the VGX's GD_ZMIN..GD_ZMAX ({ZMIN}..{ZMAX}): "
             "clamped")
    return min(max(z, ZMIN), ZMAX)


def axis(call, a):
    if not isinstance(a, str) or a.lower() not in ("x", "y", "z"):
        fail(call, f"axis {a!r} is not 'x', 'y' or 'z'", "pass one of 'x', 'y', 'z'")
    return a.lower()
