"""Separate XYZ → `separate`, outputs x, y, z."""

BL_IDNAMES = ("ShaderNodeSeparateXYZ",)


def value(scope, node, output):
    parts = scope.memo("op", lambda: scope.graph.add("separate", ["x", "y", "z"], vector=scope.input("Vector", "triple")))
    return parts[output.identifier.lower()]
