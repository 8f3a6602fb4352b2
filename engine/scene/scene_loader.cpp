#include "scene/scene_loader.h"

#include <algorithm>
#include <filesystem>

#include "core/error.h"
#include "core/log.h"
#include "core/files.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/scene_file.h"

namespace glimmer {

static bool isPlainName(const std::string& name) {
    return !name.empty() && name.find('/') == std::string::npos && name.find('\\') == std::string::npos &&
           name.find('.') == std::string::npos;
}

// Scenes of the content folder by name: `<name>.json` where the name has no dot (camera paths,
// `<scene>.path.json`, live there too and are no scenes; a dotted name could not be loaded as a name anyway).
std::vector<std::string> contentSceneNames() {
    std::vector<std::string> names;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(defaultContentDir(), error))
        if (entry.is_regular_file() && entry.path().extension() == ".json" && isPlainName(entry.path().stem().string()))
            names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

Scene loadScene(const std::string& nameOrPath) {
    if (isPlainName(nameOrPath)) {
        std::filesystem::path contentFile = defaultContentDir() / (nameOrPath + ".json");
        if (std::filesystem::is_regular_file(contentFile)) return loadSceneFile(contentFile);
        if (isBuiltinScene(nameOrPath)) return makeBuiltinScene(nameOrPath);
        std::string known;
        for (const std::string& n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
        for (const std::string& n : contentSceneNames())
            if (!isBuiltinScene(n)) known += ", " + n;
        throw UsageError("--scene: unknown scene '" + nameOrPath + "' (known: " + known +
                         "; or a path to a .json, .gltf or .glb file)");
    }
    std::filesystem::path path(nameOrPath);
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (ext != ".gltf" && ext != ".glb" && ext != ".json")
        throw UsageError("--scene: " + nameOrPath + ": unsupported scene type (use .json, .gltf, .glb or a scene name)");
    if (!std::filesystem::exists(path)) throw Error(nameOrPath + ": scene file not found");
    if (ext == ".json") return loadSceneFile(path);
    Scene scene = loadGltfScene(path);
    if (scene.fallbackLights)
        log::info(nameOrPath, ": the model has no KHR_lights_punctual light; lit by a default key and fill light");
    return scene;
}

std::vector<std::string> sceneMethodFiles(const std::string& nameOrPath) {
    std::filesystem::path file = nameOrPath;
    if (isPlainName(nameOrPath)) file = defaultContentDir() / (nameOrPath + ".json");
    if (file.extension() != ".json") return {};
    return readSceneMethodFiles(file);
}

}  // namespace glimmer
