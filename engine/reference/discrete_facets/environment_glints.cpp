#include "reference/discrete_facets/environment_glints.h"

#include <algorithm>
#include <bit>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>

#include "reference/environment_reference.h"

namespace glimmer::facets {

namespace {
constexpr double kPi = 3.14159265358979323846;

double unit(uint64_t bits) { return (double(bits >> 11) + 0.5) * (1.0 / 9007199254740992.0); }

// Smith G1 of shaders/common/brdf.glsl (GGX exact; Beckmann with Walter et al.'s rational fit, Eq. 27).
double smithG1(const glm::dvec3& w, double alpha, int ndf) {
    if (w.z <= 0.0) return 0.0;
    double tan2 = std::max(1.0 - w.z * w.z, 0.0) / (w.z * w.z);
    if (ndf == kNdfBeckmann) {
        double t = std::sqrt(tan2);
        if (t <= 0.0) return 1.0;
        double a = 1.0 / (alpha * t);
        return a >= 1.6 ? 1.0 : (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
    }
    return 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
}

glm::dvec3 schlick(const glm::dvec3& f0, double cosine) {
    double m = std::clamp(1.0 - cosine, 0.0, 1.0), m5 = m * m * m * m * m;
    return f0 + (glm::dvec3(1.0) - f0) * m5;
}
}  // namespace

EnvironmentMap::EnvironmentMap(envref::CubeImage cube, double intensity, double rotationDegrees)
    : cube_(std::move(cube)), intensity_(intensity), rotationDegrees_(rotationDegrees) {}

glm::dvec3 EnvironmentMap::radiance(const glm::dvec3& worldDirection) const {
    if (cube_.size < 2) return glm::dvec3(0.0);
    glm::vec3 d = envref::worldToEnvironment(glm::vec3(glm::normalize(worldDirection)), float(rotationDegrees_));
    return intensity_ * glm::dvec3(envref::sampleCube(cube_, d));
}

std::vector<glm::vec3> environmentGlints(const SurfaceImage& surface, const std::vector<Material>& materials,
                                         const EnvironmentMap& map, const ReferenceOptions& options,
                                         const EnvironmentOptions& environment, double* seconds) {
    const size_t pixels = size_t(surface.width) * size_t(surface.height);
    std::vector<glm::vec3> out(pixels, glm::vec3(0.0f));
    std::vector<std::unique_ptr<FacetEstimator>> estimators(materials.size());
    for (size_t i = 0; i < materials.size(); ++i)
        if (materials[i].glinty)
            estimators[i] = std::make_unique<FacetEstimator>(facetMaterial(materials[i], options, int(i)), options.filter);
    const int facetSamples = std::max(environment.facetSamples, 1);
    const int grid = std::max(1, int(std::sqrt(double(std::max(environment.smoothSamples, 1)))));
    const auto start = std::chrono::steady_clock::now();

    parallelRows(surface.height, options.threads, options.progress, "reference environment", [&](int y) {
        for (int x = 0; x < surface.width; ++x) {
            const size_t p = size_t(y) * size_t(surface.width) + size_t(x);
            const SurfacePixel& px = surface.pixels[p];
            if (!px.covered || px.material < 0 || size_t(px.material) >= estimators.size() || !estimators[size_t(px.material)])
                continue;
            const FacetEstimator& estimator = *estimators[size_t(px.material)];
            const FacetMaterial& mat = estimator.material();
            glm::dvec3 n = glm::normalize(px.normal);
            glm::dvec3 t = px.tangent - n * glm::dot(n, px.tangent);
            if (glm::length(t) < 1e-9) continue;
            t = glm::normalize(t);
            glm::dvec3 b = px.bitangentSign * glm::cross(n, t);
            const glm::dvec3 toEye = glm::normalize(surface.cameraPosition - px.position);
            const glm::dvec3 v(glm::dot(toEye, t), glm::dot(toEye, b), glm::dot(toEye, n));
            if (v.z <= 0.0) continue;
            const glm::dvec3 f0 = glm::mix(glm::dvec3(0.04), px.baseColor, px.metallic);
            const double g1v = smithG1(v, mat.alpha, mat.ndf);
            // f(h) = L(l) F G (v.h) / (n.v): the specular integrand over half vectors (0 below the horizon).
            auto integrand = [&](const glm::dvec3& h) -> glm::dvec3 {
                double vh = glm::dot(v, h);
                if (vh <= 0.0) return glm::dvec3(0.0);
                glm::dvec3 l = 2.0 * vh * h - v;
                if (l.z <= 0.0) return glm::dvec3(0.0);
                glm::dvec3 world = l.x * t + l.y * b + l.z * n;
                double g = smithG1(l, mat.alpha, mat.ndf) * g1v;
                return map.radiance(world) * schlick(f0, vh) * (g * vh / v.z);
            };
            uint64_t seed = FacetRealization::mix(uint64_t(p) * 0x9e3779b97f4a7c15ull + options.seed);

            // L_smooth: h ~ D(h) (h.n) on a jittered grid of the inverse CDF's uniforms.
            glm::dvec3 smooth(0.0);
            for (int j = 0; j < grid; ++j)
                for (int i = 0; i < grid; ++i) {
                    seed = FacetRealization::mix(seed);
                    double u1 = (double(i) + unit(seed)) / double(grid);
                    double u2 = (double(j) + unit(FacetRealization::mix(seed ^ 0x5bd1e995u))) / double(grid);
                    glm::dvec3 h = estimator.realization().normalFromUniforms(u1, u2);
                    if (h.z > 0.0) smooth += integrand(h) / h.z;
                }
            smooth /= double(grid * grid);

            // L_ref: every facet of the footprint; half vectors uniform in the cap that bounds its lobe.
            const double reach = estimator.realization().lobeRadius(), cosReach = std::cos(reach);
            const double capSolidAngle = 2.0 * kPi * (1.0 - cosReach);
            const double rho = mat.densityPerUv;
            glm::dvec3 reflected(0.0);
            estimator.forEachFootprintFacet(px.footprint, [&](const Facet& f, double weight) {
                glm::dvec3 axis = std::abs(f.m.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
                glm::dvec3 ft = glm::normalize(glm::cross(axis, f.m)), fb = glm::cross(f.m, ft);
                uint64_t s = FacetRealization::mix(seed ^ std::bit_cast<uint64_t>(f.uv.x) ^
                                                   (std::bit_cast<uint64_t>(f.uv.y) * 0xd1342543de82ef95ull));
                glm::dvec3 sum(0.0);
                for (int k = 0; k < facetSamples; ++k) {
                    s = FacetRealization::mix(s);
                    double cosTheta = 1.0 - (double(k) + unit(s)) / double(facetSamples) * (1.0 - cosReach);
                    double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
                    double psi = 2.0 * kPi * unit(FacetRealization::mix(s ^ 0x27d4eb2f165667c5ull));
                    glm::dvec3 h = cosTheta * f.m + sinTheta * (std::cos(psi) * ft + std::sin(psi) * fb);
                    if (h.z <= 0.0) continue;
                    double kernel = estimator.lobeWeight(f.m, h);
                    if (kernel <= 0.0) continue;
                    double ratio = estimator.lobeRatio(h);   // P(h) / (D(h) h.z)
                    if (!(ratio > 0.0)) continue;
                    sum += integrand(h) * (kernel / (ratio * h.z));
                }
                reflected += sum * (capSolidAngle / double(facetSamples)) * (weight / rho) * f.color;
            });
            out[p] = glm::vec3((reflected - smooth) * px.occlusion);
        }
    });
    if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace glimmer::facets
