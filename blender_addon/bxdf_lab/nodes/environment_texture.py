"""Environment Texture inside a material → `environment`: the image looked up by a direction
(Cycles' svm_node_tex_environment: the vector normalised, then its equirectangular or
mirror-ball projection), with the Image Texture's texture record and Repeat, the only
extension Cycles gives this node. An unlinked Vector (or one linked to something untranslated)
reads the world position, Cycles' default for this socket (LINK_POSITION). The world's own
Environment Texture is translated by world_export.py."""

from . import graph as g
from . import image_texture

BL_IDNAMES = ("ShaderNodeTexEnvironment",)
PROJECTIONS = {"EQUIRECTANGULAR": "equirectangular", "MIRROR_BALL": "mirror_ball"}


def value(scope, node, output):
    result = scope.memo("environment", lambda: _lookup(scope, node))
    return result["alpha" if output.identifier == "Alpha" else "color"]


def _lookup(scope, node):
    graph = scope.graph
    projection = PROJECTIONS.get(node.projection)
    if projection is None:
        scope.warn(f"projection {node.projection} is not translated; equirectangular is used")
        projection = "equirectangular"
    vector = scope.input("Vector", "triple") if scope.linked("Vector") else None
    if not g.is_reference(vector):
        vector = scope.memo("position", lambda: graph.add("position", ["vector"])["vector"])
    record = image_texture.texture(scope, node, extension="repeat")
    return graph.add("environment", ["color", "alpha"], texture=graph.texture(record),
                     vector=vector, projection=projection)
