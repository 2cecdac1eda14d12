"""The progress display of vgx-gallery and the shadow study: one tqdm bar
on standard error, with the item in progress after it.

``Progress(total)``; ``show(label)`` names the item being worked on,
``step(label)`` counts one item done, ``close()`` ends the line.
"""
import sys

from tqdm import tqdm


class Progress:
    """A tqdm bar of ``total`` items on ``stream`` (standard error)."""

    def __init__(self, total, stream=None, width=30):
        self.total = max(int(total), 1)
        self.bar = tqdm(total=self.total, file=stream if stream is not None else sys.stderr,
                        bar_format="{bar:%d} {n_fmt}/{total_fmt} {elapsed}<{remaining} {desc}"
                                   % width, leave=True)

    @property
    def done(self):
        return self.bar.n

    def show(self, label=""):
        """Name the item in progress."""
        self.bar.set_description_str(str(label)[:60], refresh=True)

    def step(self, label="", n=1):
        """Count ``n`` items done (``label``: what was done)."""
        self.bar.set_description_str(str(label)[:60], refresh=False)
        self.bar.update(min(n, self.total - self.bar.n))

    def close(self):
        self.bar.close()
