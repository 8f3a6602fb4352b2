#include "environment/ibl/wang2020_environment.h"
#include "common/bindings.glsl"

#include <array>

#include "core/files.h"
#include "core/log.h"
#include "glints/wang2020/wang2020_prefilter.h"
#include "glints/wang2020/wang2020_resources.h"

namespace glimmer {

namespace {

// What the prefiltered table depends on besides the DPF: the environment's prefiltered cube array
// (UNIT_ENV_SPECULAR) and its uniform block (intensity, rotation; BINDING_ENVIRONMENT), read back from the bound
// state.
struct EnvironmentKey {
    GLint cube = 0;
    std::array<float, 8> params{};
    bool operator==(const EnvironmentKey&) const = default;
};

EnvironmentKey currentEnvironment() {
    EnvironmentKey key;
    GLint previousUnit = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &previousUnit);
    glActiveTexture(GL_TEXTURE0 + UNIT_ENV_SPECULAR);
    glGetIntegerv(GL_TEXTURE_BINDING_CUBE_MAP_ARRAY, &key.cube);
    glActiveTexture(GLenum(previousUnit));
    GLint buffer = 0;
    glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, BINDING_ENVIRONMENT, &buffer);
    if (buffer != 0)  // EnvironmentUniforms: params and rotation follow the 9 SH vectors
        glGetNamedBufferSubData(GLuint(buffer), 9 * 16, GLsizeiptr(sizeof(float) * 8), key.params.data());
    return key;
}

class Wang2020EnvironmentResources : public IblModeResources {
public:
    std::vector<std::pair<std::string, double>> update(const ParamValues& values,
                                                       const GlintMethodResources* methodResources) override {
        std::vector<std::pair<std::string, double>> ran;
        const auto* glints = dynamic_cast<const Wang2020Resources*>(methodResources);
        if (!glints || glints->dpfTexture() == 0) return ran;  // another glint method: the shader falls back
        EnvironmentKey env = currentEnvironment();
        auto chosen = values.find("prefilter");  // ibl.prefilter: 0 dpf (the paper's, default), 1 cone
        auto estimator = chosen != values.end() && chosen->second > 0.5f ? wang2020::Prefilter::Estimator::Cone
                                                                         : wang2020::Prefilter::Estimator::Dpf;
        if (glints == owner_ && glints->dpfVersion() == version_ && env == environment_ && estimator == estimator_)
            return ran;
        if (!prefilter_) prefilter_ = std::make_unique<wang2020::Prefilter>(defaultShaderDir());
        wang2020::PrefilterResolution res = wang2020::prefilterResolution(glints->roughness());
        double ms = prefilter_->run(glints->dpfTexture(), glints->roughness(), glints->gamma() * wang2020::kDegree,
                                    estimator, res);
        owner_ = glints;
        version_ = glints->dpfVersion();
        environment_ = env;
        estimator_ = estimator;
        log::info("wang2020: environment prefilter ", res.thetaN, "x", res.phiN, "x", res.thetaO, "x", res.phiO, " (",
                  prefilter_->bytes() / (1024.0 * 1024.0), " MB) in ", ms, " ms");
        ran.push_back({"wang2020.prefilter", ms});
        return ran;
    }
    void bind() override {
        if (prefilter_) prefilter_->bind();
    }

private:
    std::unique_ptr<wang2020::Prefilter> prefilter_;
    const Wang2020Resources* owner_ = nullptr;
    uint64_t version_ = 0;
    EnvironmentKey environment_;
    wang2020::Prefilter::Estimator estimator_ = wang2020::Prefilter::Estimator::Dpf;
};

}  // namespace

std::unique_ptr<IblModeResources> createWang2020EnvironmentResources() {
    return std::make_unique<Wang2020EnvironmentResources>();
}

}  // namespace glimmer
