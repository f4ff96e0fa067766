"""Mix (Blender 3.4's unified node): colours → `mix_rgb` with its blend mode; floats and vectors
→ a + fac·(b − a) as `math` / `vector_math` ops (blend modes only apply to colours)."""

BL_IDNAMES = ("ShaderNodeMix",)


def _factor(scope, node, uniform):
    graph = scope.graph
    if uniform:
        fac = scope.input("Factor_Float", "float")
        return graph.saturate(fac) if node.clamp_factor else fac
    fac = scope.input("Factor_Vector", "triple")
    if node.clamp_factor:
        for operation, bound in (("maximum", (0.0, 0.0, 0.0)), ("minimum", (1.0, 1.0, 1.0))):
            fac = graph.add("vector_math", ["vector", "value"], operation=operation, a=fac,
                            b=bound, c=(0.0, 0.0, 0.0), scale=1.0)["vector"]
    return fac


def value(scope, node, output):
    graph = scope.graph
    if node.data_type == "RGBA":
        a, b = scope.input("A_Color", "triple"), scope.input("B_Color", "triple")
        return graph.add("mix_rgb", ["color"], blend=node.blend_type.lower(),
                         clamp=bool(node.clamp_result), fac=_factor(scope, node, True),
                         a=a, b=b)["color"]
    if node.data_type == "FLOAT":
        a, b = scope.input("A_Float", "float"), scope.input("B_Float", "float")
        difference = graph.add("math", ["value"], operation="subtract", clamp=False, a=b, b=a,
                               c=0.0)["value"]
        return graph.add("math", ["value"], operation="multiply_add", clamp=False,
                         a=_factor(scope, node, True), b=difference, c=a)["value"]
    a, b = scope.input("A_Vector", "triple"), scope.input("B_Vector", "triple")
    difference = graph.add("vector_math", ["vector", "value"], operation="subtract", a=b, b=a,
                           c=(0.0, 0.0, 0.0), scale=1.0)["vector"]
    return graph.add("vector_math", ["vector", "value"], operation="multiply_add",
                     a=_factor(scope, node, node.factor_mode == "UNIFORM"), b=difference, c=a,
                     scale=1.0)["vector"]
