// CPU reference of the lighting pass's BRDF (shaders/common/brdf.glsl, shaders/frame/lighting.frag), in double
// precision, for tests that compare renders with straightforward evaluations of the same formulas.
#pragma once
#include <glm/glm.hpp>

namespace glimmer::reference {

double ggxD(const glm::dvec3& h, double alpha);
double beckmannD(const glm::dvec3& h, double alpha);
double ggxG1(const glm::dvec3& w, double alpha);
double beckmannG1(const glm::dvec3& w, double alpha);
glm::dvec3 schlickFresnel(const glm::dvec3& f0, double cosTheta);

struct SurfacePoint {
    glm::dvec3 baseColor;
    double metallic = 0.0;
    double alpha = 0.3;
    bool beckmann = false;
};

// Outgoing radiance towards `wo` from a directional light of irradiance `irradiance` arriving from `wi`
// (shading frame, z = normal) plus the constant ambient term `ambient * diffuse albedo`, as lighting.frag does.
glm::dvec3 shadeDirectional(const SurfacePoint& surface, const glm::dvec3& wi, const glm::dvec3& wo,
                            const glm::dvec3& irradiance, const glm::dvec3& ambient);

}  // namespace glimmer::reference
