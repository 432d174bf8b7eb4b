// `hybridlab bench-raster`: the raster core's stage times (GPU timestamps per pass, wall clock for
// the rest), medians over repeated frames after warm-up (lavapipe compiles shaders at the first
// draw), beside the Whitted reference's frame time on the same view. The `raster` technique's
// frame is shadow maps + G-buffer + lighting + read-back of the image.

#include <algorithm>
#include <cstdio>
#include <map>
#include <vector>

#include "common/core/process_cpu_clock.h"
#include "common/core/wall_clock.h"
#include "common/raster/gbuffer.h"
#include "common/raster/rasterizer.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "experiments/cli/commands.h"
#include "experiments/cli/view_options.h"
#include "techniques/technique.h"

namespace hybridlab::cli {

namespace {

struct BenchRasterOptions {
    ViewOptions view;
    int repeats = 20;
    int warmup = 3;
    int shadowResolution = 2048;
    int pcfRadius = ShadowSettings{}.pcfRadius;
    int whittedRepeats = 3;
};

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Per-stage samples of repeated frames: the GPU stages, and the wall-clock parts.
struct Samples {
    std::map<std::string, std::vector<double>> stages;
    std::vector<std::string> order;

    void add(const std::string& name, double ms) {
        if (!stages.count(name)) order.push_back(name);
        stages[name].push_back(ms);
    }
    void add(const RasterFrame& f) {
        for (const auto& s : f.gpuStages) add("gpu " + s.name, s.milliseconds);
        add("cpu record", f.recordMilliseconds);
        add("cpu unpack", f.unpackMilliseconds);
        add("wall frame", f.wallMilliseconds());
    }
    double medianOf(const std::string& name) const { return stages.count(name) ? median(stages.at(name)) : 0.0; }
    // CPU time of every thread of the process (lavapipe's workers included) per frame: on a shared
    // machine it moves less with other people's load than the wall clock does.
    double cpuMillisecondsPerFrame = 0.0;
};

Samples measure(Rasterizer& raster, const RasterRequest& request, int warmup, int repeats) {
    RasterFrame frame;
    for (int i = 0; i < warmup; ++i) raster.render(request, frame);
    Samples s;
    const double cpuStart = processCpuMilliseconds();
    for (int i = 0; i < repeats; ++i) {
        raster.render(request, frame);
        s.add(frame);
    }
    s.cpuMillisecondsPerFrame = (processCpuMilliseconds() - cpuStart) / repeats;
    return s;
}

void print(const char* title, const Samples& s) {
    std::printf("%s\n", title);
    for (const auto& name : s.order) std::printf("  %-24s %10.3f ms\n", name.c_str(), s.medianOf(name));
    std::printf("  %-24s %10.3f ms (mean; all threads)\n", "cpu time per frame", s.cpuMillisecondsPerFrame);
}

void run(const BenchRasterOptions& o) {
    Scene scene = loadSceneFile(findSceneFile(o.view.scene));
    const View view = o.view.resolve(scene);
    SceneContext context(scene);
    Rasterizer& raster = context.rasterizer();

    RasterRequest frame;  // the `raster` technique's frame
    frame.camera = view.camera;
    frame.time = view.time;
    frame.width = o.view.width;
    frame.height = o.view.height;
    frame.lighting = true;
    frame.lightingOptions.shadows = true;
    frame.lightingOptions.environmentMapping = true;
    frame.shadowSettings.resolution = static_cast<std::uint32_t>(o.shadowResolution);
    frame.shadowSettings.pcfRadius = o.pcfRadius;
    frame.redrawShadowMaps = true;
    const Samples full = measure(raster, frame, o.warmup, o.repeats);
    frame.redrawShadowMaps = false;
    const Samples cached = measure(raster, frame, o.warmup, o.repeats);

    // What a hybrid technique reads back: the whole G-buffer, and the visible pixels per object.
    RasterRequest gbuffer = frame;
    gbuffer.lighting = false;
    gbuffer.readback = kGBufferAll;
    gbuffer.occlusionQueries = true;
    RasterFrame g;
    raster.render(gbuffer, g);
    const Samples readAll = measure(raster, gbuffer, o.warmup, o.repeats);
    std::vector<double> countMs;
    std::size_t visible = 0;
    for (int i = 0; i < o.repeats; ++i) {
        const auto start = WallClock::now();
        const auto counts = visiblePixelsFromIds(g.gbuffer, scene.objects.size());
        countMs.push_back(millisecondsSince(start));
        visible = static_cast<std::size_t>(std::count_if(counts.begin(), counts.end(), [](std::uint64_t c) { return c > 0; }));
    }

    std::vector<double> whittedMs;
    if (o.whittedRepeats > 0) {
        auto whitted = createTechnique("whitted", {});
        whitted->prepare(context);
        const FrameRequest request{view.camera, view.time, o.view.width, o.view.height};
        whitted->render(context, request);  // warm-up
        for (int i = 0; i < o.whittedRepeats; ++i) whittedMs.push_back(whitted->render(context, request).totalMilliseconds());
    }

    std::printf("scene %s, %dx%d, view %s, device %s, shadow maps %d^2 with PCF radius %d, medians of %d frames after %d warm-up\n",
                scene.name.c_str(), o.view.width, o.view.height, view.label.c_str(), raster.deviceName().c_str(), o.shadowResolution,
                o.pcfRadius, o.repeats, o.warmup);
    std::printf("scene upload             %10.3f ms\n", raster.uploadMilliseconds());
    print("raster frame, shadow maps redrawn every frame:", full);
    print("raster frame, static shadow maps kept (the technique's default):", cached);
    print("G-buffer for a hybrid technique (every target read back, occlusion queries):", readAll);
    std::printf("  %-24s %10.3f ms (%zu objects visible)\n", "cpu count ids", median(countMs), visible);
    if (!whittedMs.empty()) {
        const double w = median(whittedMs);
        std::printf("whitted reference frame  %10.3f ms (median of %d)\n", w, o.whittedRepeats);
        std::printf("raster / whitted         %10.4f (shadow maps redrawn), %.4f (kept)\n", full.medianOf("wall frame") / w,
                    cached.medianOf("wall frame") / w);
    }
}

}  // namespace

void addBenchRasterCommand(CLI::App& app) {
    auto o = std::make_shared<BenchRasterOptions>();
    auto* cmd = app.add_subcommand("bench-raster",
                                   "Raster core stage times (GPU timestamps, medians after warm-up) beside the Whitted reference's frame");
    o->view.addTo(cmd);
    cmd->add_option("--repeats", o->repeats, "Timed frames")->check(CLI::Range(1, 10000))->capture_default_str();
    cmd->add_option("--warmup", o->warmup, "Untimed frames first")->check(CLI::Range(1, 1000))->capture_default_str();
    cmd->add_option("--shadow-resolution", o->shadowResolution, "Shadow-map texels per side")->check(CLI::Range(64, 8192))->capture_default_str();
    cmd->add_option("--pcf-radius", o->pcfRadius, "PCF over (2r + 1)^2 filtered taps")->check(CLI::Range(0, 4))->capture_default_str();
    cmd->add_option("--whitted-repeats", o->whittedRepeats, "Timed reference frames (0: skip the reference)")
        ->check(CLI::Range(0, 100))
        ->capture_default_str();
    cmd->callback([o] { run(*o); });
}

}  // namespace hybridlab::cli
