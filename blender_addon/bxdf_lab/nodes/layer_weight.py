"""Layer Weight → `layer_weight`, outputs fresnel and facing."""

BL_IDNAMES = ("ShaderNodeLayerWeight",)


def value(scope, node, output):
    fields = scope.with_normal({"blend": scope.input("Blend", "float")})
    result = scope.memo("op", lambda: scope.graph.add("layer_weight", ["fresnel", "facing"],
                                                      **fields))
    return result[output.identifier.lower()]
