"""Add Shader: both shaders with the incoming weight."""

BL_IDNAMES = ("ShaderNodeAddShader",)


def closures(scope, node, weight):
    scope.closures(node.inputs[0].identifier, weight)
    scope.closures(node.inputs[1].identifier, weight)
