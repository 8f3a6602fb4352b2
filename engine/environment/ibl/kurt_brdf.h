// The Kurt et al. 2010 BRDF as used by "Real-time Rendering of Glossy Materials with Regular Sampling" (CGI 2014),
// Sec. 4: Lambertian kd/pi plus a sum of glossy lobes, each lobe F D / (4 (o.h) ((i.n)(o.n))^alpha) with Schlick
// Fresnel (r0) and an anisotropic normalised Beckmann D (mx, my). Also its importance sampling (Eq. 6-7) and pdf
// (Eq. 10), used by the FIS baseline and the reference. CPU reference for shaders/environment/ibl/kurt_brdf.glsl.
// Vectors live in the shading frame: x = tangent t, y = bitangent b, z = normal n (Fig. 3).
#pragma once
#include <glm/glm.hpp>

#include <vector>

namespace glimmer::ibl {

struct KurtLobe {
    double ks = 1.0;      // lobe weight k_s,n (Eq. 1)
    double r0 = 1.0;      // Schlick reflectance at normal incidence (Eq. 3)
    double mx = 0.1;      // Beckmann roughness along t (Eq. 5)
    double my = 0.1;      // Beckmann roughness along b
    double alpha = 0.0;   // shadowing/masking exponent in [0, 1] (Eq. 2)
};

struct KurtMaterial {
    double kd = 0.0;                 // diffuse reflectivity (Eq. 1)
    std::vector<KurtLobe> lobes;     // the "selectable (small) number of glossy lobes"
};

// Eq. 5: q(h) = exp(-tan^2(theta_h) (cos^2(phi_h)/mx^2 + sin^2(phi_h)/my^2)); 0 for h below the surface.
double kurtQ(glm::dvec3 h, double mx, double my);
// Eq. 4: D(h) = q(h) / (pi mx my cos^4(theta_h)).
double kurtD(glm::dvec3 h, double mx, double my);
// Eq. 3: F(u) = r0 + (1 - r0)(1 - u)^5.
double schlickFresnel(double u, double r0);
// Eq. 2 for one lobe (0 when wi or wo is below the surface).
double kurtLobe(glm::dvec3 wi, glm::dvec3 wo, const KurtLobe& lobe);
// Eq. 1.
double kurtBrdf(glm::dvec3 wi, glm::dvec3 wo, const KurtMaterial& material);

// Eq. 6-7: half vector for uniform xi1, xi2 in (0, 1]. Eq. 6's arctan is taken in the quadrant of 2 pi xi2
// (atan2), otherwise phi_h would only cover (-pi/2, pi/2).
glm::dvec3 sampleKurtHalfVector(double xi1, double xi2, double mx, double my);
// Density of sampleKurtHalfVector over half-vector solid angle: q / (pi mx my cos^3 theta_h) = D cos theta_h.
double kurtHalfVectorPdf(glm::dvec3 h, double mx, double my);
// Eq. 10: density of wi = reflect(-wo, h) over incident solid angle: q / (4 pi mx my cos^3(theta_h) (wo.h)).
double kurtPdf(glm::dvec3 wi, glm::dvec3 wo, double mx, double my);

// Half vector of wi, wo (unit).
glm::dvec3 halfVector(glm::dvec3 wi, glm::dvec3 wo);
// Mirror of wo about h: the incident direction whose half vector with wo is h.
glm::dvec3 reflectAbout(glm::dvec3 wo, glm::dvec3 h);

}  // namespace glimmer::ibl
