"""Mix Shader: folded into the closure weights, (1 − fac) for the first shader and fac for the
second, with fac clamped to [0, 1] as Cycles clamps it (svm_node_mix_closure)."""

BL_IDNAMES = ("ShaderNodeMixShader",)


def closures(scope, node, weight):
    graph = scope.graph
    fac = graph.saturate(scope.input("Fac", "float"))
    scope.closures(node.inputs[1].identifier, graph.multiply(weight, graph.one_minus(fac)))
    scope.closures(node.inputs[2].identifier, graph.multiply(weight, fac))
