#include "render/image/upscale.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace glimmer {

UpscalePass::UpscalePass(const std::filesystem::path& shaderRoot)
    : program_(shaderRoot, {"upscale", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "image/upscale.frag"}}}) {
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    vao_ = gl::VertexArray(vao);
}

void UpscalePass::draw(GLuint sourceTexture, GLuint sourceFramebuffer, int sourceW, int sourceH,
                       GLuint targetFramebuffer, int targetW, int targetH, int fromColumn) {
    fromColumn = std::clamp(fromColumn, 0, targetW);
    if (fromColumn >= targetW) return;
    if (sourceW == targetW && sourceH == targetH) {
        glBlitNamedFramebuffer(sourceFramebuffer, targetFramebuffer, fromColumn, 0, targetW, targetH, fromColumn, 0,
                               targetW, targetH, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        return;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, targetFramebuffer);
    glViewport(0, 0, targetW, targetH);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_SCISSOR_TEST);
    glScissor(fromColumn, 0, targetW - fromColumn, targetH);
    program_.use();
    glUniform2i(0, sourceW, sourceH);
    glUniform2f(1, float(sourceW) / float(targetW), float(sourceH) / float(targetH));
    glBindTextureUnit(0, sourceTexture);
    glBindVertexArray(vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_SCISSOR_TEST);
}

namespace {
std::array<float, 4> catmullRomWeights(float t) {
    float t2 = t * t, t3 = t2 * t;
    return {0.5f * (-t + 2.0f * t2 - t3), 0.5f * (2.0f - 5.0f * t2 + 3.0f * t3), 0.5f * (t + 4.0f * t2 - 3.0f * t3),
            0.5f * (-t2 + t3)};
}
}  // namespace

namespace {
// One separable pass structure for both formats: `fetch(x, y, c)` reads channel c of a source texel as a float,
// `store(o, c, v)` writes channel c of the output texel index o.
template <typename Fetch, typename Store>
void catmullRomResample(int sourceW, int sourceH, int targetW, int targetH, int channels, Fetch fetch, Store store) {
    float sx = float(sourceW) / float(targetW), sy = float(sourceH) / float(targetH);
    for (int y = 0; y < targetH; ++y) {
        float py = (float(y) + 0.5f) * sy - 0.5f, by = std::floor(py);
        auto wy = catmullRomWeights(py - by);
        for (int x = 0; x < targetW; ++x) {
            float px = (float(x) + 0.5f) * sx - 0.5f, bx = std::floor(px);
            auto wx = catmullRomWeights(px - bx);
            float sum[4] = {0, 0, 0, 0};
            for (int j = 0; j < 4; ++j) {
                int yy = std::clamp(int(by) - 1 + j, 0, sourceH - 1);
                float row[4] = {0, 0, 0, 0};
                for (int i = 0; i < 4; ++i) {
                    int xx = std::clamp(int(bx) - 1 + i, 0, sourceW - 1);
                    for (int c = 0; c < channels; ++c) row[c] += wx[size_t(i)] * fetch(xx, yy, c);
                }
                for (int c = 0; c < channels; ++c) sum[c] += wy[size_t(j)] * row[c];
            }
            size_t o = size_t(y) * size_t(targetW) + size_t(x);
            for (int c = 0; c < channels; ++c) store(o, c, sum[c]);
        }
    }
}
}  // namespace

std::vector<uint8_t> catmullRomUpscale(const std::vector<uint8_t>& source, int sourceW, int sourceH, int targetW,
                                       int targetH) {
    std::vector<uint8_t> out(size_t(targetW) * size_t(targetH) * 4, 255);
    catmullRomResample(
        sourceW, sourceH, targetW, targetH, 3,
        [&](int x, int y, int c) { return float(source[(size_t(y) * size_t(sourceW) + size_t(x)) * 4 + size_t(c)]) / 255.0f; },
        [&](size_t o, int c, float v) { out[o * 4 + size_t(c)] = uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); });
    return out;
}

std::vector<float> catmullRomUpscale(const std::vector<float>& source, int sourceW, int sourceH, int targetW,
                                     int targetH) {
    std::vector<float> out(size_t(targetW) * size_t(targetH) * 4);
    catmullRomResample(
        sourceW, sourceH, targetW, targetH, 4,
        [&](int x, int y, int c) { return source[(size_t(y) * size_t(sourceW) + size_t(x)) * 4 + size_t(c)]; },
        [&](size_t o, int c, float v) { out[o * 4 + size_t(c)] = std::max(v, 0.0f); });
    return out;
}

}  // namespace glimmer
