#include "app/common_options.h"

#include <filesystem>

#include "core/error.h"
#include "glints/methods.h"
#include "glints/user/user_methods.h"
#include "render/aov.h"
#include "environment/environment.h"
#include "environment/ibl/ibl_modes.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/scene_loader.h"

namespace glimmer {

RenderRequest readCommonRenderOptions(ArgReader& args, const std::string& defaultScene, const std::string& defaultMethod) {
    RenderRequest request;
    // Before the scene is read: glTF URIs that leave the model's folder are refused unless this is given.
    if (args.flag("--allow-outside-uris")) setAllowOutsideUris(true);
    request.scene = args.valueOr("--scene", defaultScene);
    request.camera = args.valueOr("--camera", "");
    request.backend = parseHeadlessBackend(args.valueOr("--backend", "egl"));
    // User methods before --method and --set name them: --method-file (repeatable; the first is the method unless
    // --method says otherwise), then the scene file's "methodFiles" (the first is the method when neither is given).
    std::vector<std::string> methodFiles = args.values("--method-file");
    std::string fileMethod;
    for (const std::string& file : methodFiles) {
        std::string id = loadUserMethodFile(file);
        if (fileMethod.empty()) fileMethod = id;
    }
    for (const std::string& file : sceneMethodFiles(request.scene)) {
        std::string id = loadUserMethodFile(file);
        if (fileMethod.empty()) fileMethod = id;
    }
    auto method = args.value("--method");
    request.settings.method = method ? resolveGlintMethod(*method) : (fileMethod.empty() ? defaultMethod : fileMethod);
    // Without --ibl a method with environment glints of its own (wang2020) draws them (GlintMethod::defaultIbl).
    request.settings.ibl = args.valueOr("--ibl", defaultIblOf(findGlintMethod(request.settings.method)));
    checkIblModeMethod(findIblMode(request.settings.ibl), request.settings.method);
    for (const std::string& assignment : args.values("--set")) request.settings.apply(assignment);
    if (auto aov = args.value("--aov")) request.settings.debugView = findAov(*aov).viewId;
    if (auto dir = args.value("--shader-dir")) {
        if (!std::filesystem::is_directory(*dir)) throw Error("--shader-dir: " + *dir + ": not a directory");
        request.shaderRoot = *dir;
    }
    if (auto env = args.value("--env")) {
        // Check what can be checked before a context exists; a corrupt image is reported when it is decoded.
        EnvironmentSpec spec = parseEnvironmentSpec(*env, "--env");
        if (spec.kind == EnvironmentSpec::Kind::File) {
            std::error_code ec;
            if (!std::filesystem::exists(spec.path, ec)) throw Error("--env: " + *env + ": file not found");
            if (!std::filesystem::is_regular_file(spec.path, ec)) throw Error("--env: " + *env + ": not a file");
        }
        request.environment = *env;
    }
    request.spp = args.intValue("--spp", 1, 1, 1 << 20);
    return request;
}

std::string describeScenes() {
    std::string text = "Built-in scenes:\n";
    for (const std::string& name : builtinSceneNames()) text += "  " + name + "\n";
    text += "Any .gltf / .glb path is accepted as well.\n";
    return text;
}

}  // namespace glimmer
