#pragma once
// Experiment configs (TOML, experiments/configs/; format in experiments/README.md) and the run
// list they expand to. Every error names the file, line and key, and is raised before anything
// renders: scenes are loaded (without textures) to check their camera paths and frame ranges,
// and every parameter set is checked against its technique's declarations.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "experiments/runner/interleaved_timing.h"
#include "metrics/metrics.h"
#include "techniques/parameters.h"

namespace hybridlab {

using ParameterList = std::vector<std::pair<std::string, ParamValue>>;

struct ViewSpec {
    std::string cameraPath;  // empty: the scene's camera (one frame)
    int firstFrame = 0;
    int lastFrame = 0;       // inclusive
    int stride = 1;
};

struct SceneSpec {
    std::string name;   // as written: a scenes/ name or a path
    std::string label;  // the scene's own name ([scene] name, default the file name): records say this
    std::filesystem::path file;
    std::vector<std::pair<int, int>> resolutions;
    std::vector<ViewSpec> views;
};

struct TechniqueSpec {
    std::string name;   // in the registry
    std::string label;  // distinguishes several entries of one technique; default: the name
    std::vector<ParameterList> parameterSets;  // each checked; at least one (possibly empty)
};

struct ExperimentConfig {
    std::filesystem::path file;
    std::string name;
    std::string description;
    std::string hash;          // of the config file's bytes
    // How each group of runs is timed (interleaved_timing.h): `warmup_frames`, `warmup_ms` (the
    // warm-up goes on past warmup_frames until this long: a GPU raises its clock only under load),
    // `steady_frames`, `steady_tolerance`, `max_warmup_frames`, `repeats` (the fewest rounds),
    // `max_rounds`, `precision` and `budget_s`.
    TimingProtocol timing;
    double resolutionScale = 1.0;  // `run --scale`: resolutions below are already scaled (resolution_scale.h)
    MetricSelection metrics;       // `metrics`: what each image is scored with
    bool temporalError = true;     // `metrics` holds "temporal": the error between path frames
    bool keepErrorMaps = true;     // `keep` holds "error_maps" (and a metric has a map)
    bool keepDebugImages = true;   // `keep` holds "debug_images"
    ParameterList referenceParameters;  // for the `whitted` reference
    // `[reference] timed`: the reference is timed in every group's rounds, for speed-ups over it
    // with intervals. false where it would idle the device between the settings' frames (the
    // Embree reference beside settings on a GPU).
    bool timeReference = true;
    std::vector<SceneSpec> scenes;
    std::vector<TechniqueSpec> techniques;
};

ExperimentConfig loadExperimentConfig(const std::filesystem::path& file);

// The `metrics` names of a config, in the order `metrics = [...]` accepts them.
std::vector<std::string> metricNames(const ExperimentConfig& config);

// One render of one technique with one parameter set at one frame.
struct RunSpec {
    std::size_t index = 0;       // position in the full run list
    std::string id;              // stable, file-name safe, unique within the experiment
    std::size_t scene = 0;       // into ExperimentConfig::scenes
    std::string cameraPath;      // empty: the scene camera
    int frame = -1;              // on the path; -1 for the scene camera
    int width = 0, height = 0;
    std::size_t technique = 0;   // into ExperimentConfig::techniques
    ParameterList parameters;    // as given (defaults are filled in by the technique)
    std::string parametersText;  // canonical "k=v k=v"
    std::string sequenceKey;     // frames of one path with one technique and parameter set
};

// Scenes x resolutions x view frames x techniques x parameter sets, in that nesting order.
std::vector<RunSpec> planRuns(const ExperimentConfig& config);

}  // namespace hybridlab
