"""Where an Image datablock's pixels are for the renderer: its file, or a cache file written
here for packed and generated images (keeping the image's colour space), or "missing".

Packed images are written byte for byte (the original file); generated images as float OpenEXR
holding Blender's pixel values unchanged, so that the texture record's colour space still
describes them. Cache files are named by a hash of their content and reused.
"""

import hashlib
import os
import tempfile

import bpy
import numpy as np

COLORSPACES = {"sRGB": "srgb", "Linear": "linear", "Non-Color": "non_color", "Raw": "non_color"}
ALPHA_MODES = {"STRAIGHT": "straight", "PREMUL": "premultiplied",
               "CHANNEL_PACKED": "channel_packed", "NONE": "none"}


def cache_dir():
    path = os.path.join(tempfile.gettempdir(), "bxdf_lab_images")
    os.makedirs(path, exist_ok=True)
    return path


def _write_atomically(path, write):
    if os.path.exists(path):
        return path
    partial = f"{path}.{os.getpid()}.partial{os.path.splitext(path)[1]}"
    write(partial)
    os.replace(partial, path)
    return path


def packed_file_path(image):
    data = image.packed_file.data
    extension = os.path.splitext(image.filepath)[1] or "." + image.file_format.lower()
    path = os.path.join(cache_dir(), hashlib.sha1(data).hexdigest() + extension.lower())

    def write(target):
        with open(target, "wb") as out:
            out.write(data)
    return _write_atomically(path, write)


def generated_file_path(image):
    import OpenImageIO as oiio
    width, height = image.size
    channels = image.channels
    pixels = np.empty(width * height * channels, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    # Blender's rows run bottom-up; an image file's top-down.
    pixels = np.ascontiguousarray(pixels.reshape(height, width, channels)[::-1])
    path = os.path.join(cache_dir(), hashlib.sha1(pixels.tobytes()).hexdigest() + ".exr")

    def write(target):
        out = oiio.ImageOutput.create(target)
        if out is None or not out.open(target, oiio.ImageSpec(width, height, channels, "float")):
            raise OSError(f"cannot write the cache image {target}: {oiio.geterror()}")
        out.write_image(pixels)
        out.close()
    return _write_atomically(path, write)


def locate(image, write=True):
    """(path or None, why it is missing): the file the renderer reads for `image`; with
    write=False, packed and generated images are not written and their path is ""."""
    if image is None:
        return None, "the node has no image"
    if image.source == "GENERATED":
        return (generated_file_path(image) if write else ""), ""
    if image.packed_file is not None:
        return (packed_file_path(image) if write else ""), ""
    if image.source != "FILE":
        return None, f"image '{image.name}' is a {image.source.lower()} (not translated)"
    path = bpy.path.abspath(image.filepath, library=image.library)
    if not os.path.isfile(path):
        return None, f"image '{image.name}': file {path} not found"
    return os.path.normpath(path), ""
