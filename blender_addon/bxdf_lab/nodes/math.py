"""Math → `math` (Blender's operation identifiers in lower case, its Clamp option)."""

BL_IDNAMES = ("ShaderNodeMath",)


def value(scope, node, output):
    a, b, c = (scope.input(s.identifier, "float") for s in node.inputs[:3])
    return scope.graph.add("math", ["value"], operation=node.operation.lower(),
                           clamp=bool(node.use_clamp), a=a, b=b, c=c)["value"]
