// JSON scene files for the bxdf-render CLI: meshes (OBJ files, inline arrays or generated
// shapes; "prototypes" drawn only where "instances" place them), materials (registry models,
// alone or combined, optionally emissive), lights,
// world, camera and render settings. Errors name the file, the JSON path of the field and what
// was expected.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "bxdf/params.h"
#include "bxdf/render/camera.h"
#include "bxdf/render/renderer.h"
#include "bxdf/render/scene.h"

namespace bxdf::render {

// A bad scene file. what() reads "<file>: <json path>: <problem>".
struct SceneFileError : ParameterError {
  using ParameterError::ParameterError;
};

struct LoadedScene {
  std::unique_ptr<Scene> scene;  // committed
  CameraSettings camera;
  RenderSettings settings;  // from the file's "render" object (defaults otherwise)
};

LoadedScene load_scene_json(const std::string& path);
// Same from text; `name` stands for the file in messages and relative OBJ paths resolve
// against `base_dir`.
LoadedScene parse_scene_json(const std::string& text, const std::string& name,
                             const std::string& base_dir);

}  // namespace bxdf::render
