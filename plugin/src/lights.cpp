#include "bxdf/render/lights.h"

#include <algorithm>
#include <limits>
#include <string>

#include "bxdf/frame.h"
#include "bxdf/params.h"
#include "bxdf/sampling.h"

namespace bxdf::render {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

std::string str(float v) { return std::to_string(v); }

void require_finite_point(const char* what, const Vec3& p) {
  if (!is_finite(p)) throw ParameterError(std::string(what) + " position must be finite");
}

Vec3 require_direction(const char* what, Vec3 d) {
  if (!normalize_direction(d))
    throw ParameterError(std::string(what) + " direction must be a non-zero finite vector");
  return d;
}

void require_colour(const char* what, const char* name, const RGB& c) {
  if (!finite_nonnegative(c))
    throw ParameterError(std::string(what) + " " + name + " (" + str(c.r) + ", " + str(c.g) +
                         ", " + str(c.b) + ") must be in [0, inf) per channel");
}

float smoothstep(float edge0, float edge1, float x) {
  const float t = clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace

Light point_light(const Vec3& position, const RGB& intensity) {
  require_finite_point("point light", position);
  require_colour("point light", "intensity", intensity);
  Light l;
  l.type = LightType::Point;
  l.position = position;
  l.intensity = intensity;
  return l;
}

Light point_light_from_power(const Vec3& position, float power_w, const RGB& color) {
  if (!(power_w >= 0.0f) || !std::isfinite(power_w))
    throw ParameterError("point light power " + str(power_w) + " must be in [0, inf) W");
  require_colour("point light", "color", color);
  return point_light(position, color * (power_w * kInv4Pi));
}

Light spot_light(const Vec3& position, const Vec3& direction, const RGB& intensity,
                 float spot_size, float spot_blend) {
  require_finite_point("spot light", position);
  require_colour("spot light", "intensity", intensity);
  if (!(spot_size > 0.0f && spot_size <= kPi))
    throw ParameterError("spot light spot_size " + str(spot_size) + " must be in (0, pi] radians");
  if (!(spot_blend >= 0.0f && spot_blend <= 1.0f))
    throw ParameterError("spot light spot_blend " + str(spot_blend) + " must be in [0, 1]");
  Light l;
  l.type = LightType::Spot;
  l.position = position;
  l.direction = require_direction("spot light", direction);
  l.intensity = intensity;
  // As Blender hands them to Cycles: cos of the half angle, and the blend band in cosine.
  l.cos_half_spot = std::cos(0.5f * spot_size);
  l.spot_smooth = (1.0f - l.cos_half_spot) * spot_blend;
  return l;
}

Light spot_light_from_power(const Vec3& position, const Vec3& direction, float power_w,
                            const RGB& color, float spot_size, float spot_blend) {
  if (!(power_w >= 0.0f) || !std::isfinite(power_w))
    throw ParameterError("spot light power " + str(power_w) + " must be in [0, inf) W");
  require_colour("spot light", "color", color);
  return spot_light(position, direction, color * (power_w * kInv4Pi), spot_size, spot_blend);
}

Light sun_light(const Vec3& direction, const RGB& irradiance, float angle) {
  require_colour("sun light", "irradiance", irradiance);
  if (!(angle >= 0.0f && angle < kPiOver2))
    throw ParameterError("sun light angle " + str(angle) + " must be in [0, pi/2) radians");
  Light l;
  l.type = LightType::Sun;
  l.direction = require_direction("sun light", direction);
  l.irradiance = irradiance;
  l.cos_sun_max = std::cos(0.5f * angle);
  if (angle > 0.0f) {
    // Uniform radiance over a cone of half-angle θ gives irradiance L·π·sin²θ at normal incidence.
    const float s = std::sin(0.5f * angle);
    l.radiance = irradiance / (kPi * s * s);
  } else {
    l.cos_sun_max = 1.0f;
  }
  return l;
}

Light world_light(const RGB& radiance) {
  require_colour("world", "color", radiance);
  Light l;
  l.type = LightType::World;
  l.radiance = radiance;
  return l;
}

float spot_attenuation(const Light& spot, const Vec3& dir_from_light) {
  // Cycles 3.4 (spot_light_attenuation): the cosine to the axis itself, zero outside the cone,
  // times a smoothstep across the blend band just inside the edge.
  float a = dot(dir_from_light, spot.direction);
  if (a <= spot.cos_half_spot) return 0.0f;
  const float t = a - spot.cos_half_spot;
  if (spot.spot_smooth > 0.0f && t < spot.spot_smooth) a *= smoothstep(0.0f, spot.spot_smooth, t);
  return a;
}

LightSample sample_light(const Light& light, const Vec3& p, Point2 u) {
  LightSample s;
  switch (light.type) {
    case LightType::Point:
    case LightType::Spot: {
      Vec3 d = light.position - p;
      const float d2 = length_squared(d);
      if (!(d2 > 0.0f)) return s;
      s.distance = std::sqrt(d2);
      s.wi = d / s.distance;
      float atten = 1.0f;
      if (light.type == LightType::Spot) atten = spot_attenuation(light, -s.wi);
      s.radiance = light.intensity * (atten / d2);
      s.pdf = 1.0f;
      return s;
    }
    case LightType::Sun: {
      s.distance = kInfinity;
      if (light.cos_sun_max >= 1.0f) {
        s.wi = -light.direction;
        s.radiance = light.irradiance;
        s.pdf = 1.0f;
        return s;
      }
      const Frame f = Frame::from_normal(-light.direction);
      s.wi = f.to_world(sample_uniform_cone(u, light.cos_sun_max));
      s.radiance = light.radiance;
      s.pdf = uniform_cone_pdf(light.cos_sun_max);
      return s;
    }
    case LightType::World: {
      s.distance = kInfinity;
      s.wi = sample_uniform_sphere(u);
      s.radiance = light.radiance;
      s.pdf = uniform_sphere_pdf();
      return s;
    }
    case LightType::Area: {
      if (light.triangles.empty() || !(light.total_area > 0.0f)) return s;
      // Pick a triangle by area with u.x, then reuse the rest of u.x for the point.
      const float target = u.x * light.total_area;
      const size_t i = std::min<size_t>(
          static_cast<size_t>(std::upper_bound(light.cdf.begin(), light.cdf.end(), target) -
                              light.cdf.begin()),
          light.triangles.size() - 1);
      const EmissiveTriangle& tri = light.triangles[i];
      const float lo = i == 0 ? 0.0f : light.cdf[i - 1];
      float ux = tri.area > 0.0f ? (target - lo) / tri.area : 0.5f;
      ux = clamp(ux, 0.0f, 0x1.fffffep-1f);
      // Uniform point on the triangle (square-root parametrisation).
      const float su = std::sqrt(ux);
      const float b1 = 1.0f - su, b2 = u.y * su;
      const Vec3 q = tri.p0 + tri.e1 * b1 + tri.e2 * b2;
      const Vec3 d = q - p;
      const float d2 = length_squared(d);
      if (!(d2 > 0.0f)) return s;
      s.distance = std::sqrt(d2);
      s.wi = d / s.distance;
      const float cos_light = std::fabs(dot(tri.normal, s.wi));
      if (!(cos_light > 0.0f)) return s;
      s.radiance = tri.radiance;
      s.pdf = d2 / (cos_light * light.total_area);
      return s;
    }
  }
  return s;
}

float area_light_pdf(const Light& area, const Vec3& p, const Vec3& hit_point,
                     const Vec3& hit_normal) {
  const Vec3 d = hit_point - p;
  const float d2 = length_squared(d);
  if (!(d2 > 0.0f) || !(area.total_area > 0.0f)) return 0.0f;
  const float cos_light = std::fabs(dot(hit_normal, d)) / std::sqrt(d2);
  if (!(cos_light > 0.0f)) return 0.0f;
  return d2 / (cos_light * area.total_area);
}

float environment_pdf(const Light& light, const Vec3& wi) {
  if (light.type == LightType::World) return uniform_sphere_pdf();
  if (light.type == LightType::Sun && light.cos_sun_max < 1.0f &&
      dot(wi, -light.direction) > light.cos_sun_max)
    return uniform_cone_pdf(light.cos_sun_max);
  return 0.0f;
}

RGB environment_radiance(const Light& light, const Vec3& wi) {
  if (light.type == LightType::World) return light.radiance;
  if (light.type == LightType::Sun && light.cos_sun_max < 1.0f &&
      dot(wi, -light.direction) > light.cos_sun_max)
    return light.radiance;
  return RGB(0.0f);
}

}  // namespace bxdf::render
