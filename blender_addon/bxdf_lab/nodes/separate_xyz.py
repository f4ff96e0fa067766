"""Separate XYZ → `separate`, outputs x, y, z."""

BL_IDNAMES = ("ShaderNodeSeparateXYZ",)


def value(scope, node, output):
    vector = scope.input("Vector", "triple")
    parts = scope.memo("op", lambda: scope.graph.add("separate", ["x", "y", "z"], vector=vector))
    return parts[output.identifier.lower()]
