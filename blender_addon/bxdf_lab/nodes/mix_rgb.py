"""Mix RGB (the node Blender 3.3 and older files use) → `mix_rgb`; Cycles clamps its factor."""

BL_IDNAMES = ("ShaderNodeMixRGB",)


def value(scope, node, output):
    return scope.graph.add(
        "mix_rgb", ["color"], blend=node.blend_type.lower(), clamp=bool(node.use_clamp),
        fac=scope.graph.saturate(scope.input("Fac", "float")),
        a=scope.input("Color1", "triple"), b=scope.input("Color2", "triple"))["color"]
