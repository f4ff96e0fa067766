// bxdf.render() and bxdf.render_scene_file(): the Embree renderer (plugin/) from Python.
//
// The render runs on its own C++ thread (with TBB workers under it) while the calling thread
// waits with the GIL released; whenever tiles finish or a pass completes it takes the GIL back,
// checks for Ctrl-C (PyErr_CheckSignals) and calls on_progress. Cancelling (a False return, an
// exception, KeyboardInterrupt) sets the renderer's cancel flag and waits for the render to stop
// before anything is returned or raised, so no C++ thread outlives the call.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "array_args.h"
#include "binding_modules.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/scene_json.h"
#include "scene_from_python.h"

namespace bxdf::python {

namespace py = pybind11;

namespace {

// Linear RGBA rows (top first) as a (height, width, 4) float32 array, flipped when bottom_up.
py::array_t<float> image_array(const float* rgba, int width, int height, bool bottom_up) {
  py::array_t<float> image({height, width, 4});
  float* out = image.mutable_data();
  const size_t row = static_cast<size_t>(width) * 4;
  for (int y = 0; y < height; ++y)
    std::memcpy(out + row * static_cast<size_t>(y), rgba + row * static_cast<size_t>(bottom_up ? height - 1 - y : y),
                row * sizeof(float));
  return image;
}

// The film's image as a (height, width, 4) float32 array, written straight into the array (no
// intermediate copy: a fresh image-sized buffer is memory to fault in), flipped in place when
// bottom_up.
py::array_t<float> image_array(const render::Film& film, bool bottom_up) {
  py::array_t<float> image({film.height(), film.width(), 4});
  float* out = image.mutable_data();
  film.rgba(out);
  if (bottom_up) {
    const size_t row = static_cast<size_t>(film.width()) * 4;
    for (size_t top = 0, bottom = static_cast<size_t>(film.height()) - 1; top < bottom; ++top, --bottom)
      std::swap_ranges(out + row * top, out + row * (top + 1), out + row * bottom);
  }
  return image;
}

// Tile progress reaches on_progress at most this often (pass images and the end at once).
constexpr std::chrono::milliseconds kTileReportInterval(50);

// What the render thread tells the waiting Python thread.
struct Channel {
  std::mutex mutex;
  std::condition_variable wake;
  uint64_t tiles_done = 0, tiles_total = 0;
  bool tiles_changed = false;
  // When finished tiles last woke the Python thread: they wake it at most every
  // kTileReportInterval (its wait times out as often, so no report comes later than that).
  std::chrono::steady_clock::time_point tiles_woke;
  std::vector<float> pass_image;  // the film after the latest pass not yet handed to Python
  bool pass_ready = false;
  bool finished = false;
};

py::object run_render(const render::Scene& scene, const render::CameraSettings& camera,
                      const render::RenderSettings& settings, const py::object& on_progress, bool bottom_up,
                      bool partial_images, bool return_stats, std::vector<std::string> warnings,
                      py::dict extra_stats) {
  if (!on_progress.is_none() && !PyCallable_Check(on_progress.ptr()))
    throw ParameterError("on_progress: " + py::repr(on_progress).cast<std::string>() +
                         " is not callable; expected a function (done, total, image_or_None) -> bool, or None");
  // Settings the renderer would refuse are refused here, before any thread starts.
  { render::Camera check(camera, settings.width, settings.height); }
  const render::PixelRect rect = render::rendered_rect(settings);

  Channel channel;
  std::atomic<bool> cancel{false};
  const bool has_callback = !on_progress.is_none();
  render::RenderCallbacks callbacks;
  callbacks.cancel = &cancel;
  callbacks.on_tile = [&](const render::RenderProgress& p) {
    bool wake = false;
    {
      std::lock_guard<std::mutex> lock(channel.mutex);
      channel.tiles_done = p.tiles_done;
      channel.tiles_total = p.tiles_total;
      channel.tiles_changed = true;
      // A wake-up per tile (hundreds per pass) made the Python thread take a core from the
      // render each time, only to find its report interval not yet over and sleep again.
      const auto now = std::chrono::steady_clock::now();
      if (now - channel.tiles_woke >= kTileReportInterval) {
        channel.tiles_woke = now;
        wake = true;
      }
    }
    if (wake) channel.wake.notify_one();
    return !cancel.load();
  };
  // Only partial images need passes: without on_pass the render is one pass (renderer.h).
  if (has_callback && partial_images) {
    callbacks.on_pass = [&](const render::Film& film, const render::RenderProgress& p) {
      // The last pass's image is the result.
      if (p.last) return;
      std::vector<float> rgba(static_cast<size_t>(film.width()) *
                              static_cast<size_t>(film.height()) * 4);
      film.rgba(rgba.data());
      {
        std::lock_guard<std::mutex> lock(channel.mutex);
        channel.pass_image = std::move(rgba);
        channel.pass_ready = true;
        channel.tiles_done = p.tiles_done;
        channel.tiles_total = p.tiles_total;
      }
      channel.wake.notify_one();
    };
  }

  render::Film film;
  render::RenderStats stats;
  std::exception_ptr render_error;
  std::thread worker([&] {
    try {
      film = render::render_scene(scene, camera, settings, callbacks, &stats);
    } catch (...) {
      render_error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(channel.mutex);
      channel.finished = true;
    }
    channel.wake.notify_one();
  });

  std::optional<py::error_already_set> python_error;  // from on_progress or Ctrl-C
  bool stopped_by_callback = false;
  auto last_report = std::chrono::steady_clock::now() - kTileReportInterval;  // the first tile at once
  for (;;) {
    uint64_t done = 0, total = 0;
    bool tiles_changed = false, pass_ready = false, finished = false;
    std::vector<float> pass_image;
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(channel.mutex);
      // The timeout bounds how late Ctrl-C is noticed when nothing else happens. Finished tiles
      // alone wake Python at most every kTileReportInterval: a call per tile (hundreds in a
      // short render) took the GIL and a core from the render for nothing a progress bar shows.
      channel.wake.wait_for(lock, kTileReportInterval, [&] {
        return channel.finished || channel.pass_ready ||
               (channel.tiles_changed && std::chrono::steady_clock::now() - last_report >= kTileReportInterval);
      });
      done = channel.tiles_done;
      total = channel.tiles_total;
      tiles_changed = channel.tiles_changed;
      pass_ready = channel.pass_ready;
      finished = channel.finished;
      if (pass_ready) pass_image.swap(channel.pass_image);
      channel.tiles_changed = channel.pass_ready = false;
    }
    // Cancelled: only wait for the render to stop.
    if (python_error || stopped_by_callback) {
      if (finished) break;
      continue;
    }
    if (PyErr_CheckSignals() != 0) {
      python_error.emplace();
      cancel = true;
      continue;
    }
    // The last tiles are reported too (done == total), after the render has finished.
    if (!has_callback || !(tiles_changed || pass_ready)) {
      if (finished) break;
      continue;
    }
    try {
      py::object image = pass_ready ? py::object(image_array(pass_image.data(), rect.width(), rect.height(), bottom_up))
                                    : py::object(py::none());
      last_report = std::chrono::steady_clock::now();
      py::object keep_going = on_progress(done, total, image);
      // Only an explicit False stops: a callback that returns nothing lets the render go on.
      if (keep_going.ptr() == Py_False) {
        stopped_by_callback = true;
        cancel = true;
      }
    } catch (py::error_already_set& e) {
      python_error.emplace(std::move(e));
      cancel = true;
    }
    if (finished) break;
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (python_error) throw std::move(*python_error);
  if (render_error) std::rethrow_exception(render_error);

  py::array_t<float> image = image_array(film, bottom_up);
  if (!return_stats) return std::move(image);
  py::dict s;
  s["seconds"] = stats.seconds;
  s["samples_per_pixel"] = stats.samples_per_pixel;
  s["camera_samples"] = stats.camera_samples;
  s["rays"] = stats.rays;
  s["shadow_rays"] = stats.shadow_rays;
  s["rejected_samples"] = stats.rejected_samples;
  s["cancelled"] = stats.cancelled;
  s["converged"] = stats.converged;
  py::list w;
  for (const auto& text : warnings) w.append(text);
  s["warnings"] = w;
  for (const auto& item : extra_stats) s[item.first] = item.second;
  return py::make_tuple(image, s);
}

constexpr const char* kRenderDoc = R"doc(render(scene, settings=None, on_progress=None, *, bottom_up=False, partial_images=True, return_stats=False) -> image or (image, stats)

Renders ``scene`` with the Embree path tracer and returns a ``(height, width, 4)`` float32 array of
linear RGBA (alpha 1, or coverage with ``transparent_background``). Rows run top to bottom (numpy's
image convention); ``bottom_up=True`` gives Blender's order (``RenderResult`` rects, ``Image.pixels``),
for the partial images too.

``scene`` is the dict of the Blender add-on's ``export.export_scene()`` (Blender units: metres, W):

- ``"resolution"``: ``(width, height)`` in pixels (required).
- ``"camera"``: ``{"matrix": (4, 4) camera→world (looks along −Z, +Y up; scale ignored), "lens": mm,
  "sensor_width", "sensor_height": mm, "sensor_fit": "auto"|"horizontal"|"vertical",
  "shift": (x, y) in units of the fitted side, "clip": (start, end) depths}`` (only ``matrix`` is
  required; ``"type"``, when given, must be ``"persp"``).
- ``"materials"``: list of ``{"name", "model", "params"}`` made as ``bxdf.make(model, **params)``,
  optionally with ``"emission"`` (RGB radiance, W/(m² sr), two-sided: the mesh becomes an area light).
- ``"meshes"``: list of ``{"positions": (V, 3) float, "triangles": (T, 3) int,
  "normals": (N, 3) float + "normal_indices": (T, 3) int (or both None: flat shading),
  "uvs": (U, 2) float + "uv_indices": (T, 3) int (or both None),
  "material_indices": (T,) int into "materials", -1 = none (a grey Lambertian, reflectance 0.8),
  optional "visible_camera", "visible_shadow" (bools, default True) and "terminator_offset":
  (geometry, shading) Cycles' shadow terminator offsets (default (0.1, 0))}``.
  Counter-clockwise triangles face front. Normals and UVs are indexed separately from positions;
  vertices are split only where a corner's (position, normal, uv) triple differs.
- ``"instance_mesh"``: (I,) int into "meshes" and ``"instance_matrix"``: (I, 4, 4) object→world
  (affine; each entry in [-1e9, 1e9]). A mesh placed by two or more instances is stored once, in
  object space, and each placement is an Embree instance of it (memory: one mesh and one BVH); a
  mesh placed once, or by a singular matrix, is moved into world space (normals by the inverse
  transpose; a mirroring matrix keeps the front). Without these two keys every mesh is drawn once,
  as is.
- ``"lights"``: list of dicts by ``"type"``: ``"point"``: position, intensity (RGB W/sr), radius
  (m: a disk facing the shading point, as Cycles); ``"spot"``: as point plus direction, spot_size
  (full angle, rad), spot_blend; ``"sun"``: direction (the way light travels), irradiance (RGB
  W/m²), angle (rad); ``"area"``: shape ("square"|"rectangle"|"disk"|"ellipse"), size ((x, y) m),
  matrix (light→world; it emits along −Z, one-sided), power (W), color (radiance
  power·color/(4·area), as Cycles). Each may have "visible_camera" (default False),
  "cast_shadow" and "use_mis" (default True).
- ``"world"``: ``{"color": RGB radiance, "texture": {"path": equirectangular image, "weight": RGB,
  "matrix": (3, 4) texture vector of a direction (Mapping), "interpolation": "linear"|"closest"},
  "sampling": "auto"|"manual"|"none", "map_resolution": int (0 = the image's size)}``: radiance
  color + weight·image(matrix·ω). Other keys (``"warnings"``, names, ...) are ignored.

``settings`` (dict or None; unknown keys are refused): ``samples`` (16) per pixel, ``max_bounces``
(8; 0 = direct light only), ``pixel_filter`` ("box", "gaussian", "blackman_harris" or
"pixel_center", any case; Blackman-Harris, Cycles' default), ``filter_width`` (1.5 px),
``threads`` (0 = all cores), ``seed`` (0), ``tile_size`` (16), ``samples_per_pass`` (0 =
automatic: about samples/8, at most 16, with partial images, else one pass), ``progressive``
(False: True sizes the passes by time as Cycles' viewport does, one sample first and then as many
as fit its display interval: 0.1 s in the first second, growing to 2 s; ``samples_per_pass``
must then be 0), ``russian_roulette_depth`` (1: paths may be ended at random once they have
scattered this many + 1 times; Cycles' Min Light Bounces + 1), ``transparent_max_bounces`` (8:
Cycles' setting; passes through Transparent BSDFs are not bounces, and the surface after this
many + 1 passes adds only its emission), ``transparent_background`` (False), ``region``
(None: Blender's Render Region, ``(x_min, y_min, x_max, y_max)`` pixels with rows counted from the
top, maximum exclusive: only those pixels are rendered and the image is the region's size, each
pixel as the whole image's render gives it), ``adaptive_sampling`` (False: True stops sampling
each pixel once its noise is below the threshold, as Cycles' Adaptive Sampling),
``adaptive_threshold`` (0.01, in [0, 1]; 0 = automatic, max(0.001, 1/samples); Cycles' Noise
Threshold) and ``adaptive_min_samples`` (0 = automatic from the threshold: 64 at 0.01; at most
4096; Cycles' Min Samples).

``on_progress(done, total, image)`` is called on the calling thread, holding the GIL, while the
render runs on C++ threads: ``done``/``total`` count tiles over the whole render (reported at most
every 50 ms, and once more at the end with ``done == total``); ``image`` is the
partial result (same layout as the return value) after each pass but the last, else None; with
``partial_images=False`` it is always None and no pass is copied (for a caller that shows no
partial result). Return False to cancel (any other return value, None included, continues). The
GIL is released while waiting, so other Python threads run.

Cancelled by on_progress, the render stops within a tile and the image rendered so far is
returned (``stats["cancelled"]`` is True). An exception raised in on_progress, or KeyboardInterrupt
(Ctrl-C), stops the render the same way and is then raised. A bad scene or setting raises
ValueError naming the field, e.g. ``scene['meshes'][2]['normal_indices']: index 9 out of range [0, 8)``.

With ``return_stats=True`` the result is ``(image, stats)``, stats a dict: ``seconds``,
``samples_per_pixel`` (completed), ``camera_samples``, ``rays``, ``shadow_rays``,
``rejected_samples`` (NaN/Inf/negative radiance dropped), ``cancelled``, ``converged``
(adaptive sampling stopped every pixel before ``samples``), ``warnings`` (list of str:
what was rendered approximately), ``triangles`` (as drawn), ``stored_triangles`` (an instanced mesh
counted once) and ``instances`` (Embree instances), and for :func:`render` ``convert_seconds``
(reading, welding and flattening the meshes), ``bvh_seconds`` (building Embree's BVH) and
``bvh_build`` ("quick" where the render traces few rays per triangle, else "medium");
``seconds`` is the render alone.)doc";

constexpr const char* kRenderFileDoc = R"doc(render_scene_file(path, settings=None, on_progress=None, *, bottom_up=False, partial_images=True, return_stats=False) -> image or (image, stats)

Renders a JSON scene file of the ``bxdf-render`` CLI (format: plugin/README.md). Its ``"render"``
object gives the resolution and settings; ``settings`` (same keys as :func:`render`) overrides them.
Everything else is as :func:`render`; a bad file raises ValueError naming the file and the JSON path.)doc";

}  // namespace

// What the scene holds: triangles as drawn, triangles stored (an instanced mesh once) and
// instances, for stats (memory and scale reports).
static void scene_counts(const render::Scene& scene, py::dict& out) {
  out["triangles"] = scene.num_rendered_triangles();
  out["stored_triangles"] = scene.num_triangles();
  out["instances"] = scene.num_instances();
  out["bvh_build"] = scene.quick_build() ? "quick" : "medium";
}

void bind_render(py::module_& m) {
  m.def(
      "render",
      [](const py::object& scene, const py::object& settings, const py::object& on_progress, bool bottom_up,
         bool partial_images, bool return_stats) {
        render::RenderSettings rs;
        rs.filter = render::FilterType::BlackmanHarris;  // Cycles' defaults
        rs.filter_width = 1.5f;
        // The settings first: the rays they ask for choose the BVH's build (Scene::commit).
        apply_render_settings(settings, rs);
        SceneFromPython s = scene_from_python(
            scene, double(rs.samples_per_pixel) * (1.0 + double(rs.max_bounces)));
        rs.width = s.width;
        rs.height = s.height;
        py::dict times;
        times["convert_seconds"] = s.convert_seconds;
        times["bvh_seconds"] = s.bvh_seconds;
        scene_counts(*s.scene, times);
        return run_render(*s.scene, s.camera, rs, on_progress, bottom_up, partial_images, return_stats,
                          std::move(s.warnings), times);
      },
      py::arg("scene"), py::arg("settings") = py::none(), py::arg("on_progress") = py::none(), py::kw_only(),
      py::arg("bottom_up") = false, py::arg("partial_images") = true, py::arg("return_stats") = false, kRenderDoc);

  m.def(
      "render_scene_file",
      [](const py::object& path, const py::object& settings, const py::object& on_progress, bool bottom_up,
         bool partial_images, bool return_stats) {
        const std::string file = path_argument(path);
        render::LoadedScene loaded;
        {
          py::gil_scoped_release release;
          loaded = render::load_scene_json(file);
        }
        apply_render_settings(settings, loaded.settings);
        py::dict counts;
        scene_counts(*loaded.scene, counts);
        return run_render(*loaded.scene, loaded.camera, loaded.settings, on_progress, bottom_up, partial_images,
                          return_stats, {}, counts);
      },
      py::arg("path"), py::arg("settings") = py::none(), py::arg("on_progress") = py::none(), py::kw_only(),
      py::arg("bottom_up") = false, py::arg("partial_images") = true, py::arg("return_stats") = false,
      kRenderFileDoc);
}

}  // namespace bxdf::python
