"""Geometry → `position`, `normal` (the shading normal) and `incoming` (towards the viewer), all
world space; its other outputs are not translated."""

BL_IDNAMES = ("ShaderNodeNewGeometry",)
OPS = {"Position": "position", "Normal": "normal", "Incoming": "incoming"}


def value(scope, node, output):
    op = OPS.get(output.identifier)
    if op is None:
        scope.warn(f"output '{output.name}' is not translated; (0, 0, 0) is used instead",
                   status="unsupported")
        return (0.0, 0.0, 0.0)
    return scope.memo(op, lambda: scope.graph.add(op, ["vector"])["vector"])
