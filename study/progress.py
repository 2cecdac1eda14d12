"""A tiny text progress bar on standard error (no tqdm dependency)."""
import sys
import time


class Progress:
    """``[#####.....]  12/40  0:31 elapsed  ~0:52 left  label``, redrawn in place."""

    def __init__(self, total, stream=None, width=30):
        self.total = max(int(total), 1)
        self.done = 0
        self.stream = stream if stream is not None else sys.stderr
        self.width = width
        self.start = time.perf_counter()

    def step(self, label="", n=1):
        self.done = min(self.done + n, self.total)
        self.show(label)

    def show(self, label=""):
        frac = self.done / self.total
        fill = int(round(frac * self.width))
        elapsed = time.perf_counter() - self.start
        left = elapsed / frac - elapsed if frac > 0 else 0.0
        bar = "#" * fill + "." * (self.width - fill)
        line = (f"\r[{bar}] {self.done:3d}/{self.total}  {_clock(elapsed)} elapsed  "
                f"~{_clock(left)} left  {label}")
        self.stream.write(line[:160].ljust(160))
        self.stream.flush()

    def close(self):
        self.stream.write("\n")
        self.stream.flush()


def _clock(seconds):
    m, s = divmod(int(seconds + 0.5), 60)
    return f"{m}:{s:02d}"
