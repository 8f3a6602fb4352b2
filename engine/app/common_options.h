// Options shared by render, view and bench: scene, camera, backend, method, --set, --aov, --env, --shader-dir.
#pragma once
#include <string>

#include "core/cli.h"
#include "offscreen/offscreen.h"

namespace glimmer {

RenderRequest readCommonRenderOptions(ArgReader& args, const std::string& defaultScene,
                                      const std::string& defaultMethod = "smooth");
std::string describeScenes();

}  // namespace glimmer
