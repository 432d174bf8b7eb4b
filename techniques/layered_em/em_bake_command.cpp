#include "techniques/layered_em/em_bake_command.h"

#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "common/core/atomic_file.h"
#include "common/core/cli_number_validators.h"
#include "common/core/input_error.h"
#include "common/core/progress.h"
#include "common/image/image_io.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "techniques/layered_em/em_cache.h"

namespace hybridlab {

using cli::numberIn;

namespace {

struct BakeEmOptions {
    std::string scene;
    std::string system;
    std::string cache;
    std::string images;
    int imagesViewpoint = 0;
    bool force = false;
    bool quiet = false;
    bool noPrevention = false;
    bool noOriginImages = false;
    std::string directImages = "auto";
    float viewHeight = 0.0f;
    EmBakeSettings settings;
};

const char* kindName(ShellKind k) {
    return k == ShellKind::Sphere ? "sphere" : k == ShellKind::Quad ? "quad" : "cylinder";
}

void printSummary(const Scene& scene, const LayeredEm& em) {
    std::printf("  layers (EM origin %.3g, %.3g, %.3g):\n", em.center.x, em.center.y, em.center.z);
    for (std::size_t l = 0; l < em.layers.size(); ++l) {
        const EmLayer& layer = em.layers[l];
        std::size_t unobserved = 0;
        for (const EmViewpoint& v : em.viewpoints) unobserved += v.unobservedTexels[l];
        std::printf("    L%zu %-8s mean distance %7.3f  unobserved texels %zu (over %zu viewpoints)  objects:", l + 1,
                    kindName(layer.shell.kind), layer.meanDistance, unobserved, em.viewpoints.size());
        for (std::uint32_t o : layer.objects) std::printf(" %s", scene.objects[o].name.c_str());
        std::printf("\n");
        const Shell& s = layer.shell;
        if (s.kind == ShellKind::Quad)
            std::printf("       quad at (%.3g, %.3g, %.3g), normal (%.3g, %.3g, %.3g), %.3g x %.3g\n", s.planePoint.x, s.planePoint.y,
                        s.planePoint.z, s.planeNormal.x, s.planeNormal.y, s.planeNormal.z, s.extentMax.x - s.extentMin.x,
                        s.extentMax.y - s.extentMin.y);
        else
            std::printf("       radius %.4g\n", s.radius);
    }
}

// --images-viewpoint names one of the system's viewpoint samples, checked before anything is written.
void requireViewpoint(const BakeEmOptions& o, const std::string& system, std::size_t views) {
    if (!o.images.empty() && static_cast<std::size_t>(o.imagesViewpoint) >= views)
        throw InputError("--images-viewpoint: " + std::to_string(o.imagesViewpoint) + " is not a viewpoint sample of lens system '" + system +
                         "', which has " + std::to_string(views) + " (0 to " + std::to_string(views - 1) + ")");
}

// The inferred cube maps of one viewpoint sample, one cross per layer (EXR, and PNG for a look).
void writeLayerImages(const std::filesystem::path& dir, const LayeredEm& em, int viewpoint) {
    createDirectories(dir);
    for (std::size_t l = 0; l < em.layers.size(); ++l) {
        const Image cross = cubeMapCross(em.viewpoints.at(static_cast<std::size_t>(viewpoint)).maps[l]);
        for (const char* ext : {".exr", ".png"}) {
            const auto file = dir / (em.system + "-v" + std::to_string(viewpoint) + "-L" + std::to_string(l + 1) + ext);
            writeImageAtomically(file, cross);
            std::printf("  wrote %s\n", file.string().c_str());
        }
    }
}

void run(BakeEmOptions& o) {
    Scene scene = loadSceneFile(findSceneFile(o.scene));
    auto systems = findLensSystems(scene);
    if (systems.empty()) throw InputError(scene.file.string() + ": the scene has no lens objects (set 'lens = true' on an object)");
    if (!o.system.empty()) {
        std::erase_if(systems, [&](const LensSystemInfo& s) { return s.name != o.system; });
        if (systems.empty()) throw InputError("--system: scene '" + scene.name + "' has no lens system '" + o.system + "'");
    }
    if (o.noOriginImages) o.settings.originImages = false;
    o.settings.directImageSource = directImageSourceNamed(o.directImages);
    if (o.noPrevention) o.settings.disablePrevention();
    if (o.viewHeight != 0.0f) {
        o.settings.viewpoints.height = o.viewHeight;
        o.settings.viewpoints.heightSet = true;
    }
    const std::filesystem::path dir = o.cache.empty() ? defaultLayeredEmCacheDir() : std::filesystem::path(o.cache);
    for (const LensSystemInfo& info : systems) {
        const std::string key = layeredEmCacheKey(scene, info, o.settings);
        const std::filesystem::path file = dir / (key + ".hlem");
        std::printf("lens system %s (%zu objects): %s\n", info.name.c_str(), info.objects.size(), file.string().c_str());
        if (o.settings.directImages)
            std::printf("  direct images from the %s\n",
                        directImageSourceFor(scene, info, o.settings.directImageSource) == DirectImageSource::Origin ? "EM origin (a reflective system)"
                                                                                                                : "viewpoint samples");
        if (!o.force) {
            if (auto cached = findLayeredEm(file, scene, info, o.settings)) {
                std::printf("  in the cache: %zu layers, %zu viewpoints\n", cached->layers.size(), cached->viewpoints.size());
                printSummary(scene, *cached);
                requireViewpoint(o, info.name, cached->viewpoints.size());
                if (!o.images.empty()) writeLayerImages(o.images, *cached, o.imagesViewpoint);
                continue;
            }
        }
        requireWritableLayeredEmCache(dir);  // the entry is what this command makes: fail before the bake
        EmBakeStats stats;
        const LensSystem lens(scene, info);
        const std::size_t views = viewpointSamples(scene, lens.center(), o.settings.viewpoints).size();
        requireViewpoint(o, info.name, views);
        // Figure 2: the greedy two-path model against the full ray tree, on the scene camera's rays.
        const RayQueryComparison q = compareRayQueries(lens.lensRays(), scene.camera, o.settings.width, o.settings.height, o.settings.records.paths);
        std::printf("  ray queries from the scene camera at %dx%d: %llu of %llu rays hit the lens; two greedy paths %llu, full "
                    "ray tree %llu (%.2fx)\n",
                    o.settings.width, o.settings.height, static_cast<unsigned long long>(q.lensHits),
                    static_cast<unsigned long long>(q.cameraRays), static_cast<unsigned long long>(q.pathQueries),
                    static_cast<unsigned long long>(q.treeQueries), q.ratio());
        // Each viewpoint sample twice: its records (the lens images), then the inference of its layers.
        Progress progress(2 * views, o.quiet, "bake step");
        LayeredEm em = bakeLayeredEm(scene, info, o.settings, stats, [&](const std::string& stage, int done, int total) {
            const std::size_t offset = stage == "records" ? 0 : views;
            progress.start(offset + static_cast<std::size_t>(done) - 1, "lens system " + info.name + ", " + stage + " of viewpoint sample " +
                                                                            std::to_string(done) + "/" + std::to_string(total));
        });
        progress.finish();
        writeLayeredEm(file, em);
        std::printf("  baked %zu viewpoints at %dx%d (%dx%d supersampled), cube maps %d texels a side\n", em.viewpoints.size(),
                    o.settings.width, o.settings.height, o.settings.records.supersampling, o.settings.records.supersampling,
                    o.settings.inference.size);
        double total = 0.0;
        for (const auto& [name, ms] : stats.stages) {
            std::printf("  stage %-14s %10.1f ms\n", name.c_str(), ms);
            total += ms;
        }
        std::printf("  total          %10.1f ms\n", total);
        std::printf("  records %llu, lens ray queries %llu, environment ray queries %llu\n",
                    static_cast<unsigned long long>(stats.records), static_cast<unsigned long long>(stats.lensQueries),
                    static_cast<unsigned long long>(stats.environmentQueries));
        std::printf("  tessellation: %llu vertices, %llu triangles (sum over viewpoints); inference: %llu rows, %llu unknowns, <= %d CG "
                    "iterations, relative residual <= %.3g\n",
                    static_cast<unsigned long long>(stats.tessellatedVertices), static_cast<unsigned long long>(stats.tessellatedTriangles),
                    static_cast<unsigned long long>(stats.inferenceRows),
                    static_cast<unsigned long long>(stats.inferenceUnknowns), stats.maxIterations, stats.maxRelativeResidual);
        printSummary(scene, em);
        if (!o.images.empty()) writeLayerImages(o.images, em, o.imagesViewpoint);
    }
}

// The options of `hybridlab bake-em` on `cmd`, and its callback.
void defineCommand(CLI::App& command) {
    auto o = std::make_shared<BakeEmOptions>();
    CLI::App* cmd = &command;
    cmd->add_option("--scene", o->scene, "Scene file, or the name of a built-in scene")->required();
    cmd->add_option("--system", o->system, "Only this lens system (a lens_group, or a lone lens object's name)");
    cmd->add_option("--cache", o->cache, "Cache folder (default: $HYBRIDLAB_CACHE/layered-em or ~/.cache/hybridlab/layered-em)");
    cmd->add_option("--images", o->images, "Also write a viewpoint sample's inferred cube maps (one cross per layer) into this folder");
    cmd->add_option("--images-viewpoint", o->imagesViewpoint, "The viewpoint sample --images writes (0: the first)")->check(CLI::NonNegativeNumber);
    cmd->add_flag("--force", o->force, "Bake even when the cache has the entry");
    cmd->add_flag("--quiet", o->quiet, "No progress bar");
    auto& s = o->settings;
    cmd->add_option("--width", s.width, "Lens image width (pixels)")->check(CLI::Range(8, 4096));
    cmd->add_option("--height", s.height, "Lens image height (pixels)")->check(CLI::Range(8, 4096));
    cmd->add_option("--supersampling", s.records.supersampling, "n x n incoming rays a pixel")->check(CLI::Range(1, 8));
    cmd->add_option("--confidence-angle", s.records.confidenceAngleDegrees,
                    "theta_c of the confidence image (degrees; 0: the paper's 5 at 480 lines, scaled to the lens images' height)")
        ->check(numberIn(0.0, 180.0));
    cmd->add_option("--em-size", s.inference.size, "Cube-map texels a face side")->check(CLI::Range(2, 1024));
    cmd->add_option("--layers", s.layers, "EM layers (0: automatic)")->check(CLI::Range(0, 16));
    cmd->add_option("--max-layers", s.maxLayers, "Most layers the automatic choice takes")->check(CLI::Range(1, 16));
    cmd->add_option("--tau", s.tessellation.tauPixels, "Adaptive tessellation: stop below this edge length (pixels)")->check(numberIn(0.5, 1000.0));
    cmd->add_option("--step", s.viewpoints.stepDegrees, "Viewpoint circle: degrees between samples")->check(numberIn(0.5, 360.0));
    cmd->add_option("--radius", s.viewpoints.radius, "Viewpoint circle radius (0: the scene camera's distance)")->check(numberIn(0.0, 1e6));
    cmd->add_option("--view-height", o->viewHeight, "Viewpoint circle height (world y; default: the scene camera's)")
        ->check(numberIn(-limits::kSceneCoordinate, limits::kSceneCoordinate));
    cmd->add_option("--camera-path", s.viewpoints.cameraPath, "Viewpoint samples: the frames of this camera path instead of a circle");
    cmd->add_option("--frame-stride", s.viewpoints.frameStride, "With --camera-path: every n-th frame")->check(CLI::Range(1, 100000));
    cmd->add_option("--max-viewpoints", s.viewpoints.maxSamples, "Only the first n viewpoint samples (0: all)")->check(CLI::Range(0, 100000));
    cmd->add_option("--neighbours", s.neighbourViewpoints, "Viewpoint samples on each side matched at once")->check(CLI::Range(0, 16));
    cmd->add_option("--direct-images", o->directImages,
                    "Where direct images look from: auto (the EM origin for a reflective system, the viewpoint for a refractive one, §4.3), "
                    "viewpoint or origin")
        ->check(CLI::IsMember({"auto", "viewpoint", "origin"}));
    cmd->add_flag("--no-origin-images", o->noOriginImages, "No fill from the EM origin's images where no lens image reads");
    cmd->add_flag("--no-prevention", o->noPrevention, "No EM disocclusion prevention: first hits only, one viewpoint, no direct images");
    cmd->callback([o, cmd] {
        // --max-layers bounds the automatic choice only: beside a count it would be ignored.
        if (cmd->count("--max-layers") > 0 && o->settings.layers > 0)
            throw InputError("--max-layers " + std::to_string(o->settings.maxLayers) + " bounds the automatic choice (--layers 0); with --layers " +
                             std::to_string(o->settings.layers) + " it would be ignored");
        run(*o);
    });
}

}  // namespace

CacheBakeCommand emBakeCommand() {
    return {"bake-em", "Bake the layered environment maps of a scene's lens systems (Hakura & Snyder 2001) into the cache", defineCommand};
}

}  // namespace hybridlab
