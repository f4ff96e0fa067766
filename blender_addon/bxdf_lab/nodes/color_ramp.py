"""Color Ramp → `color_ramp` with its stops [position, r, g, b, a], interpolation, colour mode
(RGB, HSV, HSL) and hue interpolation."""

BL_IDNAMES = ("ShaderNodeValToRGB",)


def _ramp(scope, node):
    ramp = node.color_ramp
    stops = [[float(e.position), *(float(c) for c in e.color)] for e in ramp.elements]
    return scope.graph.add("color_ramp", ["color", "alpha"], fac=scope.input("Fac", "float"),
                           interpolation=ramp.interpolation.lower(),
                           color_mode=ramp.color_mode.lower(),
                           hue_interpolation=ramp.hue_interpolation.lower(), stops=stops)


def value(scope, node, output):
    result = scope.memo("op", lambda: _ramp(scope, node))
    return result["alpha" if output.identifier == "Alpha" else "color"]
