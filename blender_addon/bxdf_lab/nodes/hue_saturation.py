"""Hue/Saturation/Value → `hsv`."""

BL_IDNAMES = ("ShaderNodeHueSaturation",)


def value(scope, node, output):
    return scope.graph.add("hsv", ["color"], hue=scope.input("Hue", "float"),
                           saturation=scope.input("Saturation", "float"),
                           value=scope.input("Value", "float"), fac=scope.input("Fac", "float"),
                           color=scope.input("Color", "triple"))["color"]
