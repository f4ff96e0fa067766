"""Diffuse BSDF → `cycles_oren_nayar` (Cycles' own Oren–Nayar; roughness 0 is Lambertian)."""

from .registry_params import from_sockets

BL_IDNAMES = ("ShaderNodeBsdfDiffuse",)


def closures(scope, node, weight):
    scope.add_closure("cycles_oren_nayar", weight,
                      from_sockets(scope, "cycles_oren_nayar", exclude={"Normal", "Weight"}),
                      normal=scope.normal(), count=1)
