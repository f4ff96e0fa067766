// The lights a ray can hit in space (lights.h: area lights, point and spot lights with a
// radius), for the test every traced ray makes against all of them. A room lit by several area
// lights asked each one in turn (three divisions and a dozen products per light per ray, 5% of
// area_light_room's render) although a ray finds one of them only now and then. Here the area
// lights are tested four at a time with vector operations and no division: a ray that does not
// cross a light's plane in front of it before tmax, or crosses it outside the light's bounding
// rectangle, is left out, and intersect_light() makes the exact test (and finds the radiance
// and density) for the few that are left. Point and spot lights with a radius are always left
// to it.
#pragma once

#include <cstdint>
#include <vector>

#include "bxdf/render/lights.h"

namespace bxdf::render {

class HittableLights {
 public:
  HittableLights() = default;
  explicit HittableLights(const std::vector<Light>& lights);

  bool empty() const { return groups_.empty(); }

  // Calls on_candidate(i) for each light i (an index into the lights, in increasing order) that
  // a ray from `origin` along `dir` may hit before `tmax` and that rays of its kind see (camera
  // rays: visibility.camera; others: visibility.use_mis). Every light intersect_light() finds is
  // among them.
  template <class OnCandidate>
  void for_each_candidate(const Vec3& origin, const Vec3& dir, float tmax, bool camera_ray,
                          OnCandidate&& on_candidate) const {
    for (const Group& g : groups_) {
      const unsigned seen = camera_ray ? g.camera_mask : g.mis_mask;
      if (seen == 0) continue;  // (camera rays see no light by default)
      unsigned mask = seen & (g.untested_mask | crossing_mask(g, origin, dir, tmax));
      for (; mask != 0; mask &= mask - 1) on_candidate(g.index[__builtin_ctz(mask)]);
    }
  }

 private:
  // Four lights, as a structure of arrays for the area lights' test: each one's centre, its
  // emitting normal and its edge vectors scaled so that a point's dot product with them is its
  // coordinate in [-1, 1] across the light.
  struct Group {
    alignas(16) float cx[4] = {}, cy[4] = {}, cz[4] = {};
    alignas(16) float nx[4] = {}, ny[4] = {}, nz[4] = {};
    alignas(16) float ux[4] = {}, uy[4] = {}, uz[4] = {};
    alignas(16) float vx[4] = {}, vy[4] = {}, vz[4] = {};
    uint32_t index[4] = {};
    unsigned untested_mask = 0;  // point and spot lights: left to intersect_light()
    unsigned camera_mask = 0, mis_mask = 0;  // which lights camera rays, BSDF rays see
  };
  // Which of g's area lights the ray crosses in front of, before tmax, inside their bounding
  // rectangle (bit k for entry k).
  static unsigned crossing_mask(const Group& g, const Vec3& origin, const Vec3& dir, float tmax);

  std::vector<Group> groups_;
};

}  // namespace bxdf::render
