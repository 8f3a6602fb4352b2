// GPU data of Wang et al. 2020 (shaders/glints/wang2020/wang2020.glsl): the DPF tables accumulated at the shared gamma for
// each distinct (NDF, roughness) of the glinty materials, stacked along z in one 3D texture (unit 9) with the
// material -> slot map in an SSBO (binding 9); the shared values' table alone (unit 8, slot 0 of the stack: the
// IBL mode's prefilter reads it); and the particle quadtree (SSBO, binding 8). update() re-runs only the passes a
// change needs (Sec. 4.5): N, depth or seed -> quadtree; gamma or table_scale -> every table's accumulation; one
// material's roughness or NDF -> only that table's extraction + accumulation; anything else -> nothing.
#pragma once
#include "common/bindings.glsl"
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "gl/handles.h"
#include "glints/methods.h"
#include "glints/wang2020/wang2020_dpf.h"
#include "glints/wang2020/wang2020_quadtree.h"

namespace glimmer {

class Wang2020Resources : public GlintMethodResources {
public:
    static constexpr int kDpfUnit = UNIT_METHOD_FIRST;
    static constexpr int kQuadtreeBinding = BINDING_METHOD_FIRST;
    static constexpr int kDpfStackUnit = UNIT_METHOD_FIRST + 1;
    static constexpr int kMaterialSlotBinding = BINDING_METHOD_FIRST + 1;
    void setMaterials(const std::vector<ParamValues>& perMaterial) override;
    std::vector<std::pair<std::string, double>> update(const ParamValues& values) override;
    void bind() override;
    // For the IBL mode's prefilter pass (Sec. 4.4): the accumulated DPF and what it was built for.
    GLuint dpfTexture() const { return dpf_.id(); }
    float roughness() const { return roughness_; }
    float gamma() const { return gamma_; }
    uint64_t dpfVersion() const { return dpfVersion_; }
    // The roughness of each table of the stack in slot order, each material's slot, and the number of DPF
    // extractions run since construction (tests of per-material editing).
    std::vector<float> slotRoughness() const;
    const std::vector<uint32_t>& materialSlots() const { return materialSlot_; }
    int extractionsRun() const { return extractionsRun_; }

private:
    struct TableKey {
        int ndf;           // 0 GGX, 1 Beckmann (the parameter's choice index); -1: not glinty
        float roughness;
        bool operator==(const TableKey& o) const { return ndf == o.ndf && roughness == o.roughness; }
        bool operator<(const TableKey& o) const { return ndf != o.ndf ? ndf < o.ndf : roughness < o.roughness; }
    };
    void uploadStack();

    float roughness_ = -1, gamma_ = -1, particles_ = -1, depth_ = -1, seed_ = -1, tableScale_ = -1;
    TableKey sharedKey_{-1, -1.0f};
    std::vector<TableKey> materialKeys_;          // from setMaterials()
    std::set<int> fetchedSets_;                   // NDFs whose DPF set this instance loaded at tableScale_
    std::map<TableKey, wang2020::DpfTable> tables_;
    std::vector<TableKey> slots_;
    std::vector<uint32_t> materialSlot_;
    gl::Texture dpf_, dpfStack_;
    gl::Buffer quadtree_, materialSlots_;
    uint64_t dpfVersion_ = 0;
    int extractionsRun_ = 0;
};

std::unique_ptr<GlintMethodResources> createWang2020Resources();

}  // namespace glimmer
