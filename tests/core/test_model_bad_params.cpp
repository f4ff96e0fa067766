// Bad parameters, derived from every model's own declarations: for each bounded Float or RGB
// parameter (and each bounded field of a list parameter) a value just outside each finite
// bound, NaN and a string; for each Enum an unknown choice and a number. Each is refused with
// a ParameterError whose message names the parameter, the value and the valid range; so is
// an unknown parameter name.
#include <gtest/gtest.h>

#include <cmath>

#include "bxdf/registry.h"
#include "model_grid.h"

using namespace bxdf;
using namespace bxdf::test;

namespace {

class ModelBadParams : public ::testing::TestWithParam<std::string> {};

struct BadValue {
  std::string why;
  Value value;      // what is given
  std::string shown;  // how the message must show it
};

// Values just outside the finite bounds of a numeric spec (an exclusive bound itself is
// outside), NaN, and a string.
std::vector<BadValue> bad_values(const ParamSpec& s) {
  std::vector<BadValue> out;
  auto wrap = [&](double x) -> Value {
    if (s.kind != ParamKind::RGB) return Value(x);
    return Value(RGBValue{0.5 * (std::max(s.min, -1.0) + std::min(s.max, 1.0)), x, 0.5 * (std::max(s.min, -1.0) + std::min(s.max, 1.0))});
  };
  auto add = [&](std::string why, double x) {
    const Value v = wrap(x);
    out.push_back({std::move(why), v, v.to_string()});
  };
  const double step = 1e-3;
  if (std::isfinite(s.min)) add("below min", s.min_exclusive ? s.min : s.min - step * std::max(1.0, std::fabs(s.min)));
  if (std::isfinite(s.max)) add("above max", s.max_exclusive ? s.max : s.max + step * std::max(1.0, std::fabs(s.max)));
  add("NaN", std::nan(""));
  out.push_back({"a string", Value("oops"), "'oops'"});
  return out;
}

// The message of the ParameterError that make() throws, or a description of what else happened.
std::string refusal(const std::string& model, const ParamSet& p, bool* refused) {
  *refused = false;
  try {
    make(model, p);
    return "accepted";
  } catch (const ParameterError& e) {
    *refused = true;
    return e.what();
  } catch (const std::exception& e) {
    return std::string("threw a non-ParameterError: ") + e.what();
  }
}

void expect_refused(const std::string& model, const ParamSet& p, const std::string& name,
                    const std::string& shown, const std::string& range, const std::string& why) {
  bool refused;
  const std::string msg = refusal(model, p, &refused);
  const std::string what = model + "." + name + " " + why + " (" + shown + ")";
  EXPECT_TRUE(refused) << what << ": " << msg;
  if (!refused) return;
  EXPECT_NE(msg.find("'" + name + "'"), std::string::npos) << what << ": name missing in: " << msg;
  EXPECT_NE(msg.find(shown), std::string::npos) << what << ": value missing in: " << msg;
  EXPECT_NE(msg.find(range), std::string::npos) << what << ": range " << range << " missing in: " << msg;
}

bool numeric(const ParamSpec& s) { return s.kind == ParamKind::Float || s.kind == ParamKind::RGB; }

}  // namespace

TEST_P(ModelBadParams, BoundedNumbersEnumsAndListFieldsAreRefused) {
  const std::string& model = GetParam();
  const ModelInfo* info = find_model(model);
  ASSERT_NE(info, nullptr);
  int checked = 0;
  for (const ParamSpec& s : info->params) {
    if (numeric(s)) {
      for (const BadValue& b : bad_values(s)) {
        ParamSet p;
        p.set(s.name, b.value);
        expect_refused(model, p, s.name, b.shown, s.range_string(), b.why);
        ++checked;
      }
    } else if (s.kind == ParamKind::Enum) {
      ParamSet p;
      p.set(s.name, "no_such_choice");
      expect_refused(model, p, s.name, "'no_such_choice'", s.range_string(), "unknown choice");
      p.set(s.name, 2.0);
      expect_refused(model, p, s.name, "2", s.range_string(), "a number");
      checked += 2;
    } else if (s.kind == ParamKind::List) {
      // One element whose field is bad; the other fields take their defaults.
      for (const ParamSpec& field : s.fields) {
        if (!numeric(field)) continue;
        for (const BadValue& b : bad_values(field)) {
          ParamSet element;
          element.set(field.name, b.value);
          ParamSet p;
          p.set(s.name, std::vector<ParamSet>{element});
          expect_refused(model, p, field.name, b.shown, field.range_string(), "in " + s.name + ": " + b.why);
          ++checked;
        }
      }
      ParamSet p;
      p.set(s.name, 1.0);
      expect_refused(model, p, s.name, "1", s.range_string(), "not a list");
    }
  }
  // Every model refuses an unknown name, listing the ones it knows.
  ParamSet unknown;
  unknown.set("no_such_parameter", 1.0);
  bool refused;
  const std::string msg = refusal(model, unknown, &refused);
  EXPECT_TRUE(refused) << msg;
  EXPECT_NE(msg.find("no_such_parameter"), std::string::npos) << msg;
  for (const ParamSpec& s : info->params) EXPECT_NE(msg.find(s.name), std::string::npos) << msg;
  RecordProperty("bad_values_checked", checked);
}

INSTANTIATE_TEST_SUITE_P(AllModels, ModelBadParams, ::testing::ValuesIn(registered_model_names()),
                         [](const auto& info) { return info.param; });
