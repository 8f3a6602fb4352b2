// GPU side of the IBL modes of issue 7 (`regular`, `fis`, `reference`): the Kurt et al. 2010 lobes of every
// material and, for `regular`, their regular half-vector patterns (Sec. 5), rebuilt on the CPU when a material or
// an ibl.* parameter changes and uploaded as shader storage buffers:
//   binding 16: ivec4 per material (first lobe, lobe count)
//   binding 17: per lobe  vec4(mx, my, ks, shadow alpha), vec4(r0 rgb or -1 = material F0, 0),
//                         vec4(first half vector, count, pdf constant (Eq. 18), xi0)
//   binding 18: vec4 half vectors (shading frame), all patterns back to back.
//   texture unit 16: with ibl.pyramid = box | gauss4 | gauss6, a copy of the environment's source cube whose MIP
//   pyramid is rebuilt with that filter (Sec. 3), read instead of envRadiance's box chain.
//   texture units 17-23 + binding 19: with ibl.object_maps = 1, the per-object maps of Sec. 3 (one per metallic
//   instance, at most 7; a material shared by several such instances uses the first one's map).
// Material parameters: Beckmann m = material alpha unless ibl.mx / ibl.my override it, r0 = the metalness-workflow
// F0 unless ibl.r0 >= 0, one lobe plus an optional second (ibl.lobe2_*), shadowing exponent ibl.shadow_alpha.
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "core/params.h"
#include "gl/handles.h"
#include "environment/ibl/cube_pyramid.h"
#include "environment/ibl/kurt_brdf.h"
#include "environment/ibl/object_environment.h"
#include "environment/ibl/regular_pattern.h"
#include "environment/ibl/ibl_modes.h"

namespace glimmer {
struct Material;
}

namespace glimmer::ibl {

// ibl.* parameters shared by the three modes (material overrides), then the mode's own.
std::vector<ParamSpec> kurtMaterialParams();

struct KurtLobeSetup {
    KurtLobe lobe;             // r0 here is only meaningful when useMaterialF0 is false
    bool useMaterialF0 = true;
    RegularPattern pattern;    // empty unless patterns are built
};

// The lobes of `material` under the ibl.* values; patterns built for `budget` samples with threshold xi0 when
// budget > 0 (Sec. 5 budget selection).
std::vector<KurtLobeSetup> kurtLobesForMaterial(const Material& material, const std::vector<ParamSpec>& specs,
                                                const ParamValues& values, int budget, double xi0);

class KurtIblResources : public IblModeResources {
public:
    // withPatterns: build regular patterns (mode `regular`, params "samples" and "xi0").
    KurtIblResources(std::vector<ParamSpec> specs, bool withPatterns, std::filesystem::path shaderRoot = {});
    void prepare(const ParamValues& values, const Scene& scene, GLuint environmentSource,
                 SceneCapture& capture) override;
    void bind() override;
    int uploads() const { return uploads_; }   // how many times the buffers were rebuilt (tests)

private:
    std::vector<ParamSpec> specs_;
    std::filesystem::path shaderRoot_;
    bool withPatterns_;
    std::vector<float> key_;   // inputs of the last upload
    int uploads_ = 0;
    gl::Buffer materials_, lobes_, halfVectors_;
    // ibl.pyramid != source: the environment's level 0 copied and re-filtered (Sec. 3 filters), texture unit 16.
    std::unique_ptr<CubePyramidBuilder> pyramidBuilder_;
    gl::Texture filteredEnvironment_;
    std::vector<float> pyramidKey_;
    int pyramidBuilds_ = 0;
    // ibl.object_maps: one cube per metallic instance (Sec. 3), texture units 17-23; binding 19: per material the
    // map slot (-1: the environment).
    std::unique_ptr<ObjectEnvironmentMaps> objectMaps_;
    std::vector<float> objectMapsKey_;
    gl::Buffer objectSlots_;
    std::vector<int> objectSlotValues_;
    int objectMapCount_ = 0;

public:
    int pyramidBuilds() const { return pyramidBuilds_; }
    static constexpr int kMaxObjectMaps = 7;
};

}  // namespace glimmer::ibl
