// The registry refuses bad parameters with the parameter's name, the value and the range,
// and rebuilds a model from its own params().
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "bxdf/registry.h"

using namespace bxdf;

namespace {

std::string error_of(const std::string& model, const ParamSet& p) {
  try {
    make(model, p);
  } catch (const ParameterError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Registry, UnknownModelIsRefusedWithTheKnownList) {
  const std::string msg = error_of("no_such_model", {});
  EXPECT_NE(msg.find("no_such_model"), std::string::npos);
  EXPECT_NE(msg.find("lambertian"), std::string::npos);
}

TEST(Registry, UnknownParameterIsRefusedByName) {
  ParamSet p;
  p.set("sigmaa", 3.0);
  const std::string msg = error_of("lambertian", p);
  EXPECT_NE(msg.find("sigmaa"), std::string::npos) << msg;
}

TEST(Registry, OutOfRangeAndNaNNameParameterValueAndRange) {
  ParamSet p;
  p.set("reflectance", RGBValue{0.5, 1.5, 0.5});
  std::string msg = error_of("lambertian", p);
  EXPECT_NE(msg.find("'reflectance'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("1.5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[0, 1]"), std::string::npos) << msg;
  p.set("reflectance", RGBValue{0.5, std::nan(""), 0.5});
  msg = error_of("lambertian", p);
  EXPECT_NE(msg.find("nan"), std::string::npos) << msg;
}

TEST(Registry, InfinityIsRefusedEvenWithoutAFiniteBound) {
  // microfacet_transmission's eta ranges are finite, but validation must not rely on that:
  // a Float spec with no upper bound still refuses +inf.
  ParamSpec unbounded = float_param("scale", 1.0, 0.0, std::numeric_limits<double>::infinity(), "",
                                    "test parameter");
  ParamSet p;
  p.set("scale", std::numeric_limits<double>::infinity());
  try {
    validate_params("test", {unbounded}, p);
    FAIL() << "+inf was accepted";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("'scale' = inf is not finite"), std::string::npos)
        << e.what();
  }
}

TEST(Registry, EveryModelRoundTripsThroughItsParams) {
  for (const ModelInfo& info : models()) {
    SCOPED_TRACE(info.name);
    ASSERT_FALSE(info.doc.empty());
    for (const ParamSpec& s : info.params) EXPECT_FALSE(s.doc.empty()) << s.name;
    BxDFPtr a = make(info.name);
    EXPECT_EQ(a->model_name(), info.name);
    BxDFPtr b = make(info.name, a->params());
    EXPECT_TRUE(a->params() == b->params());
  }
}

TEST(Registry, GreyNumberIsAcceptedForRGB) {
  ParamSet p;
  p.set("reflectance", 0.25);
  BxDFPtr m = make("lambertian", p);
  EXPECT_EQ(m->params().rgb("reflectance")[1], 0.25);
}

// A UI draws a colour as a swatch and per-channel numbers as number fields: indices of
// refraction and Lafortune's lobe coefficients are numbers (outside [0, 1]), reflectances colours.
TEST(Registry, RGBParametersSayWhetherTheyAreColours) {
  const auto subtype_of = [](const std::string& model, const std::string& param) {
    for (const auto& info : models()) {
      if (info.name != model) continue;
      for (const auto& spec : info.params) {
        if (spec.name == param) return spec.subtype;
        for (const auto& field : spec.fields)
          if (field.name == param) return field.subtype;
      }
    }
    ADD_FAILURE() << model << "." << param << " not found";
    return RGBSubtype::Color;
  };
  EXPECT_EQ(subtype_of("microfacet", "reflectance"), RGBSubtype::Color);
  EXPECT_EQ(subtype_of("microfacet", "eta"), RGBSubtype::PerChannel);
  EXPECT_EQ(subtype_of("specular_reflection", "k"), RGBSubtype::PerChannel);
  EXPECT_EQ(subtype_of("lafortune", "diffuse"), RGBSubtype::Color);
  for (const char* field : {"cx", "cy", "cz", "exponent"})
    EXPECT_EQ(subtype_of("lafortune", field), RGBSubtype::PerChannel) << field;
  // Every colour is a reflectance-like factor: its range lies in [0, 1].
  for (const auto& info : models())
    for (const auto& spec : info.params)
      if (spec.kind == ParamKind::RGB && spec.subtype == RGBSubtype::Color) {
        EXPECT_GE(spec.min, 0.0) << info.name << "." << spec.name;
        EXPECT_LE(spec.max, 1.0) << info.name << "." << spec.name;
      }
}
