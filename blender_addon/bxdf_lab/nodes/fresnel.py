"""Fresnel → `fresnel` (a mix factor; a linked Normal input as its normal)."""

BL_IDNAMES = ("ShaderNodeFresnel",)


def value(scope, node, output):
    fields = scope.with_normal({"ior": scope.input("IOR", "float")})
    return scope.graph.add("fresnel", ["fac"], **fields)["fac"]
