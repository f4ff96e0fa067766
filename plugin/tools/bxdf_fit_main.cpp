// bxdf-fit: fits an analytic model to a measured BRDF file and writes a material file.
//
//   bxdf-fit FILE [--model lafortune] [--lobes 2] [--out material.json] [--plot DIR]
//            [--starts N] [--iterations N] [--stride N] [--verbose]
//
// Prints the report (error, iterations, time) and the fitted registry model. --out writes it as
// a material file (plugin/io, the format bxdf.load_material and the renderer read). --plot
// writes, per incidence angle of the data, the measured and fitted BRDF in the plane of
// incidence as CSV and SVG.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>

#include "bxdf/fit/fit.h"
#include "bxdf/io/material_json.h"
#include "bxdf/measured/measured_data.h"

using namespace bxdf;

namespace {

// Measured and fitted BRDF in the plane of incidence for each incidence angle of the data.
void write_plots(const std::string& dir, const std::vector<MeasuredSample>& samples,
                 const BxDF& fitted, const std::string& title) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  std::map<int, std::vector<const MeasuredSample*>> by_theta;  // key: θi in degrees
  for (const auto& s : samples) {
    // In-plane: wo in the plane of wi (Δφ = 0 or π).
    const float cross = std::fabs(s.wo.x * s.wi.y - s.wo.y * s.wi.x);
    if (cross > 1e-3f) continue;
    by_theta[static_cast<int>(std::lround(std::acos(std::min(1.0f, s.wi.z)) * 180.0 / M_PI))].push_back(&s);
  }
  for (const auto& [theta, rows] : by_theta) {
    if (rows.size() < 3) continue;
    const std::string stem = dir + "/theta_i_" + std::to_string(theta);
    std::ofstream csv(stem + ".csv");
    csv << "theta_o_signed_deg,measured_r,measured_g,measured_b\n";
    const float ti = theta * static_cast<float>(M_PI) / 180.0f;
    const Vec3 wi(std::sin(ti), 0.0f, std::cos(ti));
    double vmax = 1e-6;
    std::vector<std::array<double, 4>> meas;
    for (const auto* s : rows) {
      // Signed outgoing angle: negative on the side of wi's azimuth... positive toward the mirror.
      const float sign = (s->wo.x * s->wi.x + s->wo.y * s->wi.y) > 0.0f ? -1.0f : 1.0f;
      const double to = sign * std::acos(std::min(1.0f, s->wo.z)) * 180.0 / M_PI;
      meas.push_back({to, s->value.r, s->value.g, s->value.b});
      csv << to << "," << s->value.r << "," << s->value.g << "," << s->value.b << "\n";
      vmax = std::max(vmax, double(s->value.max_component()));
    }
    std::vector<std::array<double, 4>> curve;
    for (int k = -89; k <= 89; ++k) {
      const float to = static_cast<float>(k) * static_cast<float>(M_PI) / 180.0f;
      const Vec3 wo(-std::sin(to), 0.0f, std::cos(to));  // k > 0: mirror side
      const RGB f = fitted.f(wo, wi);
      curve.push_back({double(k), f.r, f.g, f.b});
      vmax = std::max(vmax, double(f.max_component()));
    }
    std::ofstream fit_csv(stem + "_fit.csv");
    fit_csv << "theta_o_signed_deg,fit_r,fit_g,fit_b\n";
    for (const auto& c : curve) fit_csv << c[0] << "," << c[1] << "," << c[2] << "," << c[3] << "\n";
    // SVG, log scale on the BRDF axis.
    const double w = 640, h = 400, lo = std::log10(vmax) - 4.0, hi = std::log10(vmax) + 0.2;
    auto X = [&](double deg) { return 40.0 + (deg + 90.0) / 180.0 * (w - 60.0); };
    auto Y = [&](double v) { return h - 30.0 - (std::log10(std::max(v, 1e-12)) - lo) / (hi - lo) * (h - 50.0); };
    std::ofstream svg(stem + ".svg");
    svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << w << "' height='" << h << "'>\n"
        << "<rect width='100%' height='100%' fill='white'/>\n"
        << "<text x='40' y='16' font-size='12'>" << title << ", theta_i = " << theta
        << " deg, in-plane BRDF (log10, 4 decades); dots measured, lines fit</text>\n"
        << "<line x1='" << X(0) << "' y1='20' x2='" << X(0) << "' y2='" << h - 30 << "' stroke='#aaa'/>\n";
    const char* colour[3] = {"#d62728", "#2ca02c", "#1f77b4"};
    for (int c = 0; c < 3; ++c) {
      svg << "<polyline fill='none' stroke='" << colour[c] << "' points='";
      for (const auto& p : curve) svg << X(p[0]) << "," << Y(p[1 + c]) << " ";
      svg << "'/>\n";
      for (const auto& m : meas)
        svg << "<circle cx='" << X(m[0]) << "' cy='" << Y(m[1 + c]) << "' r='2.5' fill='" << colour[c] << "'/>\n";
    }
    svg << "</svg>\n";
  }
}

int usage() {
  std::cerr << "usage: bxdf-fit FILE [--model NAME] [--lobes N] [--out material.json] [--plot DIR]\n"
               "                [--starts N] [--iterations N] [--stride N] [--verbose]\n"
               "models:";
  for (const auto& n : fit::fit_model_names()) std::cerr << " " << n;
  std::cerr << "\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  std::string path, out, plot;
  fit::FitOptions options;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw ParameterError("option " + a + " needs a value");
        return argv[++i];
      };
      auto next_int = [&]() {
        const std::string v = next();
        size_t used = 0;
        int n = 0;
        try {
          n = std::stoi(v, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != v.size()) throw ParameterError("option " + a + " = '" + v + "' is not an integer");
        return n;
      };
      if (a == "--model") options.model = next();
      else if (a == "--lobes") options.lobes = next_int();
      else if (a == "--out") out = next();
      else if (a == "--plot") plot = next();
      else if (a == "--starts") options.max_starts = next_int();
      else if (a == "--iterations") options.max_iterations = next_int();
      else if (a == "--stride") options.merl_stride = next_int();
      else if (a == "--verbose") options.verbose = true;
      else if (a == "-h" || a == "--help") return usage();
      else if (!a.empty() && a[0] == '-') throw ParameterError("unknown option '" + a + "'");
      else if (path.empty()) path = a;
      else throw ParameterError("more than one input file ('" + path + "', '" + a + "')");
    }
    if (path.empty()) return usage();
    const auto data = load_measured_data(path);
    const std::vector<MeasuredSample> samples = data->samples(options.merl_stride);
    const fit::FitResult r = fit::fit(samples, options);
    const std::string name = std::filesystem::path(path).stem().string() + " (" + r.report.model + " fit)";
    std::printf("%s: %s data, %zu samples\n", path.c_str(), data->format_name(), r.report.samples);
    std::printf("model %s: error %.6g (f = 0: %.6g), %d iterations (best start; %d over %d starts), %.3f s\n",
                r.report.model.c_str(), r.report.error, r.report.baseline_error, r.report.iterations,
                r.report.total_iterations, r.report.starts, r.report.seconds);
    std::printf("  %s %s\n", r.model.c_str(), Value(std::vector<ParamSet>{r.params}).to_string().c_str());
    if (!out.empty()) {
      io::save_material(io::MaterialDesc{name, r.model, r.params}, out);
      std::printf("wrote %s\n", out.c_str());
    }
    if (!plot.empty()) {
      write_plots(plot, samples, *r.build(), name);
      std::printf("wrote plots to %s\n", plot.c_str());
    }
  } catch (const std::exception& e) {  // ParameterError, and file-system errors of --plot
    std::fprintf(stderr, "bxdf-fit: %s\n", e.what());
    return 1;
  }
  return 0;
}
