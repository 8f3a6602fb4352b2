#include "render/probes/probes_pass.h"

namespace glimmer {

ProbesPass::ProbesPass(std::shared_ptr<ReflectionProbes> probes, bool updates)
    : probes_(std::move(probes)), updates_(updates) {}

void ProbesPass::prepare(PrepareContext& context) {
    const IblMode& ibl = findIblMode(context.settings.ibl);
    const bool active =
        ibl.readsProbes && context.environment.enabled() && probeSettings(context.settings).enabled;
    if (active && updates_) {
        ReflectionProbes::Update update = probes_->update(context.scene, context.gpuScene, context.environment,
                                                         context.settings);
        if (update.fromDisk) {
            context.recordOnDemand("probes.load", update.loadMs);
        } else if (update.ran) {
            context.recordOnDemand("probes.capture", update.captureMs);
            context.recordOnDemand("probes.prefilter", update.prefilterMs);
        }
    }
    context.resources.publish(FrameResource::ReflectionProbes, probes_->image(active));
}

}  // namespace glimmer
