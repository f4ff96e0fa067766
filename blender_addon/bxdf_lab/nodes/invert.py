"""Invert → `invert`."""

BL_IDNAMES = ("ShaderNodeInvert",)


def value(scope, node, output):
    return scope.graph.add("invert", ["color"], fac=scope.input("Fac", "float"),
                           color=scope.input("Color", "triple"))["color"]
