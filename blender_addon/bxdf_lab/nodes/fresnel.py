"""Fresnel → `fresnel` (a mix factor; a linked Normal input as its normal)."""

BL_IDNAMES = ("ShaderNodeFresnel",)


def value(scope, node, output):
    fields = {"ior": scope.input("IOR", "float")}
    normal = scope.normal()
    if normal is not None:
        fields["normal"] = normal
    return scope.graph.add("fresnel", ["fac"], **fields)["fac"]
