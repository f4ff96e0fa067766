"""Holdout → a `holdout` closure with the incoming weight (docs/material-graph.md)."""

BL_IDNAMES = ("ShaderNodeHoldout",)


def closures(scope, node, weight):
    scope.add_closure("holdout", weight, {}, lobes=[], count=1)
