#include "ltc_fitter.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace glimmer::ltcfit {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Smith G1 of the NDF (shaders/common/brdf.glsl: GGX exact, Beckmann by Walter et al.'s rational fit, Eq. 27).
double g1(Ndf ndf, const glm::dvec3& w, double alpha) {
    if (w.z <= 0.0) return 0.0;
    double cos2 = w.z * w.z, tan2 = std::max(1.0 - cos2, 0.0) / cos2;
    if (ndf == Ndf::Ggx) return 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
    double tanTheta = std::sqrt(tan2);
    if (tanTheta <= 0.0) return 1.0;
    double a = 1.0 / (alpha * tanTheta);
    if (a >= 1.6) return 1.0;
    return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
}

// A half vector drawn from D(h) (h.n) by inverting its CDF in theta (Walter et al. 2007, Eq. 28, 35).
glm::dvec3 sampleHalfVector(Ndf ndf, double alpha, double u1, double u2) {
    double tan2 = ndf == Ndf::Ggx ? alpha * alpha * u1 / (1.0 - u1) : -alpha * alpha * std::log(1.0 - u1);
    double cosTheta = 1.0 / std::sqrt(1.0 + tan2);
    double sinTheta = std::sqrt(std::max(1.0 - cosTheta * cosTheta, 0.0));
    double phi = 2.0 * kPi * u2;
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

glm::dvec3 viewOf(double cosTheta) { return {std::sqrt(std::max(1.0 - cosTheta * cosTheta, 0.0)), 0.0, cosTheta}; }

// Density of light directions l = reflect(v about h) with h drawn as in sampleHalfVector: D(h) (h.n) / (4 |v.h|).
double lobeSamplingPdf(Ndf ndf, double alpha, const glm::dvec3& v, const glm::dvec3& l) {
    glm::dvec3 h = v + l;
    double len = glm::length(h);
    if (len < 1e-12) return 0.0;
    h /= len;
    double vh = std::abs(glm::dot(v, h));
    return vh > 0.0 ? ndfValue(ndf, h, alpha) * h.z / (4.0 * vh) : 0.0;
}

// Downhill simplex (Nelder & Mead 1965) over up to 3 parameters; returns the best point's value.
template <class F>
double nelderMead(F&& f, double* x, int n, const double* step, int maxIterations) {
    double simplex[4][3], value[4];
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; j < n; ++j) simplex[i][j] = x[j] + (i == j + 1 ? step[j] : 0.0);
        value[i] = f(simplex[i]);
    }
    for (int iteration = 0; iteration < maxIterations; ++iteration) {
        // Order: best first.
        int order[4] = {0, 1, 2, 3};
        std::sort(order, order + n + 1, [&](int a, int b) { return value[a] < value[b]; });
        double sorted[4][3], sortedValue[4];
        for (int i = 0; i <= n; ++i) {
            for (int j = 0; j < n; ++j) sorted[i][j] = simplex[order[i]][j];
            sortedValue[i] = value[order[i]];
        }
        for (int i = 0; i <= n; ++i) {
            for (int j = 0; j < n; ++j) simplex[i][j] = sorted[i][j];
            value[i] = sortedValue[i];
        }
        if (std::abs(value[n] - value[0]) <= 1e-9 * (std::abs(value[0]) + 1e-12)) break;
        double centroid[3] = {0.0, 0.0, 0.0};
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) centroid[j] += simplex[i][j] / double(n);
        auto along = [&](double t, double* out) {
            for (int j = 0; j < n; ++j) out[j] = centroid[j] + t * (simplex[n][j] - centroid[j]);
            return f(out);
        };
        double reflected[3], expanded[3], contracted[3];
        double fr = along(-1.0, reflected);
        if (fr < value[0]) {
            double fe = along(-2.0, expanded);
            if (fe < fr) {
                std::copy(expanded, expanded + n, simplex[n]);
                value[n] = fe;
            } else {
                std::copy(reflected, reflected + n, simplex[n]);
                value[n] = fr;
            }
        } else if (fr < value[n - 1]) {
            std::copy(reflected, reflected + n, simplex[n]);
            value[n] = fr;
        } else {
            bool outside = fr < value[n];
            double fc = along(outside ? -0.5 : 0.5, contracted);
            if (fc < std::min(fr, value[n])) {
                std::copy(contracted, contracted + n, simplex[n]);
                value[n] = fc;
            } else {
                for (int i = 1; i <= n; ++i) {
                    for (int j = 0; j < n; ++j) simplex[i][j] = simplex[0][j] + 0.5 * (simplex[i][j] - simplex[0][j]);
                    value[i] = f(simplex[i]);
                }
            }
        }
    }
    int best = 0;
    for (int i = 1; i <= n; ++i)
        if (value[i] < value[best]) best = i;
    std::copy(simplex[best], simplex[best] + n, x);
    return value[best];
}

}  // namespace

double ndfValue(Ndf ndf, const glm::dvec3& h, double alpha) {
    if (h.z <= 0.0) return 0.0;
    double a2 = alpha * alpha, c2 = h.z * h.z;
    if (ndf == Ndf::Ggx) {
        double d = c2 * (a2 - 1.0) + 1.0;
        return a2 / (kPi * d * d);
    }
    double tan2 = (1.0 - c2) / c2;
    return std::exp(-tan2 / a2) / (kPi * a2 * c2 * c2);
}

double lobeValue(Ndf ndf, Lobe lobe, double alpha, const glm::dvec3& v, const glm::dvec3& l) {
    if (l.z <= 0.0 || v.z <= 0.0) return 0.0;
    glm::dvec3 h = v + l;
    double len = glm::length(h);
    if (len < 1e-12) return 0.0;
    h /= len;
    double D = ndfValue(ndf, h, alpha);
    if (lobe == Lobe::NdfOnly) return D / (4.0 * std::max(std::abs(glm::dot(v, h)), 1e-12));
    return D * g1(ndf, l, alpha) * g1(ndf, v, alpha) / (4.0 * v.z);
}

double totalNdf(Ndf ndf, double alpha) {
    if (ndf == Ndf::Ggx) {
        if (alpha >= 1.0) return 2.0;
        double k = std::sqrt(1.0 - alpha * alpha);
        return 1.0 + alpha * alpha * std::log((1.0 + k) / alpha) / k;
    }
    // e^(x^2) erfc(x) for x = 1 / alpha: erfc underflows for small alpha, so its asymptotic series there.
    double x = 1.0 / alpha;
    double scaled = x < 5.0 ? std::exp(x * x) * std::erfc(x)
                            : (1.0 / (x * std::sqrt(kPi))) * (1.0 - 0.5 / (x * x) + 0.75 / (x * x * x * x) -
                                                               1.875 / (x * x * x * x * x * x));
    return 1.0 + 0.5 * std::sqrt(kPi) * alpha * scaled;
}

LobeIntegrals integrateLobe(Ndf ndf, Lobe lobe, double alpha, double cosTheta, int samplesPerAxis) {
    const glm::dvec3 v = viewOf(cosTheta);
    double magnitude = 0.0, fresnel = 0.0;
    glm::dvec3 moment(0.0);
    for (int i = 0; i < samplesPerAxis; ++i)
        for (int j = 0; j < samplesPerAxis; ++j) {
            double u1 = (double(i) + 0.5) / samplesPerAxis, u2 = (double(j) + 0.5) / samplesPerAxis;
            glm::dvec3 h = sampleHalfVector(ndf, alpha, u1, u2);
            double vh = glm::dot(v, h);
            glm::dvec3 l = 2.0 * vh * h - v;
            if (l.z <= 0.0 || vh <= 0.0) continue;
            double pdf = ndfValue(ndf, h, alpha) * h.z / (4.0 * vh);
            if (!(pdf > 0.0)) continue;
            double weight = lobeValue(ndf, lobe, alpha, v, l) / pdf;
            magnitude += weight;
            fresnel += weight * std::pow(1.0 - vh, 5.0);
            moment += weight * l;
        }
    double n = double(samplesPerAxis) * samplesPerAxis;
    LobeIntegrals result;
    result.magnitude = magnitude / n;
    result.fresnel = fresnel / n;
    moment.y = 0.0;
    result.average = glm::length(moment) > 0.0 ? glm::normalize(moment) : glm::dvec3(0.0, 0.0, 1.0);
    return result;
}

void Ltc::update() {
    M = glm::dmat3(X, Y, Z) * glm::dmat3(m11, 0.0, 0.0, 0.0, m22, 0.0, m13, 0.0, 1.0);
    invM = glm::inverse(M);
    detInvM = std::abs(glm::determinant(invM));
}

double Ltc::eval(const glm::dvec3& l) const {
    glm::dvec3 lo = invM * l;
    double len = glm::length(lo);
    if (!(len > 0.0)) return 0.0;
    double cosine = std::max(lo.z / len, 0.0);
    return cosine / kPi * detInvM / (len * len * len);
}

glm::dvec3 Ltc::sample(double u1, double u2) const {
    double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
    glm::dvec3 lo(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(1.0 - u1, 0.0)));
    return glm::normalize(M * lo);
}

double rowAlpha(int row, int size) {
    double u = double(row) / double(size - 1);
    return std::max(u * u, kAlphaMin);
}

double columnCosTheta(int column, int size) {
    double x = double(column) / double(size - 1);
    return std::max(1.0 - x * x, kCosThetaMin);
}

namespace {

// The lobe's own sample set for the fit error: directions, target values and sampling densities do not depend on the
// LTC being fitted, so they are computed once per entry (half of each error evaluation).
struct LobeSamples {
    std::vector<glm::dvec3> directions;
    std::vector<double> target, pdf;
};

LobeSamples lobeSamples(Ndf ndf, Lobe lobe, double alpha, const glm::dvec3& v, double magnitude, int samples) {
    LobeSamples set;
    for (int i = 0; i < samples; ++i)
        for (int j = 0; j < samples; ++j) {
            glm::dvec3 h = sampleHalfVector(ndf, alpha, (double(i) + 0.5) / samples, (double(j) + 0.5) / samples);
            glm::dvec3 l = 2.0 * glm::dot(v, h) * h - v;
            set.directions.push_back(l);
            set.target.push_back(lobeValue(ndf, lobe, alpha, v, l) / magnitude);
            set.pdf.push_back(lobeSamplingPdf(ndf, alpha, v, l));
        }
    return set;
}

// Multiple importance sampling (balance heuristic) of the LTC and of the lobe (Heitz et al. Sec. 5.2):
// |difference|^3 / (pdf_ltc + pdf_lobe) summed over both sample sets.
double errorWith(Ndf ndf, Lobe lobe, double alpha, const glm::dvec3& v, double magnitude, const Ltc& ltc,
                 const LobeSamples& lobeSet, int samples) {
    double sum = 0.0;
    for (int i = 0; i < samples; ++i)
        for (int j = 0; j < samples; ++j) {
            glm::dvec3 l = ltc.sample((double(i) + 0.5) / samples, (double(j) + 0.5) / samples);
            double target = lobeValue(ndf, lobe, alpha, v, l) / magnitude;
            double pdfLtc = ltc.eval(l), pdfLobe = lobeSamplingPdf(ndf, alpha, v, l);
            double d = std::abs(target - pdfLtc);
            if (pdfLtc + pdfLobe > 0.0) sum += d * d * d / (pdfLtc + pdfLobe);
        }
    for (size_t k = 0; k < lobeSet.directions.size(); ++k) {
        double pdfLtc = ltc.eval(lobeSet.directions[k]);
        double d = std::abs(lobeSet.target[k] - pdfLtc);
        if (pdfLtc + lobeSet.pdf[k] > 0.0) sum += d * d * d / (pdfLtc + lobeSet.pdf[k]);
    }
    return sum / (double(samples) * samples);
}

}  // namespace

double fitError(Ndf ndf, Lobe lobe, double alpha, const glm::dvec3& v, double magnitude, const Ltc& ltc, int samples) {
    if (!(magnitude > 0.0)) return 0.0;
    return errorWith(ndf, lobe, alpha, v, magnitude, ltc, lobeSamples(ndf, lobe, alpha, v, magnitude, samples), samples);
}

Entry fitEntry(Ndf ndf, Lobe lobe, double alpha, double cosTheta, const Entry* guess, const FitSettings& settings) {
    const glm::dvec3 v = viewOf(cosTheta);
    LobeIntegrals integrals = integrateLobe(ndf, lobe, alpha, cosTheta, settings.integralSamples);
    Ltc ltc;
    const bool isotropic = cosTheta >= 1.0 - 1e-9;
    if (!isotropic) {
        ltc.Z = integrals.average;
        ltc.Y = glm::dvec3(0.0, 1.0, 0.0);
        ltc.X = glm::normalize(glm::cross(ltc.Y, ltc.Z));
    }
    double params[3] = {guess ? guess->m11 : 1.0, guess ? guess->m22 : 1.0, guess ? guess->m13 : 0.0};
    if (isotropic) params[1] = params[0], params[2] = 0.0;
    auto apply = [&](const double* p) {
        ltc.m11 = p[0];
        ltc.m22 = isotropic ? p[0] : p[1];
        ltc.m13 = isotropic ? 0.0 : p[2];
        ltc.update();
    };
    const LobeSamples lobeSet = lobeSamples(ndf, lobe, alpha, v, integrals.magnitude, settings.errorSamples);
    auto objective = [&](const double* p) {
        if (!(p[0] > 1e-7) || (!isotropic && !(p[1] > 1e-7))) return std::numeric_limits<double>::max();
        apply(p);
        return errorWith(ndf, lobe, alpha, v, integrals.magnitude, ltc, lobeSet, settings.errorSamples);
    };
    double step[3] = {0.1 * params[0], 0.1 * params[1], 0.05};
    double error = nelderMead(objective, params, isotropic ? 1 : 3, step, settings.maxIterations);
    apply(params);

    Entry entry;
    entry.m11 = ltc.m11, entry.m22 = ltc.m22, entry.m13 = ltc.m13;
    const glm::dmat3& inv = ltc.invM;   // column-major: inv[column][row]
    double scale = inv[1][1];
    entry.invM = {float(inv[0][0] / scale), float(inv[2][0] / scale), float(inv[0][2] / scale), float(inv[2][2] / scale)};
    entry.magnitude = float(integrals.magnitude);
    entry.fresnel = float(integrals.fresnel);
    entry.error = float(error);
    return entry;
}

std::vector<Entry> fitTable(Ndf ndf, Lobe lobe, const FitSettings& settings) {
    const int n = settings.size;
    std::vector<Entry> table(size_t(n) * size_t(n));
    // Heitz et al.'s march: from the roughest row (close to a cosine) to the smoothest, each row from the normal to
    // grazing, each fit starting from its neighbour's.
    for (int row = n - 1; row >= 0; --row)
        for (int column = 0; column < n; ++column) {
            const Entry* guess = column > 0 ? &table[size_t(row * n + column - 1)]
                                 : row < n - 1 ? &table[size_t((row + 1) * n)] : nullptr;
            table[size_t(row * n + column)] = fitEntry(ndf, lobe, rowAlpha(row, n), columnCosTheta(column, n), guess, settings);
        }
    return table;
}

}  // namespace glimmer::ltcfit
