#include "scene/scene_loader.h"

#include <algorithm>
#include <filesystem>

#include "core/error.h"
#include "core/files.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"

namespace glimmer {

Scene loadScene(const std::string& nameOrPath) {
    if (isBuiltinScene(nameOrPath)) return makeBuiltinScene(nameOrPath);
    std::filesystem::path path(nameOrPath);
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (ext == ".gltf" || ext == ".glb") {
        if (!std::filesystem::exists(path)) throw Error(nameOrPath + ": scene file not found");
        return loadGltfScene(path);
    }
    std::string known;
    for (const std::string& n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
    if (ext.empty()) throw UsageError("--scene: unknown scene '" + nameOrPath + "' (built-in: " + known + ")");
    if (!std::filesystem::exists(path)) throw Error(nameOrPath + ": scene file not found");
    throw UsageError("--scene: " + nameOrPath + ": unsupported scene type (use .gltf, .glb or a built-in name)");
}

}  // namespace glimmer
