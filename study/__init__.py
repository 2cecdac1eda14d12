"""The shadow study: every shadow method of the seed papers run through the
emulator, measured against an exact ray-cast reference (error against run
time).  ``python -m study`` (or ``vgx-study``) regenerates
docs/shadow-study.md.

Modules: scenes (the geometry), reference (the exact ray caster), render
(a scene drawn with IRIS GL calls), volumes (shadow-volume geometry),
methods (the shadow methods), measure (the measures), sweep (the
configurations), report / markdown / plots (the outputs), progress (the
progress bar).
"""
