#include "bxdf/render/integrator.h"

#include <algorithm>
#include <limits>
#include <new>
#include <string>
#include <type_traits>

#include "bxdf/lone_diffuse.h"
#include "bxdf/microfacet/multiscatter_ggx.h"
#include "bxdf/models/cycles_transparent.h"
#include "bxdf/params.h"
#include "bxdf/render/textured_emission.h"
#include "bxdf/render/valid_reflection.h"
#include "bxdf/sampling.h"
#include "sampler/path_sampler.h"

namespace bxdf::render {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// What a material graph needs per hit, reused along a path without touching the heap: per
// thread, made once (the arena is reset at every hit).
struct ShadingScratch {
  Vec3 registers[MaterialGraph::kMaxRegisters];
  ClosureArena arena;
};
ShadingScratch& shading_scratch() {
  thread_local ShadingScratch scratch;
  return scratch;
}

// Distance by which a new ray starts off the surface, relative to the coordinates' size: the
// hit point comes from barycentrics, accurate to a few ulps, so ~250 ulps is safe.
float offset_scale(const Vec3& p) {
  return 3e-5f * (1.0f + std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z))));
}

// Moves p off the surface along the geometric normal, to the side that `dir` leaves towards.
// Inline, the side a select (the same bits as p - ng·eps): GCC kept it out of line, its
// arguments passed on the stack, at both rays of every path vertex.
[[gnu::always_inline]] inline Vec3 offset_origin(const Vec3& p, const Vec3& ng, const Vec3& dir) {
  const float eps = offset_scale(p);
  return p + ng * (dot(dir, ng) >= 0.0f ? eps : -eps);
}

// The normal Cycles' closures shade with, turned to the side wo is on as Cycles' shader setup
// turns it on back faces (here transmissive surfaces keep their orientation, which tells inside
// from outside): the shading normal bent until the view's mirror direction clears the surface.
Vec3 viewer_side_normal(const SurfacePoint& sp, const Vec3& wo) {
  const float side = dot(wo, sp.ng) < 0.0f ? -1.0f : 1.0f;
  return ensure_valid_reflection(sp.ng * side, wo, sp.ns * side);
}

}  // namespace

PathTracer::PathTracer(const Scene& scene, const IntegratorSettings& settings)
    : scene_(scene),
      settings_(settings),
      transparent_shadows_(scene, std::max(settings.transparent_max_bounces, 0)) {
  if (!scene.committed()) throw ParameterError("PathTracer: the scene is not committed");
  if (settings.max_bounces < 0)
    throw ParameterError("max_bounces " + std::to_string(settings.max_bounces) +
                         " must be in [0, inf)");
  if (settings.russian_roulette_depth < 0)
    throw ParameterError("russian_roulette_depth must be in [0, inf)");
  if (settings.transparent_max_bounces < 0)
    throw ParameterError("transparent_max_bounces " +
                         std::to_string(settings.transparent_max_bounces) + " must be in [0, inf)");
  plain_diffuse_.resize(scene.materials().size());
  for (size_t i = 0; i < plain_diffuse_.size(); ++i) {
    const Material& m = scene.materials()[i];
    PlainDiffuse& d = plain_diffuse_[i];
    d.lone = !m.graph && m.components.size() == 1 &&
             LoneDiffuse::constant_f(*m.components[0], RGB(1.0f), &d.f);
  }
}

template <class Scattering>
RGB PathTracer::sample_one_light(const Hit& hit, const SurfacePoint& sp, const Scattering& bsdf,
                                 const Vec3& wo, LightReceiver& receiver,
                                 const PathSampler& path_sampler, int vertex,
                                 int transparent_bounces, PathStats& stats,
                                 PendingShadow* deferred) const {
  const LightSampler& sampler = scene_.light_sampler();
  if (sampler.empty()) return RGB(0.0f);
  const Point2 u = path_sampler.light(vertex);
  const auto& lights = scene_.lights();
  float select = 0.0f;
  float u1 = 0.0f;
  const size_t index = sampler.sample(receiver, u.x, &select, &u1);
  if (!(select > 0.0f)) return RGB(0.0f);  // no light can reach this point
  const float u2 = u.y;
  const Light* light = index < lights.size() ? &lights[index] : nullptr;
  // Made in place (initialised by the call, not assigned from a temporary): copying the
  // returned sample read it back in 16-byte pieces over the callee's 4-byte stores, a
  // store-forwarding stall that perf annotate put at ~20% of this function's samples.
  const Point2 u_light(u1, u2);
  LightSample ls = !light                          ? world_light_sample(u1, u2)
                   : light->type == LightType::Mesh ? sample_mesh_light(*light, sp.p, u_light)
                                                    : sample_light(*light, sp.p, u_light);
  if (light) {
    if (ls.triangle >= 0 && ls.pdf > 0.0f && light->triangles[size_t(ls.triangle)].textured) {
      // Textured emission: the material's emission where the sample landed, seen from here.
      thread_local Vec3 registers[MaterialGraph::kMaxRegisters];
      Hit at;
      at.mesh = light->mesh;
      at.instance = light->instance;
      at.triangle = light->triangles[size_t(ls.triangle)].triangle;
      at.b1 = light->mirrored ? ls.b2 : ls.b1;
      at.b2 = light->mirrored ? ls.b1 : ls.b2;
      at.t = ls.distance;
      ls.radiance = textured_emission(scene_, at, -ls.wi, registers);
    }
  }
  if (!(ls.pdf > 0.0f) || ls.radiance.is_black()) return RGB(0.0f);
  // Lights BSDF rays cannot find (delta, or Multiple Importance off) are counted in full; the
  // others are weighed against the BSDF's pdf, evaluated with f in one pass.
  const bool counted_fully = light && (light->is_delta() || !light->visibility.use_mis);
  float bsdf_pdf = 0.0f;
  // Each closure's cosine against its own (mapped) normal.
  RGB f = counted_fully ? bsdf.f_cos(wo, ls.wi) : bsdf.f_cos_pdf(wo, ls.wi, &bsdf_pdf);
  if (f.is_black()) return RGB(0.0f);
  const TerminatorOffsets& terminator = scene_.terminator(hit.mesh);
  // The shading offset dims the viewer's side only: light through a transmissive surface is not
  // rescaled (Cycles' bsdf_eval).
  const float cos_in = dot(ls.wi, receiver.n);
  if (cos_in >= 0.0f) f *= shading_offset_factor(cos_in, terminator.shading);

  if (!light || light->visibility.cast_shadow) {
    Vec3 p = sp.p;
    SmoothTriangle tri;
    // The triangle is fetched only for the few light directions near the terminator.
    if (terminator_offset_amount(sp.ns, sp.ng, ls.wi, terminator.geometry) > 0.0f &&
        scene_.smooth_triangle(hit, &tri)) {
      bool lifted = false;
      p = terminator_shadow_origin(tri, hit.b1, hit.b2, sp.p, sp.ns, sp.ng, ls.wi,
                                   terminator.geometry, &lifted);
    }
    const Vec3 origin = offset_origin(p, sp.ng, ls.wi);
    Vec3 dir = ls.wi;
    float tmax = kInfinity;
    if (std::isfinite(ls.distance)) {
      // Aim from the (possibly lifted) origin at the light point, stopping short of the light's
      // own surface (mesh lights) by a little more than the offset.
      const Vec3 d = sp.p + ls.wi * ls.distance - origin;
      const float dist = length(d);
      if (!(dist > 0.0f)) return RGB(0.0f);
      dir = d / dist;
      tmax = std::max(0.0f, dist * (1.0f - 1e-4f) - 2.0f * offset_scale(sp.p));
    }
    ++stats.shadow_rays;
    if (deferred && !transparent_shadows_.any()) {
      // Plain occlusion, tested by the caller (an unblocked ray's f *= 1 changes no bit).
      deferred->origin = origin;
      deferred->dir = dir;
      deferred->tmax = tmax;
      deferred->active = true;
    } else {
      const RGB visible = transparent_shadows_.throughput(origin, dir, tmax, transparent_bounces);
      if (visible.is_black()) return RGB(0.0f);
      f *= visible;
    }
  }

  const float light_pdf = ls.pdf * select;
  if (counted_fully) return f * ls.radiance / light_pdf;
  return f * ls.radiance * (power_heuristic(1.0f, light_pdf, 1.0f, bsdf_pdf) / light_pdf);
}

LightSample PathTracer::world_light_sample(float u1, float u2) const {
  LightSample ls;
  ls.wi = scene_.world().sample(Point2(u1, u2), &ls.pdf);
  ls.distance = kInfinity;
  if (ls.pdf > 0.0f) ls.radiance = scene_.world().eval(ls.wi);
  return ls;
}

RGB PathTracer::lights_along_ray(const Ray& ray, float tmax, bool camera_ray, bool count_fully,
                                 float bsdf_pdf, const LightReceiver& from) const {
  RGB L(0.0f);
  const auto& lights = scene_.lights();
  scene_.hittable_lights().for_each_candidate(ray.origin, ray.dir, tmax, camera_ray,
                                              [&](uint32_t i) {
    LightHit h;
    if (!intersect_light(lights[i], ray.origin, ray.dir, tmax, &h)) return;
    if (!(h.t > ray.tmin)) return;  // before a transparent surface: seen by the last segment
    if (count_fully) {
      L += h.radiance;
    } else {
      const float light_pdf = h.pdf * scene_.light_sampler().probability(from, i);
      L += h.radiance * power_heuristic(1.0f, bsdf_pdf, 1.0f, light_pdf);
    }
  });
  return L;
}

RGB PathTracer::escaped(const Vec3& dir, bool camera_ray, bool count_fully, float bsdf_pdf) const {
  const Environment& world = scene_.world();
  RGB L(0.0f);
  if (!world.is_black()) {
    const RGB le = world.eval(dir);
    if (count_fully || !world.importance_sampled()) {
      L += le;
    } else {
      const float light_pdf =
          world.pdf(dir) * scene_.light_sampler().probability(scene_.lights().size());
      L += le * power_heuristic(1.0f, bsdf_pdf, 1.0f, light_pdf);
    }
  }
  for (uint32_t i : scene_.wide_suns()) {
    const Light& sun = scene_.lights()[i];
    if (camera_ray ? !sun.visibility.camera : !sun.visibility.use_mis) continue;
    RGB le;
    float pdf = 0.0f;
    if (!sun_radiance(sun, dir, &le, &pdf)) continue;
    if (count_fully) {
      L += le;
    } else {
      const float light_pdf = pdf * scene_.light_sampler().probability(i);
      L += le * power_heuristic(1.0f, bsdf_pdf, 1.0f, light_pdf);
    }
  }
  return L;
}

void PathTracer::begin(const Ray& camera_ray, PathState* s) const {
  // Built in place: assigning a fresh PathState() stored a zeroed temporary (rep stos) and read
  // it back in 16-byte pieces, a store-forwarding stall that perf put at ~5% of a render whose
  // paths are short (sweep_principled_multiscatter).
  static_assert(std::is_trivially_destructible_v<PathState>, "begin() reuses the storage");
  ::new (s) PathState;  // every member has its initializer
  s->ray = camera_ray;
}

void PathTracer::prepare(const PathState& s, const PathSampler& sampler, const Hit& hit,
                         PreparedHit* prepared) const {
  const uint32_t material = scene_.material_of(hit);
  const bool ends_here = s.transparent_bounces > settings_.transparent_max_bounces;
  prepared->scatters = !ends_here && s.bounce <= settings_.max_bounces;
  prepared->may_pass = !ends_here && transparent_shadows_.transparent(material);
  prepared->runs_program = false;
  prepared->roulette_rolled = false;
  prepared->ends_unshaded = false;
  const Material& mat = scene_.materials()[material];
  const MaterialGraph* graph = mat.graph.get();
  // Where the hit adds nothing of its own (no emission; past the camera ray, which may see a
  // holdout) a path that ends here ends before any shading: a vertex that neither scatters nor
  // passes, and one where Russian roulette ends it (the same number step() would draw, so the
  // same paths end). Neither costs a surface point or a program.
  if (s.bounce > 0 && !mat.may_emit()) {
    if (!prepared->scatters && !prepared->may_pass) {
      prepared->ends_unshaded = true;
      return;
    }
    if (s.continuation < 1.0f) {
      prepared->roulette_rolled = true;
      if (!(sampler.russian_roulette(s.vertex) < s.continuation)) {
        prepared->ends_unshaded = true;
        return;
      }
    }
  }
  SurfacePoint& sp = prepared->sp;
  // A lone diffuse lobe is the same about any tangent: its frame is made from the normal alone,
  // as Cycles' diffuse closures make theirs (make_orthonormals), and the hit's tangent (the
  // radial one reads the object's texture space and transform) is not worked out.
  const bool lone = plain_diffuse_[material].lone;
  // In place: a returned copy was read back before it landed.
  scene_.surface_point(hit, &sp, !lone);
  const Vec3 wo = -s.ray.dir;
  const bool flipped = face_viewer(sp, wo, scene_.transmissive(sp.material));
  // Reflection is judged against the shading normal, as Cycles' closures do: directions
  // between the flat triangle and the smooth surface are lit (the terminator offset then lets
  // their shadow rays out). Transmissive surfaces keep the geometric decision. The closures'
  // normal is Cycles' valid-reflection one, in sp.ns's orientation.
  const float viewer_side = dot(wo, sp.ng) < 0.0f ? -1.0f : 1.0f;
  prepared->viewer_n = viewer_side_normal(sp, wo);
  const Vec3 frame_n = prepared->viewer_n * viewer_side;
  prepared->frame =
      lone ? Frame::from_normal(frame_n) : Frame::from_normal_tangent(frame_n, sp.tangent);
  // A graph of constants only (no nodes; Cycles' default tangent is a node's) has nothing to
  // run: its closures and emission read no register.
  if (!graph || (graph->nodes.empty() && graph->default_tangent_reg < 0)) return;
  // The program runs where the closures are built, where the emission or (on camera rays) a
  // holdout reads it; not where only a constant emission counts.
  prepared->runs_program = prepared->scatters || prepared->may_pass ||
                           !graph->emission_is_constant() ||
                           (s.bounce == 0 && !graph->holdouts.empty());
  if (prepared->runs_program)
    prepared->ctx = ShadingContext{&scene_, &hit, sp.p, sp.ns, sp.ng, wo, flipped, &sp};
}

WalkSlots WalkSlots::of_this_thread() {
  return {microfacet::MultiscatterWalkSalt::thread_slot(),
          microfacet::MultiscatterWalkNumbers::thread_slot()};
}

namespace {

// Cycles' walk numbers at the path's next vertex: its seed grows by 16 (PRNG_BOUNCE_NUM) with
// every bounce, a transparent one too (walk_numbers.h).
microfacet::WalkNumbers vertex_walk_numbers(PathState& s, const PathSampler& sampler) {
  const uint32_t bounces = static_cast<uint32_t>(s.bounce + s.transparent_bounces);
  return microfacet::WalkNumbers(sampler.walk_seed() + 16u * bounces, &s.walk_anchor);
}

// The multiscatter walks' state for the vertex an advance() shades, in scopes that close with
// it. Multiscatter GGX evaluates a walk estimate seeded by the directions; salted per sample,
// its error averages away over a pixel's samples instead of staying fixed where they share the
// directions (multiscatter_ggx.h, Determinism), as Cycles' one walk per sample does. Its
// sampling walks (and its first eval walk) draw Cycles' numbers for the vertex.
struct VertexWalkScopes {
  microfacet::MultiscatterWalkSalt salt;
  microfacet::WalkNumbers numbers;
  microfacet::MultiscatterWalkNumbers numbers_scope;
  VertexWalkScopes(PathState& s, const PathSampler& sampler)
      : salt(sampler.walk_salt()),
        numbers(vertex_walk_numbers(s, sampler)),
        numbers_scope(&numbers) {}
};

}  // namespace

void PathTracer::advance(PathState& s, const PathSampler& sampler, PathStats& stats,
                         const Hit* found_hit) const {
  const VertexWalkScopes walks(s, sampler);
  if (!found_hit) return step(s, sampler, stats, nullptr, nullptr, nullptr);
  PreparedHit prepared;
  prepare(s, sampler, *found_hit, &prepared);
  const Vec3* registers = nullptr;
  if (prepared.runs_program) {
    Vec3* r = shading_scratch().registers;
    scene_.materials()[prepared.sp.material].graph->evaluate(prepared.ctx, r);
    registers = r;
  }
  step(s, sampler, stats, found_hit, &prepared, registers);
  test_shadow(s);
}

void PathTracer::advance(PathState& s, const PathSampler& sampler, PathStats& stats,
                         const Hit& hit, const PreparedHit& prepared,
                         const Vec3* registers) const {
  const VertexWalkScopes walks(s, sampler);
  step(s, sampler, stats, &hit, &prepared, registers);
  test_shadow(s);
}

void PathTracer::advance_deferring_shadow(PathState& s, const PathSampler& sampler,
                                          PathStats& stats, const Hit* hit,
                                          const PreparedHit* prepared,
                                          const Vec3* registers,
                                          const WalkSlots& walk_slots) const {
  // An escaped ray shades nothing: no walk evaluates or samples.
  if (!hit) return step(s, sampler, stats, nullptr, nullptr, nullptr);
  // Restored however step() leaves, so that no later evaluation on this thread sees the salt
  // or the numbers.
  struct Restore {
    const WalkSlots& slots;
    uint64_t salt;
    microfacet::WalkNumbers* numbers;
    ~Restore() {
      *slots.salt = salt;
      *slots.numbers = numbers;
    }
  } restore{walk_slots, *walk_slots.salt, *walk_slots.numbers};
  microfacet::WalkNumbers numbers = vertex_walk_numbers(s, sampler);
  *walk_slots.salt = sampler.walk_salt();
  *walk_slots.numbers = &numbers;
  step(s, sampler, stats, hit, prepared, registers);
}

void PathTracer::test_shadow(PathState& s) const {
  if (s.shadow.active)
    resolve_shadow(s, scene_.occluded(s.shadow.origin, s.shadow.dir, s.shadow.tmax));
}

void PathTracer::step(PathState& s, const PathSampler& sampler, PathStats& stats,
                      const Hit* found_hit, const PreparedHit* prepared,
                      const Vec3* registers) const {
  // One vertex of the path: what it carries from vertex to vertex lives in `s`, named here as
  // the path's own variables.
  RGB& L = s.L;
  RGB& beta = s.beta;
  float& eta_scale = s.eta_scale;
  Ray& ray = s.ray;
  bool& specular_bounce = s.specular_bounce;
  float& prev_pdf = s.prev_pdf;
  LightReceiver& prev = s.prev;
  int& bounce = s.bounce;
  int& transparent_bounces = s.transparent_bounces;
  int& vertex = s.vertex;
  PathResult& result = s.result;
  test_shadow(s);  // the previous vertex's, if the caller left it pending
  const auto& lights = scene_.lights();
  // The ways out of a vertex: the path ends here, or goes on to its next vertex.
  const auto end_path = [&s] { s.done = true; };
  const auto next_vertex = [&s] { ++s.vertex; };
  const bool camera_ray = bounce == 0;
  const bool count_fully = camera_ray || specular_bounce;
  const bool found = found_hit != nullptr;
  L += beta * lights_along_ray(ray, found ? found_hit->t : kInfinity, camera_ray, count_fully,
                               prev_pdf, prev);
  if (!found) {
    // Escaped: the world and the suns with an angle. Counted in full where light sampling
    // could not have found them (camera rays, delta bounces), else weighted against it.
    if (!(camera_ray && settings_.transparent_background))
      L += beta * escaped(ray.dir, camera_ray, count_fully, prev_pdf);
    else if (vertex > 0)  // the film shows what passed the transparent surfaces (Cycles)
      result.alpha -= std::min(beta.average(), 1.0f);
    return end_path();
  }
  if (vertex == 0) result.alpha = 1.0f;
  if (prepared->ends_unshaded) return end_path();
  const Hit& hit = *found_hit;

  const SurfacePoint& sp = prepared->sp;  // turned towards the viewer (face_viewer)
  const Vec3 wo = -ray.dir;
  const Material& mat = scene_.materials()[sp.material];
  const bool transmissive = scene_.transmissive(sp.material);
  const Vec3& viewer_n = prepared->viewer_n;
  // Where next-event estimation picks its light, and where a BSDF ray from here weighs the
  // light it finds.
  LightReceiver receiver{sp.p, viewer_n, transmissive};
  BSDF bsdf(prepared->frame, transmissive ? sp.ng : prepared->frame.n);
  // Cosine lobes sample only what can leave an opaque smooth surface: on a smooth sphere in a
  // furnace the samples lost below the triangle's plane were all of the noise. (An opaque
  // surface's sp.ng already faces the viewer: face_viewer.)
  if (!transmissive) bsdf.set_sampling_horizon(sp.ng);
  // Most vertices shade one diffuse closure: LoneDiffuse gives the same values for less work.
  LoneDiffuse lone;
  bool is_lone = false;
  RGB emitted = mat.emission;
  const bool scatters = prepared->scatters, may_pass = prepared->may_pass;
  if (mat.graph) {
    // A node material: its program has run at this point (prepared->runs_program wherever
    // what follows reads it); build its closures in place (not where only emission counts).
    if (camera_ray && !mat.graph->holdouts.empty()) {
      // Cycles' holdout: on camera rays the pixel turns transparent by the holdout weight
      // (with a transparent film), and a full holdout ends the path before its emission.
      const RGB h = mat.graph->holdout(registers);
      if (settings_.transparent_background) result.alpha -= std::min((h * beta).average(), 1.0f);
      if (h.r >= 1.0f && h.g >= 1.0f && h.b >= 1.0f) return end_path();
    }
    if (!mat.graph->emission_is_constant()) emitted = mat.graph->emitted(registers);
  }
  if (!emitted.is_black()) {
    if (count_fully) {
      L += beta * emitted;
    } else {
      // Weighted against light sampling of the mesh's light (constant or textured).
      const int li = scene_.area_light_of(hit);
      const float lp = li < 0 ? 0.0f
                              : scene_.light_sampler().probability(prev, size_t(li)) *
                                    mesh_light_pdf(lights[size_t(li)], prev.p, sp.p, sp.ng);
      L += beta * emitted * power_heuristic(1.0f, prev_pdf, 1.0f, lp);
    }
  }
  // Russian roulette, rolled here as Cycles rolls it: what the ray brought back (the lights it
  // passed, the world if it escaped, this surface's emission) counts in full whatever the roll,
  // and only what the path gathers from here on is left to chance. Rolled before the ray, it
  // threw away escaping rays' world light too: in a two-sphere furnace the noise per sample was
  // 1.42 x Cycles'. A vertex that neither scatters nor passes ends the path anyway.
  if (s.continuation < 1.0f && (scatters || may_pass)) {
    if (!prepared->roulette_rolled && !(sampler.russian_roulette(vertex) < s.continuation))
      return end_path();
    beta *= 1.0f / s.continuation;
    s.continuation = 1.0f;
  }
  if (mat.graph) {
    if (scatters || may_pass) {
      // The thread's arena is looked up only here: a thread_local in a shared object costs a
      // call (__tls_get_addr), which the materials without a graph need not pay.
      ClosureArena& arena = shading_scratch().arena;
      arena.reset();
      mat.graph->add_closures(registers, sp.tangent, arena, bsdf);
    }
  } else if (scatters && plain_diffuse_[sp.material].lone) {
    // The BSDF it would be, without building it; made in place (an assigned temporary was read
    // back in 16-byte pieces over its smaller stores: ~2% of the benchmark, in perf annotate).
    ::new (&lone) LoneDiffuse(plain_diffuse_[sp.material].f, bsdf.frame(),
                              bsdf.geometric_normal(), transmissive ? nullptr : &sp.ng);
    is_lone = true;
  } else {
    for (const BxDFPtr& c : mat.components) bsdf.add(c.get());
  }
  if (!scatters) {
    if (!may_pass) return end_path();
    const RGB passed = TransparentShadows::transparent_weight(bsdf);
    if (passed.is_black()) return end_path();
    beta *= passed;
    ++transparent_bounces;
    ray.tmin = TransparentShadows::past_hit(ray, hit.t);
    return next_vertex();
  }
  if (!is_lone) {
    if (bsdf.num_components() == 0) return end_path();
    // Cycles picks the first surface's closures defensively (closure_pick.h), for its light
    // sample's MIS weight as for its BSDF sample.
    if (bounce == 0 && transparent_bounces == 0) bsdf.use_defensive_sampling();
    is_lone = LoneDiffuse::of(bsdf, &lone);
  }
  if (is_lone || bsdf.has_non_delta()) {
    const RGB nee = is_lone ? sample_one_light(hit, sp, lone, wo, receiver, sampler, vertex,
                                               transparent_bounces, stats, &s.shadow)
                            : sample_one_light(hit, sp, bsdf, wo, receiver, sampler, vertex,
                                               transparent_bounces, stats, &s.shadow);
    if (s.shadow.active) s.shadow.contribution = beta * nee;  // added once the ray is tested
    else L += beta * nee;
  }

  const Point2 u_bsdf = sampler.bsdf(vertex);
  // The sampled direction, its pdf and lobe.
  Vec3 wi;
  float pdf;
  uint32_t flags;
  if (is_lone) {
    RGB weight;
    if (!lone.sample(wo, u_bsdf, &wi, &pdf, &weight)) return end_path();
    beta *= weight;
    flags = kReflection | kDiffuse;
  } else {
    const BSDFSample bs = bsdf.sample_f(wo, u_bsdf);
    if (!bs.valid() || bs.f.is_black()) return end_path();
    beta *= bs.f_cos / bs.pdf;
    // (Only a material with a Transparent BSDF can pass: may_pass spares the others the cast.)
    if (may_pass && bs.component >= 0 &&
        TransparentShadows::is_transparent(bsdf.component(bs.component))) {
      // A pass through: the same ray goes on behind the surface (Cycles moves only tmin).
      if (beta.is_black()) return end_path();
      ++transparent_bounces;
      ray.tmin = TransparentShadows::past_hit(ray, hit.t);
      return next_vertex();
    }
    wi = bs.wi;
    pdf = bs.pdf;
    flags = bs.flags;
  }
  ++bounce;
  // Cycles' bsdf_sample rescales every sample of a reflecting lobe, none of a transmitting one.
  if (!(flags & kTransmission))
    beta *= shading_offset_factor(dot(wi, viewer_n), scene_.terminator(hit.mesh).shading);
  if (beta.is_black()) return end_path();
  if (transmissive && (flags & kTransmission)) {
    // Entering (wo on the front side) scales radiance by (η_i/η_t)²; leaving undoes it.
    const float eta = scene_.relative_eta(sp.material);
    eta_scale *= dot(wo, sp.ng) > 0.0f ? eta * eta : 1.0f / (eta * eta);
  }
  specular_bounce = (flags & kSpecular) != 0;
  prev_pdf = pdf;
  prev = receiver;
  ray.origin = offset_origin(sp.p, sp.ng, wi);
  ray.dir = wi;
  ray.tmin = 0.0f;
  ray.tmax = kInfinity;

  // Russian roulette after scattering events only: transparent passes are bounded by their
  // own budget (unbiased either way; Cycles also rolls there). Rolled at the next hit.
  if (bounce - 1 >= settings_.russian_roulette_depth) {
    // Judged on the throughput without refraction's radiance scaling, as pbrt does, so that a
    // path inside glass is not ended more often only because its radiance is scaled down.
    // Continued with Cycles' probability √(max throughput), capped at 1: a path that still
    // carries its full throughput is never cut, so a white furnace stays noise-free.
    const float m = beta.max_component() * eta_scale;
    s.continuation = std::min(std::sqrt(m), 1.0f);
  }
  if (!scene_.rays_find_light()) {
    // Nothing a ray finds counts before the vertex it lands on scatters (a black world, no
    // light it can hit, no emission): a ray that vertex cannot scatter from is not traced,
    // and the roulette is rolled now, with the number the hit would draw. The same image as
    // rolling at the hit, without the rays that brought nothing back.
    if (bounce > settings_.max_bounces) return end_path();
    if (s.continuation < 1.0f) {
      if (!(sampler.russian_roulette(vertex + 1) < s.continuation)) return end_path();
      beta *= 1.0f / s.continuation;
      s.continuation = 1.0f;
    }
  }
  next_vertex();
}

PathResult PathTracer::finish(PathState& s, PathStats& stats) const {
  test_shadow(s);  // the last vertex's, if the caller left it
  return accepted(s.L, s.result.alpha, stats);
}

PathResult PathTracer::escaped_camera_ray(const Ray& camera_ray, PathStats& stats) const {
  // step() at a path's first vertex, its ray escaped: beta is 1, the ray a camera ray, and
  // everything it finds is counted in full (no vertex before it to weigh against).
  RGB L = lights_along_ray(camera_ray, kInfinity, true, true, 0.0f, LightReceiver{});
  if (!settings_.transparent_background) L += escaped(camera_ray.dir, true, true, 0.0f);
  return accepted(L, 0.0f, stats);
}

PathResult PathTracer::accepted(RGB L, float alpha, PathStats& stats) const {
  const bool finite = std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b);
  if (!finite || (!scene_.signed_emission() && !finite_nonnegative(L))) {
    ++stats.rejected;
    L = RGB(0.0f);
  }
  PathResult result;
  result.radiance = L;
  result.alpha = alpha;
  return result;
}

PathResult PathTracer::trace(const Ray& camera_ray, const PathSampler& sampler,
                             PathStats& stats, const CameraHit* camera_hit) const {
  PathState s;
  begin(camera_ray, &s);
  for (;;) {  // every surface hit; the sampler's dimensions follow it
    ++stats.rays;
    Hit hit;
    bool found;
    if (s.vertex == 0 && camera_hit) {
      found = camera_hit->found;
      if (found) hit = camera_hit->hit;
    } else {
      found = scene_.intersect(s.ray, &hit, s.bounce == 0);
    }
    advance(s, sampler, stats, found ? &hit : nullptr);
    if (s.done) break;
  }
  return finish(s, stats);
}

}  // namespace bxdf::render
