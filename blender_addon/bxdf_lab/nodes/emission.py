"""Emission → the graph's emission: Color × Strength × the closure weight, in W/(m²·sr)."""

BL_IDNAMES = ("ShaderNodeEmission",)


def closures(scope, node, weight):
    graph = scope.graph
    radiance = graph.scale_colour(scope.input("Color", "triple"), scope.input("Strength", "float"))
    scope.emit(graph.scale_colour(radiance, weight), count=1)
