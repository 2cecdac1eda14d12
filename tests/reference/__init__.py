"""Slow, obvious reference models the tests compare the emulator against.

Nothing here imports :mod:`vgx_emulator` or :mod:`irisgl`: the models are
written from the documented rules (docs/semantics.md §1, §2, §3, §5; the fill rule of
``scan/fixed.py``'s docstring) only.
"""
