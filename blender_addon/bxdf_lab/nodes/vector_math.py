"""Vector Math → `vector_math` (Blender's operation identifiers in lower case)."""

BL_IDNAMES = ("ShaderNodeVectorMath",)


def value(scope, node, output):
    a, b, c = (scope.input(s.identifier, "triple") for s in node.inputs[:3])
    result = scope.memo("op", lambda: scope.graph.add("vector_math", ["vector", "value"], operation=node.operation.lower(),
                             a=a, b=b, c=c, scale=scope.input("Scale", "float")))
    return result["value" if output.identifier == "Value" else "vector"]
