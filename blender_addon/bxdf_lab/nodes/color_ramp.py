"""Color Ramp → `color_ramp` with its stops [position, r, g, b, a]."""

BL_IDNAMES = ("ShaderNodeValToRGB",)


def _ramp(scope, node):
    ramp = node.color_ramp
    if ramp.color_mode != "RGB":
        scope.warn(f"colour mode {ramp.color_mode} ({ramp.hue_interpolation} hue) is not "
                   "translated; the stops are interpolated in RGB")
    stops = [[float(e.position), *(float(c) for c in e.color)] for e in ramp.elements]
    return scope.graph.add("color_ramp", ["color", "alpha"], fac=scope.input("Fac", "float"),
                           interpolation=ramp.interpolation.lower(),
                           color_mode=ramp.color_mode.lower(), stops=stops)


def value(scope, node, output):
    result = scope.memo("op", lambda: _ramp(scope, node))
    return result["alpha" if output.identifier == "Alpha" else "color"]
