// bxdf-render: renders a JSON scene file to an image.
//
//   bxdf-render scene.json -o out.exr [--spp N] [--threads T] [--max-bounces B]
//               [--filter box|gaussian|blackman_harris|pixel_center] [--filter-width W] [--seed S]
//               [--width W] [--height H] [--quiet]
//
// Command-line values override the file's "render" settings. Ctrl-C (SIGINT) or SIGTERM stops
// the render without writing: an existing output file is left as it was. Exit codes: 0 done,
// 1 bad scene file or option, 2 render or write failure, 130 cancelled.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "bxdf/render/image_io.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/scene_json.h"

namespace {

std::atomic<bool> g_cancel{false};

extern "C" void on_signal(int) { g_cancel.store(true); }

const char* kUsage =
    "usage: bxdf-render scene.json -o out.exr [--spp N] [--threads T] [--max-bounces B]\n"
    "                   [--filter box|gaussian|blackman_harris|pixel_center] [--filter-width W] [--seed S]\n"
    "                   [--width W] [--height H] [--quiet]\n";

struct Options {
  std::string scene, output;
  int spp = -1, threads = -1, max_bounces = -1, seed = -1, width = -1, height = -1;
  std::string filter;
  float filter_width = -1.0f;
  bool quiet = false;
};

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "bxdf-render: " << message << "\n" << kUsage;
  std::exit(1);
}

long parse_int(const std::string& option, const std::string& text, long lo, long hi) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < lo || v > hi)
    usage_error(option + " '" + text + "': expected an integer in [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "]");
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "-o" || a == "--output") o.output = value();
    else if (a == "--spp") o.spp = int(parse_int(a, value(), 1, 1 << 24));
    else if (a == "--threads") o.threads = int(parse_int(a, value(), 0, 4096));
    else if (a == "--max-bounces") o.max_bounces = int(parse_int(a, value(), 0, 1024));
    else if (a == "--seed") o.seed = int(parse_int(a, value(), 0, 2147483647));
    else if (a == "--width") o.width = int(parse_int(a, value(), 1, 65536));
    else if (a == "--height") o.height = int(parse_int(a, value(), 1, 65536));
    else if (a == "--filter") o.filter = value();
    else if (a == "--filter-width") {
      const std::string v = value();
      char* end = nullptr;
      o.filter_width = std::strtof(v.c_str(), &end);
      if (v.empty() || *end != '\0' || !(o.filter_width > 0.0f && o.filter_width <= 16.0f))
        usage_error("--filter-width '" + v + "': expected a number in (0, 16]");
    } else if (a == "--quiet" || a == "-q") o.quiet = true;
    else if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      std::exit(0);
    } else if (!a.empty() && a[0] == '-') usage_error("unknown option " + a);
    else if (o.scene.empty()) o.scene = a;
    else usage_error("more than one scene file given ('" + o.scene + "', '" + a + "')");
  }
  if (o.scene.empty()) usage_error("no scene file given");
  if (o.output.empty()) usage_error("no output file given (-o out.exr)");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace bxdf::render;
  const Options opt = parse(argc, argv);

  LoadedScene loaded;
  RenderSettings settings;
  try {
    loaded = load_scene_json(opt.scene);
    settings = loaded.settings;
    if (opt.spp > 0) settings.samples_per_pixel = opt.spp;
    if (opt.threads >= 0) settings.threads = opt.threads;
    if (opt.max_bounces >= 0) settings.max_bounces = opt.max_bounces;
    if (opt.seed >= 0) settings.seed = static_cast<uint64_t>(opt.seed);
    if (opt.width > 0) settings.width = opt.width;
    if (opt.height > 0) settings.height = opt.height;
    if (!opt.filter.empty()) settings.filter = parse_filter(opt.filter);
    if (opt.filter_width > 0.0f) settings.filter_width = opt.filter_width;
    rendered_rect(settings);  // the file's region inside the image the options make
    const std::string ext = opt.output.size() >= 4 ? opt.output.substr(opt.output.size() - 4) : "";
    if (ext != ".exr" && ext != ".png")
      throw bxdf::ParameterError("output file '" + opt.output + "' must end in .exr or .png");
  } catch (const std::exception& e) {
    std::cerr << "bxdf-render: " << e.what() << "\n";
    return 1;
  }

  // From here on Ctrl-C and SIGTERM cancel the render (the output stays as it was); while the
  // scene loads they end the process at once, as nothing has been written.
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  RenderCallbacks callbacks;
  callbacks.cancel = &g_cancel;
  if (!opt.quiet) {
    callbacks.on_pass = [](const Film&, const RenderProgress& p) {
      // Adaptive sampling's passes are not known ahead (passes 0).
      if (p.passes > 0)
        std::fprintf(stderr, "\rbxdf-render: pass %d/%d (%d spp)", p.pass, p.passes, p.samples_done);
      else
        std::fprintf(stderr, "\rbxdf-render: pass %d (%d spp)", p.pass, p.samples_done);
      std::fflush(stderr);
    };
  }
  RenderStats stats;
  Film film;
  try {
    film = render_scene(*loaded.scene, loaded.camera, settings, callbacks, &stats);
  } catch (const std::exception& e) {
    std::cerr << "\nbxdf-render: render failed: " << e.what() << "\n";
    return 2;
  }
  if (!opt.quiet) std::fprintf(stderr, "\n");
  if (stats.cancelled) {
    std::cerr << "bxdf-render: cancelled after " << stats.samples_per_pixel
              << " spp; '" << opt.output << "' was not written\n";
    return 130;
  }
  try {
    Image img;
    img.width = film.width();
    img.height = film.height();
    img.rgba = film.rgba();
    write_image(opt.output, img);
  } catch (const std::exception& e) {
    std::cerr << "bxdf-render: " << e.what() << "\n";
    return 2;
  }
  if (stats.converged)
    std::printf("adaptive sampling: every pixel stopped by %d spp, a mean of %.1f\n",
                stats.samples_per_pixel,
                double(stats.camera_samples) / (double(film.width()) * double(film.height())));
  const double rays = static_cast<double>(stats.rays + stats.shadow_rays);
  std::printf("%s: %dx%d, %d spp, %.3f s, %.3g samples/s, %.3g rays/s, %llu rejected samples\n",
              opt.output.c_str(), film.width(), film.height(), stats.samples_per_pixel,
              stats.seconds, double(stats.camera_samples) / stats.seconds, rays / stats.seconds,
              static_cast<unsigned long long>(stats.rejected_samples));
  return 0;
}
