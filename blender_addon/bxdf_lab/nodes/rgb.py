"""RGB → its colour, a constant."""

from . import graph as g

BL_IDNAMES = ("ShaderNodeRGB",)


def value(scope, node, output):
    return g.to_triple(tuple(node.outputs[0].default_value))
