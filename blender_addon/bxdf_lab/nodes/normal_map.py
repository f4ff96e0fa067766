"""Normal Map (tangent space) → `normal_map` with the UV map whose tangents it uses (exported
from `mesh.calc_tangents`). Object and world space maps are not translated."""

BL_IDNAMES = ("ShaderNodeNormalMap",)


def value(scope, node, output):
    graph = scope.graph
    if node.space != "TANGENT":
        scope.warn(f"space {node.space} is not translated; the smooth normal is used instead",
                   status="unsupported")
        return graph.add("normal", ["vector"])["vector"]
    return graph.add("normal_map", ["normal"], space="tangent", map=scope.uv_map(node.uv_map),
                     strength=scope.input("Strength", "float"),
                     color=scope.input("Color", "triple"))["normal"]
