"""Translucent BSDF → `cycles_translucent`."""

from .registry_params import from_sockets

BL_IDNAMES = ("ShaderNodeBsdfTranslucent",)


def closures(scope, node, weight):
    scope.add_closure("cycles_translucent", weight,
                      from_sockets(scope, "cycles_translucent", exclude={"Normal", "Weight"}),
                      normal=scope.normal(), count=1)
