// glTF 2.0 (.gltf / .glb) through tinygltf into the engine's Scene.
#pragma once
#include <filesystem>

#include "scene/scene.h"

namespace glimmer {

// Throws glimmer::Error naming the file on missing, corrupt or unsupported input.
// Limits: scene/scene_limits.h. External URIs must stay inside the model's folder (see the .cpp) unless
// setAllowOutsideUris(true) (--allow-outside-uris).
Scene loadGltfScene(const std::filesystem::path& path);
void setAllowOutsideUris(bool allow);

}  // namespace glimmer
