// One entry point for --scene: a built-in name, a scene file (.json, content/ format), or a glTF path.
#pragma once
#include <string>

#include "scene/scene.h"

namespace glimmer {

// Throws UsageError for unknown names and Error (naming the file) for missing or corrupt files.
Scene loadScene(const std::string& nameOrPath);

}  // namespace glimmer
