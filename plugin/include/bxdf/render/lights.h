// Lights as Cycles 3.4 has them (K/light/light.h), in Blender's units.
// - Point and spot: radiant intensity I = P·colour/(4π) W/sr. With a radius r > 0 the light is a
//   disk of radius r centred on the light and facing the shading point, of radiance I/(π r²)
//   (Cycles' "sphere" light: soft shadows; camera and BSDF rays can hit it). A spot adds Cycles'
//   cone mask from spot_size and spot_blend.
// - Sun: irradiance E (W/m²). With an angle the directions fill a cone of half-angle angle/2,
//   sampled as Cycles does, through a disk of radius tan(angle/2) at unit distance: the radiance
//   is E·pdf(ω), so that every light sample carries E.
// - Area: a rectangle or an ellipse (Blender's square/rectangle and disk/ellipse) emitting from
//   its front (the light's −Z) only, radiance P·colour/(4·area) (Cycles' eval_fac 1/(4A)).
//   Rectangles are sampled by solid angle (Ureña et al. 2013, as Cycles), ellipses by area.
// - Mesh: the emissive triangles of one mesh (an Emission shader), two-sided, sampled by area;
//   a textured emission is evaluated at the sampled point (textured_emission.h).
// The world is not a Light: see environment.h.
//
// All kinds live in one tagged struct and are sampled through a switch, so the per-sample path
// has no virtual calls.
#pragma once

#include <cstdint>
#include <vector>

#include "bxdf/math.h"
#include "bxdf/render/spherical_rectangle.h"
#include "bxdf/spectrum.h"

namespace bxdf::render {

enum class LightType { Point, Spot, Sun, Area, Mesh };
enum class AreaShape { Rectangle, Ellipse };

// One emissive triangle of a mesh light.
struct EmissiveTriangle {
  Vec3 p0, e1, e2;  // p0, p1 - p0, p2 - p0
  Vec3 normal;      // unit, cross(e1, e2) direction
  RGB radiance;     // constant emission; textured: the power estimate only
  float area = 0.0f;
  float inv_area = 0.0f;  // 1 / area (> 0: a degenerate triangle is not kept)
  uint32_t triangle = 0;  // its index in the mesh
  bool textured = false;  // the emission is evaluated where a sample lands
};

// Ray visibility of a light, as Blender's object and light settings give it.
struct LightVisibility {
  bool camera = false;      // camera rays see it (Blender: object visible_camera; off for lights)
  bool cast_shadow = true;  // its light samples are tested for occlusion
  bool use_mis = true;      // BSDF rays can hit it (Cycles' Multiple Importance)
};

struct Light {
  LightType type = LightType::Point;
  LightVisibility visibility;
  Vec3 position;             // point, spot; area: centre
  Vec3 direction{0, 0, -1};  // spot axis; direction sunlight travels; area: emitting normal
  RGB intensity;             // point, spot: W/sr
  RGB irradiance;            // sun: W/m² at normal incidence
  RGB radiance;              // point/spot with a radius, area: emitted radiance
  float radius = 0.0f;       // point, spot: disk radius; sun: tan(angle / 2)
  float inv_area = 1.0f;     // point/spot disk, sun disk, area: 1 / area (1 when the area is 0)
  float cos_half_spot = -1.0f;  // spot: cos(spot_size / 2)
  float spot_smooth = 0.0f;     // spot: (1 - cos_half_spot) · spot_blend
  float cos_sun_max = 1.0f;     // sun: cos(angle / 2); 1 for a delta sun
  // Area: full edge vectors along the light's X and Y (size_x, size_y, scaled), and the shape.
  Vec3 axis_u, axis_v;
  AreaShape shape = AreaShape::Rectangle;
  // Area: the rectangle those edges span, for sampling the solid angle it subtends (made with
  // them; the rectangle shape samples it).
  SphericalRectangle rectangle;
  // Mesh: its triangles and their area CDF (cdf.back() == total area).
  std::vector<EmissiveTriangle> triangles;
  std::vector<float> cdf;
  float total_area = 0.0f;
  uint32_t mesh = 0;  // mesh: its index in the scene
  // Mesh: which placement of an instanced mesh (Hit::instance; ~0u when not instanced), and
  // whether that placement mirrors it (its triangles' vertices 1 and 2 were swapped).
  uint32_t instance = ~0u;
  bool mirrored = false;

  bool is_delta() const {
    return ((type == LightType::Point || type == LightType::Spot) && radius == 0.0f) ||
           (type == LightType::Sun && cos_sun_max >= 1.0f);
  }
  // A light a ray can hit in space (not through the scene's geometry).
  bool is_hittable() const {
    return ((type == LightType::Point || type == LightType::Spot) && radius > 0.0f) ||
           type == LightType::Area;
  }
};

// Builders; each throws ParameterError naming the parameter, value and valid range.
// radius: metres, [0, inf).
Light point_light(const Vec3& position, const RGB& intensity_w_per_sr, float radius = 0.0f);
// Blender's point light: power P in W and a colour; I = P·colour/(4π).
Light point_light_from_power(const Vec3& position, float power_w, const RGB& color,
                             float radius = 0.0f);
// spot_size: full cone angle in radians (0, π]; spot_blend in [0, 1].
Light spot_light(const Vec3& position, const Vec3& direction, const RGB& intensity_w_per_sr,
                 float spot_size, float spot_blend, float radius = 0.0f);
Light spot_light_from_power(const Vec3& position, const Vec3& direction, float power_w,
                            const RGB& color, float spot_size, float spot_blend,
                            float radius = 0.0f);
// direction: the way the light travels (Blender's sun -Z axis); angle: full angular diameter
// in radians, [0, π).
Light sun_light(const Vec3& direction, const RGB& irradiance_w_per_m2, float angle);
// Blender's area light: centre, full edge vectors along its X and Y (size × the object's axes),
// power P in W and a colour. It emits along `normal` (the light's −Z) only. Radiance
// P·colour/(4·area), as Cycles.
Light area_light_from_power(const Vec3& centre, const Vec3& axis_u, const Vec3& axis_v,
                            const Vec3& normal, AreaShape shape, float power_w,
                            const RGB& color);

// Cycles 3.4's spot mask: cos α inside the cone, smoothed over the blend region, 0 outside.
float spot_attenuation(const Light& spot, const Vec3& dir_from_light);

// A sample of incident light at a point.
struct LightSample {
  RGB radiance;    // arriving along -wi (for delta lights: intensity/d² or irradiance)
  Vec3 wi;         // unit, from the shading point towards the light
  float distance = 0.0f;  // to the light point; infinity for the sun
  float pdf = 0.0f;       // solid angle density (1 for delta lights); 0 = no sample
  // Mesh lights: the sampled EmissiveTriangle (index in Light::triangles, or −1) and the
  // point's barycentrics of its vertices 1 and 2 (as Hit's). A textured triangle's radiance
  // here is its estimate; the caller evaluates the emission there.
  int32_t triangle = -1;
  float b1 = 0.0f, b2 = 0.0f;
};

LightSample sample_light(const Light& light, const Vec3& p, Point2 u);
// sample_light of a Mesh light: the path tracer calls it directly for the lights most scenes
// have, so that it is compiled into the light sample's caller instead of through the switch.
LightSample sample_mesh_light(const Light& light, const Vec3& p, Point2 u);

// What a ray from `origin` along unit `dir` finds on a hittable light before `tmax`: the
// radiance it receives and the solid-angle density with which sample_light picks `dir`.
struct LightHit {
  float t = 0.0f;
  RGB radiance;
  float pdf = 0.0f;
};
bool intersect_light(const Light& light, const Vec3& origin, const Vec3& dir, float tmax,
                     LightHit* hit);

// Solid-angle density of sample_light for a mesh light hit at hit_point with normal hit_normal.
float mesh_light_pdf(const Light& mesh, const Vec3& p, const Vec3& hit_point,
                     const Vec3& hit_normal);
// A sun with an angle seen by an escaped ray: its radiance and the density of sample_light.
bool sun_radiance(const Light& sun, const Vec3& dir, RGB* radiance, float* pdf);

// Emitted power in W (average over RGB) that the light sampler weights lights by; a sun's
// power counts what falls on a disk of the scene's bounding radius (pbrt's convention).
float light_power(const Light& light, float scene_radius);

}  // namespace bxdf::render
