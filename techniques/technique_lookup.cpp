// Techniques by name, from the registry (registry.cpp). In the library beside the registry, not in
// the technique base that every technique links: the base must not need the list of techniques.
#include "common/core/input_error.h"
#include "techniques/device_frame_work.h"
#include "techniques/technique.h"

namespace hybridlab {

const TechniqueInfo& findTechnique(const std::string& name) {
    std::string known;
    for (const auto& t : registeredTechniques()) {
        if (t.name == name) return t;
        known += (known.empty() ? "" : ", ") + t.name;
    }
    throw InputError("unknown technique '" + name + "' (techniques: " + known + ")");
}

std::unique_ptr<Technique> createTechnique(const std::string& name,
                                           const std::vector<std::pair<std::string, ParamValue>>& parameters) {
    const TechniqueInfo& info = findTechnique(name);
    return countingDeviceWork(info.create(resolveParameters(info.parameters, parameters, "technique " + name)));
}

}  // namespace hybridlab
