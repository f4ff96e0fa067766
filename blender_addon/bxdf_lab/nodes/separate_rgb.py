"""Separate RGB (before Blender 3.3) → `separate`, outputs r, g, b."""

BL_IDNAMES = ("ShaderNodeSeparateRGB",)
OUTPUTS = {"R": "r", "G": "g", "B": "b"}


def value(scope, node, output):
    colour = scope.input(node.inputs[0].identifier, "triple")
    parts = scope.memo("op", lambda: scope.graph.add("separate", ["r", "g", "b"], vector=colour))
    return parts[OUTPUTS[output.identifier]]
