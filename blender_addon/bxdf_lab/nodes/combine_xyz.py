"""Combine XYZ → `combine`."""

BL_IDNAMES = ("ShaderNodeCombineXYZ",)


def value(scope, node, output):
    return scope.graph.add("combine", ["vector", "color"], x=scope.input("X", "float"),
                           y=scope.input("Y", "float"), z=scope.input("Z", "float"))["vector"]
