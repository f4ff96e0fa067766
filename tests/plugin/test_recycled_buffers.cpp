// Mesh arrays kept from one scene for the next (recycled_buffers.h): a kept buffer comes back to
// a request of about its size, never to a much smaller one, the bound holds, and a destroyed
// Scene gives its meshes' arrays back.
#include <gtest/gtest.h>

#include "bxdf/registry.h"
#include "bxdf/render/recycled_buffers.h"
#include "bxdf/render/scene.h"
#include "bxdf/render/shapes.h"

using namespace bxdf;
using namespace bxdf::render;

TEST(RecycledBuffers, AKeptBufferComesBackToARequestOfItsSize) {
  recycled::release_all();
  std::vector<float> a = recycled::floats(1000);
  EXPECT_TRUE(a.empty());
  EXPECT_GE(a.capacity(), 1000u);
  a.assign(1000, 1.0f);
  const float* data = a.data();
  recycled::keep(std::move(a));
  EXPECT_EQ(recycled::kept_bytes(), 1000 * sizeof(float));
  // Much smaller: a new buffer (the kept one would sit half unused).
  std::vector<float> small = recycled::floats(100);
  EXPECT_NE(small.data(), data);
  // Up to a quarter smaller: the kept one, emptied.
  std::vector<float> b = recycled::floats(900);
  EXPECT_EQ(b.data(), data);
  EXPECT_TRUE(b.empty());
  EXPECT_EQ(recycled::kept_bytes(), 0u);
  // Index buffers are kept apart from float buffers.
  recycled::keep(std::move(b));
  std::vector<uint32_t> i = recycled::indices(900);
  EXPECT_NE(static_cast<const void*>(i.data()), static_cast<const void*>(data));
  recycled::release_all();
  EXPECT_EQ(recycled::kept_bytes(), 0u);
}

TEST(RecycledBuffers, TheBoundHolds) {
  recycled::release_all();
  // A buffer larger than the bound is freed, not kept.
  std::vector<float> huge;
  huge.reserve(recycled::kMaxKeptBytes / sizeof(float) + 1);
  recycled::keep(std::move(huge));
  EXPECT_EQ(recycled::kept_bytes(), 0u);
  // Many buffers: the total stays within the bound.
  const size_t quarter = recycled::kMaxKeptBytes / 4 / sizeof(uint32_t);
  for (int k = 0; k < 6; ++k) {
    std::vector<uint32_t> v;
    v.reserve(quarter);
    recycled::keep(std::move(v));
    EXPECT_LE(recycled::kept_bytes(), recycled::kMaxKeptBytes);
  }
  EXPECT_GE(recycled::kept_bytes(), 3 * quarter * sizeof(uint32_t));
  recycled::release_all();
}

TEST(RecycledBuffers, ADestroyedSceneGivesItsMeshArraysToTheNext) {
  recycled::release_all();
  const Mesh sphere = make_uv_sphere(Vec3(0, 0, 0), 1.0f, 32, 16, 0);
  {
    Scene scene;
    scene.add_material(Material{{make("lambertian")}, RGB(0.0f)});
    scene.add_mesh(sphere.view());
    scene.commit();
    EXPECT_EQ(recycled::kept_bytes(), 0u);
  }
  const size_t kept = recycled::kept_bytes();
  // Positions (+ the padding float), normals and indices at least.
  EXPECT_GE(kept, (2 * sphere.positions.size() + sphere.indices.size()) * sizeof(float));
  {
    Scene again;
    again.add_material(Material{{make("lambertian")}, RGB(0.0f)});
    again.add_mesh(sphere.view());  // copied into the kept buffers
    EXPECT_LT(recycled::kept_bytes(), kept);
    again.commit();
    Hit hit;
    Ray ray;
    ray.origin = Vec3(0, -5, 0);
    ray.dir = Vec3(0, 1, 0);
    EXPECT_TRUE(again.intersect(ray, &hit));
    EXPECT_NEAR(hit.t, 4.0f, 0.01f);
  }
  recycled::release_all();
}
