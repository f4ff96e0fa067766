#include "bxdf/io/material_json.h"

#include <cmath>
#include <cstdint>
#include <fstream>

#include "bxdf/input_file.h"
#include "bxdf/io/atomic_file.h"
#include "bxdf/io/json_text.h"
#include "bxdf/presets.h"

namespace bxdf::io {

using nlohmann::json;

namespace {

[[noreturn]] void bad_field(const std::string& where, const std::string& field,
                            const std::string& expected, const json& got) {
  throw ParameterError(printable(where + ": field '" + field + "': expected " + expected +
                                 ", got " + describe_json(got)));
}

const ParamSpec* find_spec(const std::vector<ParamSpec>& specs, const std::string& name) {
  for (const auto& s : specs)
    if (s.name == name) return &s;
  return nullptr;
}

std::string join_names(const std::vector<ParamSpec>& specs) {
  std::string s;
  for (const auto& p : specs) s += (s.empty() ? "" : ", ") + p.name;
  return s;
}

Value value_from_json(const ParamSpec& spec, const json& j, const std::string& where,
                      const std::string& field);

ParamSet record_from_json(const std::vector<ParamSpec>& specs, const json& j,
                          const std::string& where, const std::string& field) {
  if (!j.is_object()) bad_field(where, field, "an object", j);
  ParamSet out;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string sub = field.empty() ? it.key() : field + "." + it.key();
    const ParamSpec* spec = find_spec(specs, it.key());
    if (!spec)
      throw ParameterError(printable(where + ": field '" + sub + "': unknown parameter; known: " +
                                     join_names(specs)));
    out.set(it.key(), value_from_json(*spec, it.value(), where, sub));
  }
  return out;
}

double number_from_json(const json& j, const std::string& where, const std::string& field) {
  if (!j.is_number()) bad_field(where, field, "a number", j);
  return j.get<double>();
}

Value value_from_json(const ParamSpec& spec, const json& j, const std::string& where,
                      const std::string& field) {
  switch (spec.kind) {
    case ParamKind::Float: return Value(number_from_json(j, where, field));
    case ParamKind::RGB:
      if (j.is_number()) return Value(j.get<double>());
      if (!j.is_array() || j.size() != 3) bad_field(where, field, "[r, g, b] or a number", j);
      return Value(RGBValue{number_from_json(j[0], where, field + "[0]"),
                            number_from_json(j[1], where, field + "[1]"),
                            number_from_json(j[2], where, field + "[2]")});
    case ParamKind::Enum:
    case ParamKind::String:
      if (!j.is_string()) bad_field(where, field, "a string", j);
      return Value(j.get<std::string>());
    case ParamKind::Bool:
      if (!j.is_boolean()) bad_field(where, field, "true or false", j);
      return Value(j.get<bool>());
    case ParamKind::List: {
      if (!j.is_array()) bad_field(where, field, "an array of objects", j);
      std::vector<ParamSet> items;
      for (size_t i = 0; i < j.size(); ++i)
        items.push_back(
            record_from_json(spec.fields, j[i], where, field + "[" + std::to_string(i) + "]"));
      return Value(std::move(items));
    }
  }
  bad_field(where, field, "a value", j);
}

json value_to_json(const Value& v) {
  switch (v.type()) {
    case Value::Type::Number: return v.as_number();
    case Value::Type::RGB: return json::array({v.as_rgb()[0], v.as_rgb()[1], v.as_rgb()[2]});
    case Value::Type::String: return v.as_string();
    case Value::Type::Bool: return v.as_bool();
    case Value::Type::List: {
      json a = json::array();
      for (const auto& item : v.as_list()) a.push_back(params_to_json(item));
      return a;
    }
  }
  return nullptr;
}

}  // namespace

json params_to_json(const ParamSet& params) {
  json j = json::object();
  for (size_t i = 0; i < params.size(); ++i) j[params.names()[i]] = value_to_json(params.values()[i]);
  return j;
}

ParamSet params_from_json(const std::string& model, const json& j, const std::string& where) {
  const ModelInfo* info = find_model(model);
  if (!info) {
    std::string known;
    for (const auto& m : models()) known += (known.empty() ? "" : ", ") + m.name;
    throw ParameterError(where + ": field 'model': unknown model '" + printable(model) + "'; known: " + known);
  }
  const ParamSet given = record_from_json(info->params, j, where, "params");
  try {
    return validate_params(model, info->params, given);
  } catch (const ParameterError& e) {
    throw ParameterError(where + ": " + e.what());
  }
}

namespace {

// {"format", "version", "name", "graph"}: a node material, kept as JSON for the renderer.
MaterialDesc graph_material_from_json(const json& j, const std::string& where) {
  for (auto it = j.begin(); it != j.end(); ++it)
    if (it.key() != "format" && it.key() != "version" && it.key() != "name" && it.key() != "graph")
      throw ParameterError(where + ": field '" + it.key() +
                           "': unknown; a node material has format, version, name, graph");
  if (!j["graph"].is_object()) bad_field(where, "graph", "an object (docs/material-graph.md)", j["graph"]);
  MaterialDesc m;
  if (j.contains("name")) {
    if (!j["name"].is_string()) bad_field(where, "name", "a string", j["name"]);
    m.name = j["name"].get<std::string>();
  }
  m.graph = j["graph"];
  return m;
}

}  // namespace

json material_to_json(const MaterialDesc& m) {
  json j = json::object();
  j["format"] = kMaterialFormat;
  j["version"] = kMaterialVersion;
  if (!m.name.empty()) j["name"] = m.name;
  if (!m.graph.is_null()) {
    j["graph"] = m.graph;
    return j;
  }
  j["model"] = m.model;
  j["params"] = params_to_json(m.params);
  return j;
}

MaterialDesc material_from_json(const json& j, const std::string& where) {
  if (!j.is_object()) bad_field(where, "(material)", "an object", j);
  if (j.contains("format")) {
    const json& f = j["format"];
    if (!f.is_string() || f.get<std::string>() != kMaterialFormat)
      bad_field(where, "format", std::string("\"") + kMaterialFormat + "\"", f);
  }
  if (j.contains("version")) {
    const json& v = j["version"];
    // Compared as the 64-bit value JSON holds: get<int>() would wrap 4294967297 to 1.
    const bool in_range = v.is_number_unsigned()
                              ? v.get<std::uint64_t>() >= 1 && v.get<std::uint64_t>() <= kMaterialVersion
                              : v.is_number_integer() && v.get<std::int64_t>() >= 1 &&
                                    v.get<std::int64_t>() <= kMaterialVersion;
    if (!in_range)
      bad_field(where, "version", "an integer from 1 to " + std::to_string(kMaterialVersion), v);
  }
  if (j.contains("graph")) return graph_material_from_json(j, where);
  for (auto it = j.begin(); it != j.end(); ++it) {
    static const char* known[] = {"format", "version", "name", "model", "preset", "params"};
    bool ok = false;
    for (const char* k : known) ok = ok || it.key() == k;
    if (!ok)
      throw ParameterError(printable(where + ": field '" + it.key() +
                                     "': unknown; a material has format, version, name, model or preset, params"));
  }
  MaterialDesc m;
  if (j.contains("name")) {
    if (!j["name"].is_string()) bad_field(where, "name", "a string", j["name"]);
    m.name = j["name"].get<std::string>();
  }
  ParamSet base;
  if (j.contains("preset")) {
    if (j.contains("model"))
      throw ParameterError(where + ": fields 'model' and 'preset' exclude each other; give one");
    if (!j["preset"].is_string()) bad_field(where, "preset", "a preset name", j["preset"]);
    const Preset* p = find_preset(j["preset"].get<std::string>());
    if (!p)
      throw ParameterError(where + ": field 'preset': unknown preset '" +
                           printable(j["preset"].get<std::string>()) + "'; known: " + preset_names());
    m.model = p->model;
    base = p->params;
  } else {
    if (!j.contains("model")) throw ParameterError(where + ": field 'model' is missing");
    if (!j["model"].is_string()) bad_field(where, "model", "a model name", j["model"]);
    m.model = j["model"].get<std::string>();
  }
  const json params = j.contains("params") ? j["params"] : json::object();
  ParamSet given = params_from_json(m.model, params, where);
  // Preset values stand unless the file overrides them.
  if (j.contains("preset")) {
    for (size_t i = 0; i < base.size(); ++i)
      if (!params.contains(base.names()[i])) given.set(base.names()[i], base.values()[i]);
    given = validate_params(m.model, find_model(m.model)->params, given);
  }
  m.params = std::move(given);
  return m;
}

void save_material(const MaterialDesc& material, const std::string& path) {
  const std::string text = material_to_json(material).dump(2) + "\n";
  write_file_atomically(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    if (!out) throw ParameterError("cannot write material file '" + path + "'");
    out << text;
    out.close();
    if (!out) throw ParameterError("cannot write material file '" + path + "'");
  });
}

void save_material(const BxDF& model, const std::string& path, const std::string& name) {
  if (model.model_name().empty())
    throw ParameterError("save_material: the model was not made through the registry");
  save_material(MaterialDesc{name, model.model_name(), model.params()}, path);
}

MaterialDesc load_material_desc(const std::string& path) {
  const std::string text = read_input_file(path, kMaxJsonFileBytes, "material file");
  return material_from_json(parse_json(text, printable(path)), printable(path));
}

BxDFPtr make_material(const MaterialDesc& m, const std::string& where) {
  try {
    return make(m.model, m.params);
  } catch (const ParameterError& e) {
    // Models that read files (measured) fail here, after validation: name the material file.
    const std::string message = e.what();
    if (message.rfind(where, 0) == 0) throw;
    throw ParameterError(where + ": " + message);
  }
}

BxDFPtr load_material(const std::string& path) {
  const MaterialDesc m = load_material_desc(path);
  if (!m.graph.is_null())
    throw ParameterError(printable(path) + ": a node material (a graph of closures, not one model): "
                         "use it as a scene material");
  return make_material(m, printable(path));
}

}  // namespace bxdf::io
