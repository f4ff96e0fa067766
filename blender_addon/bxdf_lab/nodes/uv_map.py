"""UV Map → `uv` reading the named map (the active render map when none is named)."""

BL_IDNAMES = ("ShaderNodeUVMap",)


def value(scope, node, output):
    if node.from_instancer:
        scope.warn("'From Instancer' is not translated; the mesh's own UV map is used")
    return scope.graph.add("uv", ["vector"], map=scope.uv_map(node.uv_map))["vector"]
