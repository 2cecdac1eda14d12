"""The shadow study: every shadow method of the seed papers run through the
emulator, measured against an exact ray-cast reference (error against run
time).  ``python -m study`` (or ``vgx-study``) runs the sweep into an
output folder; ``--docs`` regenerates docs/shadow-study.md;
docs/shadow-study-at-scale.md: Dask, --resume, scene files, --full.

Modules: scenes (the geometry, scene files), reference (the exact ray
caster), render (a scene drawn with IRIS GL calls), volumes (shadow-volume
geometry), methods (the shadow methods), measure (the measures), sweep (the
configurations), tasks (what a worker does), cluster (serial or Dask
pools), store (the output folder), report / markdown / plots (the
outputs), progress (the progress bar).
"""
