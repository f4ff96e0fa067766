// Emission driven by a texture (a node material whose Emission reads the graph), as a light:
// its mesh's emissive triangles join the mesh light like constant ones, carrying a power
// estimate for the light sampler (the emission at each triangle's centroid, Cycles' "emission
// estimate" in spirit), and a light sample on them evaluates the material's emission at the
// sampled point, as Cycles evaluates the emission shader at a sampled triangle point. Within a
// mesh, points are still chosen by area, so the density never depends on the estimate and a
// poor estimate costs noise, never bias.
#pragma once

#include "bxdf/math.h"
#include "bxdf/spectrum.h"

namespace bxdf::render {

class Scene;
struct Hit;

// The emitted radiance of `hit`'s graph material seen from `towards_viewer` (unit, away from
// the surface), evaluated exactly as the path tracer evaluates it when a ray hits the surface
// (same facing and flip). `registers` holds MaterialGraph::kMaxRegisters values; nothing is
// allocated.
RGB textured_emission(const Scene& scene, const Hit& hit, const Vec3& towards_viewer,
                      Vec3* registers);

}  // namespace bxdf::render
