#include "bxdf/render/lights.h"

#include <algorithm>
#include <limits>
#include <string>

#include "bxdf/frame.h"
#include "bxdf/params.h"
#include "bxdf/render/cdf_search.h"
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

void require_power(const char* what, float power_w) {
  if (!(power_w >= 0.0f) || !std::isfinite(power_w))
    throw ParameterError(std::string(what) + " power " + str(power_w) + " must be in [0, inf) W");
}

void set_radius(Light& l, const char* what, float radius) {
  if (!(radius >= 0.0f) || !std::isfinite(radius))
    throw ParameterError(std::string(what) + " radius " + str(radius) + " must be in [0, inf) m");
  l.radius = radius;
  if (radius > 0.0f) {
    l.inv_area = 1.0f / (kPi * radius * radius);
    l.radiance = l.intensity * l.inv_area;  // I = L·π r²: the disk's intensity towards any point
  }
}

float smoothstep(float edge0, float edge1, float x) {
  const float t = clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// Cycles' lamp_light_pdf: area density → solid angle, for a surface with normal n seen along
// `to_point` (unit, from the light towards the shading point) at distance t.
float area_to_solid_angle(const Vec3& n, const Vec3& to_point, float t) {
  const float cos_light = dot(n, to_point);
  return cos_light > 0.0f ? t * t / cos_light : 0.0f;
}

// A point uniformly on the disk of radius r centred at c and facing n.
Vec3 sample_disk(const Vec3& c, const Vec3& n, float r, Point2 u) {
  Vec3 s, t;
  coordinate_system(n, &s, &t);
  const Point2 d = sample_concentric_disk(u);
  return c + (s * d.x + t * d.y) * r;
}

// The disk facing the shading point (point and spot lights with a radius): hit distance of the
// ray origin + t·dir, t in (0, tmax), or a negative value.
float intersect_facing_disk(const Vec3& centre, float radius, const Vec3& origin,
                            const Vec3& dir, float tmax) {
  Vec3 n = origin - centre;
  if (!normalize_direction(n)) return -1.0f;
  const float cos_dir = dot(dir, n);
  if (!(cos_dir < 0.0f)) return -1.0f;
  const float t = dot(centre - origin, n) / cos_dir;
  if (!(t > 0.0f && t < tmax)) return -1.0f;
  const Vec3 q = origin + dir * t - centre;
  return length_squared(q) <= radius * radius ? t : -1.0f;
}

}  // namespace

Light point_light(const Vec3& position, const RGB& intensity, float radius) {
  require_finite_point("point light", position);
  require_colour("point light", "intensity", intensity);
  Light l;
  l.type = LightType::Point;
  l.position = position;
  l.intensity = intensity;
  set_radius(l, "point light", radius);
  return l;
}

Light point_light_from_power(const Vec3& position, float power_w, const RGB& color,
                             float radius) {
  require_power("point light", power_w);
  require_colour("point light", "color", color);
  return point_light(position, color * (power_w * kInv4Pi), radius);
}

Light spot_light(const Vec3& position, const Vec3& direction, const RGB& intensity,
                 float spot_size, float spot_blend, float radius) {
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
  set_radius(l, "spot light", radius);
  return l;
}

Light spot_light_from_power(const Vec3& position, const Vec3& direction, float power_w,
                            const RGB& color, float spot_size, float spot_blend, float radius) {
  require_power("spot light", power_w);
  require_colour("spot light", "color", color);
  return spot_light(position, direction, color * (power_w * kInv4Pi), spot_size, spot_blend,
                    radius);
}

Light sun_light(const Vec3& direction, const RGB& irradiance, float angle) {
  require_colour("sun light", "irradiance", irradiance);
  if (!(angle >= 0.0f && angle < kPi))
    throw ParameterError("sun light angle " + str(angle) + " must be in [0, pi) radians");
  Light l;
  l.type = LightType::Sun;
  l.direction = require_direction("sun light", direction);
  l.irradiance = irradiance;
  if (angle > 0.0f) {
    l.radius = std::tan(0.5f * angle);
    l.inv_area = 1.0f / (kPi * l.radius * l.radius);
    l.cos_sun_max = std::cos(0.5f * angle);
  }
  return l;
}

Light area_light_from_power(const Vec3& centre, const Vec3& axis_u, const Vec3& axis_v,
                            const Vec3& normal, AreaShape shape, float power_w,
                            const RGB& color) {
  require_finite_point("area light", centre);
  require_power("area light", power_w);
  require_colour("area light", "color", color);
  if (!is_finite(axis_u) || !is_finite(axis_v))
    throw ParameterError("area light size must be finite");
  Light l;
  l.type = LightType::Area;
  l.position = centre;
  l.axis_u = axis_u;
  l.axis_v = axis_v;
  l.rectangle = SphericalRectangle(centre, axis_u, axis_v);
  l.direction = require_direction("area light", normal);
  l.shape = shape;
  const float area = length(axis_u) * length(axis_v) * (shape == AreaShape::Ellipse ? kPi / 4 : 1);
  if (!(area > 0.0f))
    throw ParameterError("area light size (" + str(length(axis_u)) + ", " + str(length(axis_v)) +
                         ") must be in (0, inf) m per axis");
  l.inv_area = 1.0f / area;
  l.radiance = color * (power_w * 0.25f * l.inv_area);
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

LightSample sample_mesh_light(const Light& light, const Vec3& p, Point2 u) {
  LightSample s;
  if (light.triangles.empty() || !(light.total_area > 0.0f)) return s;
  // Pick a triangle by area with u.x, then reuse the rest of u.x for the point.
  const float target = u.x * light.total_area;
  const size_t i = std::min(first_above(light.cdf, target), light.triangles.size() - 1);
  const EmissiveTriangle& tri = light.triangles[i];
  const float lo = i == 0 ? 0.0f : light.cdf[i - 1];
  const float ux = into_unit_interval((target - lo) * tri.inv_area);
  // Uniform point on the triangle (square-root parametrisation).
  const float su = std::sqrt(ux);
  const float b1 = 1.0f - su, b2 = u.y * su;
  const Vec3 q = tri.p0 + tri.e1 * b1 + tri.e2 * b2;
  const Vec3 d = q - p;
  const float d2 = length_squared(d);
  if (!(d2 > 0.0f)) return s;
  s.distance = std::sqrt(d2);
  s.wi = d / s.distance;
  // The light's cosine times the distance, from d itself: the pdf's division then runs beside
  // the direction's instead of after it.
  const float cos_light_distance = std::fabs(dot(tri.normal, d));
  if (!(cos_light_distance > 0.0f)) return s;
  s.radiance = tri.radiance;
  s.pdf = d2 * s.distance / (cos_light_distance * light.total_area);
  s.triangle = static_cast<int32_t>(i);
  s.b1 = b1;
  s.b2 = b2;
  return s;
}

LightSample sample_light(const Light& light, const Vec3& p, Point2 u) {
  LightSample s;
  switch (light.type) {
    case LightType::Point:
    case LightType::Spot: {
      Vec3 q = light.position;
      if (light.radius > 0.0f) {
        Vec3 n = p - light.position;
        if (!normalize_direction(n)) return s;
        q = sample_disk(light.position, n, light.radius, u);
      }
      const Vec3 d = q - p;
      const float d2 = length_squared(d);
      if (!(d2 > 0.0f)) return s;
      s.distance = std::sqrt(d2);
      s.wi = d / s.distance;
      const float atten = light.type == LightType::Spot ? spot_attenuation(light, -s.wi) : 1.0f;
      if (!(atten > 0.0f)) return s;
      if (light.radius == 0.0f) {
        s.radiance = light.intensity * (atten / d2);
        s.pdf = 1.0f;
        return s;
      }
      Vec3 n = p - light.position;
      normalize_direction(n);
      s.pdf = light.inv_area * area_to_solid_angle(n, -s.wi, s.distance);
      s.radiance = light.radiance * atten;
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
      // A disk of radius tan(angle/2) at unit distance: density inv_area/cos³θ in solid angle,
      // and radiance E times that density (Cycles' eval_fac = pdf).
      Vec3 wi = sample_disk(-light.direction, -light.direction, light.radius, u);
      if (!normalize_direction(wi)) return s;
      const float c = dot(wi, -light.direction);
      s.wi = wi;
      s.pdf = light.inv_area / (c * c * c);
      s.radiance = light.irradiance * s.pdf;
      return s;
    }
    case LightType::Area: {
      // One-sided: points behind the light get nothing.
      if (dot(light.position - p, light.direction) > 0.0f) return s;
      Vec3 q;
      if (light.shape == AreaShape::Rectangle) {
        s.pdf = light.rectangle.sample(p, u, &q);
      } else {
        const Point2 d = sample_concentric_disk(u);
        q = light.position + light.axis_u * (0.5f * d.x) + light.axis_v * (0.5f * d.y);
      }
      const Vec3 d = q - p;
      const float d2 = length_squared(d);
      if (!(d2 > 0.0f)) return LightSample{};
      s.distance = std::sqrt(d2);
      s.wi = d / s.distance;
      if (light.shape == AreaShape::Ellipse)
        s.pdf = light.inv_area * area_to_solid_angle(light.direction, -s.wi, s.distance);
      if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return LightSample{};
      s.radiance = light.radiance;
      return s;
    }
    case LightType::Mesh:
      return sample_mesh_light(light, p, u);
  }
  return s;
}

bool intersect_light(const Light& light, const Vec3& origin, const Vec3& dir, float tmax,
                     LightHit* hit) {
  if (light.type == LightType::Point || light.type == LightType::Spot) {
    if (!(light.radius > 0.0f)) return false;
    const float t = intersect_facing_disk(light.position, light.radius, origin, dir, tmax);
    if (!(t > 0.0f)) return false;
    float atten = light.type == LightType::Spot ? spot_attenuation(light, -dir) : 1.0f;
    if (!(atten > 0.0f)) return false;
    Vec3 n = origin - light.position;
    normalize_direction(n);
    hit->t = t;
    hit->radiance = light.radiance * atten;
    hit->pdf = light.inv_area * area_to_solid_angle(n, -dir, t);
    return true;
  }
  if (light.type != LightType::Area) return false;
  const float cos_dir = dot(dir, light.direction);
  if (!(cos_dir < 0.0f)) return false;  // one-sided
  const float t = dot(light.position - origin, light.direction) / cos_dir;
  if (!(t > 0.0f && t < tmax)) return false;
  const Vec3 q = origin + dir * t - light.position;
  const float x = 2.0f * dot(q, light.axis_u) / length_squared(light.axis_u);
  const float y = 2.0f * dot(q, light.axis_v) / length_squared(light.axis_v);
  const bool inside = light.shape == AreaShape::Ellipse ? x * x + y * y <= 1.0f
                                                        : std::fabs(x) <= 1.0f && std::fabs(y) <= 1.0f;
  if (!inside) return false;
  hit->t = t;
  hit->radiance = light.radiance;
  hit->pdf = light.shape == AreaShape::Ellipse
                 ? light.inv_area * area_to_solid_angle(light.direction, -dir, t)
                 : light.rectangle.pdf(origin);
  return hit->pdf > 0.0f && std::isfinite(hit->pdf);
}

float mesh_light_pdf(const Light& mesh, const Vec3& p, const Vec3& hit_point,
                     const Vec3& hit_normal) {
  const Vec3 d = hit_point - p;
  const float d2 = length_squared(d);
  if (!(d2 > 0.0f) || !(mesh.total_area > 0.0f)) return 0.0f;
  const float cos_light = std::fabs(dot(hit_normal, d)) / std::sqrt(d2);
  if (!(cos_light > 0.0f)) return 0.0f;
  return d2 / (cos_light * mesh.total_area);
}

bool sun_radiance(const Light& sun, const Vec3& dir, RGB* radiance, float* pdf) {
  if (sun.type != LightType::Sun || sun.cos_sun_max >= 1.0f) return false;
  const float c = dot(dir, -sun.direction);
  if (!(c >= sun.cos_sun_max)) return false;
  *pdf = sun.inv_area / (c * c * c);
  *radiance = sun.irradiance * *pdf;
  return true;
}

float light_power(const Light& light, float scene_radius) {
  switch (light.type) {
    case LightType::Point: return 4.0f * kPi * light.intensity.average();
    case LightType::Spot:
      // The cone's solid angle (to the outer edge; the mask's cosine is ignored).
      return 2.0f * kPi * (1.0f - light.cos_half_spot) * light.intensity.average();
    case LightType::Sun: return kPi * scene_radius * scene_radius * light.irradiance.average();
    case LightType::Area: return kPi * light.radiance.average() / light.inv_area;
    case LightType::Mesh: {
      float p = 0.0f;
      // Negative emission (Cycles' light taken away) is sampled by its magnitude.
      for (const EmissiveTriangle& t : light.triangles) p += std::fabs(t.radiance.average()) * t.area;
      return 2.0f * kPi * p;  // two-sided
    }
  }
  return 0.0f;
}

}  // namespace bxdf::render
