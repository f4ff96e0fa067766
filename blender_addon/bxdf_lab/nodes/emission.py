"""Emission → the graph's emission: Color × Strength × the closure weight, in W/(m²·sr). A
constant black colour or zero strength emits nothing (Cycles removes the node). Principled BSDF's
Emission and Emission Strength inputs go through here too."""

from . import graph as g

BL_IDNAMES = ("ShaderNodeEmission",)


def closures(scope, node, weight):
    graph = scope.graph
    names = ("Emission", "Emission Strength") if "Emission" in node.inputs else ("Color", "Strength")
    colour, strength = scope.input(names[0], "triple"), scope.input(names[1], "float")
    if ((g.is_constant(colour) and not any(colour)) or
            (g.is_constant(strength) and strength == 0.0)):
        return
    scope.emit(graph.scale_colour(graph.scale_colour(colour, strength), weight), count=1)
