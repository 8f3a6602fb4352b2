// Stepping through the glint method table (M / Shift+M, the split screen's Shift+B).
#pragma once
#include <string>

#include "glints/methods.h"

namespace glimmer {

// The method `step` places after `from` in glintMethods() (wrapping), passing over `skip` (the split screen's
// right side never shows the left side's method). `from` may be `skip` or unknown (then counting starts at 0).
const GlintMethod& cycleGlintMethod(const std::string& from, int step, const std::string& skip = "");

}  // namespace glimmer
