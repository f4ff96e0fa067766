// The curated grid itself: every registered model has entries, every entry builds, and
// together a model's entries use every choice of every enum parameter.
#include <gtest/gtest.h>

#include <set>

#include "bxdf/registry.h"
#include "model_grid.h"

using namespace bxdf;
using namespace bxdf::test;

TEST(ModelGrid, EveryRegisteredModelHasCuratedEntries) {
  std::string missing;
  for (const std::string& name : uncurated_models()) missing += " " + name;
  EXPECT_TRUE(missing.empty()) << "models without a curated grid (tests fall back to defaults):"
                               << missing;
}

TEST(ModelGrid, EveryCuratedEntryBuildsAndLabelsAreUnique) {
  for (const std::string& model : registered_model_names()) {
    std::set<std::string> labels;
    for (const GridEntry& e : grid_for(model)) {
      EXPECT_TRUE(labels.insert(e.label).second) << describe(model, e) << " label repeats";
      try {
        make_entry(model, e);
      } catch (const std::exception& ex) {
        ADD_FAILURE() << describe(model, e) << " does not build: " << ex.what();
      }
    }
  }
}

TEST(ModelGrid, EntriesCoverEveryEnumChoice) {
  for (const ModelInfo& info : models()) {
    for (const ParamSpec& spec : info.params) {
      if (spec.kind != ParamKind::Enum) continue;
      std::set<std::string> used;
      for (const GridEntry& e : grid_for(info.name)) {
        const Value* v = e.params.find(spec.name);
        used.insert(v && v->is_string() ? v->as_string() : spec.default_value.as_string());
      }
      for (const std::string& choice : spec.choices)
        EXPECT_TRUE(used.count(choice)) << info.name << ": no grid entry has " << spec.name
                                        << " = " << choice;
    }
  }
}

TEST(ModelGrid, IncidentDirectionsSpanBothHemispheresAndGrazing) {
  float max_z = -2, min_z = 2, min_abs_z = 2;
  for (const IncidentDirection& d : incident_directions()) {
    EXPECT_NEAR(length(d.wo), 1.0f, 1e-6f) << d.label;
    max_z = std::max(max_z, d.wo.z);
    min_z = std::min(min_z, d.wo.z);
    min_abs_z = std::min(min_abs_z, std::fabs(d.wo.z));
  }
  EXPECT_EQ(max_z, 1.0f);      // normal incidence
  EXPECT_LT(min_z, 0.0f);      // from below
  EXPECT_LT(min_abs_z, 0.02f); // near-grazing
}
