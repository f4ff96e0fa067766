"""Image Texture → `image` reading a texture record: the file (packed and generated images go
through a cache file), interpolation, extension, colour space and alpha mode. A missing image
reads magenta, with a warning; an unlinked Vector reads the active render UV map."""

from . import graph as g
from . import image_files

BL_IDNAMES = ("ShaderNodeTexImage",)
# Cycles' CPU kernel interpolates "Smart" as cubic (anything not closest or linear is cubic).
INTERPOLATIONS = {"Closest": "closest", "Linear": "linear", "Cubic": "cubic", "Smart": "cubic"}
EXTENSIONS = {"REPEAT": "repeat", "EXTEND": "extend", "CLIP": "clip"}


def texture(scope, node, extension=None):
    """The texture record of the node's image, warning about what is not translated;
    `extension` (a record value) for nodes without an Extension setting."""
    image = node.image
    path, why = image_files.locate(image, scope.translation.write_files)
    if path is None:
        scope.warn(f"{why}; it renders magenta (1, 0, 1), as Cycles renders a missing image")
        return {"missing": True}
    colorspace = image_files.COLORSPACES.get(image.colorspace_settings.name)
    if colorspace is None:
        scope.warn(f"colour space '{image.colorspace_settings.name}' of image '{image.name}' is "
                   "not translated; its values are read as linear")
        colorspace = "linear"
    extension = extension or EXTENSIONS.get(node.extension)
    if extension is None:
        scope.warn(f"extension {node.extension} is not translated; repeat is used")
        extension = "repeat"
    return {"path": path, "interpolation": INTERPOLATIONS[node.interpolation],
            "extension": extension, "colorspace": colorspace,
            "alpha": image_files.ALPHA_MODES.get(image.alpha_mode, "straight")}


def value(scope, node, output):
    result = scope.memo("image", lambda: _lookup(scope, node))
    return result["alpha" if output.identifier == "Alpha" else "color"]


def _lookup(scope, node):
    graph = scope.graph
    if node.projection != "FLAT":
        scope.warn(f"projection {node.projection} is not translated; flat projection is used")
    # Unlinked (or linked to something untranslated), Cycles reads the active render UV map.
    vector = scope.input("Vector", "triple") if scope.linked("Vector") else None
    if not g.is_reference(vector):
        vector = graph.add("uv", ["vector"], map=scope.uv_map(""))["vector"]
    return graph.add("image", ["color", "alpha"], texture=graph.texture(texture(scope, node)),
                     vector=vector)
