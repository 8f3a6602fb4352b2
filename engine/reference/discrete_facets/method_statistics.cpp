#include "reference/discrete_facets/method_statistics.h"

#include <cmath>
#include <cstdio>

#include "core/log.h"
#include "reference/discrete_facets/reference_render.h"

namespace glimmer::facets {

namespace {
std::vector<float> firstChannel(const RenderResult& r) {
    std::vector<float> out(size_t(r.width) * size_t(r.height));
    for (size_t i = 0; i < out.size(); ++i) out[i] = r.hdr[4 * i];
    return out;
}

double pearson(const std::vector<float>& a, const std::vector<float>& b, const std::vector<bool>& mask) {
    double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!mask[i]) continue;
        n += 1, sa += a[i], sb += b[i], saa += double(a[i]) * a[i], sbb += double(b[i]) * b[i], sab += double(a[i]) * b[i];
    }
    if (n < 2) return 0.0;
    double va = saa / n - (sa / n) * (sa / n), vb = sbb / n - (sb / n) * (sb / n);
    return va > 0 && vb > 0 ? (sab / n - (sa / n) * (sb / n)) / std::sqrt(va * vb) : 0.0;
}

std::vector<float> ratios(const GlintFrame& f) {
    std::vector<float> r(f.d.size(), 0.0f);
    for (size_t i = 0; i < r.size(); ++i) r[i] = f.inside[i] && f.smooth[i] > 0 ? f.d[i] / f.smooth[i] : 0.0f;
    return r;
}
}  // namespace

GlintFrame referenceGlintFrame(OffscreenSession& session, const SurfaceImage& surface, const RenderRequest& request) {
    RenderRequest smooth = request;
    smooth.settings.method = "smooth";
    GlintFrame f;
    f.width = request.width;
    f.height = request.height;
    f.smooth = firstChannel(session.render(smooth));
    ReferenceOptions options = referenceOptions(request.settings);
    options.maxLights = 1;
    options.progress = false;
    // The glint AOV is the lighting pass's first light: the first in gpuLightOrder.
    std::vector<Light> lights;
    for (size_t i : gpuLightOrder(session.scene().lights)) lights.push_back(session.scene().lights[i]);
    ReferenceImage image = evaluateLights(surface, session.scene().materials, lights, options);
    f.d.assign(f.smooth.size(), 0.0f);
    f.lambda.assign(f.smooth.size(), 0.0f);
    f.inside = highlightMask(f.smooth);
    for (size_t i = 0; i < f.d.size(); ++i) {
        if (image.lights == 0) {
            f.inside[i] = false;
            continue;
        }
        glm::vec3 d = image.d[i * size_t(image.lights)];
        float cpuSmooth = image.smoothD[i * size_t(image.lights)];
        float ratio = cpuSmooth > 0.0f ? (d.x + d.y + d.z) / (3.0f * cpuSmooth) : 0.0f;
        f.d[i] = ratio * f.smooth[i];
        f.lambda[i] = image.lambda[i * size_t(image.lights)];
        f.inside[i] = f.inside[i] && image.glinty[i] && cpuSmooth > 0.0f;
    }
    return f;
}

GlintFrame methodGlintFrame(OffscreenSession& session, const std::string& method, const RenderRequest& request,
                            const GlintFrame& reference) {
    RenderRequest r = request;
    r.settings.method = method;
    RenderResult result = session.render(r);
    if (result.stats["counts"]["non_finite_values"].get<size_t>() != 0)
        log::warn("glint statistics: ", method, " wrote non-finite values");
    GlintFrame f = reference;
    f.d = firstChannel(result);
    return f;
}

double meanBlockLambda(const GlintFrame& f, int block) {
    double total = 0.0;
    size_t blocks = 0;
    for (int by = 0; by + block <= f.height; by += block)
        for (int bx = 0; bx + block <= f.width; bx += block) {
            double sum = 0.0;
            bool whole = true;
            for (int y = by; y < by + block && whole; ++y)
                for (int x = bx; x < bx + block; ++x) {
                    size_t i = size_t(y) * size_t(f.width) + size_t(x);
                    if (!f.inside[i]) {
                        whole = false;
                        break;
                    }
                    sum += f.lambda[i];
                }
            if (!whole) continue;
            total += sum;
            ++blocks;
        }
    return blocks ? total / double(blocks) : 0.0;
}

TargetCheck checkTarget(const BlockStats& m, const BlockStats& ref) {
    TargetCheck c;
    c.cvRatio = ref.cv > 0.0 ? m.cv / ref.cv : 0.0;
    c.p999Ratio = ref.p999OverMean > 0.0 ? m.p999OverMean / ref.p999OverMean : 0.0;
    c.darkDifference = m.darkFraction - ref.darkFraction;
    c.meanRatio = ref.mean > 0.0 ? m.mean / ref.mean : 0.0;
    c.cv = ref.cv > 0.0 ? (c.cvRatio <= 1.5 && c.cvRatio >= 1.0 / 1.5) : m.cv < 0.05;
    c.p999 = ref.p999OverMean > 0.0 ? (c.p999Ratio <= 1.5 && c.p999Ratio >= 1.0 / 1.5) : true;
    c.dark = std::abs(c.darkDifference) <= 0.1;
    c.mean = std::abs(c.meanRatio - 1.0) <= 0.05;
    return c;
}

double lifespanDegrees(OffscreenSession& session, const SurfaceImage& surface, const RenderRequest& request,
                       const std::string& method) {
    auto frameAt = [&](double degrees) {
        RenderRequest r = request;
        char text[64];
        std::snprintf(text, sizeof text, "light.turn=%.9g", degrees);
        r.settings.apply(text);
        GlintFrame ref = referenceGlintFrame(session, surface, r);
        return method == kReferenceMethodId ? ref : methodGlintFrame(session, method, r, ref);
    };
    GlintFrame f0 = frameAt(0.0);
    std::vector<float> r0 = ratios(f0);
    double previousAngle = 0.0, previous = 1.0;
    for (double degrees = 0.02; degrees <= 20.0; degrees *= 1.5) {
        GlintFrame f = frameAt(degrees);
        std::vector<bool> both(f.inside.size());
        for (size_t i = 0; i < both.size(); ++i) both[i] = f.inside[i] && f0.inside[i];
        double rho = pearson(r0, ratios(f), both);
        if (rho <= 0.5) return previousAngle + (previous - 0.5) / (previous - rho) * (degrees - previousAngle);
        previousAngle = degrees;
        previous = rho;
    }
    return INFINITY;
}

}  // namespace glimmer::facets
