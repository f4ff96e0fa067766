"""Bright/Contrast → `bright_contrast`."""

BL_IDNAMES = ("ShaderNodeBrightContrast",)


def value(scope, node, output):
    return scope.graph.add("bright_contrast", ["color"], color=scope.input("Color", "triple"),
                           bright=scope.input("Bright", "float"),
                           contrast=scope.input("Contrast", "float"))["color"]
