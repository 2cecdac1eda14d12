"""``--threads N`` read from argv before numba (or Mesa) starts: thread
counts are fixed when those libraries load, so the benchmark scripts call
this before their other imports."""


def early_threads(argv):
    """The --threads value in argv (``--threads N`` or ``--threads=N``), or None."""
    for i, a in enumerate(argv):
        if a == "--threads" and i + 1 < len(argv):
            return argv[i + 1]
        if a.startswith("--threads="):
            return a.split("=", 1)[1]
    return None
