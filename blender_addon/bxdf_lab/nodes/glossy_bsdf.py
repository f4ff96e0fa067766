"""Glossy BSDF → `cycles_glossy`, isotropic (Cycles gives it no tangent)."""

from .registry_params import from_sockets

BL_IDNAMES = ("ShaderNodeBsdfGlossy",)


def slots(distribution):
    """Closure slots Cycles allocates: multiscatter GGX needs a MicrofacetExtra as well."""
    return 2 if distribution == "multi_ggx" else 1


def closures(scope, node, weight):
    params = from_sockets(scope, "cycles_glossy", exclude={"Normal", "Weight"})
    params["distribution"] = node.distribution.lower()
    params["anisotropy"] = 0.0
    n = slots(params["distribution"])
    scope.add_closure("cycles_glossy", weight, params, normal=scope.normal(),
                      lobes=[("glossy", n, True)], count=n)
