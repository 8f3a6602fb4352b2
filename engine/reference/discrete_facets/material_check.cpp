#include "reference/discrete_facets/material_check.h"

#include <cstdio>

#include "reference/discrete_facets/reference_render.h"
#include "render/aov.h"

namespace glimmer::facets {

std::vector<MaterialCheckRow> checkPhysicalMaterial(const std::string& methodId, const MaterialCheckOptions& options) {
    registerReferenceMethod();
    std::vector<MaterialCheckRow> rows;
    for (const std::string& scene : options.scenes) {
        RenderRequest request;
        request.scene = scene;
        request.environment = "none";
        request.width = request.height = options.size;
        request.backend = options.backend;
        request.shaderRoot = options.shaderRoot;
        request.settings.method = "smooth";
        request.settings.debugView = findAov("glint").viewId;
        OffscreenSession session(request);
        SurfaceImage surface = captureSurface(session, request);
        for (double density : options.densities)
            for (double gamma : options.gammas) {
                RenderRequest r = request;
                char text[96];
                std::snprintf(text, sizeof text, "material.glint_density=%.9g", density);
                r.settings.apply(text);
                std::snprintf(text, sizeof text, "material.glint_angular_size=%.9g", gamma);
                r.settings.apply(text);
                GlintFrame reference = referenceGlintFrame(session, surface, r);
                GlintFrame method = methodGlintFrame(session, methodId, r, reference);
                MaterialCheckRow row;
                row.scene = scene;
                row.density = density;
                row.gamma = gamma;
                row.reference = blockStats(reference.d, reference.smooth, reference.inside, reference.width, reference.height, 4);
                row.method = blockStats(method.d, method.smooth, method.inside, method.width, method.height, 4);
                row.target = checkTarget(row.method, row.reference);
                rows.push_back(row);
                if (options.progress)
                    options.progress("physical-material: " + scene + " density " + std::to_string(density) + " done");
            }
    }
    return rows;
}

std::string formatMaterialTable(const std::vector<MaterialCheckRow>& rows) {
    std::string out =
        "| scene | density /m2 | gamma | blocks | mean / ref | CV (ref) | p99.9/mean (ref) | dark (ref) | target |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
    for (const MaterialCheckRow& r : rows) {
        char line[256];
        std::snprintf(line, sizeof line, "| %s | %.0e | %.3g | %zu | %.3f | %.3f (%.3f) | %.2f (%.2f) | %.3f (%.3f) | %s |\n",
                      r.scene.c_str(), r.density, r.gamma, r.reference.blocks, r.target.meanRatio, r.method.cv,
                      r.reference.cv, r.method.p999OverMean, r.reference.p999OverMean, r.method.darkFraction,
                      r.reference.darkFraction, r.target.all() ? "yes" : "no");
        out += line;
    }
    return out;
}

}  // namespace glimmer::facets
