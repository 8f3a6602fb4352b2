// The reflection probes' place in the frame (render/probes/reflection_probes.h): prepare() captures and prefilters
// them when something they see changed (listed as probes.capture and probes.prefilter in --stats and the window's
// edit line, or probes.load when read from the disk cache) and publishes FrameResource::ReflectionProbes: the probes for IBL modes that read them
// (IblMode::readsProbes) with probes.enabled, else a block with none. It draws nothing in the frame itself.
#pragma once
#include <filesystem>
#include <memory>

#include "render/frame/pass.h"
#include "render/probes/reflection_probes.h"

namespace glimmer {

class ProbesPass : public Pass {
public:
    // `updates` false: another renderer captures `probes` (a second view of its scene); this pass only publishes them.
    ProbesPass(std::shared_ptr<ReflectionProbes> probes, bool updates);
    const char* name() const override { return "probes"; }
    PassResources resources() const override { return {.writes = {FrameResource::ReflectionProbes}}; }
    std::vector<gl::Program*> programs() override { return {}; }
    void prepare(PrepareContext& context) override;
    bool runs(const FrameContext&) const override { return false; }
    void execute(const FrameContext&) override {}
    const ReflectionProbes& probes() const { return *probes_; }

private:
    std::shared_ptr<ReflectionProbes> probes_;
    bool updates_;
};

}  // namespace glimmer
