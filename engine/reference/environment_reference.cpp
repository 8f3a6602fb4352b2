#include "reference/environment_reference.h"

#include <algorithm>
#include <cmath>

namespace glimmer::envref {

static constexpr double kPi = 3.14159265358979323846;

glm::vec2 directionToEquirect(glm::vec3 d) {
    float phi = std::atan2(d.x, -d.z);
    float theta = std::acos(std::clamp(d.y, -1.0f, 1.0f));
    return {phi / float(2.0 * kPi) + 0.5f, theta / float(kPi)};
}

glm::vec3 equirectToDirection(glm::vec2 uv) {
    float phi = (uv.x - 0.5f) * float(2.0 * kPi), theta = uv.y * float(kPi);
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

glm::vec3 sampleEquirect(const ImageF& image, glm::vec3 direction) {
    glm::vec2 uv = directionToEquirect(direction);
    float fx = uv.x * image.width - 0.5f, fy = uv.y * image.height - 0.5f;
    int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    float tx = fx - x0, ty = fy - y0;
    auto texel = [&](int x, int y) {
        x = ((x % image.width) + image.width) % image.width;
        y = std::clamp(y, 0, image.height - 1);
        return glm::vec3(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
    };
    glm::vec3 top = glm::mix(texel(x0, y0), texel(x0 + 1, y0), tx);
    glm::vec3 bottom = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), tx);
    return glm::mix(top, bottom, ty);
}

glm::vec3 sampleCube(const CubeImage& cube, glm::vec3 d) {
    glm::vec3 a = glm::abs(d);
    int face;
    float sc, tc, ma;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x > 0 ? 0 : 1; ma = a.x; sc = d.x > 0 ? -d.z : d.z; tc = -d.y;
    } else if (a.y >= a.z) {
        face = d.y > 0 ? 2 : 3; ma = a.y; sc = d.x; tc = d.y > 0 ? d.z : -d.z;
    } else {
        face = d.z > 0 ? 4 : 5; ma = a.z; sc = d.z > 0 ? d.x : -d.x; tc = -d.y;
    }
    float fx = (0.5f * (sc / ma + 1.0f)) * cube.size - 0.5f, fy = (0.5f * (tc / ma + 1.0f)) * cube.size - 0.5f;
    fx = std::clamp(fx, 0.0f, float(cube.size - 1));
    fy = std::clamp(fy, 0.0f, float(cube.size - 1));
    int x0 = std::min(int(fx), cube.size - 2), y0 = std::min(int(fy), cube.size - 2);
    float tx = fx - x0, ty = fy - y0;
    return glm::mix(glm::mix(cube.texel(face, x0, y0), cube.texel(face, x0 + 1, y0), tx),
                    glm::mix(cube.texel(face, x0, y0 + 1), cube.texel(face, x0 + 1, y0 + 1), tx), ty);
}

glm::vec3 worldToEnvironment(glm::vec3 d, float rotationDegrees) {
    // The map turns by +rotation about +y, so a world direction looks up the map at the inverse rotation.
    double a = double(rotationDegrees) * kPi / 180.0, c = std::cos(a), s = std::sin(a);
    return {float(c * d.x - s * d.z), d.y, float(s * d.x + c * d.z)};
}

double ndfD(double cosH, double alpha, int ndf) {
    if (cosH <= 0.0) return 0.0;
    double a2 = alpha * alpha, cos2 = cosH * cosH;
    if (ndf == kNdfBeckmann) return std::exp(-(1.0 - cos2) / cos2 / a2) / (kPi * a2 * cos2 * cos2);
    double d = cos2 * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

double smithG1(double cosW, double alpha, int ndf) {
    if (cosW <= 0.0) return 0.0;
    double tan2 = std::max(1.0 - cosW * cosW, 0.0) / (cosW * cosW);
    if (ndf == kNdfBeckmann) {
        double tanTheta = std::sqrt(tan2);
        if (tanTheta <= 0.0) return 1.0;
        double a = 1.0 / (alpha * tanTheta);
        if (a >= 1.6) return 1.0;
        return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
    }
    return 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
}

double schlickWeight(double cosTheta) {
    double m = std::clamp(1.0 - cosTheta, 0.0, 1.0);
    return m * m * m * m * m;
}

glm::dvec2 splitSumReference(double nDotV, double alpha, int ndf) {
    // Integrate over half vectors: dl = 4 (v.h) dh, so f cos dl = D G F (v.h) / (n.v) dh. theta_h = (pi/2) s^3
    // on a uniform s grid puts most nodes near the normal, where the lobe of a small alpha lives.
    const int thetaSteps = 3000, phiSteps = 96;
    glm::dvec3 v(std::sqrt(std::max(1.0 - nDotV * nDotV, 0.0)), 0.0, nDotV);
    glm::dvec2 sum(0.0);
    for (int i = 0; i < thetaSteps; ++i) {
        double s = (i + 0.5) / thetaSteps;
        double theta = 0.5 * kPi * s * s * s, dTheta = 1.5 * kPi * s * s / thetaSteps;
        double cosT = std::cos(theta), sinT = std::sin(theta);
        double d = ndfD(cosT, alpha, ndf);
        if (d <= 0.0) continue;
        for (int j = 0; j < phiSteps; ++j) {
            // v lies in the xz plane, so the integrand is even in phi: integrate [0, pi] and double.
            double phi = kPi * (j + 0.5) / phiSteps, dPhi = kPi / phiSteps;
            glm::dvec3 h(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
            double vDotH = glm::dot(v, h);
            if (vDotH <= 0.0) continue;
            glm::dvec3 l = 2.0 * vDotH * h - v;
            if (l.z <= 0.0) continue;
            double g = smithG1(l.z, alpha, ndf) * smithG1(nDotV, alpha, ndf);
            double w = 2.0 * d * g * vDotH / nDotV * sinT * dTheta * dPhi;
            double fc = schlickWeight(vDotH);
            sum += glm::dvec2((1.0 - fc) * w, fc * w);
        }
    }
    return sum;
}

template <class Visit> static void forEachTexel(const CubeImage& cube, Visit visit) {
    for (int face = 0; face < 6; ++face)
        for (int y = 0; y < cube.size; ++y)
            for (int x = 0; x < cube.size; ++x)
                visit(glm::dvec3(cubeTexelDirection(face, x, y, cube.size)), glm::dvec3(cube.texel(face, x, y)),
                      cubeTexelSolidAngle(x, y, cube.size));
}

glm::dvec3 prefilteredRadianceReference(const CubeImage& cube, glm::vec3 r, double alpha, int ndf) {
    glm::dvec3 n = glm::normalize(glm::dvec3(r)), sum(0.0);
    double weight = 0.0;
    forEachTexel(cube, [&](glm::dvec3 l, glm::dvec3 radiance, double solidAngle) {
        double nDotL = glm::dot(n, l);
        if (nDotL <= 0.0) return;
        double w = ndfD(glm::dot(n, glm::normalize(l + n)), alpha, ndf) * nDotL * solidAngle;
        sum += w * radiance;
        weight += w;
    });
    return weight > 0.0 ? sum / weight : glm::dvec3(0.0);
}

glm::dvec3 specularIntegralReference(const CubeImage& cube, glm::vec3 nIn, glm::vec3 vIn, double alpha, int ndf,
                                     glm::vec3 f0) {
    glm::dvec3 n = glm::normalize(glm::dvec3(nIn)), v = glm::normalize(glm::dvec3(vIn)), sum(0.0);
    double nDotV = glm::dot(n, v);
    if (nDotV <= 0.0) return sum;
    forEachTexel(cube, [&](glm::dvec3 l, glm::dvec3 radiance, double solidAngle) {
        double nDotL = glm::dot(n, l);
        if (nDotL <= 0.0) return;
        glm::dvec3 h = glm::normalize(l + v);
        double g = smithG1(nDotL, alpha, ndf) * smithG1(nDotV, alpha, ndf);
        double fc = schlickWeight(std::max(glm::dot(v, h), 0.0));
        glm::dvec3 f = glm::dvec3(f0) + (1.0 - glm::dvec3(f0)) * fc;
        double dgOver4 = ndfD(glm::dot(n, h), alpha, ndf) * g / (4.0 * nDotL * nDotV);
        sum += radiance * f * (dgOver4 * nDotL * solidAngle);
    });
    return sum;
}

glm::dvec3 diffuseReference(const CubeImage& cube, glm::vec3 nIn) {
    glm::dvec3 n = glm::normalize(glm::dvec3(nIn)), sum(0.0);
    forEachTexel(cube, [&](glm::dvec3 l, glm::dvec3 radiance, double solidAngle) {
        sum += radiance * (std::max(glm::dot(n, l), 0.0) * solidAngle);
    });
    return sum / kPi;
}

}  // namespace glimmer::envref
