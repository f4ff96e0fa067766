#include "bxdf/params.h"

#include <cmath>
#include <sstream>

namespace bxdf {

namespace {

std::string format_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::ostringstream os;
  os.precision(9);
  os << v;
  return os.str();
}

}  // namespace

bool ParamSet::has(const std::string& name) const { return find(name) != nullptr; }

const Value* ParamSet::find(const std::string& name) const {
  for (size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return &values_[i];
  return nullptr;
}

const Value& ParamSet::at(const std::string& name) const {
  const Value* v = find(name);
  if (!v) throw ParameterError("missing parameter '" + name + "'");
  return *v;
}

void ParamSet::set(const std::string& name, Value v) {
  for (size_t i = 0; i < names_.size(); ++i) {
    if (names_[i] == name) {
      values_[i] = std::move(v);
      return;
    }
  }
  names_.push_back(name);
  values_.push_back(std::move(v));
}

bool ParamSet::erase(const std::string& name) {
  for (size_t i = 0; i < names_.size(); ++i) {
    if (names_[i] == name) {
      names_.erase(names_.begin() + static_cast<long>(i));
      values_.erase(values_.begin() + static_cast<long>(i));
      return true;
    }
  }
  return false;
}

double ParamSet::number(const std::string& name) const { return at(name).as_number(); }
RGBValue ParamSet::rgb(const std::string& name) const { return at(name).as_rgb(); }
const std::string& ParamSet::string(const std::string& name) const { return at(name).as_string(); }
bool ParamSet::boolean(const std::string& name) const { return at(name).as_bool(); }
const std::vector<ParamSet>& ParamSet::list(const std::string& name) const {
  return at(name).as_list();
}

bool ParamSet::operator==(const ParamSet& o) const {
  if (names_.size() != o.names_.size()) return false;
  for (size_t i = 0; i < names_.size(); ++i) {
    const Value* v = o.find(names_[i]);
    if (!v || !(*v == values_[i])) return false;
  }
  return true;
}

std::string Value::to_string() const {
  switch (type()) {
    case Type::Number: return format_number(as_number());
    case Type::RGB: {
      const auto& c = as_rgb();
      return "(" + format_number(c[0]) + ", " + format_number(c[1]) + ", " + format_number(c[2]) +
             ")";
    }
    case Type::String: return "'" + as_string() + "'";
    case Type::Bool: return as_bool() ? "true" : "false";
    case Type::List: {
      std::string s = "[";
      const auto& l = as_list();
      for (size_t i = 0; i < l.size(); ++i) {
        if (i) s += ", ";
        s += "{";
        for (size_t j = 0; j < l[i].size(); ++j) {
          if (j) s += ", ";
          s += l[i].names()[j] + ": " + l[i].values()[j].to_string();
        }
        s += "}";
      }
      return s + "]";
    }
  }
  return "?";
}

const char* to_string(ParamKind kind) {
  switch (kind) {
    case ParamKind::Float: return "float";
    case ParamKind::RGB: return "rgb";
    case ParamKind::Enum: return "enum";
    case ParamKind::Bool: return "bool";
    case ParamKind::String: return "string";
    case ParamKind::List: return "list";
  }
  return "?";
}

std::string ParamSpec::range_string() const {
  switch (kind) {
    case ParamKind::Float:
    case ParamKind::RGB: {
      std::string s = (min_exclusive ? "(" : "[") + format_number(min) + ", " + format_number(max) +
                      (max_exclusive ? ")" : "]");
      if (kind == ParamKind::RGB) s += " per channel";
      if (!unit.empty()) s += " " + unit;
      return s;
    }
    case ParamKind::Enum: {
      std::string s = "one of {";
      for (size_t i = 0; i < choices.size(); ++i) s += (i ? ", " : "") + choices[i];
      return s + "}";
    }
    case ParamKind::Bool: return "true or false";
    case ParamKind::String: return "a string";
    case ParamKind::List: return "a list of records";
  }
  return "";
}

ParamSpec float_param(std::string name, double def, double min, double max, std::string unit,
                      std::string doc) {
  ParamSpec s;
  s.name = std::move(name);
  s.kind = ParamKind::Float;
  s.default_value = def;
  s.min = min;
  s.max = max;
  s.unit = std::move(unit);
  s.doc = std::move(doc);
  return s;
}

ParamSpec positive_param(std::string name, double def, double max, std::string unit,
                         std::string doc) {
  ParamSpec s = float_param(std::move(name), def, 0.0, max, std::move(unit), std::move(doc));
  s.min_exclusive = true;
  return s;
}

ParamSpec rgb_param(std::string name, RGBValue def, double min, double max, std::string doc) {
  ParamSpec s;
  s.name = std::move(name);
  s.kind = ParamKind::RGB;
  s.default_value = def;
  s.min = min;
  s.max = max;
  s.doc = std::move(doc);
  return s;
}

ParamSpec enum_param(std::string name, std::string def, std::vector<std::string> choices,
                     std::string doc) {
  ParamSpec s;
  s.name = std::move(name);
  s.kind = ParamKind::Enum;
  s.default_value = std::move(def);
  s.choices = std::move(choices);
  s.doc = std::move(doc);
  return s;
}

ParamSpec bool_param(std::string name, bool def, std::string doc) {
  ParamSpec s;
  s.name = std::move(name);
  s.kind = ParamKind::Bool;
  s.default_value = def;
  s.doc = std::move(doc);
  return s;
}

ParamSpec string_param(std::string name, std::string def, std::string doc) {
  ParamSpec s;
  s.name = std::move(name);
  s.kind = ParamKind::String;
  s.default_value = std::move(def);
  s.doc = std::move(doc);
  return s;
}

ParamSpec list_param(std::string name, std::vector<ParamSet> def, std::vector<ParamSpec> fields,
                     std::string doc) {
  ParamSpec s;
  s.name = std::move(name);
  s.kind = ParamKind::List;
  s.default_value = std::move(def);
  s.fields = std::move(fields);
  s.doc = std::move(doc);
  return s;
}

const char* to_string(RGBSubtype subtype) {
  return subtype == RGBSubtype::Color ? "color" : "per_channel";
}

ParamSpec per_channel(ParamSpec spec) {
  spec.subtype = RGBSubtype::PerChannel;
  return spec;
}

ParamSpec only_when(ParamSpec spec, std::string param, std::vector<std::string> values) {
  spec.when_param = std::move(param);
  spec.when_values = std::move(values);
  return spec;
}

namespace {

[[noreturn]] void refuse(const std::string& where, const ParamSpec& spec, const Value& v,
                         const std::string& why) {
  throw ParameterError(where + ": parameter '" + spec.name + "' = " + v.to_string() + " " + why +
                       "; valid: " + spec.range_string());
}

void check_number(const std::string& where, const ParamSpec& spec, const Value& shown, double x) {
  if (std::isnan(x)) refuse(where, spec, shown, "is not a number");
  if (std::isinf(x)) refuse(where, spec, shown, "is not finite");
  const bool below = spec.min_exclusive ? !(x > spec.min) : !(x >= spec.min);
  const bool above = spec.max_exclusive ? !(x < spec.max) : !(x <= spec.max);
  if (below || above) refuse(where, spec, shown, "is out of range");
}

Value coerce(const std::string& where, const ParamSpec& spec, const Value& v) {
  switch (spec.kind) {
    case ParamKind::Float:
      if (v.is_bool() || !v.is_number()) refuse(where, spec, v, "is not a number");
      check_number(where, spec, v, v.as_number());
      return v;
    case ParamKind::RGB: {
      RGBValue c;
      if (v.is_number()) {
        c = {v.as_number(), v.as_number(), v.as_number()};  // a grey given as one number
      } else if (v.is_rgb()) {
        c = v.as_rgb();
      } else {
        refuse(where, spec, v, "is not an RGB triple or a number");
      }
      for (double x : c) check_number(where, spec, v, x);
      return Value(c);
    }
    case ParamKind::Enum: {
      if (!v.is_string()) refuse(where, spec, v, "is not a string");
      for (const auto& c : spec.choices)
        if (c == v.as_string()) return v;
      refuse(where, spec, v, "is not a known choice");
    }
    case ParamKind::Bool:
      if (v.is_bool()) return v;
      if (v.is_number() && (v.as_number() == 0.0 || v.as_number() == 1.0))
        return Value(v.as_number() != 0.0);
      refuse(where, spec, v, "is not a boolean");
    case ParamKind::String:
      if (!v.is_string()) refuse(where, spec, v, "is not a string");
      return v;
    case ParamKind::List: {
      if (!v.is_list()) refuse(where, spec, v, "is not a list");
      std::vector<ParamSet> out;
      const auto& items = v.as_list();
      for (size_t i = 0; i < items.size(); ++i)
        out.push_back(validate_params(where + " " + spec.name + "[" + std::to_string(i) + "]",
                                      spec.fields, items[i]));
      return Value(std::move(out));
    }
  }
  return v;
}

}  // namespace

ParamSet validate_params(const std::string& model, const std::vector<ParamSpec>& specs,
                         const ParamSet& given) {
  for (const auto& name : given.names()) {
    bool known = false;
    for (const auto& s : specs) known = known || s.name == name;
    if (!known) {
      std::string list;
      for (size_t i = 0; i < specs.size(); ++i) list += (i ? ", " : "") + specs[i].name;
      throw ParameterError(model + ": unknown parameter '" + name + "'; known parameters: " +
                           (list.empty() ? "none" : list));
    }
  }
  ParamSet out;
  for (const auto& s : specs) {
    const Value* v = given.find(s.name);
    out.set(s.name, coerce(model, s, v ? *v : s.default_value));
  }
  return out;
}

}  // namespace bxdf
