"""Separate RGB (before Blender 3.3) → `separate`, outputs r, g, b."""

BL_IDNAMES = ("ShaderNodeSeparateRGB",)
OUTPUTS = {"R": "r", "G": "g", "B": "b"}


def value(scope, node, output):
    parts = scope.memo("op", lambda: scope.graph.add("separate", ["x", "y", "z", "r", "g", "b"],
                            vector=scope.input(node.inputs[0].identifier, "triple")))
    return parts[OUTPUTS[output.identifier]]
