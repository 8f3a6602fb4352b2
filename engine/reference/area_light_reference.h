// CPU reference of the area lights (shaders/lights/ltc.glsl, shaders/lights/area_light.glsl), in double precision:
// the LTC integrals of polygons, disks and spheres as the shaders compute them (same formulas, same table
// lookups), and brute-force quadrature of any lobe over a light's directions, which the tests judge both by.
#pragma once
#include <glm/glm.hpp>

#include <functional>
#include <vector>

namespace glimmer::reference {

enum class AreaShape { Rect, Disk, Sphere };

// A light in world space. Rect: the parallelogram centre +- halfU +- halfV; disk: centre + halfU cos t + halfV
// sin t (halfU, halfV orthogonal, equal length = radius); both emit on the side of cross(halfU, halfV) (both
// sides when twoSided). Sphere: centre and radius.
struct AreaLightGeometry {
    AreaShape shape = AreaShape::Rect;
    glm::dvec3 centre{0.0};
    glm::dvec3 halfU{1.0, 0.0, 0.0}, halfV{0.0, 1.0, 0.0};
    double radius = 0.0;
    bool twoSided = false;
};

// (1 / pi) x the integral of max(0, l.z) over the directions through a polygon (vertices relative to the shaded
// point, z up): clipped to the upper hemisphere, then Lambert's sum over its edges (Heitz et al. 2016, Eq. 11).
double polygonCosineIntegral(std::vector<glm::dvec3> vertices);
// (1 / pi) x the integral of max(0, l.z) over a spherical cap with sin^2(half-angle) = sinSigma2 whose axis has
// z = cosElevation: exact (the cap clipped by the horizon; Snyder 1996).
double capCosineIntegral(double sinSigma2, double cosElevation);
// The same over the elliptic cone through an ellipse (centre C, conjugate semi-axes U, V; relative to the point):
// its vector form factor from the cone's principal axes (exact), clipped by the horizon as the cap of the same
// form factor and axis (Heitz & Hill 2017, "Real-Time Line- and Disk-Light Shading"; exact when no part of it is
// below the horizon).
double ellipseCosineIntegral(const glm::dvec3& C, const glm::dvec3& U, const glm::dvec3& V);
// Form factor and axis of the elliptic cone (|axis| = 1, the nappe through C); false when degenerate.
bool ellipseFormFactor(const glm::dvec3& C, const glm::dvec3& U, const glm::dvec3& V, double& formFactor,
                       glm::dvec3& axis);

// The shading frame of the LTC tables: rows t1 (towards the view in the tangent plane), t2, n.
glm::dmat3 ltcFrame(const glm::dvec3& n, const glm::dvec3& toEye);
// Integral of the LTC with inverse matrix invM (shading frame) over the light seen from `position`: the light's
// shape mapped by invM x frame, then integrated against the clamped cosine. invM = identity gives the diffuse form
// factor. 0 when a one-sided light faces away.
double ltcIntegral(const AreaLightGeometry& light, const glm::dvec3& position, const glm::dmat3& frame,
                   const glm::dmat3& invM);

// The tables of engine/render/lights/ltc_tables.h read at (alpha, cos theta) with the GPU's bilinear filtering
// (texel centres at the ends, clamped).
struct LtcLookup {
    glm::dmat3 invSpecular{1.0}, invNdfOnly{1.0};
    double A = 0.0, B = 0.0;           // specular lobe: integral = f0 A + B
    double ndfOnlyIntegral = 0.0;      // integral of D(h) / (4 |v.h|) over the hemisphere of lights
};
LtcLookup ltcLookup(double alpha, double cosTheta, bool beckmann);

// Integral of f(l) over the directions from `position` that hit the light (world unit vectors), by stratified
// quadrature with n x n points over the light's area (rect, disk; front side) or its cone of directions (sphere).
double integrateOverLight(const AreaLightGeometry& light, const glm::dvec3& position,
                          const std::function<double(const glm::dvec3&)>& f, int n);

}  // namespace glimmer::reference
