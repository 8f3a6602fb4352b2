#include "render/probes/probes_pass.h"

namespace glimmer {

ProbesPass::ProbesPass(std::shared_ptr<ReflectionProbes> probes, bool updates)
    : probes_(std::move(probes)), updates_(updates) {}

void ProbesPass::prepare(PrepareContext& context) {
    const IblMode& ibl = findIblMode(context.settings.ibl);
    const bool active =
        ibl.readsProbes && context.environment.enabled() && probeSettings(context.settings).enabled;
    if (active && updates_) {
        // A capture is a refinement (seconds on llvmpipe): the window's first picture lights with the environment
        // alone and a later frame captures. The disk cache is read at once.
        ReflectionProbes::Update update = probes_->update(context.scene, context.gpuScene, context.environment,
                                                         context.settings, false);
        if (update.waiting && context.environment.refined() && context.refinements.take("reflection probes"))
            update = probes_->update(context.scene, context.gpuScene, context.environment, context.settings, true);
        if (update.waiting) {
            if (!context.environment.refined()) context.refinements.wait("reflection probes");
            context.resources.publish(FrameResource::ReflectionProbes, probes_->image(false));
            return;
        }
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
