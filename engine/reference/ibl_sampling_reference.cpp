#include "reference/ibl_sampling_reference.h"

#include <algorithm>
#include <cmath>

#include "reference/brdf_reference.h"

namespace glimmer::iblref {

namespace k25 = glimmer::kemppinen2025;
constexpr double kPi = 3.14159265358979323846;

uint32_t hash(uint32_t v) {
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

uint32_t sampleSeed(glm::ivec2 pixel, uint32_t sampleIndex, uint32_t seed) {
    return hash(uint32_t(pixel.x) ^ hash(uint32_t(pixel.y) ^ hash(sampleIndex ^ hash(seed))));
}

double Rng::next() {
    state = state * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    word = (word >> 22u) ^ word;
    return double(word >> 8) * (1.0 / 16777216.0);
}

static double smoothD(const glm::dvec3& h, double alpha, int ndf) {
    return ndf == k25::kBeckmann ? reference::beckmannD(h, alpha) : reference::ggxD(h, alpha);
}

static double smoothG1(const glm::dvec3& w, double alpha, int ndf) {
    return ndf == k25::kBeckmann ? reference::beckmannG1(w, alpha) : reference::ggxG1(w, alpha);
}

glm::dvec3 sampleSmoothNdf(double u1, double u2, double alpha, int ndf) {
    double a2 = alpha * alpha;
    double tan2 = ndf == k25::kBeckmann ? -a2 * std::log(std::max(1.0 - u1, 1e-12))
                                        : a2 * u1 / std::max(1.0 - u1, 1e-12);
    double cosTheta = 1.0 / std::sqrt(1.0 + tan2);
    double sinTheta = std::sqrt(std::max(1.0 - cosTheta * cosTheta, 0.0));
    double phi = 2.0 * kPi * u2;
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

double smoothNdfPdf(const glm::dvec3& h, double alpha, int ndf) { return smoothD(h, alpha, ndf) * std::max(h.z, 0.0); }

glm::dvec3 sampleCosine(double u1, double u2) {
    double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(1.0 - u1, 0.0))};
}

glm::dvec3 specularEstimate(const ShadingPoint& p, const NdfFn& ndf, const glm::dvec3& h, double pdfH,
                            const RadianceFn& environment) {
    const glm::dvec3& wo = p.wo;
    double woDotH = glm::dot(wo, h);
    if (!(pdfH > 0.0) || h.z <= 0.0 || woDotH <= 0.0 || wo.z <= 0.0) return glm::dvec3(0.0);
    glm::dvec3 wi = 2.0 * woDotH * h - wo;
    if (wi.z <= 0.0) return glm::dvec3(0.0);
    double G = smoothG1(wi, p.alpha, p.ndf) * smoothG1(wo, p.alpha, p.ndf);
    glm::dvec3 F = reference::schlickFresnel(p.f0, woDotH);
    glm::dvec3 weight = ndf(h) * G * F * (woDotH / (wo.z * pdfH));
    return weight * environment(p.frame * wi);
}

glm::dvec3 specularIntegral(const ShadingPoint& p, const NdfFn& ndf, const RadianceFn& environment, int grid) {
    // int_H D G F |wo.h| / |wo.n| L dh, with dh = dx / |J_T(h)| over the prior disk of the smooth NDF.
    glm::dvec2 alpha(p.alpha);
    double dx = 1.0 / grid;
    glm::dvec3 sum(0.0);
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            glm::dvec2 x((i + 0.5) * dx, (j + 0.5) * dx);
            if (glm::dot(x - 0.5, x - 0.5) >= 0.25) continue;
            glm::dvec3 h = k25::fromPrior(x, alpha, p.ndf);
            double jacobian = k25::priorJacobian(h, alpha, p.ndf);
            if (!(jacobian > 0.0)) continue;
            // The estimator with pdfH = |J_T| is exactly the integrand per unit prior area.
            sum += specularEstimate(p, ndf, h, jacobian, environment) * dx * dx;
        }
    return sum;
}

glm::dvec3 estimate(Mode mode, const ShadingPoint& p, bool glinty, const NdfFn& ndf, const GlintPixel& glint,
                    glm::ivec2 pixel, uint32_t sampleIndex, uint32_t seed, const RadianceFn& environment) {
    Rng rng{sampleSeed(pixel, sampleIndex, seed)};
    // Diffuse: one cosine-weighted sample (the shader draws both numbers before testing the albedo).
    double u1 = rng.next(), u2 = rng.next();
    glm::dvec3 diffuse(0.0);
    if (p.diffuseAlbedo != glm::dvec3(0.0)) diffuse = p.diffuseAlbedo * environment(p.frame * sampleCosine(u1, u2));
    NdfFn smooth = [&](const glm::dvec3& h) { return glm::dvec3(smoothD(h, p.alpha, p.ndf)); };
    const NdfFn& d = glinty ? ndf : smooth;
    glm::dvec3 h;
    double pdfH = 0.0;
    if (mode == Mode::GlintIs && glinty) {
        k25::SamplerRng glintRng(0u);
        glintRng.state = hash(rng.state);   // glint_is.glsl: iblHash(rng) is the sampler's state
        k25::HalfVectorSample s = k25::sampleHalfVector(*glint.params, *glint.setup, p.ndf, glintRng);
        h = s.h;
        pdfH = s.pdf;
    } else {
        double v1 = rng.next(), v2 = rng.next();
        h = sampleSmoothNdf(v1, v2, p.alpha, p.ndf);
        pdfH = smoothNdfPdf(h, p.alpha, p.ndf);
    }
    return diffuse + specularEstimate(p, d, h, pdfH, environment);
}

}  // namespace glimmer::iblref
