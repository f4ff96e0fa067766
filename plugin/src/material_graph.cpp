#include "bxdf/render/material_graph.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "bxdf/render/environment.h"
#include "bxdf/render/graph_ops.h"
#include "bxdf/render/scene.h"
#include "bxdf/uninitialised.h"

namespace bxdf::render {

namespace {

Vec3 splat(float v) { return {v, v, v}; }

}  // namespace

// Rodrigues' rotation of p about the unit axis, as Cycles' rotate_around_axis.
Vec3 rotate_around_axis(const Vec3& p, const Vec3& axis, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return p * c + cross(axis, p) * s + axis * (dot(axis, p) * (1.0f - c));
}

// Where one hit of a batch reads the surface: the hit, or the bump offsets p + dpdx, p + dpdy
// (with the hit's barycentrics moved along, so that attributes follow, as Cycles' bump_dx nodes
// do); filled only for graphs with bumps (reads_offsets).
struct MaterialGraph::HitSurfaces {
  Hit offset_hits[2];
  Vec3 offset_points[2];
  Vec3 dpdx, dpdy;
};

void MaterialGraph::evaluate(const ShadingContext& ctx, Vec3* registers) const {
  evaluate_batch(&ctx, &registers, 1);
}

void MaterialGraph::evaluate_batch(const ShadingContext* ctxs, Vec3* const* registers, int n) const {
  for (int first = 0; first < n; first += kBatchChunk) {
    const int m = std::min(kBatchChunk, n - first);
    const ShadingContext* const chunk_ctxs = ctxs + first;
    Vec3* const* const chunk_registers = registers + first;
    // Left uninitialised: only graphs with bumps write (and read) them.
    Uninitialised<HitSurfaces, kBatchChunk> surface_storage;
    HitSurfaces* const surfaces = surface_storage.items;
    for (int k = 0; k < m; ++k) {
      const ShadingContext& ctx = chunk_ctxs[k];
      Vec3* const r = chunk_registers[k];
      if (reads_offsets) {
        HitSurfaces& hs = surfaces[k];
        Vec3 a, b;
        coordinate_system(ctx.ng, &a, &b);
        const float scale = std::max({1.0f, std::fabs(ctx.p.x), std::fabs(ctx.p.y), std::fabs(ctx.p.z)});
        hs.dpdx = a * (kBumpOffset * scale);
        hs.dpdy = b * (kBumpOffset * scale);
        hs.offset_hits[0] = ctx.scene->offset_hit(*ctx.hit, hs.dpdx);
        hs.offset_hits[1] = ctx.scene->offset_hit(*ctx.hit, hs.dpdy);
        hs.offset_points[0] = ctx.p + hs.dpdx;
        hs.offset_points[1] = ctx.p + hs.dpdy;
      }
      if (default_tangent_reg >= 0) {
        // Cycles' Tangent node default, made perpendicular to N as the node does.
        Vec3 t = ctx.scene->radial_tangent(*ctx.hit, ctx.p);
        if (normalize_direction(t)) {
          Vec3 side = cross(t, ctx.n);
          t = normalize_direction(side) ? cross(ctx.n, side) : Vec3(0.0f, 0.0f, 0.0f);
        }
        r[default_tangent_reg] = t;
      }
    }
    // Node by node, each over the chunk's hits: the hits' work is independent, so one hit's
    // latency chains (texel loads, the normal map's square roots and divisions) overlap the
    // next hit's instead of following one another.
    for (const GraphNode& node : nodes) {
      if (node.grouped) continue;  // looked up with its group's first node
      for (int k = 0; k < m; ++k)
        run_node(node, chunk_ctxs[k], chunk_registers[k], surfaces[k]);
    }
  }
}

// Inlined into evaluate_batch's per-hit loop: a call's prologue per node and hit cost more than
// most nodes' work.
[[gnu::always_inline]] inline void MaterialGraph::run_node(const GraphNode& node,
                                                           const ShadingContext& ctx, Vec3* r,
                                                           const HitSurfaces& surfaces) const {
  const Scene& scene = *ctx.scene;
  auto in = [&](int i) { return read_input(node.in[size_t(i)], r); };
  auto in_float = [&](int i) { return read_float(node.in[size_t(i)], r); };
  Vec3* out = r + node.out;
  const bool at_hit = node.offset == 0;
  const Hit& hit = at_hit ? *ctx.hit : surfaces.offset_hits[node.offset - 1];
  const Vec3& p = at_hit ? ctx.p : surfaces.offset_points[node.offset - 1];
  switch (node.op) {
    case GraphOp::Const: out[0] = in(0); break;
    case GraphOp::UV: out[0] = scene.uv(hit, node.index); break;
    case GraphOp::Generated: out[0] = scene.generated(hit, p); break;
    case GraphOp::Object: out[0] = scene.object_position(hit, p); break;
    case GraphOp::Position: out[0] = p; break;
    case GraphOp::Normal: out[0] = ctx.n; break;
    case GraphOp::Incoming: out[0] = ctx.incoming; break;
    case GraphOp::Image: {
      if (node.grouped) break;  // looked up with its group's first node
      const Vec3 uv = in(0);
      const Texture& texture = *textures[size_t(node.index)];
      if (node.group_count == 0) {
        texture.lookup(uv.x, uv.y, node.flag, out);
        break;
      }
      const TexelFootprint footprint = texture.footprint(uv.x, uv.y);
      if (node.texture_group >= 0) {
        const size_t at = size_t(node.group_first);
        texture_groups[size_t(node.texture_group)]->lookup(footprint, &group_unassociate[at],
                                                            &group_outputs[at], r);
        break;
      }
      for (int k = 0; k < node.group_count; ++k) {
        const GraphNode& member = nodes[size_t(image_groups[size_t(node.group_first + k)])];
        textures[size_t(member.index)]->lookup(footprint, member.flag, r + member.out);
      }
      break;
    }
    case GraphOp::Environment: {
      // Cycles' svm_node_tex_environment: the vector normalised (zero stays zero), then
      // projected to image coordinates and looked up as an Image Texture is.
      Vec3 dir = in(0);
      if (!normalize_direction(dir)) dir = Vec3(0.0f, 0.0f, 0.0f);
      const Point2 uv = EnvironmentProjection(node.mode) == EnvironmentProjection::MirrorBall
                            ? direction_to_mirrorball(dir)
                            : direction_to_equirect(dir);
      textures[size_t(node.index)]->lookup(uv.x, uv.y, node.flag, out);
      break;
    }
    case GraphOp::Transform:
      out[0] = transform(matrices[size_t(node.index)], TransformKind(node.mode), in(0), node.flag);
      break;
    case GraphOp::MixRGB:
      out[0] = mix_rgb(MixBlend(node.mode), in_float(0), in(1), in(2), node.clamp);
      break;
    case GraphOp::Math:
      out[0] = splat(math(MathOp(node.mode), in_float(0), in_float(1), in_float(2), node.clamp));
      break;
    case GraphOp::VectorMath: {
      float value = 0.0f;
      vector_math(VectorMathOp(node.mode), in(0), in(1), in(2), in_float(3), &out[0], &value);
      out[1] = splat(value);
      break;
    }
    case GraphOp::Invert: out[0] = invert(in_float(0), in(1)); break;
    case GraphOp::Gamma: out[0] = gamma(in(0), in_float(1)); break;
    case GraphOp::BrightContrast: out[0] = bright_contrast(in(0), in_float(1), in_float(2)); break;
    case GraphOp::HSV:
      out[0] = hsv(in_float(0), in_float(1), in_float(2), in_float(3), in(4));
      break;
    case GraphOp::Separate: {
      const Vec3 v = in(0);
      out[0] = splat(v.x);
      out[1] = splat(v.y);
      out[2] = splat(v.z);
      break;
    }
    case GraphOp::Combine: out[0] = Vec3(in_float(0), in_float(1), in_float(2)); break;
    case GraphOp::ColorRamp: {
      float alpha = 0.0f;
      color_ramp(ramps[size_t(node.index)], in_float(0), &out[0], &alpha);
      out[1] = splat(alpha);
      break;
    }
    case GraphOp::Fresnel:
      out[0] = splat(fresnel_node(in_float(0), ctx.incoming,
                                  node.in[1].reg < 0 ? ctx.n : in(1), ctx.backfacing));
      break;
    case GraphOp::LayerWeight: {
      float fresnel = 0.0f, facing = 0.0f;
      layer_weight(in_float(0), ctx.incoming, node.in[1].reg < 0 ? ctx.n : in(1),
                   ctx.backfacing, &fresnel, &facing);
      out[0] = splat(fresnel);
      out[1] = splat(facing);
      break;
    }
    case GraphOp::NormalMap: {
      Vec3 tangent;
      float sign = 1.0f;
      if (!scene.tangent(hit, node.index, &tangent, &sign)) {
        out[0] = ctx.n;  // Cycles: no tangent attribute, unperturbed normal
        break;
      }
      // Cycles composes the mapped normal in object space (tangent and smooth normal there)
      // and moves it to world space as a normal; it also makes every closure normal a valid
      // reflection, done here once per map.
      // The smooth normal is unnormalised (shorter between differing vertex normals), and
      // keeps its length in object space as Cycles' object-space interpolation has it.
      const Vec3 smooth = at_hit && ctx.point ? ctx.point->smooth_normal : scene.smooth_normal(hit);
      Vec3 normal = scene.normal_to_object(hit, smooth);
      const float object_length2 = length_squared(normal);
      if (object_length2 > 0.0f)
        normal = normal * std::sqrt(length_squared(smooth) / object_length2);
      // Normalised once, after the transform: Cycles' safe_normalize before it gives the
      // same direction (the transform is linear).
      Vec3 mapped = scene.normal_to_world(hit, normal_map_direction(in(1), tangent, sign, normal));
      if (!normalize_direction(mapped)) mapped = Vec3(0.0f, 0.0f, 0.0f);
      out[0] = ensure_valid_reflection(
          ctx.ng, ctx.incoming, normal_map_finish(mapped, in_float(0), ctx.n, ctx.backfacing));
      break;
    }
    case GraphOp::Bump: {
      BumpInputs b;
      b.strength = in_float(0);
      b.distance = in_float(1);
      b.height = in_float(2);
      b.normal = node.in[3].reg < 0 ? ctx.n : in(3);
      b.height_x = in_float(4);
      b.height_y = in_float(5);
      // (Every graph with a bump reads the offsets; the zero step is a hand-built graph's.)
      b.dpdx = reads_offsets ? surfaces.dpdx : Vec3();
      b.dpdy = reads_offsets ? surfaces.dpdy : Vec3();
      b.invert = node.flag;
      out[0] = bump_normal(b, ctx.ng, ctx.incoming);
      break;
    }
  }
}

void MaterialGraph::prefetch_texels(const Scene& scene, const Hit& hit) const {
  for (const UVLookup& l : uv_lookups) {
    const Vec3 uv = scene.uv(hit, l.uv_map);
    const TexelFootprint f = l.texture->footprint(uv.x, uv.y);
    if (l.group) l.group->prefetch(f);
    else l.texture->prefetch(f);
  }
}

void MaterialGraph::group_images() {
  image_groups.clear();
  group_unassociate.clear();
  group_outputs.clear();
  texture_groups.clear();
  for (GraphNode& node : nodes) {
    node.group_first = node.group_count = 0;
    node.grouped = false;
    node.texture_group = -1;
  }
  for (size_t i = 0; i < nodes.size(); ++i) {
    GraphNode& first = nodes[i];
    if (first.op != GraphOp::Image || first.grouped) continue;
    const GraphInput& coords = first.in[0];
    const Texture& texture = *textures[size_t(first.index)];
    std::vector<int> group;
    for (size_t j = i; j < nodes.size(); ++j) {
      const GraphNode& other = nodes[j];
      const GraphInput& c = other.in[0];
      // Registers are written once, so one register (or one constant) is one point.
      if (other.op == GraphOp::Image && !other.grouped && other.offset == first.offset &&
          c.reg == coords.reg && c.convert == coords.convert &&
          (c.reg >= 0 || c.constant == coords.constant) &&
          texture.shares_footprints(*textures[size_t(other.index)]))
        group.push_back(int(j));
    }
    if (group.size() < 2) continue;
    first.group_first = int(image_groups.size());
    first.group_count = int(group.size());
    for (size_t k = 1; k < group.size(); ++k) nodes[size_t(group[k])].grouped = true;
    image_groups.insert(image_groups.end(), group.begin(), group.end());
    std::vector<const Texture*> images;
    for (int j : group) {
      const GraphNode& member = nodes[size_t(j)];
      images.push_back(textures[size_t(member.index)].get());
      group_unassociate.push_back(member.flag ? 1 : 0);
      group_outputs.push_back(member.out);
    }
    if (auto interleaved = TextureGroup::make(images)) {
      first.texture_group = int(texture_groups.size());
      texture_groups.push_back(std::move(interleaved));
    }
  }
  // Lookups at a UV map's point at the hit itself (not at bump offsets), read straight from
  // the UV node's register.
  uv_lookups.clear();
  for (const GraphNode& node : nodes) {
    if (node.op != GraphOp::Image || node.grouped || node.offset != 0 || node.in[0].reg < 0 ||
        node.in[0].convert != GraphConvert::None)
      continue;
    for (const GraphNode& source : nodes) {
      if (source.op == GraphOp::UV && source.offset == 0 && source.out == node.in[0].reg) {
        UVLookup l;
        l.uv_map = source.index;
        l.texture = textures[size_t(node.index)].get();
        l.group = node.texture_group >= 0 ? texture_groups[size_t(node.texture_group)].get() : nullptr;
        uv_lookups.push_back(l);
        break;
      }
    }
  }
}

RGB MaterialGraph::emitted(const Vec3* registers) const {
  // Signed, as Cycles lets a negative Emission strength or colour take light away; a
  // non-finite channel emits nothing.
  const Vec3 e = read_input(emission, registers);
  auto finite_or_zero = [](float x) { return std::isfinite(x) ? x : 0.0f; };
  return RGB(finite_or_zero(e.x), finite_or_zero(e.y), finite_or_zero(e.z));
}

RGB MaterialGraph::holdout(const Vec3* registers) const {
  RGB total(0.0f);
  for (const GraphInput& h : holdouts) {
    const Vec3 w = read_input(h, registers);
    total += RGB(std::max(w.x, 0.0f), std::max(w.y, 0.0f), std::max(w.z, 0.0f));
  }
  return total;
}

void MaterialGraph::add_closures(const Vec3* registers, const Vec3& tangent,
                                 ClosureArena& arena, BSDF& bsdf) const {
  // Left uninitialised: zeroing all 48 at every hit cost more than the closures' own set-up;
  // each closure writes the values it reads.
  Uninitialised<PlainValue, kMaxClosureParams> storage;
  PlainValue* const values = storage.items;
  int frame_reg = -1;  // closures that share a normal share its frame
  Frame frame;
  for (const GraphClosure& c : closures) {
    const Vec3 w = read_input(c.weight, registers);
    const RGB weight(std::max(w.x, 0.0f), std::max(w.y, 0.0f), std::max(w.z, 0.0f));
    // Cycles drops closures whose weight is below CLOSURE_WEIGHT_CUTOFF.
    if (!(weight.r + weight.g + weight.b > 3e-5f) || !finite_nonnegative(weight)) continue;
    const BxDF* model = c.prebuilt.get();
    if (!model) {
      std::memcpy(values, c.constants.data(), c.constants.size() * sizeof(PlainValue));
      for (const GraphClosure::BoundParam& b : c.bound) {
        // Into the registry's range, as Cycles clamps closure inputs (NaN to the lower end).
        const Vec3 v = read_input(b.input, registers);
        const float lo = b.lo, hi = b.hi;
        auto clamp_one = [lo, hi](float x) { return !(x >= lo) ? lo : (x > hi ? hi : x); };
        values[b.index] = {clamp_one(v.x), clamp_one(v.y), clamp_one(v.z)};
      }
      model = c.model->place(values, arena);
      if (!model) continue;  // cannot happen: the reader checked the arena's capacity
    }
    if (c.oriented()) {
      // Cycles' Anisotropic BSDF: its Tangent (or the point's), turned about the closure's
      // normal by Rotation · 2π when that is not 0; a frame of its own.
      Vec3 n = bsdf.frame().n;
      if (c.normal_reg >= 0) {
        Vec3 mapped = registers[c.normal_reg];
        if (normalize_direction(mapped)) n = mapped;
      }
      Vec3 t = c.has_tangent            ? read_input(c.tangent, registers)
               : default_tangent_reg >= 0 ? registers[default_tangent_reg]
                                          : tangent;
      const float turns = read_float(c.rotation, registers);
      if (turns != 0.0f) t = rotate_around_axis(t, n, turns * 2.0f * kPi);
      const Frame oriented = Frame::from_normal_tangent(n, t);
      bsdf.add(model, weight, &oriented, c.diffuse_closure);
      continue;
    }
    if (c.normal_reg >= 0) {
      if (c.normal_reg != frame_reg) {
        Vec3 n = registers[c.normal_reg];
        frame_reg = normalize_direction(n) ? c.normal_reg : -2;
        if (frame_reg >= 0) frame = Frame::from_normal_tangent(n, tangent);
      }
      if (frame_reg == c.normal_reg) {
        bsdf.add(model, weight, &frame, c.diffuse_closure);
        continue;
      }
    }
    bsdf.add(model, weight);
  }
}

uint32_t MaterialGraph::flags() const {
  uint32_t f = 0;
  for (const GraphClosure& c : closures) {
    if (c.prebuilt) {
      f |= c.prebuilt->flags();
    } else {
      ClosureArena arena;
      if (const BxDF* m = c.model->place(c.constants.data(), arena)) f |= m->flags();
    }
  }
  return f;
}

}  // namespace bxdf::render
