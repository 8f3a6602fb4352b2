#include "environment/ibl/kurt_ibl_resources.h"
#include "common/bindings.glsl"

#include <algorithm>
#include <cmath>

#include "core/files.h"
#include "scene/scene.h"

namespace glimmer::ibl {

namespace {
float valueOf(const std::vector<ParamSpec>& specs, const ParamValues& values, const std::string& name,
              float fallback) {
    for (const ParamSpec& s : specs)
        if (s.name == name) return paramOr(values, s);
    return fallback;
}
}  // namespace

std::vector<ParamSpec> kurtMaterialParams() {
    return {
        {"mx", 0.0f, 0.0f, 1.0f, "Kurt lobe Beckmann roughness along the tangent (0: the material's alpha)"},
        {"my", 0.0f, 0.0f, 1.0f, "Kurt lobe Beckmann roughness along the bitangent (0: the material's alpha)"},
        {"r0", -1.0f, -1.0f, 1.0f, "Schlick reflectance at normal incidence (-1: the material's F0)"},
        {"shadow_alpha", 0.0f, 0.0f, 1.0f, "Kurt shadowing/masking exponent alpha (Eq. 2)"},
        {"lobe2_ks", 0.0f, 0.0f, 1.0f, "weight of a second glossy lobe (0: one lobe)"},
        {"lobe2_mx", 0.3f, 0.01f, 1.0f, "second lobe roughness along the tangent"},
        {"lobe2_my", 0.3f, 0.01f, 1.0f, "second lobe roughness along the bitangent"},
    };
}

std::vector<KurtLobeSetup> kurtLobesForMaterial(const Material& material, const std::vector<ParamSpec>& specs,
                                                const ParamValues& values, int budget, double xi0) {
    const RingRule rule = valueOf(specs, values, "ring_rule", 0.0f) > 0.5f ? RingRule::Eq13 : RingRule::Arc;
    const double materialM = std::clamp(double(material.alpha), 0.01, 1.0);
    double mx = valueOf(specs, values, "mx", 0.0f), my = valueOf(specs, values, "my", 0.0f);
    double r0 = valueOf(specs, values, "r0", -1.0f);
    double shadow = valueOf(specs, values, "shadow_alpha", 0.0f);
    std::vector<KurtLobeSetup> lobes(1);
    lobes[0].lobe = {1.0, std::max(r0, 0.0), mx > 0.0 ? mx : materialM, my > 0.0 ? my : materialM, shadow};
    lobes[0].useMaterialF0 = r0 < 0.0;
    double ks2 = valueOf(specs, values, "lobe2_ks", 0.0f);
    if (ks2 > 0.0) {
        KurtLobeSetup second = lobes[0];
        second.lobe.ks = ks2;
        second.lobe.mx = valueOf(specs, values, "lobe2_mx", 0.3f);
        second.lobe.my = valueOf(specs, values, "lobe2_my", 0.3f);
        lobes.push_back(second);
    }
    if (budget > 0)
        for (KurtLobeSetup& l : lobes) l.pattern = selectPatternForBudget(l.lobe.mx, l.lobe.my, xi0, budget, 24, rule);
    return lobes;
}

KurtIblResources::KurtIblResources(std::vector<ParamSpec> specs, bool withPatterns, std::filesystem::path shaderRoot)
    : specs_(std::move(specs)),
      shaderRoot_(shaderRoot.empty() ? defaultShaderDir() : std::move(shaderRoot)),
      withPatterns_(withPatterns) {}

void KurtIblResources::prepare(const ParamValues& values, const Scene& scene, GLuint environmentSource,
                               SceneCapture& capture) {
    const int pyramid = int(valueOf(specs_, values, "pyramid", 0.0f) + 0.5f);   // 0 source, 1 box, 2 gauss4, 3 gauss6
    if (pyramid > 0 && environmentSource != 0) {
        GLint size = 0;
        glGetTextureLevelParameteriv(environmentSource, 0, GL_TEXTURE_WIDTH, &size);
        // The source id alone may be reused by GL after an environment change; the key also samples its texels.
        float probe[4] = {0, 0, 0, 0};
        glGetTextureSubImage(environmentSource, 0, size / 3, size / 5, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof(probe), probe);
        std::vector<float> key = {float(environmentSource), float(size), float(pyramid), probe[0], probe[1], probe[2]};
        if (key != pyramidKey_ || !filteredEnvironment_) {
            pyramidKey_ = key;
            if (!pyramidBuilder_) pyramidBuilder_ = std::make_unique<CubePyramidBuilder>(shaderRoot_, GL_RGBA32F);
            filteredEnvironment_ = createPyramidCube(size, GL_RGBA32F);
            glCopyImageSubData(environmentSource, GL_TEXTURE_CUBE_MAP, 0, 0, 0, 0, filteredEnvironment_.id(),
                               GL_TEXTURE_CUBE_MAP, 0, 0, 0, 0, size, size, 6);
            const PyramidFilter filters[] = {PyramidFilter::Box2, PyramidFilter::Gauss4, PyramidFilter::Gauss6};
            GLint current = 0;   // prepare() runs with the lighting program bound: keep it bound
            glGetIntegerv(GL_CURRENT_PROGRAM, &current);
            pyramidBuilder_->build(filteredEnvironment_.id(), size, filters[std::min(pyramid, 3) - 1]);
            glUseProgram(GLuint(current));
            ++pyramidBuilds_;
        }
    }
    // Sec. 3 per-object maps.
    std::vector<int> slots(std::max<size_t>(scene.materials.size(), 1), -1);
    objectMapCount_ = 0;
    if (valueOf(specs_, values, "object_maps", 0.0f) > 0.5f) {
        const int faceSize = int(valueOf(specs_, values, "object_map_size", 128.0f));
        const PyramidFilter filters[] = {PyramidFilter::Box2, PyramidFilter::Box2, PyramidFilter::Gauss4,
                                         PyramidFilter::Gauss6};
        const PyramidFilter filter = filters[std::clamp(pyramid, 0, 3)];
        std::vector<float> key = {float(faceSize), float(int(filter))};
        if (key != objectMapsKey_ || !objectMaps_) {
            objectMaps_ = std::make_unique<ObjectEnvironmentMaps>(shaderRoot_, faceSize, filter);
            objectMapsKey_ = key;
        }
        std::vector<uint32_t> glossy;
        for (uint32_t i = 0; i < scene.instances.size() && int(glossy.size()) < kMaxObjectMaps; ++i) {
            uint32_t material = scene.instances[i].material;
            if (material >= scene.materials.size() || scene.materials[material].metallic < 0.5f) continue;
            if (slots[material] >= 0) continue;
            slots[material] = int(glossy.size());
            glossy.push_back(i);
        }
        objectMaps_->update(scene, glossy, capture);   // re-renders only the maps whose scene inputs changed
        objectMapCount_ = int(glossy.size());
    }
    if (slots != objectSlotValues_ || !objectSlots_) {
        objectSlots_ = gl::createBuffer(GLsizeiptr(slots.size() * sizeof(int)), slots.data());
        objectSlotValues_ = slots;
    }

    const int budget = withPatterns_ ? int(valueOf(specs_, values, "samples", 14.0f)) : 0;
    const double xi0 = valueOf(specs_, values, "xi0", 0.2f);
    // Everything the buffers depend on; equal keys skip the rebuild (patterns change only with the parameters).
    std::vector<float> key;
    for (const ParamSpec& s : specs_) key.push_back(paramOr(values, s));
    key.push_back(float(scene.materials.size()));
    for (const Material& m : scene.materials) key.push_back(m.alpha);
    if (key == key_ && materials_) return;
    key_ = key;

    std::vector<glm::ivec4> materialRecords;
    std::vector<glm::vec4> lobeRecords, halfVectors;
    std::vector<Material> materials = scene.materials;
    if (materials.empty()) materials.emplace_back();
    for (const Material& material : materials) {
        std::vector<KurtLobeSetup> lobes = kurtLobesForMaterial(material, specs_, values, budget, xi0);
        materialRecords.push_back({int(lobeRecords.size() / 3), int(lobes.size()), 0, 0});
        for (const KurtLobeSetup& l : lobes) {
            lobeRecords.push_back({float(l.lobe.mx), float(l.lobe.my), float(l.lobe.ks), float(l.lobe.alpha)});
            float r0 = l.useMaterialF0 ? -1.0f : float(l.lobe.r0);
            lobeRecords.push_back({r0, r0, r0, 0.0f});
            lobeRecords.push_back({float(halfVectors.size()), float(l.pattern.size()), float(l.pattern.pdfConstant),
                                   float(l.pattern.params.xi0)});
            for (const glm::dvec3& h : l.pattern.halfVectors) halfVectors.push_back({glm::vec3(h), 0.0f});
        }
    }
    if (halfVectors.empty()) halfVectors.push_back(glm::vec4(0, 0, 1, 0));
    materials_ = gl::createBuffer(GLsizeiptr(materialRecords.size() * sizeof(glm::ivec4)), materialRecords.data());
    lobes_ = gl::createBuffer(GLsizeiptr(lobeRecords.size() * sizeof(glm::vec4)), lobeRecords.data());
    halfVectors_ = gl::createBuffer(GLsizeiptr(halfVectors.size() * sizeof(glm::vec4)), halfVectors.data());
    ++uploads_;
}

void KurtIblResources::bind() {
    if (!materials_) return;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_IBL_FIRST + 0, materials_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_IBL_FIRST + 1, lobes_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_IBL_FIRST + 2, halfVectors_.id());
    glBindTextureUnit(UNIT_IBL_FIRST, filteredEnvironment_ ? filteredEnvironment_.id() : 0);
    if (objectSlots_) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_IBL_FIRST + 3, objectSlots_.id());
    for (int i = 0; i < kMaxObjectMaps; ++i)
        glBindTextureUnit(GLuint(UNIT_IBL_FIRST + 1 + i), i < objectMapCount_ ? objectMaps_->cube(size_t(i)) : 0);
}

}  // namespace glimmer::ibl
