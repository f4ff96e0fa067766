"""Velvet BSDF → `cycles_velvet` (Ashikhmin's velvet, σ)."""

from .registry_params import from_sockets

BL_IDNAMES = ("ShaderNodeBsdfVelvet",)


def closures(scope, node, weight):
    scope.add_closure("cycles_velvet", weight,
                      from_sockets(scope, "cycles_velvet", exclude={"Normal", "Weight"}),
                      normal=scope.normal(), count=1)
