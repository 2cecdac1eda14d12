"""The study's progress display: the project's one tqdm bar
(vgx_emulator/progress.py), with the same ``Progress(total, stream)``,
``show``, ``step`` and ``close``."""
from vgx_emulator.progress import Progress

__all__ = ["Progress"]
