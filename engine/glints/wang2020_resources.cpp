#include "glints/wang2020_resources.h"

#include <map>
#include <mutex>

#include "core/clock.h"
#include "core/log.h"

namespace glimmer {

namespace {

float valueOf(const ParamValues& values, const char* name) {
    for (const ParamSpec& spec : findGlintMethod("wang2020").params)
        if (spec.name == name) return paramOr(values, spec);
    return 0.0f;
}

// The DPF generation pass runs once per process and resolution (and once per machine thanks to the disk cache).
std::shared_ptr<const wang2020::DpfSet> dpfSetFor(int scale) {
    static std::mutex mutex;
    static std::map<int, std::shared_ptr<const wang2020::DpfSet>> sets;
    std::lock_guard<std::mutex> lock(mutex);
    auto& slot = sets[scale];
    if (!slot) {
        wang2020::DpfResolution res{90 / scale, 90 / scale, 180 / scale};
        slot = std::make_shared<wang2020::DpfSet>(wang2020::loadOrGenerateDpfSet(res, wang2020::defaultDpfCacheDir()));
    }
    return slot;
}

}  // namespace

std::vector<std::pair<std::string, double>> Wang2020Resources::update(const ParamValues& values) {
    std::vector<std::pair<std::string, double>> ran;
    float roughness = valueOf(values, "roughness"), gamma = valueOf(values, "gamma");
    float particles = valueOf(values, "particles"), depth = valueOf(values, "depth"), seed = valueOf(values, "seed");
    float tableScale = valueOf(values, "table_scale");
    if (tableScale != tableScale_) {
        Stopwatch clock;
        dpfSet_ = dpfSetFor(int(tableScale));
        tableScale_ = tableScale;
        roughness_ = -1;  // the accumulated table must follow the new resolution
        ran.push_back({"wang2020.dpf_generation", clock.elapsedMs()});
    }
    if (roughness != roughness_ || gamma != gamma_) {
        // Sec. 4.4 "DPF Extraction and Accumulation" (CPU here, a GPU pass in the paper).
        Stopwatch clock;
        wang2020::DpfTable table =
            wang2020::accumulateDpf(wang2020::extractDpf(*dpfSet_, roughness), gamma * wang2020::kDegree);
        const wang2020::DpfResolution& r = table.res;
        GLuint id = 0;
        glCreateTextures(GL_TEXTURE_3D, 1, &id);
        dpf_ = gl::Texture(id);
        glTextureStorage3D(id, 1, GL_R32F, r.phi, r.thetaO, r.thetaI);
        glTextureSubImage3D(id, 0, 0, 0, 0, r.phi, r.thetaO, r.thetaI, GL_RED, GL_FLOAT, table.values.data());
        for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
            glTextureParameteri(id, wrap, GL_CLAMP_TO_EDGE);
        glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        roughness_ = roughness;
        gamma_ = gamma;
        ++dpfVersion_;
        ran.push_back({"wang2020.dpf_accumulation", clock.elapsedMs()});
        log::debug("wang2020: DPF extraction + accumulation (alpha ", roughness, ", gamma ", gamma, " deg) in ",
                   clock.elapsedMs(), " ms");
    }
    if (particles != particles_ || depth != depth_ || seed != seed_) {
        // Sec. 4.4 "Spatial Tree Construction" (CPU here, a GPU pass in the paper).
        Stopwatch clock;
        wang2020::Quadtree tree = wang2020::buildQuadtree(particles, int(depth), uint32_t(seed));
        quadtree_ = gl::createBuffer(GLsizeiptr(tree.bytes()), tree.counts.data(), 0);
        particles_ = particles;
        depth_ = depth;
        seed_ = seed;
        ran.push_back({"wang2020.quadtree", clock.elapsedMs()});
        log::info("wang2020: quadtree depth ", int(depth), ", N ", particles, ": ", tree.bytes() / (1024.0 * 1024.0),
                  " MB, built in ", clock.elapsedMs(), " ms");
    }
    return ran;
}

void Wang2020Resources::bind() {
    glBindTextureUnit(kDpfUnit, dpf_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kQuadtreeBinding, quadtree_.id());
}

std::unique_ptr<GlintMethodResources> createWang2020Resources() { return std::make_unique<Wang2020Resources>(); }

}  // namespace glimmer
