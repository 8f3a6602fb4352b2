#include "glints/methods.h"

#include <algorithm>
#include <cmath>
#include <cctype>

#include "core/error.h"
#include "common/bindings.glsl"
#include "glints/chermain2020/resources.h"
#include "glints/deliot2023/deliot2023_resources.h"
#include "glints/wang2020/wang2020_post_pass.h"
#include "glints/wang2020/wang2020_resources.h"

namespace glimmer {

// The smooth reference: the analytic NDF, no glints. Every glint method must converge to it.
static GlintMethod smoothMethod() {
    return {"smooth", "Smooth (no glints)", "GLINT_METHOD_SMOOTH", "glints/smooth.glsl",
            "Cook & Torrance 1982; Walter et al. 2007 (GGX); Beckmann 1963", {}};
}

// The material mappings' factors on the facet count, measured against the discrete-facet reference (issue 36,
// docs/glint_statistics.md): deliot2023's log_density row and kemppinen2025's density row say why.
constexpr float kDeliotPhysicalDensityScale = 0.2f;
constexpr float kKemppinenPhysicalDensityScale = 0.1f;

// Deliot & Belcour 2023: shaders/glints/deliot2023/deliot2023.glsl; defaults and ranges from methods.md (public ports).
static GlintMethod deliot2023Method() {
    GlintMethod method{"deliot2023", "Deliot & Belcour 2023 (distributed binomial laws, anisotropic grids)",
            "GLINT_METHOD_DELIOT2023", "glints/deliot2023/deliot2023.glsl",
            "Deliot & Belcour 2023, Real-time rendering of glinty appearances using distributed binomial laws on "
            "anisotropic grids, Computer Graphics Forum 42(8)",
            {{"log_density", 16.0f, 0.0f, 50.0f, "natural log of the microfacet density per unit UV area"},
             {"microfacet_roughness", 0.005f, 1e-5f, 1.0f,
              "R, ratio of micro- to macro-roughness: lower = fewer, brighter glints (useful 0.005-0.25)", {}, false,
              true},
             {"density_randomization", 2.0f, 0.0f, 10.0f, "std. deviation of the per-vertex log density"},
             {"screen_space_scale", 1.5f, 0.1f, 10.0f, "grid cell size in pixels across the footprint's minor axis"},
             // Where the paper is vague or the authors' supplemental code differs from its text, the default is
             // the authors' code (it made the paper's figures); the other reading stays as a choice (docs/deliot2023.md).
             {"normalization", 0.0f, 0.0f, 1.0f,
              "vertex: each grid vertex's count over its own randomized facets (authors' code); footprint: the "
              "summed count over the footprint's total facets",
              {"vertex", "footprint"}},
             {"angular_grid", 0.0f, 0.0f, 1.0f,
              "Eq. 14 cell width: projected = R in units of the projected h (authors' code); lobe = sqrt(R / D(n))",
              {"projected", "lobe"}},
             {"gate", 0.0f, 0.0f, 1.0f,
              "Eq. 18 gate: soft = smooth step of half-width 0.1 sat(10 P1) sat(10 (1 - P1)) (authors' code); hard",
              {"soft", "hard"}},
             // Issue 36's residual against the authors' randomized counts (docs/deliot2023.md): their normal variate
             // is an inverse CDF (unbounded tails), and their NDF is clamped to 20 D(n); both kept as choices.
             {"density_normal", 0.0f, 0.0f, 1.0f,
              "normal variate of the density randomization: irwin_hall (4 uniforms, tails cut at 3.46 sigma) or "
              "exact (inverse CDF, Giles' erfinv, as the authors' code)",
              {"irwin_hall", "exact"}},
             {"max_ratio", 0.0f, 0.0f, 1000.0f,
              "clamp of D_P / D(n) (authors' code: 20, 'grazing angle extremities'); 0 = none"},
             // Kneiphof & Klein 2024 (glints under area lights; shaders/glints/deliot2023.glsl, docs/area_lights.md).
             {"probability", 0.0f, 0.0f, 1.0f,
              "facet success probability: kk24 = the facets whose mirror direction hits the light, from its solid "
              "angle or LTC integral over the total NDF (Kneiphof & Klein 2024); db23 = Eq. 4's R D(h) / D(n)",
              {"kk24", "db23"}},
             {"total_ndf", 0.0f, 0.0f, 1.0f,
              "kk24's denominator, the integral of D over the hemisphere: fit = 1 + alpha^1.4109 (their GGX fit; "
              "Beckmann always exact); exact", {"fit", "exact"}},
             {"light_integral", 0.0f, 0.0f, 1.0f,
              "kk24 under area lights: the NDF-only term times the specular LTC's integral (their default) or the "
              "dedicated NDF-only LTC's", {"specular_ltc", "ndf_ltc"}},
             {"facets", 0.0f, 0.0f, 1.0f,
              "kk24: cone = facets reflect within pi alpha^2 R steradians, widened by the light (ours; punctual "
              "lights keep their glints); mirror = the paper's mirror facets (a light without size shows none)",
              {"cone", "mirror"}}},
            createDeliot2023Resources};
    method.materialMapping = {
        {"log_density", GlintQuantity::Density, kDeliotPhysicalDensityScale, 1.0f, 0.0f, true,
         "Sec. 3: N(P) = facet density x area, its natural log per unit UV area, x 0.2: the 4 angular cells of "
         "Eq. 14 are lerped and the 12 grid vertices blended, which averages independent draws; a fifth of the "
         "facets restores the material's variance over 4x4 pixels (measured against the discrete-facet "
         "reference, docs/glint_statistics.md). With a density randomization set, the log-median keeps the mean "
         "count (minus sigma^2 / 2)",
         "density_randomization"},
        {"density_randomization", GlintQuantity::Density, 0.0f, 0.0f, 0.0f, false,
         "0: the authors' per-vertex log-normal count is a clumping device of their code, not a quantity of the "
         "material (issue 36); --set deliot2023.density_randomization=2 restores it"},
        {"angular_grid", GlintQuantity::Density, 1.0f, 0.0f, 0.0f, false,
         "lobe: Eq. 14's cell holds the fraction R of the lobe, sqrt(R / D(n)) = gamma sqrt(pi) wide, about the "
         "facets' own cone, so a glint lives as long in angle as the material's (plane90, gamma 0.015: the "
         "correlation halves after 7.5 degrees of light turn, the discrete-facet reference's after 5.0; the "
         "authors' projected cell, R wide, after 0.73); --set deliot2023.angular_grid=projected restores it"},
        {"gate", GlintQuantity::Density, 1.0f, 0.0f, 0.0f, false,
         "hard (Eq. 18 as printed): the authors' soft gate lights sparse pixels at partial counts, a smoothing "
         "device; the hard gate's dark fraction is the material's closer (docs/glint_statistics.md); --set "
         "deliot2023.gate=soft restores it"},
        {"microfacet_roughness", GlintQuantity::AngularSize, 1.0f, 2.0f, -2.0f, false,
         "Eq. 2-4: a facet reflects h with p = R D(h) / D(n); a cone of half-angle gamma holds p = pi gamma^2 D(h) "
         "(h.n), and D(n) = 1 / (pi alpha^2) (GGX, Beckmann), so R = (gamma / alpha)^2 at h = n"}};
    method.convergence = {{"log_density", 40.0f}};   // Sec. 3, Fig. 13: e^40 facets per unit UV area is the smooth NDF
    method.environmentGlints = true;   // Kneiphof & Klein 2025 (glintEnvironmentFactor)
    return method;
}

// Zirr & Kaplanyan 2016, the baseline both glint papers compare with: shaders/glints/zirr2016/zirr2016.glsl.
static GlintMethod zirr2016Method() {
    GlintMethod method{"zirr2016", "Zirr & Kaplanyan 2016 (baseline: mip grids, lerped binomials)", "GLINT_METHOD_ZIRR2016",
            "glints/zirr2016/zirr2016.glsl",
            "Zirr & Kaplanyan 2016, Real-time rendering of procedural multiscale materials, I3D 2016",
            // The authors' shader's parameters with their defaults, except `variation` (raises the mean; left out).
            {{"log_density", 16.0f, 0.0f, 50.0f, "natural log of the microfacet density per unit UV area"},
             {"search_cone", 0.01f, 0.001f, 0.2f,
              "gamma: half-angle (radians) of the cone around h in which a facet reflects; also the angular cell",
              {}, false, true},
             {"dynamic_range", 50000.0f, 1.0f, 1e9f, "largest D / D_smooth a pixel may reach (their clamp)", {}, false,
              true}}};
    method.materialMapping = {
        {"log_density", GlintQuantity::Density, 1.0f, 1.0f, 0.0f, true,
         "Sec. 4: facets per unit UV area, as its natural log"},
        {"search_cone", GlintQuantity::AngularSize, 1.0f, 1.0f, 0.0f, false,
         "Sec. 4.1: gamma is the half-angle of the cone around h (p = pi gamma^2 D(h) (h.n)): the same quantity"}};
    method.convergence = {{"log_density", 40.0f}};
    return method;
}

// Kemppinen et al. 2025: semi-discrete NDF as a Gaussian mixture on an implicit 4D grid (shaders/glints/
// kemppinen2025.glsl). Density is per unit UV area (UVs of the built-in scenes are metres).
static GlintMethod kemppinen2025Method() {
    GlintMethod method{"kemppinen2025",
            "Kemppinen et al. 2025 (constant-time glinty NDF)",
            "GLINT_METHOD_KEMPPINEN2025",
            "glints/kemppinen2025/kemppinen2025.glsl",
            "Kemppinen, Paulin, Thonat, Thiery, Lehtinen, Boubekeur 2025, Evaluating and Sampling Glinty NDFs in "
            "Constant Time, ACM TOG 44(6)",
            {
                {"density", 2e6f, 1e2f, 1e14f, "glint points per unit UV area (Table 1 K_P), x material density scale",
                 {}, false, true},
                {"micro_roughness", 0.01f, 0.001f, 0.1f, "alpha*: angular width of one glint (Table 1, Eq. 4)", {},
                 false, true},
                {"filter_size", 0.7f, 0.5f, 1.2f, "f: Gaussian pixel filter, Sigma_s = f^2 J J^T (Algorithm 1)"},
                {"neighbors", 0.0f, 0.0f, 1.0f, "k nearest angular cells evaluated explicitly (Sec. 3.3.4)",
                 {"4", "16"}},
                {"glint_anisotropy", 1.0f, 1.0f, 64.0f, "A*: stretch of the glints along the tangent (Sec. 3.3.6)",
                 {}, false, true},
                {"roughness_anisotropy", 1.0f, 0.1f, 10.0f,
                 "alpha_x / alpha_y of the base NDF (alpha_x alpha_y = alpha^2; Sec. 3.2.1 M)", {}, false, true},
                {"color_variation", 0.0f, 0.0f, 1.0f, "per-glint colour variation (Sec. 3.3.6; mean colour white)"},
                {"triplanar", 0.0f, 0.0f, 1.0f, "UV-free triplanar mode: 3 world-plane processes (Sec. 3.3.6)", {},
                 true},
                // Defaults follow the authors' published shader where it differs from our reading of the paper
                // (docs/kemppinen2025.md); the paper's reading stays as a choice.
                {"angular_covariance", 0.0f, 0.0f, 1.0f,
                 "Sigma_a = d (alpha* A*^-1)^2 with d = pi D(h) (authors' code, |J| of the mapping) or d = D(h)",
                 {"pi_d", "d"}},
                {"lod", 0.0f, 0.0f, 1.0f,
                 "level: authors = log2(f max|J_i| sqrt(N)) + 2^f (authors' code); cells = log2(6 sigma_major "
                 "sqrt(N)) (spatial cells 3-6 filter deviations, our earlier reading)",
                 {"authors", "cells"}},
            },
            nullptr};
    method.materialMapping = {
        {"density", GlintQuantity::Density, kKemppinenPhysicalDensityScale, 1.0f, 0.0f, false,
         "Table 1: K_P points per unit (UV) area, x 0.1: one point per cell of a jittered 4D grid with Gaussian "
         "lobes varies far less over an area than Poisson facets; a tenth of the points restores the material's CV "
         "and p99.9 / mean over 4x4 pixels (measured against the discrete-facet reference, "
         "docs/glint_statistics.md)"},
        {"micro_roughness", GlintQuantity::AngularSize, 0.70710678f, 1.0f, 0.0f, false,
         "Eq. 4, Algorithm 1: one glint is a Gaussian of angular deviation alpha* (Sigma_a = pi D(h) alpha*^2 in "
         "the prior disk, where area pi D(h) (h.n) per steradian); its equivalent area 2 pi alpha*^2 equals the "
         "cone's pi gamma^2 when alpha* = gamma / sqrt(2)"},
        {"glint_anisotropy", GlintQuantity::Anisotropy, 1.0f, 1.0f, 0.0f, false, "Sec. 3.3.6: A*"},
        {"color_variation", GlintQuantity::ColorVariation, 1.0f, 1.0f, 0.0f, false,
         "Sec. 3.3.6: per-glint colours"}};
    method.convergence = {{"density", 1e13f}};   // tests/kemppinen2025_test.cpp HighDensityConvergesToSmooth
    return method;
}

// Wang, Deng & Holzschuch 2020: prefiltered discrete stochastic microfacets (shaders/glints/wang2020/wang2020.glsl).
// Particle count N is per unit UV square (UVs of the built-in scenes are metres); the square tiles the plane.
static GlintMethod wang2020Method() {
    GlintMethod method{"wang2020", "Wang, Deng & Holzschuch 2020 (prefiltered discrete stochastic microfacets)",
            "GLINT_METHOD_WANG2020", "glints/wang2020/wang2020.glsl",
            "Wang, Deng & Holzschuch 2020, Real-time glints rendering with prefiltered discrete stochastic "
            "microfacets, Computer Graphics Forum 39(6)",
            {{"particles", 1e5f, 1.0f, 1e9f, "N, particles per unit UV square (Eq. 4); edits rebuild the quadtree", {},
              false, true},
             {"gamma", 2.0f, 1.0f, 10.0f, "search cone half-angle gamma in degrees (Sec. 3.1; paper 1-6)"},
             {"roughness", 0.1f, 0.02f, 1.0f, "roughness alpha of the particle normals (DPF extraction, Sec. 4.4)"},
             {"ndf", 1.0f, 0.0f, 1.0f,
              "distribution of the particle normals: mapped from the material's NDF (default without a material: "
              "the paper's Beckmann; a Beckmann DPF under a GGX material is 19-27 % too bright in the highlight); "
              "edits load or generate that DPF set",
              {"ggx", "beckmann"}},
             {"depth", 11.0f, 4.0f, 12.0f, "quadtree depth (paper: 11)", {}, true},
             {"micro_max", 4.0f, 0.0f, 1000.0f, "expected particles in footprint below which micro-scale (Sec. 4.3)"},
             {"macro_min", 64.0f, 1.0f, 100000.0f, "expected particles in footprint above which macro-scale"},
             {"transition", 1.0f, 0.0f, 3.0f,
              "octaves of E over which neighbouring scales blend (ours; 0 = the paper's hard thresholds)"},
             {"seed", 1.0f, 0.0f, 1e6f, "random seed of the quadtree's multinomial splitting", {}, true},
             {"table_scale", 1.0f, 1.0f, 3.0f, "DPF table resolution divisor: 1 = 90x90x180 (paper), 2 = 45x45x90",
              {}, true},
             {"color_r", 1.0f, 0.0f, 1.0f, "glint colour, red (tint of the glints; edits re-run no pass, Sec. 4.5)"},
             {"color_g", 1.0f, 0.0f, 1.0f, "glint colour, green"},
             {"color_b", 1.0f, 0.0f, 1.0f, "glint colour, blue"},
             {"blur_occlusion", 9.0f, 1.0f, 31.0f,
              "taps of the Gaussian blur of the directional occlusion (Sec. 4.4; paper 9; 1 = none; odd)", {}, true},
             {"blur_glints", 3.0f, 1.0f, 15.0f,
              "taps of the Gaussian blur of the glints (Sec. 4.4; paper 3; 1 = none; odd)", {}, true}},
            createWang2020Resources};
    // Sec. 4.4: the lighting pass leaves the glints to the post pass. RGBA32F: a micro-scale glint can exceed
    // half-float range (one particle's radiance over a whole footprint).
    method.lightingTargets = {{"wang2020 environment glints", GL_RGBA32F}, {"wang2020 light glints", GL_RGBA32F}};
    method.defaultIbl = "wang2020";   // Sec. 4: its own environment glints (the IBL mode of the same name)
    method.createPasses = glintpost::createPasses;
    // N, gamma and roughness shape the quadtree and the DPF tables, built once for the densest glinty material;
    // the others thin its particles (shaders/glints/wang2020/wang2020.glsl) and share its gamma and tabulated roughness.
    method.sharedDataMaterial = "particles";
    method.materialMapping = {
        {"particles", GlintQuantity::Density, 1.0f, 1.0f, 0.0f, false, "Eq. 4: N particles per unit UV square"},
        {"gamma", GlintQuantity::AngularSize, 360.0f / 3.14159265f, 1.0f, 0.0f, false,
         "Sec. 3.1: gamma is the cone around the outgoing direction o, in degrees; a normal tilted by d turns the "
         "reflection by 2 d (d omega_o = 4 (o.h) d omega_h), so gamma_o = 2 gamma"},
        {"roughness", GlintQuantity::Alpha, 1.0f, 1.0f, 0.0f, false,
         "Sec. 4.4: the roughness of the particle normals is the material's alpha (tabulated: shared)"},
        {"ndf", GlintQuantity::Ndf, 1.0f, 1.0f, 0.0f, false,
         "Sec. 3.2, Eq. 6: the DPF integrates the particle normals' distribution; it is the material's NDF (GGX "
         "tables are ours, the paper tabulates Beckmann)"},
        {"color_r", GlintQuantity::ColorR, 1.0f, 1.0f, 0.0f, false, "glint colour"},
        {"color_g", GlintQuantity::ColorG, 1.0f, 1.0f, 0.0f, false, "glint colour"},
        {"color_b", GlintQuantity::ColorB, 1.0f, 1.0f, 0.0f, false, "glint colour"}};
    return method;
}

// Chermain et al. 2020 (procedural physically based glints, the dictionary of multiscale marginals) and its 2021
// options (geometric glint anti-aliasing, LEAN-filtered normal maps): shaders/glints/chermain2020/chermain2020.glsl,
// docs/chermain2020.md. `chermain2021` is the same shader with the 2021 options on (the form Unreal Engine 5 ships).
// Defaults are the authors' demos' (ASTex-ICube/real_time_glint and aa_real_time_glint).
static GlintMethod chermainMethod(bool version2021) {
    GlintMethod method{
        version2021 ? "chermain2021" : "chermain2020",
        version2021 ? "Chermain et al. 2021 (2020 + geometric glint anti-aliasing, LEAN normal maps)"
                    : "Chermain et al. 2020 (procedural physically based glints, dictionary of marginals)",
        "GLINT_METHOD_CHERMAIN2020",
        "glints/chermain2020/chermain2020.glsl",
        version2021 ? "Chermain, Lucas, Sauvage, Dischler, Dachsbacher 2021, Real-Time Geometric Glint Anti-Aliasing "
                      "with Normal Map Filtering, PACMCGIT 4(1) (on Chermain et al. 2020, CGF 39(7))"
                    : "Chermain, Sauvage, Dischler, Dachsbacher 2020, Procedural Physically based BRDF for Real-Time "
                      "Rendering of Glints, Computer Graphics Forum 39(7)",
        {{"log_density", 27.0f, 0.0f, 80.0f,
          "natural log of the microfacets per unit UV area (Alg. 3 line 5: a cell holds e^log_density x its area)"},
         {"microfacet_relative_area", 1.0f, 0.001f, 1.0f,
          "fraction of the grid cells that hold microfacets; the others reflect nothing (Alg. 3 line 4)"},
         {"density_randomization", 2.0f, 0.0f, 8.0f,
          "zeta: standard deviation of a cell's dictionary level around log4 n (Alg. 3 line 8; authors: 2)"},
         {"max_anisotropy", version2021 ? 4.0f : 8.0f, 1.0f, 64.0f,
          "largest footprint eccentricity; longer footprints widen their minor axis (Alg. 1 line 4)"},
         {"lod_bias", 0.0f, -8.0f, 8.0f,
          "added to the grid level: negative = finer cells with fewer microfacets each, sparser brighter glints "
          "(like Unreal's r.Substrate.Glints.LevelBias)"},
         {"roughness_anisotropy", 1.0f, 0.1f, 10.0f, "alpha_x / alpha_y of the target NDF (alpha_x alpha_y = alpha^2)",
          {}, false, true},
         {"slope_correlation", 0.0f, -0.99f, 0.99f, "rho: correlation of the target's x and y slopes (2021 Eq. 18)"},
         {"glint_anisotropy", 1.0f, 1.0f, 64.0f,
          "grid cells (and glints) this many times longer along the tangent than across it (density per area kept)",
          {}, false, true},
         {"glint_angle", 0.0f, 0.0f, 0.5f,
          "gamma (radians) of one glint; 0 or below the dictionary's lobe: the dictionary's own width (ours)"},
         {"lobe_count", 0.0f, 0.0f, 1.0f,
          "clamped: the authors' (a cell holds at least level 0's 4 lobes; glints no narrower than the dictionary's); "
          "material (ours): cells below one microfacet are empty with the matching probability, and a glint_angle "
          "below the dictionary's lobe thins the lobes so that the number reflecting stays the material's",
          {"clamped", "material"}},
         {"anti_aliasing", version2021 ? 1.0f : 0.0f, 0.0f, 2.0f,
          "ggaa: the pixel's range of half vectors filters the marginals (2021 GGAA), its footprint from the "
          "derivatives of the projected half vector (the authors' default); ggaa_slope: from those of its slope "
          "(the authors' other choice); none: 2020",
          {"none", "ggaa", "ggaa_slope"}},
         {"kernel_size", 0.5f, 0.0f, 2.0f, "scale of the GGAA filter over the pixel's slope footprint (authors: 0.5)"},
         {"normal_filtering", version2021 ? 1.0f : 0.0f, 0.0f, 2.0f,
          "lean: the normal map's filtered slope covariance widens the NDF (2021 normal map filtering, LEAN mapping); "
          "lean_without_rho: its variances only; none",
          {"none", "lean", "lean_without_rho"}},
         {"seed", 0.0f, 0.0f, 1e6f, "random seed of the cells", {}, true}},
        createChermain2020Resources};
    method.surfaceDerivatives = true;   // GGAA (2021) needs the pixel's range of half vectors
    method.slopeCovariance = true;      // LEAN-filtered normal maps (2021)
    method.materialMapping = {
        {"log_density", GlintQuantity::Density, 0.25f, 1.0f, 0.0f, true,
         "Alg. 3: a cell of n microfacets uses dictionary level log4 n, whose product of marginals has "
         "4^(l+1) = 4 n lobes (each 1D marginal's 2^l lobes and their mirror twins): n is a quarter of the facets "
         "per unit UV area"},
        {"density_randomization", GlintQuantity::Density, 0.0f, 0.0f, 0.0f, false,
         "0: the authors' zeta = 2 spreads each cell's facet count log-normally (16x either way at one sigma), a "
         "device of theirs, not a quantity of the material; with it the dense views' CV is 1.7-3.6x the "
         "discrete-facet reference's (docs/chermain2020.md); --set chermain2020.density_randomization=2 restores it"},
        {"lobe_count", GlintQuantity::Density, 1.0f, 0.0f, 0.0f, false,
         "material: cells below one microfacet are empty with the matching probability (dark pixels of sparse "
         "materials) and glints narrower than the dictionary's lobe thin the lobes instead (deviation 16); "
         "--set chermain2020.lobe_count=clamped restores the authors'"},
        {"glint_angle", GlintQuantity::AngularSize, 1.0f, 1.0f, 0.0f, false,
         "gamma: a facet reflects h within a cone of half-angle gamma (solid angle pi gamma^2); a Gaussian lobe of "
         "deviation s in slope space has the same area when s = gamma / sqrt 2 (ours: the paper ties the lobe "
         "width to the dictionary, 0.02 alpha / alpha_dist)"},
        {"glint_anisotropy", GlintQuantity::Anisotropy, 1.0f, 1.0f, 0.0f, false,
         "glints stretched along the tangent: the authors' texCoord *= (1000, 1) remark, as cells stretched along u"}};
    method.convergence = {{"log_density", 60.0f}};   // every cell of a 128-pixel view at l_dist = L: the smooth NDF
    return method;
}

static std::vector<GlintMethod>& methodTable() {
    static std::vector<GlintMethod> methods = {
        smoothMethod(),
        deliot2023Method(),
        zirr2016Method(),
        kemppinen2025Method(),
        wang2020Method(),
        chermainMethod(false),
        chermainMethod(true),
    };
    return methods;
}

const std::vector<GlintMethod>& glintMethods() { return methodTable(); }

std::string registerGlintMethod(GlintMethod method) {
    GlintMethod* sameFile = nullptr;
    for (GlintMethod& existing : methodTable()) {
        if (existing.isUserMethod() && existing.sourceFile == method.sourceFile) sameFile = &existing;
        else if (existing.id == method.id && !existing.isUserMethod())
            throw Error(method.sourceFile.string() + ": method name '" + method.id + "' is a built-in method's");
        else if (existing.id == method.id)
            throw Error(method.sourceFile.string() + ": method name '" + method.id + "' is already used by " +
                        existing.sourceFile.string());
    }
    if (!sameFile) {
        methodTable().push_back(std::move(method));
        return "";
    }
    std::string previous = sameFile->id;
    *sameFile = std::move(method);
    return previous;
}

const GlintMethod& findGlintMethod(const std::string& id) {
    for (const GlintMethod& m : glintMethods())
        if (m.id == id) return m;
    std::string known;
    for (const GlintMethod& m : glintMethods()) known += (known.empty() ? "" : ", ") + m.id;
    throw UsageError("--method: unknown method '" + id + "' (known: " + known + ")");
}

std::string parameterBlockGlsl(const std::vector<ParamSpec>& params, unsigned binding, const std::string& blockName,
                              const std::string& arrayName, const std::string& macroPrefix, int capacity) {
    if (int(params.size()) > capacity) throw Error("internal: " + blockName + " holds at most " + std::to_string(capacity) + " parameters");
    std::string glsl = "layout(std140, binding = " + std::to_string(binding) + ") uniform " + blockName + " { vec4 " +
                       arrayName + "[" + std::to_string(capacity / 4) + "]; };\n";
    static const char* lanes = "xyzw";
    for (size_t i = 0; i < params.size(); ++i) {
        std::string upper = params[i].name;
        std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
        glsl += "#define " + macroPrefix + upper + " " + arrayName + "[" + std::to_string(i / 4) + "]." + lanes[i % 4] + "\n";
    }
    return glsl;
}

std::vector<float> packParameters(const std::vector<ParamSpec>& params, const ParamValues& values, int capacity) {
    std::vector<float> packed(size_t(capacity), 0.0f);
    for (size_t i = 0; i < params.size() && i < packed.size(); ++i) packed[i] = paramOr(values, params[i]);
    return packed;
}

ParamValues uniformChoices(const GlintMethod& method, const std::vector<ParamValues>& perMaterial) {
    ParamValues constants;
    if (perMaterial.empty()) return constants;
    for (const ParamSpec& spec : method.params) {
        if (spec.choices.empty()) continue;
        const float first = paramOr(perMaterial.front(), spec);
        bool same = true;
        for (const ParamValues& row : perMaterial) same = same && paramOr(row, spec) == first;
        if (same && first == std::floor(first)) constants[spec.name] = first;   // an index (parseParamValue)
    }
    return constants;
}

std::string methodParamsGlsl(const GlintMethod& method, bool perMaterial, const ParamValues& constants) {
    std::string glsl = parameterBlockGlsl(method.params, 3, "MethodParamBlock", "u_methodParams", "PS_", kMaxMethodParams);
    if (!perMaterial) {
        for (const ParamSpec& spec : method.params) {
            std::string upper = spec.name;
            std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
            glsl += "#define P_" + upper + " PS_" + upper + "\n";
        }
        return glsl + "const int g_glintMaterial = -1;   // no material: the shared values\n";
    }
    // One row of kMaxMethodParams / 4 vec4 per material, selected by g_glintMaterial (set by lighting.frag).
    glsl += "layout(std430, binding = " + std::to_string(BINDING_MATERIAL_METHOD_PARAMS) + ") readonly buffer MaterialMethodParamBlock { vec4 u_materialMethodParams[]; };\n"
            "int g_glintMaterial = 0;\n";
    static const char* lanes = "xyzw";
    for (size_t i = 0; i < method.params.size(); ++i) {
        std::string upper = method.params[i].name;
        std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
        if (auto constant = constants.find(method.params[i].name); constant != constants.end()) {
            // An enumeration's index: an integer, exact as a float literal.
            glsl += "#define P_" + upper + " " + std::to_string(int(constant->second)) + ".0\n";
            continue;
        }
        glsl += "#define P_" + upper + " u_materialMethodParams[g_glintMaterial * " + std::to_string(kMaxMethodParams / 4) +
                " + " + std::to_string(i / 4) + "]." + lanes[i % 4] + "\n";
    }
    return glsl;
}

std::vector<float> packMethodParams(const GlintMethod& method, const ParamValues& values) {
    return packParameters(method.params, values, kMaxMethodParams);
}

}  // namespace glimmer
