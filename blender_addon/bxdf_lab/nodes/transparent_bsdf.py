"""Transparent BSDF → `cycles_transparent` (a pass-through)."""

from .registry_params import from_sockets

BL_IDNAMES = ("ShaderNodeBsdfTransparent",)


def closures(scope, node, weight):
    scope.add_closure("cycles_transparent", weight,
                      from_sockets(scope, "cycles_transparent", exclude={"Weight"}),
                      lobes=[("transparent", 1, True)], count=1)
