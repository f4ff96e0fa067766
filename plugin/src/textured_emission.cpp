#include "bxdf/render/textured_emission.h"

#include "bxdf/render/material_graph.h"
#include "bxdf/render/scene.h"

namespace bxdf::render {

RGB textured_emission(const Scene& scene, const Hit& hit, const Vec3& towards_viewer,
                      Vec3* registers) {
  SurfacePoint sp = scene.surface_point(hit);
  const Material& mat = scene.materials()[sp.material];
  if (!mat.graph || mat.graph->emission_is_constant()) return mat.emission;
  const bool flipped = face_viewer(sp, towards_viewer, scene.transmissive(sp.material));
  const ShadingContext ctx{&scene, &hit, sp.p, sp.ns, sp.ng, towards_viewer, flipped, &sp};
  mat.graph->evaluate(ctx, registers);
  return mat.graph->emitted(registers);
}

}  // namespace bxdf::render
