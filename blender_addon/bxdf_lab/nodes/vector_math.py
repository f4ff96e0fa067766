"""Vector Math → `vector_math` (Blender's operation identifiers in lower case)."""

BL_IDNAMES = ("ShaderNodeVectorMath",)


def _op(scope, node):
    a, b, c = (scope.input(s.identifier, "triple") for s in node.inputs[:3])
    return scope.graph.add("vector_math", ["vector", "value"], operation=node.operation.lower(),
                           a=a, b=b, c=c, scale=scope.input("Scale", "float"))


def value(scope, node, output):
    result = scope.memo("op", lambda: _op(scope, node))
    return result["value" if output.identifier == "Value" else "vector"]
