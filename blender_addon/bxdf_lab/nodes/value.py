"""Value → its number, a constant."""

BL_IDNAMES = ("ShaderNodeValue",)


def value(scope, node, output):
    return float(node.outputs[0].default_value)
