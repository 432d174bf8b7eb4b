#include "techniques/layered_em/em_cache_entry_check.h"

#include <cmath>

namespace hybridlab {
namespace {

template <typename Vec>
bool allFinite(const Vec& v) {
    for (int i = 0; i < Vec::length(); ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

bool shellUsable(const Shell& s) {
    const bool kindKnown = s.kind == ShellKind::Sphere || s.kind == ShellKind::Quad || s.kind == ShellKind::Cylinder;
    return kindKnown && allFinite(s.center) && std::isfinite(s.radius) && allFinite(s.planePoint) && allFinite(s.planeNormal) &&
           allFinite(s.axisU) && allFinite(s.axisV) && allFinite(s.extentMin) && allFinite(s.extentMax) && std::isfinite(s.farDistance);
}

std::optional<std::string> layerMismatch(const EmLayer& layer, std::size_t index, const Scene& scene) {
    const std::string name = "layer " + std::to_string(index + 1);
    if (!shellUsable(layer.shell) || !std::isfinite(layer.meanDistance)) return name + " has an unknown or non-finite impostor";
    for (std::uint32_t o : layer.objects)
        if (o >= scene.objects.size())
            return name + " names object " + std::to_string(o) + "; the scene has " + std::to_string(scene.objects.size());
    return std::nullopt;
}

// One viewpoint sample: a usable camera, and per layer a cube map of the bake's size (its whole MIP
// chain, premultiplied RGBA the renderer blends: finite) and its count of unobserved texels.
std::optional<std::string> viewpointMismatch(const EmViewpoint& v, std::size_t index, std::size_t layers, int emSize) {
    const std::string name = "viewpoint sample " + std::to_string(index);
    if (!v.camera.placementUsable()) return name + " has an unusable camera";
    if (v.maps.size() != layers || v.unobservedTexels.size() != layers)
        return name + " has " + std::to_string(v.maps.size()) + " cube maps and " + std::to_string(v.unobservedTexels.size()) +
               " unobserved-texel counts for " + std::to_string(layers) + " layers";
    for (std::size_t l = 0; l < layers; ++l) {
        const LayerCubeMap& m = v.maps[l];
        const std::string map = name + "'s cube map of layer " + std::to_string(l + 1);
        if (m.size != emSize) return map + " is " + std::to_string(m.size) + " texels a side; the bake's em_size is " + std::to_string(emSize);
        if (m.texels.size() != cubeMapTexelCount(m.size))
            return map + " holds " + std::to_string(m.texels.size()) + " texels; its size needs " + std::to_string(cubeMapTexelCount(m.size));
        for (const glm::vec4& t : m.texels)
            if (!allFinite(t)) return map + " has a non-finite texel";
    }
    return std::nullopt;
}

}  // namespace

std::optional<std::string> layeredEmEntryMismatch(const LayeredEm& em, const Scene& scene, const LensSystemInfo& system,
                                                  const EmBakeSettings& settings) {
    if (em.system != system.name) return "it is an entry of lens system '" + em.system + "', not '" + system.name + "'";
    if (!allFinite(em.center)) return "its EM origin is not finite";
    // The bake makes `layers` layers when asked for a number (fewer only when fewer objects are
    // seen), else at most maxLayers (§4.2's clustering); the renderer needs at least one.
    const std::size_t mostLayers = static_cast<std::size_t>(settings.layers > 0 ? settings.layers : settings.maxLayers);
    if (em.layers.empty()) return "it has no layers";
    if (em.layers.size() > mostLayers)
        return "it has " + std::to_string(em.layers.size()) + " layers; the bake makes 1 to " + std::to_string(mostLayers);
    for (std::size_t l = 0; l < em.layers.size(); ++l)
        if (auto problem = layerMismatch(em.layers[l], l, scene)) return problem;
    // The count of viewpoint samples depends on the settings and the scene's camera (paths), not
    // on where the circle is centred, so the entry's own origin serves to count them.
    const std::size_t views = viewpointSamples(scene, em.center, settings.viewpoints).size();
    if (em.viewpoints.empty()) return "it has no viewpoint samples";
    if (em.viewpoints.size() != views)
        return "it has " + std::to_string(em.viewpoints.size()) + " viewpoint samples; the bake makes " + std::to_string(views);
    for (std::size_t v = 0; v < em.viewpoints.size(); ++v)
        if (auto problem = viewpointMismatch(em.viewpoints[v], v, em.layers.size(), settings.inference.size)) return problem;
    return std::nullopt;
}

}  // namespace hybridlab
