"""irisgl: the IRIS GL calls, with their C names, argument order and values.

``from irisgl import *`` gives every implemented call, every constant of
gl.h / device.h / get.h and the C types (porting conventions 1).  The calls
validate their arguments, convert units and drive the emulated VGX in
:mod:`vgx_emulator`; anything that is not IRIS GL (PNG output, error mode,
the runner) lives there.
"""
from vgx_emulator.errors import GLError

from . import accum as _accum
from . import colormap as _colormap
from . import constants as _constants
from . import curves as _curves
from . import depth as _depth
from . import events as _events
from . import fragment as _fragment
from . import pattern as _pattern
from . import stencil as _stencil
from . import lighting as _lighting
from . import matrix as _matrix
from . import objects as _objects
from . import pixels as _pixels
from . import primitives as _primitives
from . import texture as _texture
from . import types as _types
from . import window as _window
from .accum import *         # noqa: F401,F403
from .colormap import *      # noqa: F401,F403
from .constants import *     # noqa: F401,F403
from .curves import *        # noqa: F401,F403
from .depth import *         # noqa: F401,F403
from .events import *        # noqa: F401,F403
from .fragment import *      # noqa: F401,F403
from .pattern import *       # noqa: F401,F403
from .stencil import *       # noqa: F401,F403
from .lighting import *      # noqa: F401,F403
from .matrix import *        # noqa: F401,F403
from .objects import *       # noqa: F401,F403
from .pixels import *        # noqa: F401,F403
from .primitives import *    # noqa: F401,F403
from .texture import *       # noqa: F401,F403
from .types import *         # noqa: F401,F403
from .window import *        # noqa: F401,F403

__all__ = sorted(set(["GLError"] + _constants.__all__ + _types.__all__ + _window.__all__
                     + _matrix.__all__ + _primitives.__all__ + _lighting.__all__
                     + _depth.__all__ + _events.__all__ + _colormap.__all__
                     + _pixels.__all__ + _fragment.__all__ + _pattern.__all__
                     + _stencil.__all__ + _accum.__all__ + _objects.__all__ + _curves.__all__
                     + _texture.__all__))
