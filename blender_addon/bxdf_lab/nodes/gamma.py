"""Gamma → `gamma`."""

BL_IDNAMES = ("ShaderNodeGamma",)


def value(scope, node, output):
    return scope.graph.add("gamma", ["color"], color=scope.input("Color", "triple"),
                           gamma=scope.input("Gamma", "float"))["color"]
