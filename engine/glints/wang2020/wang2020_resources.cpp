#include "glints/wang2020/wang2020_resources.h"

#include <algorithm>
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
// One set per resolution and particle NDF (generated only for the NDFs a scene uses).
std::shared_ptr<const wang2020::DpfSet> dpfSetFor(int scale, wang2020::ParticleNdf ndf) {
    static std::mutex mutex;
    static std::map<std::pair<int, int>, std::shared_ptr<const wang2020::DpfSet>> sets;
    std::lock_guard<std::mutex> lock(mutex);
    auto& slot = sets[{scale, int(ndf)}];
    if (!slot) {
        wang2020::DpfResolution res{90 / scale, 90 / scale, 180 / scale};
        slot = std::make_shared<wang2020::DpfSet>(
            wang2020::loadOrGenerateDpfSet(res, wang2020::defaultDpfCacheDir(), 0, ndf));
    }
    return slot;
}

}  // namespace

namespace {

gl::Texture createDpfTexture(const std::vector<float>& values, const wang2020::DpfResolution& r, int stacked) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &id);
    gl::Texture texture(id);
    glTextureStorage3D(id, 1, GL_R32F, r.phi, r.thetaO, r.thetaI * stacked);
    glTextureSubImage3D(id, 0, 0, 0, 0, r.phi, r.thetaO, r.thetaI * stacked, GL_RED, GL_FLOAT, values.data());
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(id, wrap, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return texture;
}

wang2020::ParticleNdf particleNdf(float ndf) { return ndf > 0.5f ? wang2020::ParticleNdf::Beckmann : wang2020::ParticleNdf::Ggx; }

}  // namespace

void Wang2020Resources::setMaterials(const std::vector<ParamValues>& perMaterial) {
    materialKeys_.assign(perMaterial.size(), TableKey{-1, -1.0f});
    for (size_t i = 0; i < perMaterial.size(); ++i)
        if (!perMaterial[i].empty())
            materialKeys_[i] = {int(valueOf(perMaterial[i], "ndf") > 0.5f), valueOf(perMaterial[i], "roughness")};
}

std::vector<std::pair<std::string, double>> Wang2020Resources::update(const ParamValues& values) {
    std::vector<std::pair<std::string, double>> ran;
    float gamma = valueOf(values, "gamma");
    float particles = valueOf(values, "particles"), depth = valueOf(values, "depth"), seed = valueOf(values, "seed");
    float tableScale = valueOf(values, "table_scale");
    if (tableScale != tableScale_) fetchedSets_.clear();
    if (tableScale != tableScale_ || gamma != gamma_) tables_.clear();   // every table follows resolution and gamma
    tableScale_ = tableScale;
    gamma_ = gamma;

    // Slot 0: the shared values' table (the IBL mode's prefilter and code outside the lighting pass read it);
    // then one slot per further distinct (NDF, roughness) of the glinty materials, in material order.
    const TableKey shared{int(valueOf(values, "ndf") > 0.5f), valueOf(values, "roughness")};
    std::vector<TableKey> wanted = {shared};
    std::vector<uint32_t> materialSlot(std::max<size_t>(materialKeys_.size(), 1), 0u);
    for (size_t i = 0; i < materialKeys_.size(); ++i) {
        if (materialKeys_[i].ndf < 0) continue;
        auto it = std::find(wanted.begin(), wanted.end(), materialKeys_[i]);
        materialSlot[i] = uint32_t(it - wanted.begin());
        if (it == wanted.end()) wanted.push_back(materialKeys_[i]);
    }

    // Sec. 4.4 "DPF Extraction and Accumulation" (CPU here, a GPU pass in the paper) for the keys not accumulated
    // yet at this gamma and resolution (an edit of one material's roughness re-runs only its own); tables no
    // material uses any more are dropped. The DPF sets (generation) load once per process, NDF and resolution.
    std::vector<TableKey> extracted;
    double generationMs = 0.0;
    Stopwatch clock;
    for (const TableKey& key : wanted) {
        if (tables_.count(key)) continue;
        Stopwatch generation;
        std::shared_ptr<const wang2020::DpfSet> set = dpfSetFor(int(tableScale), particleNdf(float(key.ndf)));
        if (fetchedSets_.insert(key.ndf).second) generationMs += std::max(generation.elapsedMs(), 1e-3);
        tables_[key] = wang2020::accumulateDpf(wang2020::extractDpf(*set, key.roughness), gamma * wang2020::kDegree);
        extracted.push_back(key);
    }
    for (auto it = tables_.begin(); it != tables_.end();)
        it = std::find(wanted.begin(), wanted.end(), it->first) == wanted.end() ? tables_.erase(it) : std::next(it);
    if (generationMs > 0.0) ran.push_back({"wang2020.dpf_generation", generationMs});   // a set new to this instance
    if (!extracted.empty() || wanted != slots_ || materialSlot != materialSlot_) {
        slots_ = wanted;
        materialSlot_ = materialSlot;
        uploadStack();
    }
    if (!extracted.empty() || !(shared == sharedKey_)) {
        const wang2020::DpfTable& table = tables_.at(shared);
        dpf_ = createDpfTexture(table.values, table.res, 1);
        sharedKey_ = shared;
        roughness_ = shared.roughness;
        ++dpfVersion_;
    }
    if (!extracted.empty()) {
        ran.push_back({"wang2020.dpf_accumulation", clock.elapsedMs() - generationMs});
        log::debug("wang2020: DPF extraction + accumulation of ", extracted.size(), " table(s) (first alpha ",
                   extracted.front().roughness, ", gamma ", gamma, " deg) in ", clock.elapsedMs(), " ms");
    }
    if (particles != particles_ || depth != depth_ || seed != seed_) {
        // Sec. 4.4 "Spatial Tree Construction" (CPU here, a GPU pass in the paper).
        Stopwatch tree;
        wang2020::Quadtree quadtree = wang2020::buildQuadtree(particles, int(depth), uint32_t(seed));
        std::vector<uint32_t> words = wang2020::shaderNodeWords(quadtree);
        quadtree_ = gl::createBuffer(GLsizeiptr(words.size() * sizeof(uint32_t)), words.data(), 0);
        particles_ = particles;
        depth_ = depth;
        seed_ = seed;
        ran.push_back({"wang2020.quadtree", tree.elapsedMs()});
        log::info("wang2020: quadtree depth ", int(depth), ", N ", particles, ": ",
                  quadtree.bytes() / (1024.0 * 1024.0), " MB, built in ", tree.elapsedMs(), " ms");
    }
    return ran;
}

// The stacked tables (slot k's theta_i rows at z in [k T, (k + 1) T)) and the slot buffer of
// shaders/glints/wang2020/wang2020.glsl: uvec4 (slot count, theta_i rows per slot, 0, 0), then one slot per material.
void Wang2020Resources::uploadStack() {
    const wang2020::DpfResolution& res = tables_.at(slots_.front()).res;
    std::vector<float> stacked;
    stacked.reserve(res.size() * slots_.size());
    for (const TableKey& key : slots_) {
        const std::vector<float>& v = tables_.at(key).values;
        stacked.insert(stacked.end(), v.begin(), v.end());
    }
    dpfStack_ = createDpfTexture(stacked, res, int(slots_.size()));
    std::vector<uint32_t> buffer = {uint32_t(slots_.size()), uint32_t(res.thetaI), 0u, 0u};
    buffer.insert(buffer.end(), materialSlot_.begin(), materialSlot_.end());
    materialSlots_ = gl::createBuffer(GLsizeiptr(buffer.size() * sizeof(uint32_t)), buffer.data(), 0);
}

void Wang2020Resources::bind() {
    glBindTextureUnit(kDpfUnit, dpf_.id());
    glBindTextureUnit(kDpfStackUnit, dpfStack_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kQuadtreeBinding, quadtree_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaterialSlotBinding, materialSlots_.id());
}

std::unique_ptr<GlintMethodResources> createWang2020Resources() { return std::make_unique<Wang2020Resources>(); }

}  // namespace glimmer
