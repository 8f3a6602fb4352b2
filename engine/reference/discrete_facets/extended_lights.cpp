#include "reference/discrete_facets/extended_lights.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace glimmer::facets {

namespace {
constexpr double kPi = 3.14159265358979323846;

double unit(uint64_t bits) { return (double(bits >> 11) + 0.5) * (1.0 / 9007199254740992.0); }

// Two unit vectors orthogonal to unit `a` and to each other.
void basisAround(const glm::dvec3& a, glm::dvec3& x, glm::dvec3& y) {
    glm::dvec3 helper = std::abs(a.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    x = glm::normalize(glm::cross(helper, a));
    y = glm::cross(a, x);
}

// A stratified direction in the cone of unit axis a (basis x, y) and cos of the half-angle cosMax: cell (i, j) of
// a side x side grid in (cos theta, azimuth), each uniform in solid angle.
glm::dvec3 coneDirection(const glm::dvec3& a, const glm::dvec3& x, const glm::dvec3& y, double cosMax, int i, int j,
                         int side, uint64_t bits) {
    const double cosTheta = 1.0 - (double(i) + unit(bits)) / double(side) * (1.0 - cosMax);
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    const double psi = 2.0 * kPi * (double(j) + unit(bits * 0x9e3779b97f4a7c15ull + 0x632be59bd9b4e019ull)) / double(side);
    return cosTheta * a + sinTheta * (std::cos(psi) * x + std::sin(psi) * y);
}

int gridSide(int samples) { return std::max(1, int(std::sqrt(double(std::max(samples, 1))))); }
}  // namespace

LightShape lightShape(const Light& light) {
    LightShape s;
    s.centre = glm::dvec3(light.vector);
    switch (light.type) {
        case LightType::Directional:
            if (!(light.angularDiameter > 0.0f)) return s;
            s.kind = LightShape::Cone;
            s.direction = glm::normalize(glm::dvec3(light.vector));
            s.cosHalfAngle = std::cos(0.5 * double(light.angularDiameter));
            return s;
        case LightType::Point:
        case LightType::Spot:
        case LightType::Sphere:
            if (!(light.radius > 0.0f)) return s;
            s.kind = LightShape::Sphere;
            s.radius = light.radius;
            return s;
        case LightType::Rect:
        case LightType::Disk: {
            s.kind = light.type == LightType::Rect ? LightShape::Rect : LightShape::Disk;
            // The axes of render/gpu_scene.cpp: right orthogonalized against the normal, up = normal x right.
            s.direction = glm::normalize(glm::dvec3(light.spotDirection));
            glm::dvec3 right(light.right);
            s.right = glm::normalize(right - s.direction * glm::dot(s.direction, right));
            s.up = glm::cross(s.direction, s.right);
            s.halfWidth = 0.5 * double(light.width);
            s.halfHeight = 0.5 * double(light.height);
            s.radius = light.radius;
            s.twoSided = light.twoSided;
            if (s.kind == LightShape::Rect ? !(s.halfWidth > 0.0 && s.halfHeight > 0.0) : !(s.radius > 0.0))
                s.kind = LightShape::None;
            return s;
        }
    }
    return s;
}

bool LightShape::hits(const glm::dvec3& position, const glm::dvec3& ray) const {
    switch (kind) {
        case None: return false;
        case Cone: return glm::dot(ray, direction) >= cosHalfAngle;
        case Sphere: {
            const glm::dvec3 oc = centre - position;
            const double along = glm::dot(oc, ray), distance2 = glm::dot(oc, oc);
            if (distance2 <= radius * radius) return true;   // inside: every direction
            return along > 0.0 && distance2 - along * along <= radius * radius;
        }
        case Rect:
        case Disk: {
            const double denominator = glm::dot(ray, direction);
            // One-sided lights emit towards `direction`: the ray must arrive at their front.
            if (twoSided ? denominator == 0.0 : denominator >= 0.0) return false;
            const double t = glm::dot(centre - position, direction) / denominator;
            if (!(t > 0.0)) return false;
            const glm::dvec3 q = position + t * ray - centre;
            if (kind == Disk) return glm::dot(q, q) <= radius * radius;
            return std::abs(glm::dot(q, right)) <= halfWidth && std::abs(glm::dot(q, up)) <= halfHeight;
        }
    }
    return false;
}

void LightShape::boundingCone(const glm::dvec3& position, glm::dvec3& axis, double& halfAngle) const {
    if (kind == Cone) {
        axis = direction;
        halfAngle = std::acos(std::clamp(cosHalfAngle, -1.0, 1.0));
        return;
    }
    // The sphere that holds the shape: the sphere itself, the rect's circumscribed one, the disk's.
    const double bound = kind == Rect ? std::sqrt(halfWidth * halfWidth + halfHeight * halfHeight) : radius;
    const glm::dvec3 d = centre - position;
    const double distance = glm::length(d);
    axis = distance > 0.0 ? d / distance : glm::dvec3(0.0, 0.0, 1.0);
    halfAngle = distance > bound ? std::asin(bound / distance) : kPi;
}

ExtendedEstimate estimateOverLight(const FacetEstimator& estimator, const PixelFootprint& footprint,
                                   const glm::dvec3& position, const glm::dvec3& n, const glm::dvec3& t,
                                   const glm::dvec3& b, const glm::dvec3& v, const LightShape& light,
                                   const ExtendedLightOptions& options, uint64_t seed) {
    ExtendedEstimate result;
    if (light.kind == LightShape::None) return result;
    auto toShading = [&](const glm::dvec3& w) { return glm::dvec3(glm::dot(w, t), glm::dot(w, b), glm::dot(w, n)); };
    auto toWorld = [&](const glm::dvec3& w) { return w.x * t + w.y * b + w.z * n; };
    const glm::dvec3 vs = toShading(v);
    if (vs.z <= 0.0) return result;

    // M and lambda: stratified directions over the cone that bounds the light.
    glm::dvec3 axis;
    double halfAngle;
    light.boundingCone(position, axis, halfAngle);
    glm::dvec3 ax, ay;
    basisAround(axis, ax, ay);
    const double cosMax = std::cos(std::min(halfAngle, kPi));
    const double coneSolidAngle = 2.0 * kPi * (1.0 - cosMax);
    // Calls visit(l in the shading frame) for each of side x side stratified directions of the cone that hit the
    // light above the horizon.
    auto forEachLightDirection = [&](int side, uint64_t bits, auto&& visit) {
        for (int i = 0; i < side; ++i)
            for (int j = 0; j < side; ++j) {
                bits = FacetRealization::mix(bits);
                const glm::dvec3 l = coneDirection(axis, ax, ay, cosMax, i, j, side, bits);
                if (!light.hits(position, l)) continue;
                const glm::dvec3 ls = toShading(l);
                if (ls.z > 0.0) visit(ls);
            }
    };
    const int lightSide = gridSide(options.lightSamples);
    double expected = 0.0, facetsSeeing = 0.0;
    forEachLightDirection(lightSide, FacetRealization::mix(seed ^ 0x3c6ef372fe94f82bull), [&](const glm::dvec3& ls) {
        const glm::dvec3 h = glm::normalize(ls + vs);
        const double d = estimator.smoothD(h);
        expected += d;
        facetsSeeing += d * h.z / (4.0 * glm::dot(vs, h));
    });
    const double perSample = coneSolidAngle / double(lightSide * lightSide);
    result.expected = expected * perSample;
    const FacetMaterial& material = estimator.material();
    const double rho = material.densityPerUv;
    result.lambda = rho * FacetEstimator::footprintArea(footprint) * facetsSeeing * perSample;
    if (!(result.expected > 0.0) || !(rho > 0.0)) return result;

    // The half vectors of the light lie within `spread` of hCentre: |(v + l) - (v + l_c)| <= the chord
    // 2 sin(halfAngle / 2), and vectors within distance r of a vector of length L make an angle <= asin(r / L).
    const glm::dvec3 axisShading = toShading(axis);
    const glm::dvec3 sum = vs + axisShading;
    const double sumLength = glm::length(sum), chord = 2.0 * std::sin(0.5 * std::min(halfAngle, kPi));
    const glm::dvec3 hCentre = sumLength > 0.0 ? sum / sumLength : glm::dvec3(0.0, 0.0, 1.0);
    const double spread = chord < sumLength ? std::asin(chord / sumLength) : kPi;

    const double reach = estimator.realization().lobeRadius(), cosReach = std::cos(reach);
    const double capSolidAngle = 2.0 * kPi * (1.0 - cosReach);
    const int facetSide = gridSide(options.facetSamples);
    // A light smaller than the directions one facet reflects (4 (v.h) times its lobe's solid angle, the mirror's
    // Jacobian) is sampled over the light instead: N = int over the light of D_est(h(l)) dl with D_est counted
    // exactly at each of the stratified directions (facet_estimator.h estimate). Sampling a facet's lobe would
    // rarely meet so small a light (the sun: 2 % of a gamma = 0.015 lobe's directions).
    const double reflectedSolidAngle = 4.0 * std::max(glm::dot(vs, hCentre), 0.0) * capSolidAngle;
    if (coneSolidAngle <= reflectedSolidAngle) {
        glm::dvec3 reflected(0.0);
        long tested = 0;
        forEachLightDirection(facetSide, FacetRealization::mix(seed ^ 0x7f4a7c159e3779b9ull), [&](const glm::dvec3& ls) {
            const FacetEstimate e = estimator.estimate(footprint, glm::normalize(ls + vs));
            reflected += e.d;
            tested += e.facetsTested;
        });
        result.factor = reflected * (coneSolidAngle / double(facetSide * facetSide)) / result.expected;
        result.facetsTested = tested;
        return result;
    }

    const FacetEstimator::FootprintTest area = estimator.footprintTest(footprint);
    if (!area.valid) return result;
    FacetRegion region = estimator.realization().lobeRegion(hCentre, spread);
    region.uvMin = area.lo;
    region.uvMax = area.hi;
    const double perFacetSample = capSolidAngle / double(facetSide * facetSide);
    const double cosSpread = std::cos(std::min(spread + reach, kPi));
    glm::dvec3 reflected(0.0);
    long tested = 0;
    estimator.realization().forEach(region, [&](const Facet& f) {
        ++tested;
        const double w = area.weight(f.uv);
        if (w <= 0.0) return;
        if (glm::dot(f.m, hCentre) < cosSpread) return;   // its lobe meets no half vector of the light
        glm::dvec3 fx, fy;
        basisAround(f.m, fx, fy);
        // Per facet from its position, so a facet's samples do not depend on which pixel or query visits it first.
        uint64_t s = FacetRealization::mix(seed ^ std::bit_cast<uint64_t>(f.uv.x) ^
                                           (std::bit_cast<uint64_t>(f.uv.y) * 0xd1342543de82ef95ull));
        double sumFacet = 0.0;
        for (int i = 0; i < facetSide; ++i)
            for (int j = 0; j < facetSide; ++j) {
                s = FacetRealization::mix(s);
                const glm::dvec3 h = coneDirection(f.m, fx, fy, cosReach, i, j, facetSide, s);
                if (h.z <= 0.0) continue;
                const double vh = glm::dot(vs, h);
                if (vh <= 0.0) continue;
                const glm::dvec3 l = 2.0 * vh * h - vs;
                if (l.z <= 0.0) continue;
                const double kernel = estimator.lobeWeight(f.m, h);
                if (kernel <= 0.0) continue;
                if (!light.hits(position, glm::normalize(toWorld(l)))) continue;
                const double ratio = estimator.lobeRatio(h);   // P(h) / (D(h) h.z)
                if (!(ratio > 0.0)) continue;
                sumFacet += kernel / (ratio * h.z) * 4.0 * vh;
            }
        reflected += (sumFacet * perFacetSample * w / rho) * f.color;
    });
    result.factor = reflected / result.expected;
    result.facetsTested = tested;
    return result;
}

}  // namespace glimmer::facets
