#pragma once
// Baking the layered EMs of one lens system (Hakura & Snyder 2001 §4): outgoing-ray records at
// every viewpoint sample, LBG layers over all of them with the whole-object rule and one impostor
// per layer, then per viewpoint sample the inferred cube map of every layer, matched to both terms
// of the lens images at the sample and its neighbours and to direct images of the environment
// (EM disocclusion prevention, §6). What the part-2 renderer loads.
#include <functional>
#include <string>
#include <vector>

#include "techniques/layered_em/em_cube_map.h"
#include "techniques/layered_em/em_inference.h"
#include "techniques/layered_em/layer_shells.h"
#include "techniques/shared/lens_system.h"
#include "techniques/layered_em/lens_tessellation.h"
#include "techniques/layered_em/outgoing_records.h"
#include "techniques/layered_em/viewpoint_samples.h"
#include "techniques/technique.h"

namespace hybridlab {

// Where the direct images of the environment (§4.3) look from: "Direct images from the lens object
// center tend to work better for reflective objects while direct images from the viewpoint are
// better suited for refractive (transparent) objects." Automatic follows that rule per lens system.
enum class DirectImageSource { Automatic, Viewpoint, Origin };

struct EmBakeSettings {
    int width = 96, height = 72;           // lens images (each pixel supersampled by records.supersampling)
    RecordSettings records;
    TessellationSettings tessellation;
    ViewpointSettings viewpoints;
    int layers = 0;                        // 0: the smallest count under maxRelativeRms
    int maxLayers = 4;
    double maxRelativeRms = 0.15;
    EmInferenceSettings inference;
    int neighbourViewpoints = 1;           // samples on each side matched at once (§4.3)
    bool directImages = true;              // direct images of the environment (§4.3)
    DirectImageSource directImageSource = DirectImageSource::Automatic;
    bool originImages = true;              // ... and from the EM origin (six cube faces), where no lens image reads
    float directMissingDistance = 0.05f;   // relative to the shell distance: a direct hit this far from
                                           // every lens record is a missing part (confidence 1)
    std::size_t clusterSampleLimit = 400000;

    // Disocclusion prevention off: first hits only, one viewpoint, no direct images.
    void disablePrevention() {
        records.continueRays = false;
        neighbourViewpoints = 0;
        directImages = false;
    }
};

struct EmLayer {
    Shell shell;
    std::vector<std::uint32_t> objects;   // scene objects in this layer
    double meanDistance = 0.0;
};

struct EmViewpoint {
    Camera camera;
    std::vector<LayerCubeMap> maps;             // per layer
    std::vector<std::size_t> unobservedTexels;  // per layer
};

struct LayeredEm {
    std::string system;
    glm::vec3 center{0.0f};
    std::vector<EmLayer> layers;
    std::vector<EmViewpoint> viewpoints;
};

struct EmBakeStats {
    std::vector<StageTime> stages;  // in order: setup, records, clustering, tessellation, layer images, inference
    std::uint64_t records = 0, lensQueries = 0, environmentQueries = 0;
    std::uint64_t tessellatedVertices = 0, tessellatedTriangles = 0, inferenceRows = 0, inferenceUnknowns = 0;
    int maxIterations = 0;
    double maxRelativeResidual = 0.0;
};

// Progress: stage name, items done, items in the stage.
using BakeProgress = std::function<void(const std::string&, int, int)>;

// "auto", "viewpoint" or "origin" (the technique parameter's and bake-em's spelling); throws
// std::invalid_argument for anything else.
DirectImageSource directImageSourceNamed(const std::string& name);

// The source the direct images of `system` come from: Automatic resolved by §4.3's rule (the
// viewpoint when any of its objects refracts, the EM origin when they only reflect).
DirectImageSource directImageSourceFor(const Scene& scene, const LensSystemInfo& system, DirectImageSource requested);

LayeredEm bakeLayeredEm(const Scene& scene, const LensSystemInfo& system, const EmBakeSettings& settings, EmBakeStats& stats,
                        const BakeProgress& progress = {});

}  // namespace hybridlab
