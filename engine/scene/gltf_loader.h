// glTF 2.0 (.gltf / .glb) through tinygltf into the engine's Scene.
#pragma once
#include <filesystem>

#include "scene/scene.h"

namespace glimmer {

// Throws glimmer::Error naming the file on missing, corrupt or unsupported input.
Scene loadGltfScene(const std::filesystem::path& path);

}  // namespace glimmer
