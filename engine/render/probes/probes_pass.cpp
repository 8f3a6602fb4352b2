#include "render/probes/probes_pass.h"

namespace glimmer {

ProbesPass::ProbesPass(const std::filesystem::path& shaderRoot) : probes_(shaderRoot) {}

void ProbesPass::prepare(PrepareContext& context) {
    const IblMode& ibl = findIblMode(context.settings.ibl);
    const bool active =
        ibl.readsProbes && context.environment.enabled() && probeSettings(context.settings).enabled;
    if (active) {
        ReflectionProbes::Update update = probes_.update(context.scene, context.gpuScene, context.environment,
                                                         context.settings);
        if (update.fromDisk) {
            context.recordOnDemand("probes.load", update.loadMs);
        } else if (update.ran) {
            context.recordOnDemand("probes.capture", update.captureMs);
            context.recordOnDemand("probes.prefilter", update.prefilterMs);
        }
    }
    context.resources.publish(FrameResource::ReflectionProbes, probes_.image(active));
}

}  // namespace glimmer
