#include "reference/discrete_facets/facet_image.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <thread>

#include "core/log.h"

namespace glimmer::facets {

int workerCount(int threads) {
    return threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

void parallelRows(int rows, int threads, bool progress, const std::string& what, const std::function<void(int)>& body) {
    const int workers = std::min(workerCount(threads), std::max(rows, 1));
    std::atomic<int> next{0}, done{0};
    std::mutex logMutex;
    int lastDecile = 0;
    const auto start = std::chrono::steady_clock::now();
    auto work = [&] {
        for (int row = next++; row < rows; row = next++) {
            body(row);
            int finished = ++done;
            if (!progress) continue;
            int decile = finished * 10 / rows;
            std::lock_guard<std::mutex> lock(logMutex);
            if (decile > lastDecile) {
                lastDecile = decile;
                double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                log::info(what, ": ", decile * 10, " % of ", rows, " rows (", int(s * 10.0) / 10.0, " s)");
            }
        }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < workers; ++i) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
}

FacetMaterial facetMaterial(const Material& material, const ReferenceOptions& options, int materialIndex) {
    FacetMaterial m;
    m.densityPerUv = double(material.glint.density) * double(material.surfacePerUvArea) *
                     double(material.glintDensityScale);
    m.gamma = material.glint.angularSize;
    m.alpha = std::max(double(material.alpha), 1e-4);
    m.ndf = material.ndf == NdfType::Beckmann ? kNdfBeckmann : kNdfGgx;
    m.anisotropy = std::max(1.0, double(material.glint.anisotropy));
    m.color = glm::dvec3(material.glint.color);
    m.colorVariation = material.glint.colorVariation;
    m.seed = (options.seed << 20) + uint64_t(materialIndex);
    m.lobe = options.lobe;
    return m;
}

ReferenceImage evaluateLights(const SurfaceImage& surface, const std::vector<Material>& materials,
                              const std::vector<Light>& lights, const ReferenceOptions& options) {
    ReferenceImage image;
    image.width = surface.width;
    image.height = surface.height;
    image.lights = std::min(int(lights.size()), std::max(options.maxLights, 0));
    const size_t pixels = size_t(surface.width) * size_t(surface.height);
    image.d.assign(pixels * size_t(image.lights), glm::vec3(0.0f));
    image.smoothD.assign(pixels * size_t(image.lights), 0.0f);
    image.lambda.assign(pixels * size_t(image.lights), 0.0f);
    image.glinty.assign(pixels, 0);
    image.threads = workerCount(options.threads);

    std::vector<std::unique_ptr<FacetEstimator>> estimators(materials.size());
    for (size_t i = 0; i < materials.size(); ++i)
        if (materials[i].glinty)
            estimators[i] = std::make_unique<FacetEstimator>(facetMaterial(materials[i], options, int(i)), options.filter);

    std::atomic<long long> tested{0};
    const auto start = std::chrono::steady_clock::now();
    parallelRows(surface.height, options.threads, options.progress, "reference", [&](int y) {
        long long rowTested = 0;
        for (int x = 0; x < surface.width; ++x) {
            const size_t p = size_t(y) * size_t(surface.width) + size_t(x);
            const SurfacePixel& px = surface.pixels[p];
            if (!px.covered || px.material < 0 || size_t(px.material) >= estimators.size() || !estimators[size_t(px.material)])
                continue;
            const FacetEstimator& estimator = *estimators[size_t(px.material)];
            image.glinty[p] = 1;
            // The shading frame of the lighting pass: n, t orthogonalized against n, b = sign x cross(n, t).
            glm::dvec3 n = glm::normalize(px.normal);
            glm::dvec3 t = px.tangent - n * glm::dot(n, px.tangent);
            if (glm::length(t) < 1e-9) continue;
            t = glm::normalize(t);
            glm::dvec3 b = px.bitangentSign * glm::cross(n, t);
            auto toShading = [&](const glm::dvec3& w) { return glm::dvec3(glm::dot(w, t), glm::dot(w, b), glm::dot(w, n)); };
            glm::dvec3 wo = toShading(glm::normalize(surface.cameraPosition - px.position));
            if (wo.z <= 0.0) continue;
            for (int k = 0; k < image.lights; ++k) {
                const Light& light = lights[size_t(k)];
                glm::dvec3 toward = light.type == LightType::Directional
                                        ? glm::normalize(glm::dvec3(light.vector))
                                        : glm::normalize(glm::dvec3(light.vector) - px.position);
                glm::dvec3 wi = toShading(toward);
                const bool extent = options.lightExtent >= (light.type == LightType::Directional ? 2 : 1);
                const LightShape shape = extent ? lightShape(light) : LightShape{};
                if (shape.kind != LightShape::None) {
                    // A light of a size may reach the pixel with its centre below the horizon (the lighting pass
                    // lifts that direction to 1e-4 for h).
                    const glm::dvec3 h = glm::normalize(glm::dvec3(wi.x, wi.y, std::max(wi.z, 1e-4)) + wo);
                    const uint64_t seed = FacetRealization::mix((uint64_t(p) << 8 | uint64_t(k)) * 0x9e3779b97f4a7c15ull +
                                                                options.seed);
                    ExtendedEstimate e = estimateOverLight(estimator, px.footprint, px.position, n, t, b,
                                                           glm::normalize(surface.cameraPosition - px.position),
                                                           shape, options.extended, seed);
                    const double smooth = estimator.smoothD(h);
                    image.d[p * size_t(image.lights) + size_t(k)] = glm::vec3(e.factor * smooth);
                    image.smoothD[p * size_t(image.lights) + size_t(k)] = float(smooth);
                    image.lambda[p * size_t(image.lights) + size_t(k)] = float(e.lambda);
                    rowTested += e.facetsTested;
                    continue;
                }
                if (wi.z <= 0.0) continue;
                glm::dvec3 h = glm::normalize(wi + wo);
                FacetEstimate e = estimator.estimate(px.footprint, h);
                image.d[p * size_t(image.lights) + size_t(k)] = glm::vec3(e.d);
                image.smoothD[p * size_t(image.lights) + size_t(k)] = float(estimator.smoothD(h));
                image.lambda[p * size_t(image.lights) + size_t(k)] = float(e.lambda);
                rowTested += e.facetsTested;
            }
        }
        tested += rowTested;
    });
    image.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    image.facetsTested = double(tested.load());
    return image;
}

}  // namespace glimmer::facets
