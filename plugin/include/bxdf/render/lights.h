// Lights in Blender's units. Point and spot lights have radius 0 and a radiant intensity I in
// W/sr (Blender: I = P·colour/(4π) for power P in W); a spot adds Cycles 3.4's cone mask from
// spot_size and spot_blend. A sun gives irradiance E in W/m² on a surface facing it, either from
// one direction (angle 0) or from a small cone of uniform radiance. Area lights are emissive
// triangles (two-sided, as an emission shader on a mesh in Cycles), and the world is a constant
// radiance from every direction.
//
// All kinds live in one tagged struct and are sampled through a switch, so the per-sample
// path has no virtual calls.
#pragma once

#include <cstdint>
#include <vector>

#include "bxdf/math.h"
#include "bxdf/spectrum.h"

namespace bxdf::render {

enum class LightType { Point, Spot, Sun, Area, World };

// One emissive triangle of an area light.
struct EmissiveTriangle {
  Vec3 p0, e1, e2;  // p0, p1 - p0, p2 - p0
  Vec3 normal;      // unit, cross(e1, e2) direction
  RGB radiance;
  float area = 0.0f;
};

struct Light {
  LightType type = LightType::Point;
  Vec3 position;           // point, spot
  Vec3 direction{0, 0, -1};  // spot axis / direction sunlight travels (unit)
  RGB intensity;           // point, spot: W/sr
  RGB irradiance;          // sun: W/m² at normal incidence
  RGB radiance;            // sun with a cone: E / (π sin²θmax); world: its radiance
  float cos_half_spot = -1.0f;  // spot: cos(spot_size / 2)
  float spot_smooth = 0.0f;     // spot: (1 - cos_half_spot) · spot_blend
  float cos_sun_max = 1.0f;     // sun: cos(angle / 2); 1 for a delta sun
  // Area: its triangles and their area CDF (cdf.back() == total area).
  std::vector<EmissiveTriangle> triangles;
  std::vector<float> cdf;
  float total_area = 0.0f;

  bool is_delta() const {
    return type == LightType::Point || type == LightType::Spot ||
           (type == LightType::Sun && cos_sun_max >= 1.0f);
  }
};

// Builders; each throws ParameterError naming the parameter, value and valid range.
Light point_light(const Vec3& position, const RGB& intensity_w_per_sr);
// Blender's point light: power P in W and a colour; I = P·colour/(4π).
Light point_light_from_power(const Vec3& position, float power_w, const RGB& color);
// spot_size: full cone angle in radians (0, π]; spot_blend in [0, 1].
Light spot_light(const Vec3& position, const Vec3& direction, const RGB& intensity_w_per_sr,
                 float spot_size, float spot_blend);
Light spot_light_from_power(const Vec3& position, const Vec3& direction, float power_w,
                            const RGB& color, float spot_size, float spot_blend);
// direction: the way the light travels (Blender's sun -Z axis); angle: full angular diameter
// in radians, [0, π/2).
Light sun_light(const Vec3& direction, const RGB& irradiance_w_per_m2, float angle);
Light world_light(const RGB& radiance);

// Cycles 3.4's spot mask: cos α inside the cone, smoothed over the blend region, 0 outside.
float spot_attenuation(const Light& spot, const Vec3& dir_from_light);

// A sample of incident light at a point.
struct LightSample {
  RGB radiance;    // arriving along -wi (for delta lights: intensity/d² or irradiance)
  Vec3 wi;         // unit, from the shading point towards the light
  float distance = 0.0f;  // to the light point; infinity for sun and world
  float pdf = 0.0f;       // solid angle density (1 for delta lights); 0 = no sample
};

LightSample sample_light(const Light& light, const Vec3& p, Point2 u);

// Solid-angle density with which sample_light picks direction wi from p, for a direction that
// reaches the light (hit point on an area light, or an escaped ray for sun and world).
float area_light_pdf(const Light& area, const Vec3& p, const Vec3& hit_point,
                     const Vec3& hit_normal);
float environment_pdf(const Light& light, const Vec3& wi);
// Radiance an escaped ray in direction wi receives from a sun (within its cone) or the world.
RGB environment_radiance(const Light& light, const Vec3& wi);

}  // namespace bxdf::render
