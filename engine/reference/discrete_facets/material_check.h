// check-method's rule `physical-material` (issue 36): the method's statistics at its mapped parameters (its
// `map:` lines for a user method, GlintMethod::materialMapping for a built-in) against the discrete-facet
// reference of the same glint material, over 4x4 blocks of plane90 and plane25 at three densities: the issue's
// target (CV and p99.9 / mean within 1.5x, dark fraction within 0.1, mean within 5 %), one row per view. The rule
// reports (status "info": where a method's design cannot represent the material is documented, not a defect).
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "reference/discrete_facets/block_stats.h"
#include "platform/context.h"
#include "reference/discrete_facets/method_statistics.h"

namespace glimmer::facets {

struct MaterialCheckOptions {
    int size = 128;
    std::vector<std::string> scenes = {"plane90", "plane25"};
    std::vector<double> densities = {1e5, 1e6, 1e7};   // facets per m^2 (the built-in planes: UV in metres)
    std::vector<double> gammas = {0.015};
    Backend backend = Backend::Egl;
    std::filesystem::path shaderRoot;
    std::function<void(const std::string&)> progress;
};

struct MaterialCheckRow {
    std::string scene;
    double density = 0.0, gamma = 0.0;
    BlockStats method, reference;
    TargetCheck target;
};

std::vector<MaterialCheckRow> checkPhysicalMaterial(const std::string& methodId, const MaterialCheckOptions& options);
// The rows as a Markdown table.
std::string formatMaterialTable(const std::vector<MaterialCheckRow>& rows);

}  // namespace glimmer::facets
