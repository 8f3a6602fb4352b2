// One entry point for --scene: a built-in name, a scene file (.json, content/ format), or a glTF path.
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"

namespace glimmer {

// Resolution order: a name with a file in the content folder (content/<name>.json, see defaultContentDir()),
// then a generated built-in scene, then a path to a .json scene file or a .gltf / .glb model.
// Throws UsageError for unknown names and Error (naming the file) for missing or corrupt files.
Scene loadScene(const std::string& nameOrPath);

// The "methodFiles" of the scene file that `nameOrPath` resolves to (empty for generated scenes and glTF models):
// read before the scene is built so the command line can name their methods. Errors as loadScene's.
std::vector<std::string> sceneMethodFiles(const std::string& nameOrPath);

// Names of the scene files in the content folder (without .json), sorted; empty when the folder is missing.
std::vector<std::string> contentSceneNames();

}  // namespace glimmer
