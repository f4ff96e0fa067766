// The path tracer (pbrt's PathIntegrator with one-light next-event estimation): at each vertex
// one light is picked (light_sampler.h: by power, and among a few local lights by how much
// each can give the point) and sampled, the BSDF is sampled to continue the path, and both
// strategies are combined with the power heuristic; delta lights and delta lobes are counted by
// the one strategy that can find them. Lights are not geometry: rays pass through them,
// collecting their radiance (as Cycles' lights_intersect). A constant world is found by BSDF
// sampling alone (Cycles does not light-sample it). Shadow rays leave from Cycles'
// terminator-offset point. Russian roulette as Cycles plays it: from russian_roulette_depth + 1
// scatterings on, with probability √(max throughput), rolled at the hit the next ray finds once
// what that ray brought back has counted.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "bxdf/microfacet/walk_numbers.h"
#include "bxdf/render/material_graph.h"
#include "bxdf/render/ray.h"
#include "bxdf/render/scene.h"
#include "bxdf/render/transparent_shadows.h"

namespace bxdf::render {

class PathSampler;  // sampler/path_sampler.h: the path's Sobol-Burley numbers

struct IntegratorSettings {
  // 0 = direct light only (emitters seen from the first hit); n = up to n indirect bounces.
  int max_bounces = 8;
  // Paths may be ended at random once they have scattered this many + 1 times: 1 is Cycles'
  // default (Min Light Bounces 0; Cycles' kernel counts one bounce more).
  int russian_roulette_depth = 1;
  // Passes through Transparent BSDFs a path may make (Cycles' transparent_max_bounces; they are
  // not bounces): the surface after one more pass adds only its emission. Also the shadow
  // rays' budget, less the path's passes so far.
  int transparent_max_bounces = TransparentShadows::kDefaultMaxBounces;
  bool transparent_background = false;  // camera rays that escape get no world radiance
};

// Per-thread counters, summed after the render.
struct PathStats {
  uint64_t rays = 0;         // closest-hit queries
  uint64_t shadow_rays = 0;  // occlusion queries
  uint64_t rejected = 0;     // samples with NaN, Inf or negative radiance, dropped
};

// A camera sample's result: radiance along the ray and coverage (1 if it hit geometry).
struct PathResult {
  RGB radiance;
  float alpha = 0.0f;
};

// A vertex's light sample whose shadow ray is still to be tested (scenes without Transparent
// BSDFs, where the test is plain occlusion): `contribution` joins L if nothing blocks the ray.
// Tested before the path's next vertex adds to L, so L sums in the same order either way.
struct PendingShadow {
  Vec3 origin, dir;
  float tmax = 0.0f;
  RGB contribution{0.0f};
  bool active = false;
};

// One camera sample's path between two intersections: what the path tracer carries from one
// vertex to the next, so that a batch of paths can be advanced vertex by vertex.
struct PathState {
  Ray ray;                 // the ray to trace next
  RGB L{0.0f}, beta{1.0f};
  float eta_scale = 1.0f;  // product of (η_wi/η_wo)² over refractions: undoes radiance scaling
  bool specular_bounce = false;
  float prev_pdf = 0.0f;   // BSDF pdf of the direction that led here (for MIS)
  // The vertex that scattered the ray, as light selection saw it there (the light a BSDF ray
  // finds is weighed with the probability that vertex would have picked it with).
  LightReceiver prev;
  // Cycles counts a pass through a Transparent BSDF apart from the bounces (path_state_next:
  // LABEL_TRANSPARENT): it uses no bounce, keeps the path's flags (a camera ray stays one), its
  // MIS pdf and its ray origin (only tmin moves on), and the path ends at the surface after
  // transparent_max_bounces + 1 passes, counting only that surface's emission.
  int bounce = 0;               // scattering events so far (Cycles' `bounce`)
  int transparent_bounces = 0;  // passes through transparent surfaces so far
  int vertex = 0;               // surface hits so far; the sampler's dimensions follow it
  // Russian roulette's probability of going on past the ray's hit: set where the path
  // scattered, rolled at the hit once what the ray brought back has counted (Cycles rolls in
  // intersect_closest, and never for a ray that escapes).
  float continuation = 1.0f;
  PathResult result;
  bool done = false;
  PendingShadow shadow;  // the last vertex's, until resolve_shadow()
  // Where the path's first multiscatter sampling walk put its stratified facet among Cycles'
  // walk numbers, for its later walks to keep Cycles' shift from it (walk_numbers.h).
  microfacet::WalkAnchor walk_anchor;
};

// This thread's multiscatter walk state (multiscatter_ggx.h, walk_numbers.h), looked up once
// per batch of paths: advance_deferring_shadow sets both for the vertex it shades (the camera
// sample's salt, the vertex's walk numbers) and restores them.
struct WalkSlots {
  uint64_t* salt = nullptr;
  microfacet::WalkNumbers** numbers = nullptr;
  static WalkSlots of_this_thread();
};

// What advance() works out at a hit before the material's program runs: the surface point,
// turned towards the viewer, and whether the program runs there (not where only a constant
// emission counts) with what it reads. PathBatch prepares its paths' hits together and runs
// their programs hit-batch-wise (MaterialGraph::evaluate_batch).
struct PreparedHit {
  SurfacePoint sp;
  // Cycles' valid-reflection normal on the viewer's side (viewer_side_normal), and the
  // closures' frame about it in sp.ns's orientation.
  Vec3 viewer_n;
  Frame frame;
  // Past the transparent budget only this surface's emission counts (Cycles' PATH_RAY_
  // TERMINATE_ON_NEXT_SURFACE); past max_bounces only its Transparent closures remain, which
  // the path passes through with their summed weight (PATH_RAY_TERMINATE_AFTER_TRANSPARENT).
  bool scatters = false;      // the vertex scatters
  bool may_pass = false;      // it may pass the surface's Transparent closures
  bool runs_program = false;  // a node material whose program this hit needs
  // Russian roulette, rolled by prepare() where the hit emits nothing (step() rolls it
  // otherwise, after the emission has counted).
  bool roulette_rolled = false;
  // The path ends at this hit, which adds nothing (no emission; it neither scatters nor passes,
  // or the roulette ended it): only what the ray passed on its way here counts, and nothing
  // else of the hit (sp, frame, ctx) is worked out.
  bool ends_unshaded = false;
  ShadingContext ctx;         // the program's inputs (when runs_program); points at sp
};

class PathTracer {
 public:
  // The scene must be committed. Throws ParameterError for max_bounces < 0.
  PathTracer(const Scene& scene, const IntegratorSettings& settings);

  // Radiance along a camera ray; never NaN, Inf or negative (such samples are counted in
  // stats->rejected and returned as 0).
  // `camera_hit`, when given, is the camera ray's first hit, already found
  // (Scene::intersect_camera_rays).
  PathResult trace(const Ray& camera_ray, const PathSampler& sampler, PathStats& stats,
                   const CameraHit* camera_hit = nullptr) const;

  // trace() in steps, for paths traced in batches: begin, then for each intersection of s.ray
  // (stats.rays counted by the caller; camera rays are those of s.bounce == 0) advance with its
  // hit (null: the ray escaped) until s.done, then finish.
  void begin(const Ray& camera_ray, PathState* s) const;
  void advance(PathState& s, const PathSampler& sampler, PathStats& stats, const Hit* hit) const;
  // advance() in two steps, for batches: prepare the hit (s's next vertex; `hit` must outlive
  // `prepared`), run the program where prepared->runs_program (into `registers`), then advance
  // with both. The same path as advance(s, sampler, stats, &hit). Russian roulette is rolled
  // here where the hit emits nothing, so that a path it ends costs no shading.
  void prepare(const PathState& s, const PathSampler& sampler, const Hit& hit,
               PreparedHit* prepared) const;
  void advance(PathState& s, const PathSampler& sampler, PathStats& stats, const Hit& hit,
               const PreparedHit& prepared, const Vec3* registers) const;
  // The same as that advance(), but the vertex's shadow ray may stay pending (s.shadow): the
  // caller tests it, for many paths at once (Scene::occluded_stream), and calls
  // resolve_shadow(s, occluded) before the path's next vertex and before finish(). A null
  // `hit` (and `prepared`) is an escaped ray. `walk_slots`: this thread's
  // (WalkSlots::of_this_thread()).
  void advance_deferring_shadow(PathState& s, const PathSampler& sampler, PathStats& stats,
                                const Hit* hit, const PreparedHit* prepared,
                                const Vec3* registers, const WalkSlots& walk_slots) const;
  static void resolve_shadow(PathState& s, bool occluded) {
    if (!s.shadow.active) return;
    s.shadow.active = false;
    if (!occluded) s.L += s.shadow.contribution;
  }
  PathResult finish(PathState& s, PathStats& stats) const;
  // A camera sample whose ray escaped (it hit nothing, not even a transparent surface): the
  // result begin(), advance() with no hit and finish() give, without a PathState.
  PathResult escaped_camera_ray(const Ray& camera_ray, PathStats& stats) const;

 private:
  // One vertex: `prepared` and `registers` (its program's, where it ran) for a found hit. The
  // caller has set the thread's multiscatter walk salt to the sample's (see Determinism in
  // multiscatter_ggx.h).
  void step(PathState& s, const PathSampler& sampler, PathStats& stats, const Hit* hit,
            const PreparedHit* prepared, const Vec3* registers) const;
  // A finished path's result: L where it is finite (and non-negative, unless the scene has
  // negative emission), else 0 and the sample counted in stats.rejected.
  PathResult accepted(RGB L, float alpha, PathStats& stats) const;
  // Tests s's pending shadow ray alone and resolves it.
  void test_shadow(PathState& s) const;
  // `receiver`: the hit's point and viewer_side_normal (PreparedHit::viewer_n, computed once
  // by prepare), for which the light is picked (and which keeps the light distribution's
  // normalisation there). With `deferred`, a plain-occlusion shadow ray is not tested but left
  // in *deferred (active), and the radiance returned is what an unblocked ray gives. The
  // light's numbers are `path_sampler`'s of `vertex` (PathSampler::light), drawn only where the
  // scene has a light to pick: x picks the light and, remapped within its interval, is the
  // light point's first coordinate. `bsdf`: the vertex's BSDF, or its LoneDiffuse where it
  // is one (what is asked of it: f_cos, f_cos_pdf).
  template <class Scattering>
  RGB sample_one_light(const Hit& hit, const SurfacePoint& sp, const Scattering& bsdf,
                       const Vec3& wo, LightReceiver& receiver, const PathSampler& path_sampler,
                       int vertex, int transparent_bounces, PathStats& stats,
                       PendingShadow* deferred = nullptr) const;
  // A direction towards the world (light sampler entry lights().size()), drawn from (u1, u2).
  LightSample world_light_sample(float u1, float u2) const;
  // Radiance a ray collects from the lights it passes through before `tmax`; MIS-weighted
  // against light sampling at `from` (the vertex that scattered it) unless `count_fully`
  // (camera rays, delta bounces).
  RGB lights_along_ray(const Ray& ray, float tmax, bool camera_ray, bool count_fully,
                       float bsdf_pdf, const LightReceiver& from) const;
  // Radiance an escaped ray receives from the world and the suns with an angle (camera rays
  // see a sun only when it is visible to the camera).
  RGB escaped(const Vec3& dir, bool camera_ray, bool count_fully, float bsdf_pdf) const;

  const Scene& scene_;
  IntegratorSettings settings_;
  TransparentShadows transparent_shadows_;  // shadow rays through Transparent BSDFs
  // Per material: where a plain material (no graph) is one LoneDiffuse closure, its f. Worked
  // out once, so that step() builds the closure without asking the model at every vertex.
  struct PlainDiffuse {
    bool lone = false;
    RGB f;
  };
  std::vector<PlainDiffuse> plain_diffuse_;
};

}  // namespace bxdf::render
