// Output channels of `glimmer render --aov` and the window's debug views. Ids are the VIEW_* of
// shaders/common/aov_ids.glsl, which the shaders include too.
#pragma once
#include <string>
#include <vector>

namespace glimmer {

struct AovInfo {
    std::string name;
    int viewId;
    std::string meaning;
};

const std::vector<AovInfo>& aovTable();
// Throws UsageError naming --aov for unknown names.
const AovInfo& findAov(const std::string& name);
// The debug view `step` entries after `viewId` in table order (N / Shift+N), wrapping, over the first entry of
// each view id: aliases ("glintscale" is wang2020's name for "extra") are not stops of their own.
const AovInfo& nextDebugView(int viewId, int step);

}  // namespace glimmer
