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


DRAW = r"""
from irisgl import *
prefsize(16, 16); winopen("x"); RGBmode(); gconfig()
ortho2(-0.5, 15.5, -0.5, 15.5)
cpack(0xffffffff); clear(); move2(1, 1); draw2(10, 12); rectf(2, 2, 5, 5); gflush()
print(int(lrectread(3, 3, 3, 3)[0, 0]))
"""


def _draw(cache_dir):
    import os
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir))
    return subprocess.run([sys.executable, "-c", DRAW], capture_output=True, text=True,
                          timeout=600, env=env)


def test_a_damaged_cache_is_compiled_again_not_fatal(tmp_path):
    """Garbage in every index and data file of the cache: the next run
    compiles again and draws the same, instead of dying with UnpicklingError."""
    first = _draw(tmp_path)
    assert first.returncode == 0, first.stderr
    files = [p for p in tmp_path.rglob("*") if p.suffix in (".nbi", ".nbc")]
    assert files
    for p in files:
        data = p.read_bytes()
        p.write_bytes(data[:len(data) // 3] + b"\x80garbage")
    again = _draw(tmp_path)
    assert again.returncode == 0, again.stderr[-2000:]
    assert again.stdout == first.stdout
