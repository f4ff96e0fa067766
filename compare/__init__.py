"""Comparison harness: renders reference scenes with BxDF Lab, Cycles and POV-Ray through Blender,
computes analytic truth where it exists, and writes an image-diff report
(`python3 -m compare run`)."""

ENGINES = ("BXDF_LAB", "CYCLES", "POVRAY_RENDER")
ANALYTIC = "ANALYTIC"
ALL_ENGINES = ENGINES + (ANALYTIC,)
