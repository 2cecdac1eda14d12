"""numba's disk cache keys a kernel on the pickled contents of its closure
cells; a cell that pickles differently in each process (a dispatcher, a
module) makes every process compile the kernel again.  The line, point and
pixel-write kernels must have closure cells that pickle identically in two
fresh processes (they compiled anew in every process before)."""
import subprocess
import sys

SCRIPT = r"""
import hashlib, pickle
import numpy as np
from irisgl import *
from vgx_emulator.scan import lines, spans
prefsize(16, 16); winopen("x"); RGBmode(); gconfig()
ortho2(-0.5, 15.5, -0.5, 15.5)
move2(1, 1); draw2(10, 12)
bgnpoint(); v2f((3, 3)); endpoint()
lrectwrite(0, 0, 1, 1, np.zeros(4, np.uint32))
gflush()
for table in (lines._kernels, spans._pixel_kernels):
    for key, k in sorted(table.items(), key=lambda kv: str(kv[0])):
        f = k.py_func
        cells = [(n, c.cell_contents) for n, c in zip(f.__code__.co_freevars, f.__closure__)]
        print(f.__name__, hashlib.md5(pickle.dumps(cells)).hexdigest())
"""


def _cells():
    r = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True,
                       timeout=300, check=True)
    return r.stdout.split("\n")


def test_kernel_closures_pickle_the_same_in_every_process():
    first, second = _cells(), _cells()
    names = {line.split()[0] for line in first if line}
    assert {"draw_lines", "draw_points", "write_pixels"} <= names
    assert first == second
