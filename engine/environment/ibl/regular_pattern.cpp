#include "environment/ibl/regular_pattern.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.h"
#include "environment/ibl/kurt_brdf.h"

namespace glimmer::ibl {

namespace {
constexpr double kPi = std::numbers::pi;

glm::dvec3 polar(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

struct Ring {
    std::vector<glm::dvec3> kept;
    double qSum = 0.0;
};

// One circle of n samples at theta, starting at phi = offset * 2 pi / n; samples with q < xi0 are rejected.
Ring buildRing(double theta, int n, double offset, const PatternParams& p) {
    Ring ring;
    for (int j = 0; j < n; ++j) {
        glm::dvec3 h = polar(theta, 2.0 * kPi * (j + offset) / n);
        double q = kurtQ(h, p.mx, p.my);
        if (q < p.xi0) continue;
        ring.kept.push_back(h);
        ring.qSum += q;
    }
    return ring;
}
}  // namespace

double thetaMax(double xi0, double mx, double my) {
    return std::atan(std::sqrt(-std::log(xi0)) * std::max(mx, my));
}

int ringSampleCount(int n0, double thetaI, double theta0) {
    return 2 * int(std::floor(n0 * std::sin(thetaI) / (2.0 * std::sin(theta0)) + 0.5));
}

int ringSampleCountArc(int n0, double thetaI, double theta0, double spacing) {
    double n = n0 + 2.0 * kPi * (std::sin(thetaI) - std::sin(theta0)) / std::sin(spacing);
    return 2 * int(std::floor(n / 2.0 + 0.5));
}

RegularPattern generateRegularPattern(const PatternParams& params) {
    if (params.nc < 1) throw Error("regular pattern: nc must be >= 1, got " + std::to_string(params.nc));
    if (!(params.xi0 > 0.0 && params.xi0 < 1.0))
        throw Error("regular pattern: xi0 must be in (0, 1), got " + std::to_string(params.xi0));
    if (!(params.mx > 0.0 && params.my > 0.0)) throw Error("regular pattern: mx and my must be > 0");

    RegularPattern pattern;
    pattern.params = params;
    pattern.thetaMax = thetaMax(params.xi0, params.mx, params.my);
    const bool s1 = params.spacing == RingSpacing::S1;
    const double spacing = pattern.thetaMax / (params.nc + (s1 ? 1 : 2));   // Eq. 12
    const int n0 = s1 ? 6 : 4;
    const int firstK = s1 ? 0 : 1;
    const int lastK = s1 ? params.nc - 1 : params.nc;
    const double theta0 = spacing;   // first non-degenerate circle in both spacings
    for (int k = firstK; k <= lastK; ++k) {
        if (k == 0) {   // the pole: q = 1 >= xi0 always
            pattern.halfVectors.push_back({0.0, 0.0, 1.0});
            pattern.ringCounts.push_back(1);
            pattern.ringHalfOffset.push_back(false);
            continue;
        }
        double theta = k * spacing;
        int n = params.rule == RingRule::Arc ? ringSampleCountArc(n0, theta, theta0, spacing)
                                             : ringSampleCount(n0, theta, theta0);   // Eq. 13
        // Anisotropic extension: reject q < xi0 and keep the better of the ring and its half-offset twin
        // (highest sum of q over the kept samples). Isotropic rings lie inside theta_max, so nothing is rejected
        // and both variants tie: the unshifted ring is kept.
        Ring straight = buildRing(theta, n, 0.0, params);
        Ring shifted = buildRing(theta, n, 0.5, params);
        bool useShifted = shifted.qSum > straight.qSum * (1.0 + 1e-12);
        const Ring& ring = useShifted ? shifted : straight;
        pattern.halfVectors.insert(pattern.halfVectors.end(), ring.kept.begin(), ring.kept.end());
        pattern.ringCounts.push_back(int(ring.kept.size()));
        pattern.ringHalfOffset.push_back(useShifted);
    }
    double dSum = 0.0;   // Eq. 18
    for (const glm::dvec3& h : pattern.halfVectors) dSum += kurtD(h, params.mx, params.my);
    pattern.pdfConstant = dSum / pattern.halfVectors.size();
    return pattern;
}

RegularPattern selectPatternForBudget(double mx, double my, double xi0, int budget, int maxCircles, RingRule rule) {
    if (budget < 1) throw Error("regular pattern: sample budget must be >= 1, got " + std::to_string(budget));
    RegularPattern best;
    bool have = false;
    for (int nc = 1; nc <= maxCircles; ++nc) {
        for (RingSpacing spacing : {RingSpacing::S1, RingSpacing::S2}) {
            RegularPattern candidate = generateRegularPattern({mx, my, xi0, nc, spacing, rule});
            if (!have) { best = candidate; have = true; continue; }
            int dc = std::abs(candidate.size() - budget), db = std::abs(best.size() - budget);
            if (dc < db || (dc == db && candidate.size() < best.size())) best = candidate;
        }
    }
    return best;
}

double lobeCrossSectionArea(glm::dvec3 wo, double mx, double my, double xi0) {
    const double border = std::sqrt(-std::log(xi0));
    glm::dvec3 hU = polar(std::atan(border * mx), 0.0);         // q(hU) = xi0 along t
    glm::dvec3 hV = polar(std::atan(border * my), 0.5 * kPi);   // q(hV) = xi0 along b
    glm::dvec3 wC = reflectAbout(wo, {0.0, 0.0, 1.0});
    glm::dvec3 wU = reflectAbout(wo, hU), wV = reflectAbout(wo, hV);
    // Eq. 14-15; the angles are capped below 90 degrees so tan stays finite at grazing views.
    const double cap = 0.5 * kPi - 1e-3;
    double aU = std::min(std::acos(std::clamp(glm::dot(wC, wU), -1.0, 1.0)), cap);
    double aV = std::min(std::acos(std::clamp(glm::dot(wC, wV), -1.0, 1.0)), cap);
    return kPi * std::tan(aU) * std::tan(aV);
}

double pixelsPerSample(double area, int faceTexels, int numSamples, glm::dvec3 wiWorld, double wiDotH) {
    glm::dvec3 a = glm::abs(wiWorld);
    double inf = std::max({a.x, a.y, a.z});
    double cubeDistortion = glm::length(wiWorld) / inf;   // distance to the unit cube along wi
    return area * faceTexels / (4.0 * numSamples) * cubeDistortion / std::max(wiDotH, 1e-4);
}

double mipLevelForSample(double pixels, double bias) {
    return std::max(0.0, 0.5 * std::log2(std::max(pixels, 1e-12)) + bias);
}

}  // namespace glimmer::ibl
