"""Layer Weight → `layer_weight`, outputs fresnel and facing."""

BL_IDNAMES = ("ShaderNodeLayerWeight",)


def value(scope, node, output):
    fields = {"blend": scope.input("Blend", "float")}
    normal = scope.normal()
    if normal is not None:
        fields["normal"] = normal
    result = scope.memo("op", lambda: scope.graph.add("layer_weight", ["fresnel", "facing"], **fields))
    return result[output.identifier.lower()]
