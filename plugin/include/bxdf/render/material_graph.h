// A material graph (docs/material-graph.md) compiled for the renderer: a flat program of value
// nodes evaluated per hit into fixed registers, a weighted list of closures (registry models
// whose parameters are constants or registers) with an optional per-closure normal, and an
// emission value. Constants are validated once when the graph is built; at a hit nothing is
// validated or allocated: the program runs, referenced parameters are clamped into the
// registry's ranges, and each closure is placed into the caller's ClosureArena.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "bxdf/bsdf.h"
#include "bxdf/registry.h"
#include "bxdf/render/texture.h"
#include "bxdf/render/texture_group.h"

namespace bxdf::render {

class Scene;
struct Hit;
struct SurfacePoint;

enum class GraphOp : uint8_t {
  Const, UV, Generated, Object, Position, Normal, Incoming, Image, Transform, MixRGB, Math,
  VectorMath, Invert, Gamma, BrightContrast, HSV, Separate, Combine, ColorRamp, Fresnel,
  LayerWeight, NormalMap, Bump, Environment,
};

// The Environment Texture node's projections (GraphNode::mode of an Environment op).
enum class EnvironmentProjection : uint8_t { Equirectangular, MirrorBall };

// Registers hold a float as (f, f, f), colours and vectors as themselves; reading a colour or a
// vector where a float is expected converts as Cycles does.
enum class GraphConvert : uint8_t { None, ColorToFloat, VectorToFloat };

struct GraphInput {
  int32_t reg = -1;  // register, or -1: the constant
  GraphConvert convert = GraphConvert::None;
  Vec3 constant;
};

struct GraphNode {
  GraphOp op = GraphOp::Const;
  int mode = 0;        // the op's choice: blend, operation, transform kind, ...
  bool clamp = false;  // mix_rgb, math: saturate the result
  bool flag = false;   // image: unassociate alpha; transform: normalise
  int index = -1;      // texture, UV map, ramp or matrix
  // Where the node reads the surface: at the hit (0), or at the bump offsets dx (1) or dy (2)
  // when it is a copy in a bump's height sub-program.
  uint8_t offset = 0;
  std::array<GraphInput, 6> in{};
  int out = 0;  // first output register; a node's outputs are consecutive
  // Image nodes reading one point of images of one size and settings (textures on one UV
  // map, the common case) form a group: its first node finds the texels' footprint once and
  // looks up every image of the group (node indices MaterialGraph::image_groups[group_first,
  // + group_count)); the others are then done (`grouped`).
  int group_first = 0, group_count = 0;
  bool grouped = false;
  int texture_group = -1;  // the group's interleaved copy (MaterialGraph::texture_groups), or −1
};

struct GraphClosure {
  const ModelInfo* model = nullptr;
  GraphInput weight;                 // colour (a float weight is stored grey)
  std::vector<GraphInput> params;    // one per declared parameter, in declaration order
  std::vector<PlainValue> constants; // the validated constant of each parameter
  // The parameters read from registers: each one's index, input and registry range (as
  // floats); the others keep their constant.
  struct BoundParam {
    uint32_t index;
    GraphInput input;
    float lo, hi;
  };
  std::vector<BoundParam> bound;
  bool all_constant = true;
  BxDFPtr prebuilt;                  // when every parameter is constant: built once
  int normal_reg = -1;               // register of a perturbed normal, or -1
  bool diffuse_closure = false;      // one of Cycles' diffuse closures (bump-shadowed)
  // Anisotropic orientation: a tangent value (world space; reg −1 and no constant: the point's
  // own tangent) and a rotation in turns about the normal (Cycles' Anisotropic BSDF).
  bool has_tangent = false;
  GraphInput tangent;
  GraphInput rotation;  // constant 0: none
  bool anisotropic = false;  // an anisotropy parameter that is referenced or not 0
  bool oriented() const {
    return anisotropic || has_tangent || rotation.reg >= 0 || rotation.constant.x != 0.0f;
  }
};

struct ColorRampTable {
  static constexpr int kSize = 256;  // Cycles' RAMP_TABLE_SIZE
  std::array<Vec3, kSize> color;
  std::array<float, kSize> alpha;
  bool interpolate = true;
};

// What the program reads at a hit (world space; n, ng already facing the viewer).
struct ShadingContext {
  const Scene* scene = nullptr;
  const Hit* hit = nullptr;
  Vec3 p, n, ng, incoming;
  bool backfacing = false;
  // The hit's surface point when the caller has it (its smooth normal saves the normal map a
  // second read of the vertex normals); else the scene is asked.
  const SurfacePoint* point = nullptr;
};

class MaterialGraph {
 public:
  static constexpr int kMaxRegisters = 256;
  static constexpr size_t kMaxClosureParams = 48;

  std::vector<GraphNode> nodes;
  std::vector<GraphClosure> closures;
  GraphInput emission;
  std::vector<std::shared_ptr<const Texture>> textures;
  std::vector<ColorRampTable> ramps;
  std::vector<std::array<float, 12>> matrices;  // 3×4 rows
  int num_registers = 0;
  bool reads_offsets = false;  // some node is a bump's copy at an offset point
  // Register of Cycles' default tangent (radial about the object's Z axis, from generated
  // coordinates), filled before the program runs when an oriented closure needs it; or −1.
  int default_tangent_reg = -1;

  // The length of the bump offsets, in world units, relative to the point's distance from the
  // origin (so that p + offset stays well resolved in float): Cycles' offsets are its ray
  // differentials, about a pixel's footprint; ours are a fixed small step (docs/material-graph.md).
  static constexpr float kBumpOffset = 1e-3f;

  std::vector<int> image_groups;
  // Per entry of image_groups: its node's unassociate flag and first output register; and the
  // groups stored interleaved (TextureGroup), read in one pass.
  std::vector<uint8_t> group_unassociate;
  std::vector<int> group_outputs;
  std::vector<std::shared_ptr<const TextureGroup>> texture_groups;
  // Forms the image groups once the nodes and textures are final.
  void group_images();
  // Image lookups at a UV map's point at the hit (a group's, or a lone image node's), found by
  // group_images: what prefetch_texels starts loading.
  struct UVLookup {
    int uv_map = 0;
    const Texture* texture = nullptr;        // its footprint
    const TextureGroup* group = nullptr;     // or null: the texture's own texels
  };
  std::vector<UVLookup> uv_lookups;
  // Starts loading the texels these lookups will read at `hit` (a hint, for a batch of hits
  // shaded after).
  void prefetch_texels(const Scene& scene, const Hit& hit) const;

  // Runs the program; `registers` holds kMaxRegisters (num_registers are written).
  void evaluate(const ShadingContext& ctx, Vec3* registers) const;
  // Runs the program at n hits, hit k's registers at registers[k]: node by node over chunks of
  // kBatchChunk hits, so that the hits' independent work overlaps. Each hit's registers are
  // what evaluate() gives it, bit for bit.
  static constexpr int kBatchChunk = 8;
  void evaluate_batch(const ShadingContext* ctxs, Vec3* const* registers, int n) const;
  RGB emitted(const Vec3* registers) const;
  // Holdout closures' total weight (Cycles makes the pixel transparent by it on camera rays).
  std::vector<GraphInput> holdouts;
  RGB holdout(const Vec3* registers) const;
  bool emission_is_constant() const { return emission.reg < 0; }
  // Adds each closure with a non-zero weight to `bsdf`, placing per-hit models in `arena`.
  // `tangent` orients anisotropic closures (as the point's own frame does).
  void add_closures(const Vec3* registers, const Vec3& tangent, ClosureArena& arena,
                    BSDF& bsdf) const;
  // Flags of the union of the closures' models (from their constant or default parameters).
  uint32_t flags() const;

 private:
  struct HitSurfaces;
  void run_node(const GraphNode& node, const ShadingContext& ctx, Vec3* registers,
                const HitSurfaces& surfaces) const;
};

// Cycles' colour → float: Rec.709 luminance with its coefficients.
inline float luminance(const Vec3& c) {
  return 0.2126729f * c.x + 0.7151522f * c.y + 0.0721750f * c.z;
}

// Reads a register input, converting as the consumer expects (a vector → float is the mean).
// Inline: every node input and closure parameter goes through it at every hit.
inline Vec3 read_input(const GraphInput& in, const Vec3* registers) {
  const Vec3 v = in.reg < 0 ? in.constant : registers[in.reg];
  switch (in.convert) {
    case GraphConvert::None: return v;
    case GraphConvert::ColorToFloat: {
      const float y = luminance(v);
      return {y, y, y};
    }
    case GraphConvert::VectorToFloat: {
      const float m = (v.x + v.y + v.z) * (1.0f / 3.0f);
      return {m, m, m};
    }
  }
  return v;
}
inline float read_float(const GraphInput& in, const Vec3* registers) {
  return read_input(in, registers).x;
}

}  // namespace bxdf::render
