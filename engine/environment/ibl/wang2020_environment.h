// Resources of IBL mode `wang2020` (shaders/environment/ibl/wang2020.glsl): the environment prefilter pass (Sec. 4.4) into the
// 4D glint table, re-run only when the glint method's DPF (roughness, gamma) or the environment changed.
#pragma once
#include <memory>

#include "environment/ibl/ibl_modes.h"

namespace glimmer {

std::unique_ptr<IblModeResources> createWang2020EnvironmentResources();

}  // namespace glimmer
