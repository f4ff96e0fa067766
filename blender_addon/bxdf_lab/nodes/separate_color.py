"""Separate Color (Blender 3.3+) in RGB mode → `separate`; HSV and HSL modes are not
translated."""

BL_IDNAMES = ("ShaderNodeSeparateColor",)
OUTPUTS = {"Red": "r", "Green": "g", "Blue": "b"}


def value(scope, node, output):
    if node.mode != "RGB":
        scope.warn(f"mode {node.mode} is not translated; output '{output.name}' is 0",
                   status="unsupported")
        return 0.0
    colour = scope.input("Color", "triple")
    parts = scope.memo("op", lambda: scope.graph.add("separate", ["r", "g", "b"], vector=colour))
    return parts[OUTPUTS[output.identifier]]
