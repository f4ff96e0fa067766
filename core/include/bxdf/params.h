// Parameter values and schemas. Every model declares its parameters once, as ParamSpecs in
// its own source file; validation, the Python API, the Blender panel and JSON files all
// read those declarations.
#pragma once

#include <array>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace bxdf {

// A bad parameter, file field or argument. Maps to Python's ValueError.
struct ParameterError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

using RGBValue = std::array<double, 3>;
class Value;

// An ordered name → value map (order kept so that files and reprs read as declared).
class ParamSet {
 public:
  bool has(const std::string& name) const;
  const Value* find(const std::string& name) const;
  const Value& at(const std::string& name) const;  // throws ParameterError when missing
  void set(const std::string& name, Value v);
  bool erase(const std::string& name);
  size_t size() const { return names_.size(); }
  const std::vector<std::string>& names() const { return names_; }
  const std::vector<Value>& values() const { return values_; }

  // Typed reads of validated sets (the registry has already coerced the kinds).
  double number(const std::string& name) const;
  RGBValue rgb(const std::string& name) const;
  const std::string& string(const std::string& name) const;
  bool boolean(const std::string& name) const;
  const std::vector<ParamSet>& list(const std::string& name) const;

  bool operator==(const ParamSet& o) const;

 private:
  std::vector<std::string> names_;
  std::vector<Value> values_;
};

class Value {
 public:
  enum class Type { Number, RGB, String, Bool, List };
  Value() : v_(0.0) {}
  Value(double d) : v_(d) {}
  Value(float d) : v_(static_cast<double>(d)) {}
  Value(int d) : v_(static_cast<double>(d)) {}
  Value(RGBValue c) : v_(c) {}
  Value(const char* s) : v_(std::string(s)) {}
  Value(std::string s) : v_(std::move(s)) {}
  Value(bool b) : v_(b) {}
  Value(std::vector<ParamSet> l) : v_(std::move(l)) {}

  Type type() const { return static_cast<Type>(v_.index()); }
  bool is_number() const { return type() == Type::Number; }
  bool is_rgb() const { return type() == Type::RGB; }
  bool is_string() const { return type() == Type::String; }
  bool is_bool() const { return type() == Type::Bool; }
  bool is_list() const { return type() == Type::List; }
  double as_number() const { return std::get<double>(v_); }
  const RGBValue& as_rgb() const { return std::get<RGBValue>(v_); }
  const std::string& as_string() const { return std::get<std::string>(v_); }
  bool as_bool() const { return std::get<bool>(v_); }
  const std::vector<ParamSet>& as_list() const { return std::get<std::vector<ParamSet>>(v_); }
  std::string to_string() const;  // for messages and reprs
  bool operator==(const Value& o) const { return v_ == o.v_; }

 private:
  std::variant<double, RGBValue, std::string, bool, std::vector<ParamSet>> v_;
};

enum class ParamKind { Float, RGB, Enum, Bool, String, List };
const char* to_string(ParamKind kind);

// What the three numbers of an RGB parameter are: a colour (a reflectance, shown as a swatch) or
// three independent numbers per channel (an index of refraction, a lobe coefficient), which a UI
// shows as number fields.
enum class RGBSubtype { Color, PerChannel };
const char* to_string(RGBSubtype subtype);

// One parameter of one model, as declared by the model.
struct ParamSpec {
  std::string name;
  ParamKind kind = ParamKind::Float;
  Value default_value;
  // Valid range for Float and for every channel of RGB (and for list fields).
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
  std::string unit;                 // "degrees", "W/sr", "" ...
  std::string doc;                  // one line, shown as a tooltip
  std::vector<std::string> choices; // Enum
  std::vector<ParamSpec> fields;    // List: the schema of each element
  // Relevant only when parameter `when_param` has one of `when_values` (UI hides it otherwise).
  std::string when_param;
  std::vector<std::string> when_values;
  RGBSubtype subtype = RGBSubtype::Color;  // RGB only

  std::string range_string() const;  // "[0, 90] degrees", "(0, inf)", "{none, dielectric}"
};

// Builders that keep model declarations to one line per parameter.
ParamSpec float_param(std::string name, double def, double min, double max, std::string unit,
                      std::string doc);
ParamSpec positive_param(std::string name, double def, double max, std::string unit, std::string doc);
ParamSpec rgb_param(std::string name, RGBValue def, double min, double max, std::string doc);
ParamSpec enum_param(std::string name, std::string def, std::vector<std::string> choices,
                     std::string doc);
ParamSpec bool_param(std::string name, bool def, std::string doc);
ParamSpec string_param(std::string name, std::string def, std::string doc);
ParamSpec list_param(std::string name, std::vector<ParamSet> def, std::vector<ParamSpec> fields,
                     std::string doc);
ParamSpec only_when(ParamSpec spec, std::string param, std::vector<std::string> values);
ParamSpec per_channel(ParamSpec spec);  // an RGB parameter that is not a colour

// Checks `given` against `specs`: fills defaults, coerces numbers to RGB (grey), refuses
// unknown names, wrong kinds, NaN and out-of-range values with a ParameterError that names
// the model, the parameter, the value and the valid range.
ParamSet validate_params(const std::string& model, const std::vector<ParamSpec>& specs,
                         const ParamSet& given);

}  // namespace bxdf
