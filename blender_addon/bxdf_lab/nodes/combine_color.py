"""Combine Color (Blender 3.3+) in RGB mode → `combine`; HSV and HSL modes are not translated."""

BL_IDNAMES = ("ShaderNodeCombineColor",)


def value(scope, node, output):
    if node.mode != "RGB":
        scope.warn(f"mode {node.mode} is not translated; its output is black", status="unsupported")
        return (0.0, 0.0, 0.0)
    return scope.graph.add("combine", ["vector", "color"], x=scope.input("Red", "float"),
                           y=scope.input("Green", "float"), z=scope.input("Blue", "float"))["color"]
