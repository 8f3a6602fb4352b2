// The discrete-facet reference over a whole image: per pixel of a G-buffer (read from the renderer's AOVs, so any
// scene works: planes, sphere, atrium, glTF), the NDF D_est of each light (facet_estimator.h) and, optionally, the
// environment's specular radiance reflected by the pixel's facets. Multithreaded over rows, with progress.
#pragma once
#include <glm/glm.hpp>

#include <functional>
#include <string>
#include <vector>

#include "reference/discrete_facets/extended_lights.h"
#include "reference/discrete_facets/facet_estimator.h"
#include "scene/scene.h"

namespace glimmer::facets {

// One pixel of the G-buffer, in world space (what the AOVs normal, tangent, uv, duvdx, duvdy, depth and material
// hold; the bitangent is sign x cross(n, t) as in the lighting pass).
struct SurfacePixel {
    bool covered = false;
    glm::dvec3 position{0.0}, normal{0.0, 0.0, 1.0}, tangent{1.0, 0.0, 0.0};
    double bitangentSign = 1.0;
    PixelFootprint footprint;
    int material = -1;
    // For the environment (environment_glints.h): base colour and metalness (F0 = mix(0.04, base, metallic), as
    // the lighting pass) and the ambient occlusion that multiplies the environment term.
    glm::dvec3 baseColor{0.8};
    double metallic = 0.0, occlusion = 1.0;
};

struct SurfaceImage {
    int width = 0, height = 0;                 // pixels bottom-up (GL order), as RenderResult::hdr
    std::vector<SurfacePixel> pixels;
    glm::dvec3 cameraPosition{0.0};
};

struct ReferenceOptions {
    Lobe lobe = Lobe::Cone;
    FootprintFilter filter = FootprintFilter::Box;
    uint64_t seed = 0;        // realization: material i uses seed x 2^20 + i
    int maxLights = 8;        // lights beyond this many are not evaluated (their D stays 0)
    int threads = 0;          // 0 = every hardware thread
    bool progress = true;     // log::info every 10 % of the rows
    // Lights of a size (extended_lights.h): each facet's lobe integrated over the light for area lights and point
    // lights of a radius (1), also over the sun's disk (2), or the facets that reflect every light's centre
    // direction counted as for a punctual light (0, the earlier reading). The sun's 0.53 degrees change the glint
    // statistics by little against the facets' lobe (docs/discrete_facet_reference.md) and cost a lobe
    // integration per facet on every measured plane, so 1 is the default.
    int lightExtent = 1;
    ExtendedLightOptions extended;
};

// The realization parameters of a scene material (density per unit UV = glint density x m^2 per unit UV x the
// legacy density scale; its NDF, alpha, gamma, anisotropy and colours).
FacetMaterial facetMaterial(const Material& material, const ReferenceOptions& options, int materialIndex);

struct ReferenceImage {
    int width = 0, height = 0, lights = 0;
    std::vector<glm::vec3> d;          // [pixel x lights + light]: D_est per channel (0 where not glinty or unlit)
    std::vector<float> smoothD;        // [pixel x lights + light]: the smooth D(h) at the same h
    std::vector<float> lambda;         // [pixel x lights + light]: expected reflecting facets rho A P(h)
    std::vector<uint8_t> glinty;       // per pixel: a glinty material was evaluated there
    double seconds = 0.0;              // wall time of the evaluation
    double facetsTested = 0.0;         // facets whose lobe weight was evaluated, all pixels and lights
    int threads = 1;
};

// D_est of every light at every pixel of `surface` whose material is glinty, `lights` in the order given. Punctual
// lights: at the half vector of their direction (directional) or of their position (point, spot). Lights of a size
// with options.lightExtent: (N / M) x D(h_centre) (extended_lights.h), h_centre from the direction to their centre
// lifted to 1e-4 above the horizon as the lighting pass does; smoothD holds D(h_centre).
ReferenceImage evaluateLights(const SurfaceImage& surface, const std::vector<Material>& materials,
                              const std::vector<Light>& lights, const ReferenceOptions& options);

// Runs body(row) for rows 0..rows-1 on `threads` workers (0 = hardware threads), logging `what` every 10 %.
void parallelRows(int rows, int threads, bool progress, const std::string& what, const std::function<void(int)>& body);
int workerCount(int threads);

}  // namespace glimmer::facets
