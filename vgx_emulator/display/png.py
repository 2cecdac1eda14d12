"""PNG output of what a window shows."""
from pathlib import Path

from PIL import Image


def write_png(path, rgb_image):
    """Save an (h, w, 3) uint8 image (top row first)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    Image.fromarray(rgb_image, "RGB").save(path)
    return path
