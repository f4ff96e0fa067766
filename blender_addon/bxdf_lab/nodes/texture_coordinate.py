"""Texture Coordinate → `uv` (the active render map), `generated`, `object` (or, with an Object
set, the world position in that object's space through `transform`). Normal, Camera, Window and
Reflection are not translated."""

import numpy as np

BL_IDNAMES = ("ShaderNodeTexCoord",)


def value(scope, node, output):
    graph = scope.graph
    kind = output.identifier
    if node.from_instancer:
        scope.warn("'From Instancer' is not translated; the object's own coordinates are used")
    if kind == "UV":
        return graph.add("uv", ["vector"], map=scope.uv_map(""))["vector"]
    if kind == "Generated":
        return graph.add("generated", ["vector"])["vector"]
    if kind == "Object":
        if node.object is None:
            return graph.add("object", ["vector"])["vector"]
        world_to_object = np.linalg.inv(np.array(node.object.matrix_world, dtype=np.float64))
        position = graph.add("position", ["vector"])["vector"]
        return graph.add("transform", ["vector"], vector=position, kind="point", normalize=False,
                         matrix=world_to_object[:3, :4].tolist())["vector"]
    scope.warn(f"output '{output.name}' is not translated; (0, 0, 0) is used instead",
               status="unsupported")
    return (0.0, 0.0, 0.0)
