// bxdf-rho-table: prints every registered model's (defaults) and every preset's directional
// albedo ρhd(θo) at a few angles and its ρhh — a quick look at how much light each model keeps.
#include <cstdio>
#include <exception>
#include <string>

#include "bxdf/presets.h"
#include "bxdf/registry.h"

namespace {

constexpr int kSamples = 1 << 16;
const float kAnglesDeg[] = {0, 30, 60, 80, 89};

void print_row(const std::string& label, const bxdf::BxDF& m) {
  std::printf("%-34s", label.c_str());
  for (float deg : kAnglesDeg) {
    const float t = bxdf::radians(deg);
    const bxdf::RGB rho = m.rho_hd(bxdf::Vec3(std::sin(t), 0.0f, std::cos(t)), kSamples);
    std::printf(" %6.3f", rho.average());
  }
  std::printf(" | %6.3f\n", m.rho_hh(kSamples).average());
}

}  // namespace

int main() {
  std::printf("Directional albedo rho_hd(theta_o) (RGB average, %d samples) and rho_hh\n", kSamples);
  std::printf("%-34s", "model / preset");
  for (float deg : kAnglesDeg) std::printf(" %5.0f°", deg);
  std::printf(" | rho_hh\n");
  int failures = 0;
  for (const auto& info : bxdf::models()) {
    try {
      print_row(info.name + " (defaults)", *bxdf::make(info.name));
    } catch (const std::exception& e) {  // e.g. `measured`, whose default needs a file
      std::printf("%-34s %s\n", (info.name + " (defaults)").c_str(), e.what());
    }
  }
  for (const auto& p : bxdf::presets()) {
    try {
      print_row("preset " + p.name + " (" + p.model + ")", *bxdf::make_preset(p.name));
    } catch (const std::exception& e) {
      std::printf("%-34s cannot build: %s\n", ("preset " + p.name).c_str(), e.what());
      ++failures;
    }
  }
  return failures == 0 ? 0 : 1;
}
