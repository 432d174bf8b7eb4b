#include "techniques/device_frame_work.h"

#include "common/raster/vulkan_device.h"

namespace hybridlab {

namespace {

// The counters of the device work since `before`, where there was any.
void recordDeviceWork(const DeviceWork& before, FrameResult& result) {
    const DeviceWork work = VulkanDevice::workSoFar() - before;
    if (work == DeviceWork{}) return;
    result.counters["device_submissions"] = static_cast<double>(work.submissions);
    result.counters["device_readback_bytes"] = static_cast<double>(work.readBackBytes);
    result.counters["device_allocations"] = static_cast<double>(work.allocations);
    result.counters["device_diagnostic_submissions"] = static_cast<double>(work.diagnosticSubmissions);
    result.counters["device_diagnostic_readback_bytes"] = static_cast<double>(work.diagnosticReadBackBytes);
}

class DeviceWorkCountingTechnique : public Technique {
public:
    explicit DeviceWorkCountingTechnique(std::unique_ptr<Technique> technique) : technique_(std::move(technique)) {}

    void prepare(SceneContext& context) override { technique_->prepare(context); }

    FrameResult render(SceneContext& context, const FrameRequest& frame) override {
        const DeviceWork before = VulkanDevice::workSoFar();
        FrameResult result = technique_->render(context, frame);
        recordDeviceWork(before, result);
        return result;
    }

private:
    std::unique_ptr<Technique> technique_;
};

}  // namespace

std::unique_ptr<Technique> countingDeviceWork(std::unique_ptr<Technique> technique) {
    return std::make_unique<DeviceWorkCountingTechnique>(std::move(technique));
}

}  // namespace hybridlab
