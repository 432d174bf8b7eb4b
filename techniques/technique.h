#pragma once
// The technique interface (DESIGN.md "The technique interface"). A technique is one folder with a
// class behind this interface and one line in registry.cpp; the CLI and the experiment runner
// know techniques only through the registry.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/image/image.h"
#include "common/scene/camera.h"
#include "techniques/cache_bake_command.h"
#include "techniques/parameters.h"
#include "techniques/scene_context.h"
#include "techniques/search_space.h"

namespace hybridlab {

// One frame to render.
struct FrameRequest {
    Camera camera;
    double time = 0.0;  // scene time (animation)
    int width = 0;
    int height = 0;
    float aspect() const { return static_cast<float>(width) / static_cast<float>(height); }
    // The rasterizer's request for this frame's view (camera, time, size); the caller adds what to
    // draw and read back.
    RasterRequest rasterRequest() const {
        RasterRequest r;
        r.camera = camera;
        r.time = time;
        r.width = width;
        r.height = height;
        return r;
    }
};

struct StageTime {
    std::string name;
    double milliseconds = 0.0;
};

// Everything a technique produces: a linear HDR image, named stage times, counters and debug
// images (DESIGN.md "A frame, as data").
struct FrameResult {
    Image image;
    std::vector<StageTime> stages;
    std::map<std::string, double> counters;
    std::map<std::string, Image> debugImages;

    double totalMilliseconds() const;
};

class Technique {
public:
    virtual ~Technique() = default;

    // Per-scene work done once (BVHs, baked environment maps); its time is reported separately.
    virtual void prepare(SceneContext& context) { (void)context; }

    virtual FrameResult render(SceneContext& context, const FrameRequest& frame) = 0;
};

struct TechniqueInfo {
    std::string name;
    std::string description;  // one line
    std::vector<ParamSpec> parameters;
    std::function<std::unique_ptr<Technique>(const ParameterSet&)> create;
    // Time a pixel of a frame takes at the default parameters, relative to the Whitted reference's
    // (1): what `hybridlab run --shard` balances shards by (shard_partition.h). A class, not a
    // measurement of any one scene.
    double relativeCost = 1.0;
    // The subcommand that bakes what prepare() caches on disk ahead of rendering, for a technique
    // that caches anything (layered_em: `hybridlab bake-em`); the program finds it here.
    std::optional<CacheBakeCommand> bakeCommand;
    // The knobs `hybridlab tune` searches (search_space.h); none: it is not searched.
    std::vector<SearchDimension> searchSpace;
};

// The registry (registry.cpp), in display order.
const std::vector<TechniqueInfo>& registeredTechniques();

// Throws InputError listing the known names.
const TechniqueInfo& findTechnique(const std::string& name);

// Resolves parameters against the technique's declarations and creates it, its frames counting
// their device work (device_frame_work.h).
std::unique_ptr<Technique> createTechnique(const std::string& name,
                                           const std::vector<std::pair<std::string, ParamValue>>& parameters);

}  // namespace hybridlab
