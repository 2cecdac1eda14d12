"""The measured tables of docs/stability.md: ``python tests/stability_tables.py``
(from the repository root) prints them, from the same code the stability
tests run."""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))   # tests/ as pytest sees it

from irisgl import FALSE, TRUE  # noqa: E402
from stability_helpers import MYZERO  # noqa: E402
from test_stability_volumes import EYES, expected_counts, volume_counts  # noqa: E402
from test_stability_depth import DFAR, RATIOS, depth_separation, floor_fight, one_level, acne  # noqa: E402
from test_stability_float32 import float_differences  # noqa: E402


# the tables of docs/stability.md
def _print_tables():
    print("depth: smallest separable relative depth difference at d = far/10 and far/2, "
          f"far = {DFAR:g}")
    for ratio in RATIOS:
        cells = []
        for bits in (24, 16):
            for frac in (10, 2):
                d = DFAR / frac
                _, _, measured = depth_separation(ratio, bits, d)
                cells.append(f"{bits}b f/{frac}: {measured:.2e} (1 level {one_level(DFAR / ratio, bits, d):.2e})")
        print(f"  far/near {ratio:.0e}: " + " | ".join(cells))
    print("floor 1 below the eye and a second 0.01 below it: pixels of the lower one shown")
    for ratio in RATIOS:
        print(f"  far/near {ratio:.0e}: " + " | ".join(
            "{}b {}: {} of {}".format(bits, "subpixel" if sub else "snapped",
                                      *floor_fight(ratio, bits, sub)[::-1])
            for bits in (24, 16) for sub in (TRUE, FALSE)))
    print("acne (% of ground points) vs bias in z units, and with the slope bound b*")
    biases = [0, 256, 4096, 65536, 1 << 20]
    for elev in (60.0, 30.0, 10.0, 3.0, 1.0, 0.3):
        fr, bound = acne(elev, biases)
        near_bound, _ = acne(elev, lambda b: [0.5 * b, 0.9 * b, 1.01 * b])
        print(f"  {elev:5.1f} deg  b* = {bound:10.0f}  " +
              " ".join(f"{b}: {100 * f:.1f}" for b, f in zip(biases, fr)) +
              "  | b*/2 {:.1f} 0.9b* {:.2f} 1.01b* {:.2f}".format(*(100 * f for f in near_bound)))
    print("float32 vs float64 four spheres: drawn, coverage diff, colour diff, max channel "
          "diff, z diff, max z diff")
    for subpix in (FALSE, TRUE):
        print("  ", "subpixel" if subpix else "snapped", float_differences(subpix))
    for where in sorted(EYES):
        for zfail in (False, True):
            for far in (None, 20.0, 12.0):
                eye, ref_pt = EYES[where]
                sure, want, _ = expected_counts(eye, ref_pt, zfail, far or math.inf)
                got = volume_counts(eye, ref_pt, zfail, far)
                print(f"  volume eye {where} {'zfail' if zfail else 'zpass'} far {far}: "
                      f"{int(sure.sum())} ground px, {int((sure & (got != want)).sum())} wrong, "
                      f"{int((sure & (want != MYZERO)).sum())} != MYZERO")


if __name__ == "__main__":
    _print_tables()
