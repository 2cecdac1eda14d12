"""The reference's viewing matrices rebuilt in float64, independent of the
library (docs/semantics.md §2; row vectors, p' = p . M): the shadow study's
(study/reference.py), one copy for the study and the tests."""
from study.reference import lookat_matrix, perspective_matrix  # noqa: F401
