#include "reference/area_light_reference.h"

#include <algorithm>
#include <cmath>

#include "render/lights/ltc_tables.h"

namespace glimmer::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Eigen-decomposition of a symmetric 3 x 3 matrix by cyclic Jacobi rotations: values[i] with vectors column i.
void symmetricEigen(glm::dmat3 a, glm::dvec3& values, glm::dmat3& vectors) {
    vectors = glm::dmat3(1.0);
    for (int sweep = 0; sweep < 50; ++sweep) {
        double off = a[1][0] * a[1][0] + a[2][0] * a[2][0] + a[2][1] * a[2][1];
        if (off < 1e-30 * (a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2] + 1e-300)) break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                if (std::abs(a[q][p]) < 1e-300) continue;
                double theta = (a[q][q] - a[p][p]) / (2.0 * a[q][p]);
                double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                glm::dmat3 rotation(1.0);
                rotation[p][p] = c, rotation[q][q] = c, rotation[q][p] = s, rotation[p][q] = -s;
                a = glm::transpose(rotation) * a * rotation;
                vectors = vectors * rotation;
            }
    }
    values = {a[0][0], a[1][1], a[2][2]};
}

glm::dmat3 invFromEntry(const float* e) {
    glm::dmat3 m(0.0);
    m[0][0] = e[0];   // a (row 0, column 0)
    m[2][0] = e[1];   // b (row 0, column 2)
    m[1][1] = 1.0;
    m[0][2] = e[2];   // c (row 2, column 0)
    m[2][2] = e[3];   // d
    return m;
}

// Bilinear read of `layer` at table coordinates x (column) and y (row) in [0, 1], texel centres at the ends.
glm::dvec4 bilinear(int layer, double x, double y) {
    const int n = ltc::kTableSize;
    double fx = std::clamp(x, 0.0, 1.0) * (n - 1), fy = std::clamp(y, 0.0, 1.0) * (n - 1);
    int x0 = std::min(int(fx), n - 2), y0 = std::min(int(fy), n - 2);
    double tx = fx - x0, ty = fy - y0;
    glm::dvec4 result(0.0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const float* e = ltc::tableEntry(layer, y0 + j, x0 + i);
            double w = (i ? tx : 1.0 - tx) * (j ? ty : 1.0 - ty);
            result += w * glm::dvec4(e[0], e[1], e[2], e[3]);
        }
    return result;
}

glm::dvec3 anyPerpendicular(const glm::dvec3& d) {
    glm::dvec3 a = std::abs(d.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    return glm::normalize(glm::cross(d, a));
}

}  // namespace

double polygonCosineIntegral(std::vector<glm::dvec3> vertices) {
    // Clip to z >= 0 (Sutherland-Hodgman against one plane).
    std::vector<glm::dvec3> clipped;
    for (size_t i = 0; i < vertices.size(); ++i) {
        const glm::dvec3& a = vertices[i];
        const glm::dvec3& b = vertices[(i + 1) % vertices.size()];
        if (a.z >= 0.0) clipped.push_back(a);
        if ((a.z >= 0.0) != (b.z >= 0.0)) clipped.push_back(a + (a.z / (a.z - b.z)) * (b - a));
    }
    if (clipped.size() < 3) return 0.0;
    double sum = 0.0;
    for (size_t i = 0; i < clipped.size(); ++i) {
        glm::dvec3 a = glm::normalize(clipped[i]), b = glm::normalize(clipped[(i + 1) % clipped.size()]);
        double x = std::clamp(glm::dot(a, b), -1.0, 1.0);
        double s = std::sqrt(std::max(1.0 - x * x, 0.0));
        double thetaOverSin = s > 1e-12 ? std::acos(x) / s : 1.0;
        sum += thetaOverSin * glm::cross(a, b).z;
    }
    return std::abs(sum) / (2.0 * kPi);
}

double capCosineIntegral(double sinSigma2, double cosElevation) {
    double s = std::clamp(sinSigma2, 0.0, 1.0), c = std::clamp(cosElevation, -1.0, 1.0);
    if (s <= 0.0) return 0.0;
    if (c * c >= s) return c > 0.0 ? s * c : 0.0;   // wholly above (or below) the horizon
    double sinElevation = std::sqrt(std::max(1.0 - c * c, 0.0));
    double x = std::sqrt(std::max(1.0 / s - 1.0, 0.0));   // cot(sigma)
    double y = sinElevation > 0.0 ? std::clamp(-x * c / sinElevation, -1.0, 1.0) : 0.0;
    double w = sinElevation * std::sqrt(std::max(1.0 - y * y, 0.0));
    double result = (c * std::acos(y) - x * w) * s + (x > 0.0 ? std::atan(w / x) : 0.5 * kPi);
    return std::max(result / kPi, 0.0);
}

bool ellipseFormFactor(const glm::dvec3& C, const glm::dvec3& U, const glm::dvec3& V, double& formFactor,
                       glm::dvec3& axis) {
    glm::dmat3 basis(U, V, C);
    double det = glm::determinant(basis);
    double scale = glm::length(U) * glm::length(V) * glm::length(C);
    if (!(std::abs(det) > 1e-9 * scale)) return false;   // seen edge-on: the cone is flat
    glm::dmat3 inv = glm::inverse(basis);
    // The cone through the ellipse: points x with y = B^-1 x satisfying y.x^2 + y.y^2 <= y.z^2.
    glm::dmat3 Q = glm::transpose(inv) * glm::dmat3(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -1.0) * inv;
    glm::dvec3 values;
    glm::dmat3 vectors;
    symmetricEigen(Q, values, vectors);
    int negative = 0;
    for (int i = 1; i < 3; ++i)
        if (values[i] < values[negative]) negative = i;
    double l3 = values[negative], l1 = values[(negative + 1) % 3], l2 = values[(negative + 2) % 3];
    if (!(l3 < 0.0 && l1 > 0.0 && l2 > 0.0)) return false;
    // Cross-section at unit distance along the axis: an ellipse of semi-axes sqrt(-l3 / l1), sqrt(-l3 / l2); its
    // cone's form factor is L1 L2 / sqrt((1 + L1^2)(1 + L2^2)).
    formFactor = -l3 / std::sqrt((l1 - l3) * (l2 - l3));
    axis = glm::normalize(vectors[negative]);
    if (glm::dot(axis, C) < 0.0) axis = -axis;
    return true;
}

double ellipseCosineIntegral(const glm::dvec3& C, const glm::dvec3& U, const glm::dvec3& V) {
    double formFactor;
    glm::dvec3 axis;
    if (!ellipseFormFactor(C, U, V, formFactor, axis)) return 0.0;
    return capCosineIntegral(formFactor, axis.z);
}

glm::dmat3 ltcFrame(const glm::dvec3& n, const glm::dvec3& toEye) {
    glm::dvec3 t1 = toEye - n * glm::dot(n, toEye);
    t1 = glm::length(t1) > 1e-9 ? glm::normalize(t1) : anyPerpendicular(n);
    glm::dvec3 t2 = glm::cross(n, t1);
    return glm::transpose(glm::dmat3(t1, t2, n));   // rows t1, t2, n
}

double ltcIntegral(const AreaLightGeometry& light, const glm::dvec3& position, const glm::dmat3& frame,
                   const glm::dmat3& invM) {
    const glm::dmat3 toLtc = invM * frame;
    const glm::dvec3 c = light.centre - position;
    if (light.shape != AreaShape::Sphere && !light.twoSided && glm::dot(-c, glm::cross(light.halfU, light.halfV)) <= 0.0)
        return 0.0;
    if (light.shape == AreaShape::Rect) {
        return polygonCosineIntegral({toLtc * (c - light.halfU - light.halfV), toLtc * (c + light.halfU - light.halfV),
                                      toLtc * (c + light.halfU + light.halfV), toLtc * (c - light.halfU + light.halfV)});
    }
    glm::dvec3 U = light.halfU, V = light.halfV;
    if (light.shape == AreaShape::Sphere) {
        // The sphere's cone of directions is the cone through the disk facing the point at its centre's distance,
        // of radius d tan(sigma) (sin(sigma) = r / d; clamped just inside the sphere).
        double d = glm::length(c);
        double sinSigma = std::min(light.radius / std::max(d, 1e-12), 0.9995);
        double r = d * sinSigma / std::sqrt(1.0 - sinSigma * sinSigma);
        glm::dvec3 dir = c / std::max(d, 1e-12);
        U = r * anyPerpendicular(dir);
        V = r * glm::cross(dir, glm::normalize(U));
    }
    return ellipseCosineIntegral(toLtc * c, toLtc * U, toLtc * V);
}

LtcLookup ltcLookup(double alpha, double cosTheta, bool beckmann) {
    double x = std::sqrt(1.0 - std::clamp(cosTheta, 0.0, 1.0));
    double y = std::sqrt(std::clamp(alpha, 0.0, 1.0));
    int ndf = beckmann ? 1 : 0;
    glm::dvec4 spec = bilinear(ltc::kSpecularLayer + ndf, x, y);
    glm::dvec4 only = bilinear(ltc::kNdfOnlyLayer + ndf, x, y);
    glm::dvec4 mag = bilinear(ltc::kMagnitudeLayer + ndf, x, y);
    float s[4] = {float(spec.x), float(spec.y), float(spec.z), float(spec.w)};
    float o[4] = {float(only.x), float(only.y), float(only.z), float(only.w)};
    LtcLookup result;
    result.invSpecular = invFromEntry(s);
    result.invNdfOnly = invFromEntry(o);
    result.A = mag.x;
    result.B = mag.y;
    result.ndfOnlyIntegral = mag.z;
    return result;
}

double integrateOverLight(const AreaLightGeometry& light, const glm::dvec3& position,
                          const std::function<double(const glm::dvec3&)>& f, int n) {
    double sum = 0.0;
    if (light.shape == AreaShape::Sphere) {
        glm::dvec3 c = light.centre - position;
        double d = glm::length(c);
        if (d <= light.radius) return 0.0;
        double cosSigma = std::sqrt(1.0 - (light.radius / d) * (light.radius / d));
        glm::dvec3 w = c / d, u = anyPerpendicular(w), v = glm::cross(w, u);
        double solidAngle = 2.0 * kPi * (1.0 - cosSigma);
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                double cosTheta = 1.0 - (double(i) + 0.5) / n * (1.0 - cosSigma);
                double sinTheta = std::sqrt(std::max(1.0 - cosTheta * cosTheta, 0.0));
                double phi = 2.0 * kPi * (double(j) + 0.5) / n;
                sum += f(cosTheta * w + sinTheta * (std::cos(phi) * u + std::sin(phi) * v));
            }
        return sum * solidAngle / (double(n) * n);
    }
    glm::dvec3 normal = glm::cross(light.halfU, light.halfV);
    double area = light.shape == AreaShape::Rect ? 4.0 * glm::length(normal) : kPi * glm::length(normal);
    normal = glm::normalize(normal);
    if (!light.twoSided && glm::dot(position - light.centre, normal) <= 0.0) return 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            double s = (double(i) + 0.5) / n, t = (double(j) + 0.5) / n;
            glm::dvec3 x;
            if (light.shape == AreaShape::Rect) {
                x = light.centre + (2.0 * s - 1.0) * light.halfU + (2.0 * t - 1.0) * light.halfV;
            } else {
                double r = std::sqrt(s), phi = 2.0 * kPi * t;   // uniform in area
                x = light.centre + r * (std::cos(phi) * light.halfU + std::sin(phi) * light.halfV);
            }
            glm::dvec3 toLight = x - position;
            double distance2 = glm::dot(toLight, toLight);
            glm::dvec3 l = toLight / std::sqrt(distance2);
            double solidAngle = std::abs(glm::dot(l, normal)) / distance2;
            sum += f(l) * solidAngle;
        }
    return sum * area / (double(n) * n);
}

}  // namespace glimmer::reference
