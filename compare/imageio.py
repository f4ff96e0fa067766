"""Image files through OpenImageIO: linear float EXR in and out, 16-bit PNG in, 8-bit PNG out."""
from __future__ import annotations

import numpy as np
import OpenImageIO as oiio


def read(path) -> np.ndarray:
    """HxWx3 float32, rows top-down, values as stored (a linear 16-bit PNG is scaled to [0, 1]
    with no transfer function applied)."""
    # Read past OIIO's shared image cache, which an ImageBuf goes through: a file rewritten under
    # the same name within its timestamp's resolution read back as the old image (seen in
    # Blender, one render after another to the same path).
    inp = oiio.ImageInput.open(str(path))
    if inp is None:
        raise OSError(f"cannot read image {path}: {oiio.geterror()}")
    try:
        pixels = inp.read_image(oiio.FLOAT)
        error = inp.geterror() if pixels is None else ""
    finally:
        inp.close()
    if pixels is None or pixels.size == 0:
        raise OSError(f"cannot read image {path}: {error or 'no pixels'}")
    if pixels.ndim == 2:
        pixels = pixels[..., None]
    if pixels.shape[2] == 1:
        pixels = np.repeat(pixels, 3, axis=2)
    return np.ascontiguousarray(pixels[..., :3], dtype=np.float32)


def write_exr(path, image) -> None:
    image = np.ascontiguousarray(image, dtype=np.float32)
    h, w, c = image.shape
    spec = oiio.ImageSpec(w, h, c, oiio.FLOAT)
    spec.attribute("compression", "zip")
    buf = oiio.ImageBuf(spec)
    buf.set_pixels(oiio.ROI(0, w, 0, h, 0, 1, 0, c), image)
    if not buf.write(str(path)):
        raise OSError(f"cannot write {path}: {buf.geterror()}")


def write_png8(path, image) -> None:
    """`image` already in display values [0, 1]."""
    image = np.ascontiguousarray(np.clip(image, 0.0, 1.0), dtype=np.float32)
    h, w, c = image.shape
    buf = oiio.ImageBuf(oiio.ImageSpec(w, h, c, oiio.FLOAT))
    buf.set_pixels(oiio.ROI(0, w, 0, h, 0, 1, 0, c), image)
    if not buf.write(str(path), oiio.UINT8):
        raise OSError(f"cannot write {path}: {buf.geterror()}")
