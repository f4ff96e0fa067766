// Baking a model into numpy images, curves and meshes for display (Blender lobe textures,
// BRDF-Explorer-style plots): every pixel or vertex is one f evaluation, done through the
// core's batch API in row chunks on all cores.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <tbb/parallel_for.h>

#include <cmath>
#include <string>

#include "array_args.h"
#include "batch.h"
#include "binding_modules.h"
#include "bxdf/registry.h"
#include "model.h"

namespace bxdf::python {

namespace {

enum class Hemisphere { Upper, Lower };

Hemisphere hemisphere_argument(const std::string& h) {
  if (h == "upper") return Hemisphere::Upper;
  if (h == "lower") return Hemisphere::Lower;
  throw ParameterError("argument 'hemisphere' = '" + h + "' is not known; valid: 'upper' or 'lower'");
}

// wo given either as a vector or as (theta_o, phi_o) in degrees, never both.
Vec3 outgoing_direction(py::handle wo, py::handle theta_o, py::handle phi_o) {
  if (!wo.is_none() && !theta_o.is_none())
    throw ParameterError("give either 'wo' (a direction) or 'theta_o'/'phi_o' (degrees), not both");
  if (!wo.is_none()) return direction_argument(wo, "wo");
  if (theta_o.is_none())
    throw ParameterError("missing the outgoing direction: give 'wo' (a (3,) direction) or "
                         "'theta_o' (degrees from the normal, with 'phi_o')");
  const float theta = radians(static_cast<float>(
      number_in_range(theta_o, "theta_o", 0.0, 180.0, "[0, 180] degrees")));
  const float phi = radians(static_cast<float>(
      number_in_range(phi_o, "phi_o", -360.0, 360.0, "[-360, 360] degrees")));
  return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

// Evaluates f(wo, dir(k)) for k in [0, count) and hands each RGB to put(k, f, wi).
// dir fills a unit direction (or the zero vector for "nothing here", which f answers with 0).
template <class DirFn, class PutFn>
void eval_with_fixed_wo(const BxDF& bxdf, const Vec3& wo, size_t count, const DirFn& dir,
                        const PutFn& put) {
  SoA3 wo_s, wi_s, f_s;
  std::fill_n(wo_s.a, kChunk, wo.x);
  std::fill_n(wo_s.b, kChunk, wo.y);
  std::fill_n(wo_s.c, kChunk, wo.z);
  for (size_t begin = 0; begin < count; begin += kChunk) {
    const size_t n = std::min(kChunk, count - begin);
    for (size_t i = 0; i < n; ++i) {
      const Vec3 w = dir(begin + i);
      wi_s.a[i] = w.x;
      wi_s.b[i] = w.y;
      wi_s.c[i] = w.z;
    }
    bxdf.f_batch(n, wo_s.in(), wi_s.in(), f_s.rgb());
    for (size_t i = 0; i < n; ++i)
      put(begin + i, RGB(f_s.a[i], f_s.b[i], f_s.c[i]), Vec3(wi_s.a[i], wi_s.b[i], wi_s.c[i]));
  }
}

// Lambert azimuthal equal-area projection of the upper hemisphere onto the unit disk:
// the point (x, y) with r² = x² + y² ≤ 1 is the direction (x√(2 − r²), y√(2 − r²), 1 − r²).
// Equal areas of the disk are equal solid angles (disk area π ↔ 2π sr).
Vec3 equal_area_direction(float x, float y) {
  const float r2 = x * x + y * y;
  if (r2 > 1.0f) return Vec3();
  const float s = std::sqrt(2.0f - r2);
  return Vec3(x * s, y * s, 1.0f - r2);
}

py::array_t<float> bake_lobe_polar(const Model& model, py::handle wo_arg, py::handle res_arg,
                                   const std::string& parameterization, py::handle theta_o,
                                   py::handle phi_o, const std::string& hemisphere_name) {
  const Vec3 wo = outgoing_direction(wo_arg, theta_o, phi_o);
  const int res = int_in_range(res_arg, "resolution", 1, 4096);
  const Hemisphere hemisphere = hemisphere_argument(hemisphere_name);
  const bool equal_area = parameterization == "equal_area";
  if (!equal_area && parameterization != "lat_long")
    throw ParameterError("argument 'parameterization' = '" + parameterization +
                         "' is not known; valid: 'equal_area' or 'lat_long'");
  const size_t n = static_cast<size_t>(res);
  py::array_t<float> image({n, n, size_t{3}});
  float* pixels = image.mutable_data();
  const BxDF& bxdf = *model;
  const float inv_res = 1.0f / static_cast<float>(res);
  const float z_sign = hemisphere == Hemisphere::Upper ? 1.0f : -1.0f;
  {
    py::gil_scoped_release nogil;
    tbb::parallel_for(size_t{0}, n, [&](size_t row) {
      const float fr = (static_cast<float>(row) + 0.5f) * inv_res;
      auto dir = [&](size_t col) {
        const float fc = (static_cast<float>(col) + 0.5f) * inv_res;
        Vec3 w;
        if (equal_area) {
          w = equal_area_direction(2.0f * fc - 1.0f, 1.0f - 2.0f * fr);
        } else {
          const float theta = kPiOver2 * fr, phi = 2.0f * kPi * fc;
          w = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta));
        }
        w.z *= z_sign;
        return w;
      };
      float* out = pixels + row * n * 3;
      eval_with_fixed_wo(bxdf, wo, n, dir, [&](size_t col, const RGB& f, const Vec3& wi) {
        const float c = std::fabs(wi.z);
        out[3 * col] = f.r * c;
        out[3 * col + 1] = f.g * c;
        out[3 * col + 2] = f.b * c;
      });
    });
  }
  return image;
}

py::array_t<float> bake_slice_half_diff(const Model& model, py::handle phi_d_arg,
                                        py::handle res_arg, py::handle phi_h_arg) {
  const float phi_d = radians(static_cast<float>(
      number_in_range(phi_d_arg, "phi_d", -360.0, 360.0, "[-360, 360] degrees")));
  const float phi_h = radians(static_cast<float>(
      number_in_range(phi_h_arg, "phi_h", -360.0, 360.0, "[-360, 360] degrees")));
  const int res = int_in_range(res_arg, "resolution", 1, 4096);
  const size_t n = static_cast<size_t>(res);
  py::array_t<float> image({n, n, size_t{3}});
  float* pixels = image.mutable_data();
  const BxDF& bxdf = *model;
  const float step = kPiOver2 / static_cast<float>(res);
  const float cos_pd = std::cos(phi_d), sin_pd = std::sin(phi_d);
  const float cos_ph = std::cos(phi_h), sin_ph = std::sin(phi_h);
  {
    py::gil_scoped_release nogil;
    tbb::parallel_for(size_t{0}, n, [&](size_t row) {
      const float theta_d = (static_cast<float>(row) + 0.5f) * step;
      const Vec3 d(std::sin(theta_d) * cos_pd, std::sin(theta_d) * sin_pd, std::cos(theta_d));
      float* out = pixels + row * n * 3;
      // wi = Rz(φh) Ry(θh) d and wo = Rz(φh) Ry(θh) d', d' = d mirrored about the z axis, so
      // that the half vector of (wo, wi) is Rz(φh) Ry(θh) ẑ = (θh, φh).
      auto rotate = [&](const Vec3& v, float cos_th, float sin_th) {
        const Vec3 r(v.x * cos_th + v.z * sin_th, v.y, -v.x * sin_th + v.z * cos_th);
        return Vec3(r.x * cos_ph - r.y * sin_ph, r.x * sin_ph + r.y * cos_ph, r.z);
      };
      SoA3 wo_s, wi_s, f_s;
      for (size_t begin = 0; begin < n; begin += kChunk) {
        const size_t count = std::min(kChunk, n - begin);
        for (size_t i = 0; i < count; ++i) {
          const float theta_h = (static_cast<float>(begin + i) + 0.5f) * step;
          const float ct = std::cos(theta_h), st = std::sin(theta_h);
          const Vec3 wi = rotate(d, ct, st);
          const Vec3 wo = rotate(Vec3(-d.x, -d.y, d.z), ct, st);
          wi_s.a[i] = wi.x;
          wi_s.b[i] = wi.y;
          wi_s.c[i] = wi.z;
          wo_s.a[i] = wo.x;
          wo_s.b[i] = wo.y;
          wo_s.c[i] = wo.z;
        }
        bxdf.f_batch(count, wo_s.in(), wi_s.in(), f_s.rgb());
        scatter3(f_s, begin, count, out);
      }
    });
  }
  return image;
}

py::tuple bake_albedo_curve(const Model& model, py::handle n_theta_arg, py::handle n_samples_arg,
                            py::handle phi_o_arg, py::handle seed_arg) {
  const int n_theta = int_in_range(n_theta_arg, "n_theta", 1, 100000);
  const int n_samples = int_in_range(n_samples_arg, "n_samples", 1, 2147483647LL);
  const float phi_o = radians(static_cast<float>(
      number_in_range(phi_o_arg, "phi_o", -360.0, 360.0, "[-360, 360] degrees")));
  const uint64_t seed = static_cast<uint64_t>(int_in_range(seed_arg, "seed", 0, 2147483647LL));
  const size_t n = static_cast<size_t>(n_theta);
  py::array_t<float> theta_out(n), albedo({n, size_t{3}});
  float* theta_deg = theta_out.mutable_data();
  float* rho = albedo.mutable_data();
  const BxDF& bxdf = *model;
  {
    py::gil_scoped_release nogil;
    tbb::parallel_for(size_t{0}, n, [&](size_t k) {
      const float deg = 90.0f * (static_cast<float>(k) + 0.5f) / static_cast<float>(n);
      const float t = radians(deg);
      const Vec3 wo(std::sin(t) * std::cos(phi_o), std::sin(t) * std::sin(phi_o), std::cos(t));
      const RGB r = bxdf.rho_hd(wo, n_samples, seed);
      theta_deg[k] = deg;
      rho[3 * k] = r.r;
      rho[3 * k + 1] = r.g;
      rho[3 * k + 2] = r.b;
    });
  }
  return py::make_tuple(theta_out, albedo);
}

py::tuple lobe_mesh(const Model& model, py::handle wo_arg, py::handle res_arg, py::handle theta_o,
                    py::handle phi_o, const std::string& hemisphere_name) {
  const Vec3 wo = outgoing_direction(wo_arg, theta_o, phi_o);
  const int res = int_in_range(res_arg, "resolution", 1, 1024);
  const Hemisphere hemisphere = hemisphere_argument(hemisphere_name);
  const size_t rings = static_cast<size_t>(res), segments = 4 * rings;
  const size_t n_vertices = 1 + rings * segments;
  const size_t n_triangles = segments + 2 * segments * (rings - 1);
  py::array_t<float> vertices({n_vertices, size_t{3}});
  py::array_t<int32_t> triangles({n_triangles, size_t{3}});
  float* v = vertices.mutable_data();
  int32_t* t = triangles.mutable_data();
  const BxDF& bxdf = *model;
  const float z_sign = hemisphere == Hemisphere::Upper ? 1.0f : -1.0f;
  {
    py::gil_scoped_release nogil;
    // Vertex 0 is the pole; ring i (1..rings) at θ = (π/2) i / rings holds `segments`
    // vertices at φ = 2π j / segments, index 1 + (i - 1) segments + j.
    auto direction = [&](size_t index) {
      if (index == 0) return Vec3(0.0f, 0.0f, z_sign);
      const size_t i = (index - 1) / segments + 1, j = (index - 1) % segments;
      const float theta = kPiOver2 * static_cast<float>(i) / static_cast<float>(rings);
      const float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(segments);
      return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                  z_sign * std::cos(theta));
    };
    for_each_chunk(n_vertices, [&](size_t begin, size_t end) {
      eval_with_fixed_wo(
          bxdf, wo, end - begin, [&](size_t k) { return direction(begin + k); },
          [&](size_t k, const RGB& f, const Vec3& wi) {
            const float radius = (f * std::fabs(wi.z)).luminance();
            float* p = v + 3 * (begin + k);
            p[0] = wi.x * radius;
            p[1] = wi.y * radius;
            p[2] = wi.z * radius;
          });
    });
    // Counter-clockwise seen from outside the lobe (normals point away from the origin); the
    // lower hemisphere is mirrored, so its winding flips.
    const bool flip = hemisphere == Hemisphere::Lower;
    size_t k = 0;
    auto add = [&](size_t a, size_t b, size_t c) {
      t[3 * k] = static_cast<int32_t>(a);
      t[3 * k + 1] = static_cast<int32_t>(flip ? c : b);
      t[3 * k + 2] = static_cast<int32_t>(flip ? b : c);
      ++k;
    };
    auto at = [&](size_t ring, size_t j) { return 1 + (ring - 1) * segments + j % segments; };
    for (size_t j = 0; j < segments; ++j) add(0, at(1, j), at(1, j + 1));
    for (size_t i = 1; i < rings; ++i) {
      for (size_t j = 0; j < segments; ++j) {
        add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
    }
  }
  return py::make_tuple(vertices, triangles);
}

}  // namespace

void bind_bake(py::module_& m) {
  m.def("bake_lobe_polar", &bake_lobe_polar, py::arg("model"), py::arg("wo") = py::none(),
        py::arg("resolution") = 256, py::arg("parameterization") = "equal_area", py::kw_only(),
        py::arg("theta_o") = py::none(), py::arg("phi_o") = 0.0,
        py::arg("hemisphere") = "upper",
        R"doc(bake_lobe_polar(model, wo=None, resolution=256, parameterization="equal_area", *,
                theta_o=None, phi_o=0.0, hemisphere="upper") -> ndarray (R, R, 3) float32

The reflection lobe for one outgoing direction as an image: pixel value f(wo, wi) |cos theta_i|
(RGB) over the directions wi of a hemisphere, R = `resolution` in [1, 4096].

The outgoing direction is `wo` (a (3,) vector, normalised here) or, instead, `theta_o` (degrees
from the normal, in [0, 180]) and `phi_o` (degrees, in [-360, 360]):
wo = (sin theta_o cos phi_o, sin theta_o sin phi_o, cos theta_o).

Pixel [row, col] samples its centre: u = (col + 0.5) / R, v = (row + 0.5) / R.

- ``"equal_area"``: the hemisphere seen from above (+x to the right, +y up, row 0 at the top)
  through Lambert's azimuthal equal-area projection: x = 2u - 1, y = 1 - 2v,
  r^2 = x^2 + y^2, wi = (x sqrt(2 - r^2), y sqrt(2 - r^2), 1 - r^2); pixels outside the unit
  disk (r > 1) are 0. Every pixel covers the same solid angle, 8 / R^2 sr, so
  ``image.sum(axis=(0, 1)) * 8 / R**2`` approximates rho_hd(wo) (edge pixels are cut by the disk).
- ``"lat_long"``: theta_i = (pi/2) v down the rows (0 = normal at the top), phi_i = 2 pi u along
  the columns. A pixel covers sin(theta_i) (pi/2)(2 pi) / R^2 sr.

`hemisphere` = "upper" samples wi with z > 0; "lower" mirrors the grid to z < 0 (transmission).)doc");

  m.def("bake_slice_half_diff", &bake_slice_half_diff, py::arg("model"), py::arg("phi_d") = 90.0,
        py::arg("resolution") = 256, py::kw_only(), py::arg("phi_h") = 0.0,
        R"doc(bake_slice_half_diff(model, phi_d=90.0, resolution=256, *, phi_h=0.0)
    -> ndarray (R, R, 3) float32

BRDF Explorer's "image slice": f (RGB, no cosine) over Rusinkiewicz's half/difference angles at a
fixed difference azimuth phi_d (degrees, in [-360, 360]) and half-vector azimuth phi_h (degrees;
matters for anisotropic models only). R = `resolution` in [1, 4096].

Pixel [row, col] has theta_d = (pi/2)(row + 0.5)/R and theta_h = (pi/2)(col + 0.5)/R: theta_h
grows along a row, theta_d down the rows (row 0 is theta_d near 0; Blender, whose image rows go
bottom-up, shows theta_d = 0 at the bottom, as BRDF Explorer does). With
d = (sin theta_d cos phi_d, sin theta_d sin phi_d, cos theta_d) and R_h = Rz(phi_h) Ry(theta_h):
wi = R_h d and wo = R_h (-d_x, -d_y, d_z), so that (wo + wi) points along the half vector
(theta_h, phi_h). Directions below the horizon give whatever the model gives (0 for reflection).)doc");

  m.def("bake_albedo_curve", &bake_albedo_curve, py::arg("model"), py::arg("n_theta") = 90,
        py::arg("n_samples") = 4096, py::kw_only(), py::arg("phi_o") = 0.0, py::arg("seed") = 0,
        R"doc(bake_albedo_curve(model, n_theta=90, n_samples=4096, *, phi_o=0.0, seed=0)
    -> (theta_o (n_theta,) float32 degrees, albedo (n_theta, 3) float32)

Directional albedo rho_hd against the outgoing zenith angle: theta_o[k] = 90 (k + 0.5) / n_theta
degrees (cell centres, so never exactly grazing), at azimuth phi_o (degrees), and
albedo[k] = model.rho(wo_k, n_samples, seed). n_theta in [1, 100000], n_samples in
[1, 2147483647]. Angles run in parallel.)doc");

  m.def("lobe_mesh", &lobe_mesh, py::arg("model"), py::arg("wo") = py::none(),
        py::arg("resolution") = 32, py::kw_only(), py::arg("theta_o") = py::none(),
        py::arg("phi_o") = 0.0, py::arg("hemisphere") = "upper",
        R"doc(lobe_mesh(model, wo=None, resolution=32, *, theta_o=None, phi_o=0.0, hemisphere="upper")
    -> (vertices (V, 3) float32, triangles (T, 3) int32)

A 3D polar plot of the lobe for the outgoing direction `wo` (or theta_o/phi_o in degrees, as in
bake_lobe_polar): the vertex for direction wi is wi * L(f(wo, wi) |cos theta_i|), with L the
Rec.709 luminance of the RGB value.

Grid: with n = `resolution` (in [1, 1024]) rings and 4n segments, vertex 0 is the pole and
vertex 1 + (i - 1) 4n + j is at theta = (pi/2) i / n, phi = 2 pi j / (4n), i = 1..n, j = 0..4n-1;
so V = 1 + 4n^2 and T = 4n + 8n(n - 1). Triangles wind counter-clockwise seen from outside.
`hemisphere` = "lower" mirrors the grid to z < 0 (transmission lobes).)doc");
}

}  // namespace bxdf::python
