"""GLError and the strict/lenient switch (docs/porting.md §4, docs/semantics.md §14)."""
import os
import sys
import warnings

import numpy as np

from . import config


class GLError(Exception):
    """A call used wrongly.  The message starts with the call's name and says
    what was wrong and what is allowed; the call changed no state."""


class VGXWarning(UserWarning):
    """Something was dropped or clamped (non-finite vertex, undefined object)."""


_mode = {"lenient": config.ERROR_MODE == "lenient"}


def set_error_mode(mode):
    """'strict' (default: raise GLError) or 'lenient' (print ``GL: ...`` on
    stderr and ignore the call, as the original library did)."""
    if mode not in ("strict", "lenient"):
        raise ValueError("error mode is 'strict' or 'lenient'")
    _mode["lenient"] = mode == "lenient"


def error_mode():
    return "lenient" if _mode["lenient"] else "strict"


def is_lenient():
    return _mode["lenient"]


def report(err):
    """Lenient mode: what the original libgl did, a diagnostic on stderr."""
    print(f"GL: {err}", file=sys.stderr)


def fail(call, what, allowed=None):
    """Raise GLError("<call>: <what>; <allowed>")."""
    msg = f"{call}: {what}"
    if allowed:
        msg += f"; {allowed}"
    raise GLError(msg)


#: the emulator's own source folders: a warning is placed at the first frame outside them
_OURS = tuple(os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), d, "")
              for d in ("vgx_emulator", "irisgl"))


def warn(call, what):
    """A VGXWarning "<call>: <what>", shown at the program's line that made
    the call (the first caller outside vgx_emulator and irisgl, however deep
    the call wrapper, an object's replay or a flush put it), so Python's
    default filter shows it once per line of the program."""
    level, f = 2, sys._getframe(1)
    while f is not None and f.f_code.co_filename.startswith(_OURS):
        f, level = f.f_back, level + 1
    warnings.warn(f"{call}: {what}", VGXWarning, stacklevel=level)


try:        # numpy 2: the floating-point error state is a context variable
    from numpy._core._ufunc_config import _extobj_contextvar as _FP_STATE, _make_extobj
    _FP_IGNORE = _make_extobj(all="ignore")

    def fp_quiet():
        """numpy's floating-point warnings off, as ``np.errstate(all="ignore")``
        is, until ``fp_restore(token)``: the form the call wrapper and the
        matrix products use, since entering np.errstate costs 1.5-2 us and
        setting numpy's context variable 0.1 us.  (The captured state keeps
        numpy's default buffer size and error callback.)"""
        return _FP_STATE.set(_FP_IGNORE)

    fp_restore = _FP_STATE.reset
except ImportError:         # another numpy: np.errstate itself
    def fp_quiet():
        """numpy's floating-point warnings off until ``fp_restore(token)``."""
        token = np.errstate(all="ignore")
        token.__enter__()
        return token

    def fp_restore(token):
        token.__exit__(None, None, None)
