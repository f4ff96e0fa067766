"""Bump → `bump`, whose height sub-program the renderer re-evaluates at offset points. An
unlinked Height leaves the normal as it is (the Normal input, or the smooth normal)."""

from . import graph as g

BL_IDNAMES = ("ShaderNodeBump",)


def value(scope, node, output):
    graph = scope.graph
    normal = scope.normal()
    height = scope.input("Height", "float")
    if g.is_constant(height):
        return normal if normal is not None else graph.add("normal", ["vector"])["vector"]
    fields = scope.with_normal({"strength": scope.input("Strength", "float"),
                                "distance": scope.input("Distance", "float"),
                                "invert": bool(node.invert), "height": height})
    return graph.add("bump", ["normal"], **fields)["normal"]
