"""The C types of the IRIS GL headers (docs/porting.md §1, docs/semantics.md §1).

``Matrix`` is a 4x4 float32 numpy array type (``m[row][col]`` as in C); the
scalar types are the plain Python numbers they hold.
"""
import numpy as np


class Matrix(np.ndarray):
    """``float Matrix[4][4]``.  ``Matrix()`` is all zeros (C leaves it
    uninitialised); ``Matrix(rows)`` converts a nested sequence."""

    def __new__(cls, data=None):
        if data is None:
            return np.zeros((4, 4), np.float32).view(cls)
        return np.array(data, dtype=np.float32).reshape(4, 4).view(cls)


Coord = float
Icoord = int
Scoord = int
Screencoord = int
Angle = int
Colorindex = int
RGBvalue = int
Device = int
Boolean = int
Object = int
Tag = int
Offset = int
Pattern16 = list
Pattern32 = list
Pattern64 = list

__all__ = ["Matrix", "Coord", "Icoord", "Scoord", "Screencoord", "Angle", "Colorindex",
           "RGBvalue", "Device", "Boolean", "Object", "Tag", "Offset", "Pattern16",
           "Pattern32", "Pattern64"]
