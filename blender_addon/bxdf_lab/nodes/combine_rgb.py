"""Combine RGB (before Blender 3.3) → `combine`."""

BL_IDNAMES = ("ShaderNodeCombineRGB",)


def value(scope, node, output):
    return scope.graph.add("combine", ["vector", "color"], x=scope.input("R", "float"),
                           y=scope.input("G", "float"), z=scope.input("B", "float"))["color"]
