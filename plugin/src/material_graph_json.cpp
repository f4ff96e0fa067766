#include "bxdf/render/material_graph_json.h"

#include <filesystem>
#include <map>

#include "bxdf/io/material_json.h"
#include "bxdf/render/graph_ops.h"

namespace bxdf::render {

using nlohmann::json;

namespace {

enum class Kind { Float, Color, Vector };

struct InputSpec {
  const char* name;
  Kind kind;
  Vec3 default_value;
  bool reference_only = false;  // an optional normal: absent means the shading normal
};
struct OutputSpec {
  const char* name;
  int offset;
  Kind kind;
};
struct OpSpec {
  const char* name;
  GraphOp op;
  std::vector<InputSpec> inputs;  // in GraphNode::in order
  std::vector<OutputSpec> outputs;
};

Vec3 grey(float v) { return {v, v, v}; }

const std::vector<OpSpec>& op_specs() {
  static const std::vector<OpSpec> specs = {
      {"const", GraphOp::Const, {{"value", Kind::Color, grey(0)}}, {{"value", 0, Kind::Color}}},
      {"uv", GraphOp::UV, {}, {{"vector", 0, Kind::Vector}}},
      {"generated", GraphOp::Generated, {}, {{"vector", 0, Kind::Vector}}},
      {"object", GraphOp::Object, {}, {{"vector", 0, Kind::Vector}}},
      {"position", GraphOp::Position, {}, {{"vector", 0, Kind::Vector}}},
      {"normal", GraphOp::Normal, {}, {{"vector", 0, Kind::Vector}}},
      {"incoming", GraphOp::Incoming, {}, {{"vector", 0, Kind::Vector}}},
      {"image", GraphOp::Image, {{"vector", Kind::Vector, grey(0)}},
       {{"color", 0, Kind::Color}, {"alpha", 1, Kind::Float}}},
      {"transform", GraphOp::Transform, {{"vector", Kind::Vector, grey(0)}},
       {{"vector", 0, Kind::Vector}}},
      {"mix_rgb", GraphOp::MixRGB,
       {{"fac", Kind::Float, grey(0.5f)}, {"a", Kind::Color, grey(0.5f)}, {"b", Kind::Color, grey(0.5f)}},
       {{"color", 0, Kind::Color}}},
      {"math", GraphOp::Math,
       {{"a", Kind::Float, grey(0.5f)}, {"b", Kind::Float, grey(0.5f)}, {"c", Kind::Float, grey(0.5f)}},
       {{"value", 0, Kind::Float}}},
      {"vector_math", GraphOp::VectorMath,
       {{"a", Kind::Vector, grey(0)}, {"b", Kind::Vector, grey(0)}, {"c", Kind::Vector, grey(0)},
        {"scale", Kind::Float, grey(1)}},
       {{"vector", 0, Kind::Vector}, {"value", 1, Kind::Float}}},
      {"invert", GraphOp::Invert, {{"fac", Kind::Float, grey(1)}, {"color", Kind::Color, grey(0)}},
       {{"color", 0, Kind::Color}}},
      {"gamma", GraphOp::Gamma, {{"color", Kind::Color, grey(1)}, {"gamma", Kind::Float, grey(1)}},
       {{"color", 0, Kind::Color}}},
      {"bright_contrast", GraphOp::BrightContrast,
       {{"color", Kind::Color, grey(1)}, {"bright", Kind::Float, grey(0)},
        {"contrast", Kind::Float, grey(0)}},
       {{"color", 0, Kind::Color}}},
      {"hsv", GraphOp::HSV,
       {{"hue", Kind::Float, grey(0.5f)}, {"saturation", Kind::Float, grey(1)},
        {"value", Kind::Float, grey(1)}, {"fac", Kind::Float, grey(1)},
        {"color", Kind::Color, grey(0.8f)}},
       {{"color", 0, Kind::Color}}},
      {"separate", GraphOp::Separate, {{"vector", Kind::Vector, grey(0)}},
       {{"x", 0, Kind::Float}, {"y", 1, Kind::Float}, {"z", 2, Kind::Float},
        {"r", 0, Kind::Float}, {"g", 1, Kind::Float}, {"b", 2, Kind::Float}}},
      {"combine", GraphOp::Combine,
       {{"x", Kind::Float, grey(0)}, {"y", Kind::Float, grey(0)}, {"z", Kind::Float, grey(0)}},
       {{"vector", 0, Kind::Vector}, {"color", 0, Kind::Color}}},
      {"color_ramp", GraphOp::ColorRamp, {{"fac", Kind::Float, grey(0.5f)}},
       {{"color", 0, Kind::Color}, {"alpha", 1, Kind::Float}}},
      {"fresnel", GraphOp::Fresnel,
       {{"ior", Kind::Float, grey(1.45f)}, {"normal", Kind::Vector, grey(0), true}},
       {{"fac", 0, Kind::Float}}},
      {"layer_weight", GraphOp::LayerWeight,
       {{"blend", Kind::Float, grey(0.5f)}, {"normal", Kind::Vector, grey(0), true}},
       {{"fresnel", 0, Kind::Float}, {"facing", 1, Kind::Float}}},
      {"normal_map", GraphOp::NormalMap,
       {{"strength", Kind::Float, grey(1)}, {"color", Kind::Color, Vec3(0.5f, 0.5f, 1.0f)}},
       {{"normal", 0, Kind::Vector}}},
      // Inputs 4 and 5 (the height at the two offsets) are filled by the reader.
      {"bump", GraphOp::Bump,
       {{"strength", Kind::Float, grey(1)}, {"distance", Kind::Float, grey(1)},
        {"height", Kind::Float, grey(1)}, {"normal", Kind::Vector, grey(0), true}},
       {{"normal", 0, Kind::Vector}}},
      {"environment", GraphOp::Environment, {{"vector", Kind::Vector, grey(0)}},
       {{"color", 0, Kind::Color}, {"alpha", 1, Kind::Float}}},
  };
  return specs;
}

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

[[noreturn]] void fail(const std::string& field, const std::string& problem) {
  throw GraphFieldError(field, problem);
}
std::string got(const json& j) {
  std::string text = j.dump();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

// The ops that look a texture up (Image, Environment): their colour is unassociated from alpha
// when their Alpha output is used.
bool looks_up_texture(GraphOp op) { return op == GraphOp::Image || op == GraphOp::Environment; }

struct NodeOutputs {
  const OpSpec* spec = nullptr;
  int first_register = 0;
  bool alpha_used = false;
};

class GraphReader {
 public:
  GraphReader(std::string base_dir, TextureStore& store) : base_(std::move(base_dir)), store_(store) {}

  std::shared_ptr<const MaterialGraph> read(const json& j, const std::string& field) {
    if (!j.is_object()) fail(field, "expected an object, got " + got(j));
    only_keys(j, field, {"nodes", "closures", "emission", "textures"});
    if (j.contains("textures")) read_textures(j["textures"], field + ".textures");
    if (j.contains("nodes")) {
      const json& nodes = j["nodes"];
      if (!nodes.is_array()) fail(field + ".nodes", "expected an array of nodes, got " + got(nodes));
      total_nodes_ = nodes.size();
      for (size_t i = 0; i < nodes.size(); ++i)
        read_node(nodes[i], field + ".nodes[" + std::to_string(i) + "]", int(i));
    }
    // An image's colour is unassociated from alpha only when its Alpha output is used (Cycles).
    for (size_t i = 0; i < outputs_.size(); ++i) {
      GraphNode& node = g_->nodes[node_of_[i]];
      if (!looks_up_texture(node.op) || !outputs_[i].alpha_used) continue;
      const TextureSettings& t = g_->textures[size_t(node.index)]->settings();
      node.flag = t.colorspace != TextureColorspace::NonColor &&
                  (t.alpha == TextureAlpha::Straight || t.alpha == TextureAlpha::Premultiplied);
    }
    for (size_t k = 0; k < g_->nodes.size(); ++k)  // bump copies read images as the originals do
      if (looks_up_texture(g_->nodes[k].op)) g_->nodes[k].flag = g_->nodes[original_[k]].flag;
    const json& closures = j.contains("closures") ? j["closures"] : json::array();
    if (!closures.is_array() || closures.size() > size_t(BSDF::kMaxComponents))
      fail(field + ".closures", "expected an array of at most " +
                                    std::to_string(BSDF::kMaxComponents) + " closures, got " + got(closures));
    size_t arena_bytes = 0;
    for (size_t k = 0; k < closures.size(); ++k) {
      const std::string path = field + ".closures[" + std::to_string(k) + "]";
      const size_t before = g_->closures.size();
      read_closure(closures[k], path, int(node_count_));
      if (g_->closures.size() == before) continue;  // a holdout
      const GraphClosure& c = g_->closures.back();
      if (!c.prebuilt) arena_bytes += c.model->place_size + 64;
    }
    if (arena_bytes > ClosureArena::kCapacity)
      fail(field + ".closures", "the textured closures need " + std::to_string(arena_bytes) +
                                    " bytes per hit; at most " + std::to_string(ClosureArena::kCapacity));
    g_->emission = j.contains("emission")
                       ? read_value(j["emission"], field + ".emission", Kind::Color, int(node_count_))
                       : GraphInput{};
    // A negative emission is allowed: Cycles renders it as light taken away.
    if (closures.empty() && g_->emission.reg < 0 && g_->emission.constant == Vec3())
      fail(field, "a graph needs at least one closure or an emission");
    g_->num_registers = next_register_;
    g_->group_images();
    return g_;
  }

 private:
  void only_keys(const json& j, const std::string& field, std::initializer_list<const char*> keys) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool ok = false;
      std::vector<std::string> names;
      for (const char* k : keys) {
        ok = ok || it.key() == k;
        names.emplace_back(k);
      }
      if (!ok) fail(field + "." + it.key(), "unknown field; expected one of {" + join(names) + "}");
    }
  }
  float number(const json& j, const std::string& field) {
    if (!j.is_number() || !std::isfinite(j.get<double>()))
      fail(field, "expected a finite number, got " + got(j));
    return j.get<float>();
  }
  int integer(const json& j, const std::string& field, int lo, int hi) {
    if (!j.is_number_integer() || j.get<long long>() < lo || j.get<long long>() > hi)
      fail(field, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                      "], got " + got(j));
    return j.get<int>();
  }
  std::string choice(const json& j, const std::string& field, const std::vector<std::string>& names,
                     int* index = nullptr) {
    if (j.is_string())
      for (size_t i = 0; i < names.size(); ++i)
        if (names[i] == j.get<std::string>()) {
          if (index) *index = int(i);
          return names[i];
        }
    fail(field, "expected one of {" + join(names) + "}, got " + got(j));
  }
  bool boolean(const json& j, const std::string& field) {
    if (!j.is_boolean()) fail(field, "expected true or false, got " + got(j));
    return j.get<bool>();
  }

  void read_textures(const json& j, const std::string& field) {
    if (!j.is_array()) fail(field, "expected an array of textures, got " + got(j));
    for (size_t i = 0; i < j.size(); ++i) {
      const std::string path = field + "[" + std::to_string(i) + "]";
      const json& t = j[i];
      if (!t.is_object()) fail(path, "expected an object, got " + got(t));
      only_keys(t, path, {"path", "missing", "interpolation", "extension", "colorspace", "alpha", "name"});
      TextureSettings s;
      int k = 0;
      if (t.contains("missing")) s.missing = boolean(t["missing"], path + ".missing");
      if (t.contains("interpolation")) {
        choice(t["interpolation"], path + ".interpolation", {"closest", "linear", "cubic"}, &k);
        s.interpolation = TextureInterpolation(k);
      }
      if (t.contains("extension")) {
        choice(t["extension"], path + ".extension", {"repeat", "extend", "clip"}, &k);
        s.extension = TextureExtension(k);
      }
      if (t.contains("colorspace")) {
        choice(t["colorspace"], path + ".colorspace", {"srgb", "linear", "non_color"}, &k);
        s.colorspace = TextureColorspace(k);
      }
      if (t.contains("alpha")) {
        choice(t["alpha"], path + ".alpha", {"straight", "premultiplied", "channel_packed", "none"}, &k);
        s.alpha = TextureAlpha(k);
      }
      if (!s.missing) {
        if (!t.contains("path") || !t["path"].is_string() || t["path"].get<std::string>().empty())
          fail(path + ".path", "expected the image's file name (or \"missing\": true)");
        std::filesystem::path file(t["path"].get<std::string>());
        if (file.is_relative() && !base_.empty()) file = std::filesystem::path(base_) / file;
        s.path = file.string();
        try {
          g_->textures.push_back(store_.get(s));
        } catch (const ParameterError& e) {
          fail(path + ".path", e.what());
        }
      } else {
        g_->textures.push_back(store_.get(s));
      }
    }
  }

  // A value: a number, [x, y, z] or {"node": i, "out": name} of a node before `before`.
  GraphInput read_value(const json& j, const std::string& field, Kind kind, int before) {
    GraphInput in;
    if (j.is_number()) {
      in.constant = grey(number(j, field));
      return in;
    }
    if (j.is_array()) {
      if (j.size() != 3) fail(field, "expected a number, [x, y, z] or a node reference, got " + got(j));
      in.constant = Vec3(number(j[0], field + "[0]"), number(j[1], field + "[1]"), number(j[2], field + "[2]"));
      if (kind == Kind::Float) in.constant = grey(luminance(in.constant));
      return in;
    }
    if (!j.is_object() || !j.contains("node"))
      fail(field, "expected a number, [x, y, z] or {\"node\": i, \"out\": name}, got " + got(j));
    only_keys(j, field, {"node", "out"});
    if (!j["node"].is_number_integer()) fail(field + ".node", "expected a node index, got " + got(j["node"]));
    const long long node = j["node"].get<long long>();
    if (node < 0 || node >= before)
      fail(field, "node " + std::to_string(node) + " is not earlier than " + std::to_string(before) +
                      (node >= 0 && node < static_cast<long long>(total_nodes_) ? "" : " (no such node)"));
    NodeOutputs& source = outputs_[size_t(node)];
    std::vector<std::string> names;
    for (const OutputSpec& o : source.spec->outputs) names.emplace_back(o.name);
    const std::string out = j.contains("out") ? choice(j["out"], field + ".out", names)
                                              : std::string(source.spec->outputs[0].name);
    for (const OutputSpec& o : source.spec->outputs) {
      if (out != o.name) continue;
      in.reg = source.first_register + o.offset;
      if (looks_up_texture(source.spec->op) && o.offset == 1) source.alpha_used = true;
      if (kind == Kind::Float && o.kind == Kind::Color) in.convert = GraphConvert::ColorToFloat;
      if (kind == Kind::Float && o.kind == Kind::Vector) in.convert = GraphConvert::VectorToFloat;
    }
    return in;
  }

  int add_node(GraphNode node, const OpSpec& spec) {
    int count = 0;
    for (const OutputSpec& o : spec.outputs) count = std::max(count, o.offset + 1);
    return add_node(node, count);
  }
  int add_node(GraphNode node, int count) {
    node.out = next_register_;
    next_register_ += count;
    if (next_register_ > MaterialGraph::kMaxRegisters)
      fail("graph.nodes", "the graph needs more than " + std::to_string(MaterialGraph::kMaxRegisters) +
                              " registers");
    register_owner_.insert(register_owner_.end(), size_t(count), g_->nodes.size());
    output_count_.push_back(count);
    original_.push_back(g_->nodes.size());
    g_->nodes.push_back(node);
    return node.out;
  }

  // A copy of the program behind `value` evaluated at bump offset `offset` (1: dx, 2: dy):
  // the nodes it depends on that read the surface, directly or through their inputs, are
  // copied with offset set; the rest are shared with the original.
  GraphInput offset_copy(const GraphInput& value, uint8_t offset, const std::string& field) {
    if (value.reg < 0) return value;
    const size_t count = g_->nodes.size();
    std::vector<char> needed(count, 0);
    needed[register_owner_[size_t(value.reg)]] = 1;
    for (size_t i = count; i-- > 0;)
      if (needed[i])
        for (const GraphInput& in : g_->nodes[i].in)
          if (in.reg >= 0) needed[register_owner_[size_t(in.reg)]] = 1;
    std::vector<int> copied(size_t(next_register_), -1);  // register → its copy's register
    for (size_t i = 0; i < count; ++i) {
      if (!needed[i]) continue;
      GraphNode node = g_->nodes[i];
      bool varies = node.op == GraphOp::UV || node.op == GraphOp::Generated ||
                    node.op == GraphOp::Object || node.op == GraphOp::Position ||
                    node.op == GraphOp::NormalMap;
      for (GraphInput& in : node.in)
        if (in.reg >= 0 && copied[size_t(in.reg)] >= 0) {
          in.reg = copied[size_t(in.reg)];
          varies = true;
        }
      if (!varies) continue;
      if (node.op == GraphOp::Bump)
        fail(field, "a bump's height cannot depend on another bump's normal");
      node.offset = offset;
      const int outputs = output_count_[i];
      const int first = add_node(node, outputs);
      original_.back() = i;
      for (int k = 0; k < outputs; ++k) copied[size_t(g_->nodes[i].out + k)] = first + k;
    }
    GraphInput out = value;
    if (copied[size_t(value.reg)] >= 0) out.reg = copied[size_t(value.reg)];
    return out;
  }

  void read_node(const json& j, const std::string& field, int index) {
    if (!j.is_object() || !j.contains("op")) fail(field, "expected a node object with \"op\", got " + got(j));
    std::vector<std::string> names;
    const OpSpec* spec = nullptr;
    for (const OpSpec& s : op_specs()) {
      names.emplace_back(s.name);
      if (j["op"].is_string() && j["op"].get<std::string>() == s.name) spec = &s;
    }
    if (!spec) {
      fail(field + ".op", "expected one of {" + join(names) + "}, got " + got(j["op"]));
    }
    GraphNode node;
    node.op = spec->op;
    std::vector<const char*> keys = {"op", "name"};
    for (const InputSpec& in : spec->inputs) keys.push_back(in.name);
    auto field_of = [&](const char* key) { return field + "." + key; };
    auto take = [&](const char* key) { keys.push_back(key); return j.contains(key); };
    switch (spec->op) {
      case GraphOp::UV:
        node.index = take("map") ? integer(j["map"], field_of("map"), 0, 7) : 0;
        break;
      case GraphOp::Environment:
        if (take("projection"))
          choice(j["projection"], field_of("projection"), {"equirectangular", "mirror_ball"}, &node.mode);
        [[fallthrough]];
      case GraphOp::Image:
        if (!take("texture")) fail(field_of("texture"), "is missing");
        if (g_->textures.empty()) fail(field_of("texture"), "the graph declares no \"textures\"");
        node.index = integer(j["texture"], field_of("texture"), 0, int(g_->textures.size()) - 1);
        break;
      case GraphOp::Transform: {
        if (!take("matrix")) fail(field_of("matrix"), "is missing");
        std::array<float, 12> m{};
        const json& mj = j["matrix"];
        if (!mj.is_array() || mj.size() != 3) fail(field_of("matrix"), "expected 3 rows of 4 numbers, got " + got(mj));
        for (int r = 0; r < 3; ++r) {
          const std::string row = field_of("matrix") + "[" + std::to_string(r) + "]";
          if (!mj[size_t(r)].is_array() || mj[size_t(r)].size() != 4) fail(row, "expected 4 numbers, got " + got(mj[size_t(r)]));
          for (int c = 0; c < 4; ++c) m[size_t(4 * r + c)] = number(mj[size_t(r)][size_t(c)], row + "[" + std::to_string(c) + "]");
        }
        node.mode = 0;
        if (take("kind")) choice(j["kind"], field_of("kind"), kTransformKindNames, &node.mode);
        if (TransformKind(node.mode) == TransformKind::Normal) m = inverse_transpose(m, field_of("matrix"));
        node.flag = take("normalize") && boolean(j["normalize"], field_of("normalize"));
        node.index = int(g_->matrices.size());
        g_->matrices.push_back(m);
        break;
      }
      case GraphOp::MixRGB:
        if (take("blend")) choice(j["blend"], field_of("blend"), kMixBlendNames, &node.mode);
        node.clamp = take("clamp") && boolean(j["clamp"], field_of("clamp"));
        break;
      case GraphOp::Math:
        if (!take("operation")) fail(field_of("operation"), "is missing");
        choice(j["operation"], field_of("operation"), kMathOpNames, &node.mode);
        node.clamp = take("clamp") && boolean(j["clamp"], field_of("clamp"));
        break;
      case GraphOp::VectorMath:
        if (!take("operation")) fail(field_of("operation"), "is missing");
        choice(j["operation"], field_of("operation"), kVectorMathOpNames, &node.mode);
        break;
      case GraphOp::ColorRamp: {
        int interpolation = int(RampInterpolation::Linear), color_mode = 0, hue = 0;
        if (take("color_mode")) choice(j["color_mode"], field_of("color_mode"), kRampColorModeNames, &color_mode);
        if (take("hue_interpolation"))
          choice(j["hue_interpolation"], field_of("hue_interpolation"), kRampHueNames, &hue);
        if (take("interpolation"))
          choice(j["interpolation"], field_of("interpolation"), kRampInterpolationNames, &interpolation);
        if (!take("stops") || !j["stops"].is_array() || j["stops"].empty())
          fail(field_of("stops"), "expected [[pos, r, g, b, a], ...] (at least one stop)");
        std::vector<std::array<float, 5>> stops;
        for (size_t s = 0; s < j["stops"].size(); ++s) {
          const std::string p = field_of("stops") + "[" + std::to_string(s) + "]";
          const json& st = j["stops"][s];
          if (!st.is_array() || st.size() != 5) fail(p, "expected [pos, r, g, b, a], got " + got(st));
          std::array<float, 5> v{};
          for (size_t c = 0; c < 5; ++c) v[c] = number(st[c], p + "[" + std::to_string(c) + "]");
          stops.push_back(v);
        }
        try {
          node.index = int(g_->ramps.size());
          g_->ramps.push_back(color_ramp_table(stops, RampInterpolation(interpolation),
                                               RampColorMode(color_mode), RampHue(hue)));
        } catch (const GraphFieldError&) {
          throw;
        } catch (const ParameterError& e) {
          fail(field_of("stops"), e.what());
        }
        break;
      }
      case GraphOp::NormalMap:
        if (take("space")) choice(j["space"], field_of("space"), {"tangent"});
        node.index = take("map") ? integer(j["map"], field_of("map"), 0, 7) : 0;
        break;
      case GraphOp::Bump:
        node.flag = take("invert") && boolean(j["invert"], field_of("invert"));
        break;
      default:
        break;
    }
    if (spec->op == GraphOp::Const) {
      if (!j.contains("value")) fail(field_of("value"), "is missing");
    }
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool known = false;
      for (const char* k : keys) known = known || it.key() == k;
      if (!known) {
        std::vector<std::string> list(keys.begin(), keys.end());
        fail(field + "." + it.key(), "unknown field for op '" + std::string(spec->name) +
                                         "'; expected one of {" + join(list) + "}");
      }
    }
    for (size_t i = 0; i < spec->inputs.size(); ++i) {
      const InputSpec& in = spec->inputs[i];
      if (j.contains(in.name)) {
        node.in[i] = read_value(j[in.name], field_of(in.name), in.kind, index);
        if (in.reference_only && node.in[i].reg < 0)
          fail(field_of(in.name), "expected a node reference (leave it out for the shading normal)");
      } else if (spec->op == GraphOp::Image && i == 0) {
        // Cycles' default for an unlinked image vector: the active UV map.
        GraphNode uv;
        uv.op = GraphOp::UV;
        uv.index = 0;
        node.in[i].reg = add_node(uv, op_specs()[1]);
      } else if (spec->op == GraphOp::Environment && i == 0) {
        // Cycles' default for an unlinked environment vector (LINK_POSITION): the position.
        GraphNode position;
        position.op = GraphOp::Position;
        node.in[i].reg = add_node(position, op_specs()[4]);
      } else {
        node.in[i].constant = in.default_value;
      }
    }
    if (spec->op == GraphOp::Bump) {
      // The height again at the two offset points: copies of the nodes it depends on that
      // read the surface (Cycles compiles the height sub-graph three times the same way).
      node.in[4] = offset_copy(node.in[2], 1, field_of("height"));
      node.in[5] = offset_copy(node.in[2], 2, field_of("height"));
      g_->reads_offsets = true;
    }
    node_of_.push_back(g_->nodes.size());
    NodeOutputs outs;
    outs.spec = spec;
    outs.first_register = add_node(node, *spec);
    outputs_.push_back(outs);
    ++node_count_;
  }

  std::array<float, 12> inverse_transpose(const std::array<float, 12>& m, const std::string& field) {
    const float a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9], k = m[10];
    const float det = a * (e * k - f * h) - b * (d * k - f * g) + c * (d * h - e * g);
    if (!(std::fabs(det) > 1e-30f)) fail(field, "is singular (cannot transform normals)");
    // (M⁻¹)ᵀ: the cofactor matrix over the determinant.
    return {(e * k - f * h) / det, (f * g - d * k) / det, (d * h - e * g) / det, 0.0f,
            (c * h - b * k) / det, (a * k - c * g) / det, (b * g - a * h) / det, 0.0f,
            (b * f - c * e) / det, (c * d - a * f) / det, (a * e - b * d) / det, 0.0f};
  }

  void read_closure(const json& j, const std::string& field, int before) {
    if (!j.is_object() || !j.contains("model"))
      fail(field, "expected a closure object with \"model\", got " + got(j));
    if (!j["model"].is_string()) fail(field + ".model", "expected a model name, got " + got(j["model"]));
    const std::string name = j["model"].get<std::string>();
    if (name == "holdout") {
      // Not a BSDF: its weight makes the pixel transparent (camera rays) and it reflects nothing.
      only_keys(j, field, {"model", "weight", "params", "name"});
      if (j.contains("params") && !(j["params"].is_object() && j["params"].empty()))
        fail(field + ".params", "a holdout has no parameters, got " + got(j["params"]));
      GraphInput w;
      w.constant = grey(1.0f);
      if (j.contains("weight")) w = read_value(j["weight"], field + ".weight", Kind::Color, before);
      if (w.reg < 0 && !finite_nonnegative(RGB(w.constant.x, w.constant.y, w.constant.z)))
        fail(field + ".weight", "must be in [0, inf) per channel, got " + got(j["weight"]));
      g_->holdouts.push_back(w);
      return;
    }
    only_keys(j, field, {"model", "weight", "params", "normal", "tangent", "rotation", "name"});
    GraphClosure c;
    c.model = find_model(name);
    if (!c.model) {
      std::vector<std::string> known;
      for (const auto& m : models()) known.push_back(m.name);
      fail(field + ".model", "unknown model '" + name + "'; known: " + join(known));
    }
    if (c.model->params.size() > MaterialGraph::kMaxClosureParams)
      fail(field + ".model", "model '" + name + "' has too many parameters for a graph");
    c.weight.constant = grey(1.0f);
    if (j.contains("weight")) c.weight = read_value(j["weight"], field + ".weight", Kind::Color, before);
    if (c.weight.reg < 0 && !finite_nonnegative(RGB(c.weight.constant.x, c.weight.constant.y, c.weight.constant.z)))
      fail(field + ".weight", "must be in [0, inf) per channel, got " + got(j["weight"]));
    const json params = j.contains("params") ? j["params"] : json::object();
    if (!params.is_object()) fail(field + ".params", "expected an object, got " + got(params));
    json constants = json::object();
    c.params.resize(c.model->params.size());
    for (auto it = params.begin(); it != params.end(); ++it) {
      const std::string pfield = field + ".params." + it.key();
      size_t index = 0;
      try {
        index = param_index(c.model->params, it.key());
      } catch (const ParameterError&) {
        std::vector<std::string> known;
        for (const auto& p : c.model->params) known.push_back(p.name);
        fail(pfield, "unknown parameter of '" + name + "'; known: " + join(known));
      }
      const ParamSpec& spec = c.model->params[index];
      if (it.value().is_object()) {
        if (spec.kind != ParamKind::Float && spec.kind != ParamKind::RGB)
          fail(pfield, std::string(to_string(spec.kind)) + " parameters must be constants");
        if (!c.model->place)
          fail(pfield, "model '" + name + "' cannot take per-hit parameters; give constants");
        c.params[index] = read_value(it.value(), pfield,
                                     spec.kind == ParamKind::Float ? Kind::Float : Kind::Color, before);
        c.all_constant = false;
      } else {
        constants[it.key()] = it.value();
      }
    }
    ParamSet validated;
    try {
      validated = io::params_from_json(name, constants, "");
    } catch (const ParameterError& e) {
      std::string msg = e.what();
      if (msg.rfind(": ", 0) == 0) msg = msg.substr(2);
      fail(field + ".params", msg);
    }
    if (c.all_constant) {
      c.prebuilt = make(name, validated);
    } else {
      c.constants = plain_values(*c.model, validated);
      for (size_t i = 0; i < c.params.size(); ++i) {
        if (c.params[i].reg < 0) {
          c.params[i].constant = Vec3(c.constants[i].x, c.constants[i].y, c.constants[i].z);
          continue;
        }
        // clamp_plain's bounds, once: the per-hit clamp is then two compares.
        const ParamSpec& spec = c.model->params[i];
        const PlainValue lo = clamp_plain(spec, {-INFINITY, -INFINITY, -INFINITY});
        const PlainValue hi = clamp_plain(spec, {INFINITY, INFINITY, INFINITY});
        c.bound.push_back({uint32_t(i), c.params[i], lo.x, hi.x});
      }
    }
    // Cycles' CLOSURE_IS_BSDF_DIFFUSE closures among the registry's models (Diffuse, Oren–Nayar,
    // Translucent); Principled's diffuse and sheen lobes are inside one model and are not.
    for (const char* diffuse : {"lambertian", "oren_nayar", "cycles_oren_nayar",
                                "lambertian_transmission", "cycles_translucent"})
      c.diffuse_closure = c.diffuse_closure || name == diffuse;
    if (j.contains("normal")) {
      const GraphInput n = read_value(j["normal"], field + ".normal", Kind::Vector, before);
      if (n.reg < 0) fail(field + ".normal", "expected a node reference (a normal_map or bump output)");
      c.normal_reg = n.reg;
    }
    if (j.contains("tangent")) {
      c.tangent = read_value(j["tangent"], field + ".tangent", Kind::Vector, before);
      c.has_tangent = true;
    }
    if (j.contains("rotation")) c.rotation = read_value(j["rotation"], field + ".rotation", Kind::Float, before);
    // Anisotropic closures are oriented by Cycles' default tangent unless given their own.
    for (const char* key : {"anisotropy", "anisotropic"})
      if (params.contains(key))
        c.anisotropic = c.anisotropic || !params[key].is_number() || params[key].get<double>() != 0.0;
    if (c.oriented() && !c.has_tangent && g_->default_tangent_reg < 0) {
      g_->default_tangent_reg = next_register_++;
      if (next_register_ > MaterialGraph::kMaxRegisters)
        fail(field, "the graph needs more than " + std::to_string(MaterialGraph::kMaxRegisters) +
                        " registers");
    }
    g_->closures.push_back(std::move(c));
  }

  std::string base_;
  TextureStore& store_;
  std::shared_ptr<MaterialGraph> g_ = std::make_shared<MaterialGraph>();
  std::vector<NodeOutputs> outputs_;  // per file node
  std::vector<size_t> node_of_;       // file node → program node
  std::vector<size_t> register_owner_;  // register → program node
  std::vector<int> output_count_;       // program node → its number of registers
  std::vector<size_t> original_;        // program node → the node it copies (itself if none)
  size_t node_count_ = 0, total_nodes_ = 0;
  int next_register_ = 0;
};

}  // namespace

std::shared_ptr<const MaterialGraph> read_material_graph(const json& graph, const std::string& field,
                                                         const std::string& base_dir,
                                                         TextureStore& textures) {
  return GraphReader(base_dir, textures).read(graph, field);
}

}  // namespace bxdf::render
