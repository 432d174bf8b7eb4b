// Baking layered EMs end to end (Hakura & Snyder 2001 §4, §6): on the paper's teapot-lens scene
// the clustering finds the cup, the columns and the walls as the teapot's three layers (Figure 7),
// and disocclusion prevention leaves fewer texels unobserved than single-viewpoint inference; the
// cache round-trips an entry exactly; viewpoint samples and the bake-em command.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include "common/core/input_error.h"
#include "common/scene/scene_file.h"
#include "techniques/layered_em/em_cache.h"
#include "techniques/shared/lens_system.h"
#include "tests/support/cli_runner.h"
#include "tests/support/scene_fixtures.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

EmBakeSettings smallBake() {
    EmBakeSettings s;
    s.width = 48;
    s.height = 36;
    s.records.supersampling = 2;
    s.records.maxHitsPerRay = 4;
    s.viewpoints.stepDegrees = 45.0f;
    s.inference.size = 8;
    s.layers = 3;
    return s;
}

std::size_t objectIndex(const Scene& s, const std::string& name) {
    for (std::size_t i = 0; i < s.objects.size(); ++i)
        if (s.objects[i].name == name) return i;
    ADD_FAILURE() << name;
    return 0;
}

TEST(EmBake, TeapotLayersAreCupColumnsWallsAndPreventionFillsTexels) {
    Scene scene = loadSceneFile(test::builtinSceneFile("teapot-lens"), {.loadTextures = false});
    auto systems = findLensSystems(scene);
    ASSERT_EQ(systems.size(), 2u) << "the teapot and the cup are two lens systems";
    ASSERT_EQ(systems[0].name, "teapot");
    EmBakeSettings settings = smallBake();
    EmBakeStats stats;
    LayeredEm em = bakeLayeredEm(scene, systems[0], settings, stats);
    ASSERT_EQ(em.layers.size(), 3u);
    ASSERT_EQ(em.viewpoints.size(), 8u);
    auto layerOf = [&](const std::string& name) {
        const std::uint32_t o = static_cast<std::uint32_t>(objectIndex(scene, name));
        for (std::size_t l = 0; l < em.layers.size(); ++l)
            for (std::uint32_t x : em.layers[l].objects)
                if (x == o) return static_cast<int>(l);
        return -1;
    };
    EXPECT_EQ(layerOf("cup"), 0);
    for (int c = 0; c < 8; ++c) EXPECT_EQ(layerOf("column-" + std::to_string(c)), 1) << c;
    for (const char* w : {"wall-north", "wall-south", "wall-east", "wall-west"}) EXPECT_EQ(layerOf(w), 2) << w;
    EXPECT_LT(em.layers[0].meanDistance, em.layers[1].meanDistance);
    EXPECT_LT(em.layers[1].meanDistance, em.layers[2].meanDistance);
    std::string kinds;
    for (const EmLayer& l : em.layers) kinds += l.shell.kind == ShellKind::Sphere ? "S" : l.shell.kind == ShellKind::Quad ? "Q" : "C";
    RecordProperty("shell_kinds", kinds);
    EXPECT_EQ(kinds, "QCS") << "Figure 7: a quad for the sparse cup layer, a cylinder for the columns, a sphere for the walls";
    EXPECT_LT(stats.maxRelativeResidual, 1e-3);
    // The quad's texture is its rectangle: a texel no ray from the origin meets within it (with two
    // texels' margin) stays empty, though rays travelling away from the plane are forced onto it.
    const int size = settings.inference.size;
    std::size_t heldTexels = 0;
    for (const EmViewpoint& v : em.viewpoints) {
        for (std::uint32_t t = 0; t < cubeMapLevelOffset(size, 1); ++t) {
            const bool held = shellHolds(em.layers[0].shell, cubeMapTexelDirection(t, size), 2.0f * glm::half_pi<float>() / static_cast<float>(size));
            heldTexels += held ? 1 : 0;
            if (!held) {
                ASSERT_EQ(v.maps[0].texels[t], glm::vec4(0.0f)) << t;
            }
        }
    }
    EXPECT_GT(heldTexels, 0u);

    EmBakeSettings single = settings;
    single.disablePrevention();
    EmBakeStats singleStats;
    LayeredEm without = bakeLayeredEm(scene, systems[0], single, singleStats);
    ASSERT_EQ(without.layers.size(), em.layers.size());
    std::size_t unobservedWith = 0, unobservedWithout = 0;
    for (const EmViewpoint& v : em.viewpoints)
        for (std::size_t u : v.unobservedTexels) unobservedWith += u;
    for (const EmViewpoint& v : without.viewpoints)
        for (std::size_t u : v.unobservedTexels) unobservedWithout += u;
    RecordProperty("unobserved_with_prevention", std::to_string(unobservedWith));
    RecordProperty("unobserved_without_prevention", std::to_string(unobservedWithout));
    EXPECT_LT(unobservedWith, unobservedWithout);
}

// The viewpoint samples circle in one plane, so the cup's reflections never show the top of the
// column beside it (53 degrees up from the cup); the images from the EM origin fill that part of
// the column's layer, and only what the viewpoints left empty. (The cup's own direct images come
// from the origin, which would see the top too: here they come from the viewpoints, as a refractive
// system's do.)
TEST(EmBake, OriginImagesFillWhatNoViewpointSampleSaw) {
    Scene scene = loadSceneFile(test::builtinSceneFile("teapot-lens"), {.loadTextures = false});
    auto systems = findLensSystems(scene);
    ASSERT_EQ(systems[1].name, "cup");
    EmBakeSettings settings = smallBake();
    settings.directImageSource = DirectImageSource::Viewpoint;
    settings.viewpoints.maxSamples = 2;
    settings.inference.size = 16;
    EmBakeStats stats;
    const LayeredEm with = bakeLayeredEm(scene, systems[1], settings, stats);
    settings.originImages = false;
    const LayeredEm without = bakeLayeredEm(scene, systems[1], settings, stats);
    ASSERT_EQ(with.layers.size(), without.layers.size());
    const std::uint32_t column = static_cast<std::uint32_t>(objectIndex(scene, "column-0"));
    std::size_t layer = with.layers.size();
    for (std::size_t l = 0; l < with.layers.size(); ++l)
        for (std::uint32_t o : with.layers[l].objects)
            if (o == column) layer = l;
    ASSERT_LT(layer, with.layers.size());
    // Near the column's top (at 2 above its centre): about 8 degrees below it as the origin sees it, a
    // texel and a half at 16 texels a face, where a bilinear lookup reads the column alone.
    const glm::vec3 columnTop = scene.objects[column].transform.position + glm::vec3(0.0f, 1.0f, 0.0f);
    const Shell& shell = with.layers[layer].shell;
    EXPECT_EQ(shell.kind, ShellKind::Cylinder) << "the column's layer, by the column's shape rather than the band the samples saw";
    const glm::vec3 index = shellTextureDirection(shell, with.center, glm::normalize(columnTop - with.center));
    const CubeMapLookup lookup = cubeMapLookup(index, settings.inference.size);
    const float alphaWith = with.viewpoints[0].maps[layer].sample(lookup).a;
    const float alphaWithout = without.viewpoints[0].maps[layer].sample(lookup).a;
    RecordProperty("column_top_alpha_with", std::to_string(alphaWith));
    RecordProperty("column_top_alpha_without", std::to_string(alphaWithout));
    EXPECT_GT(alphaWith, 0.9f) << "the origin sees the column's top";
    EXPECT_LT(alphaWithout, 0.05f) << "no viewpoint sample saw it";
    std::size_t unobservedWith = 0, unobservedWithout = 0;
    for (std::size_t v = 0; v < with.viewpoints.size(); ++v) {
        for (std::size_t l = 0; l < with.layers.size(); ++l) {
            unobservedWith += with.viewpoints[v].unobservedTexels[l];
            unobservedWithout += without.viewpoints[v].unobservedTexels[l];
        }
    }
    EXPECT_LT(unobservedWith, unobservedWithout);
}

// §4.3's direct images observe what the lens images missed. Where a direct ray from the EM origin
// reaches the sky, each layer it did not meet is empty along it, and the direct image says so:
// with only the rays that met a wall observed, the inference spreads the wall's top edge into the
// sky by the regulariser's reach, and a cup's flat top, seen from above the samples' plane,
// reflects wall where the sky is. And every object the direct images see has a layer, although the
// two viewpoint samples' lens images meet only some of the walls.
TEST(EmBake, DirectImagesSayWhereALayerIsEmptyAndGiveWhatTheySeeALayer) {
    Scene scene = loadSceneFile(test::builtinSceneFile("teapot-lens"), {.loadTextures = false});
    auto systems = findLensSystems(scene);
    ASSERT_EQ(systems[1].name, "cup");
    EmBakeSettings settings = smallBake();
    settings.viewpoints.maxSamples = 2;
    settings.inference.size = 32;
    EmBakeStats stats;
    const LayeredEm em = bakeLayeredEm(scene, systems[1], settings, stats);
    for (const char* wall : {"wall-north", "wall-south", "wall-east", "wall-west"}) {
        const std::uint32_t o = static_cast<std::uint32_t>(objectIndex(scene, wall));
        bool found = false;
        for (const EmLayer& layer : em.layers) found = found || std::find(layer.objects.begin(), layer.objects.end(), o) != layer.objects.end();
        EXPECT_TRUE(found) << wall << " has no layer";
    }
    // Level-0 texels of the outermost layer along which the EM origin sees the sky, and of those the
    // ones the inferred map makes opaque.
    const LensSystem system(scene, systems[1]);
    const std::size_t last = em.layers.size() - 1;
    std::size_t sky = 0, skyOpaque = 0;
    for (std::uint32_t t = 0; t < cubeMapLevelOffset(settings.inference.size, 1); ++t) {
        SurfaceHit hit;
        if (system.environmentRays().intersect({em.center, glm::normalize(cubeMapTexelDirection(t, settings.inference.size))}, 0.0f, std::numeric_limits<float>::infinity(), hit))
            continue;
        ++sky;
        skyOpaque += em.viewpoints[0].maps[last].texels[t].a > 0.5f;
    }
    RecordProperty("sky_texels_opaque", std::to_string(skyOpaque) + " of " + std::to_string(sky));
    EXPECT_GT(sky, 1000u);
    EXPECT_LT(skyOpaque, 10u);
}

// Whether the ray from `origin` along `direction` passes through `box` grown by `margin`.
bool rayMeetsBox(glm::vec3 origin, glm::vec3 direction, Aabb box, float margin) {
    box.lo -= glm::vec3(margin);
    box.hi += glm::vec3(margin);
    float t0 = 0.0f, t1 = std::numeric_limits<float>::max();
    for (int a = 0; a < 3; ++a) {
        if (std::abs(direction[a]) < 1e-8f) {
            if (origin[a] < box.lo[a] || origin[a] > box.hi[a]) return false;
            continue;
        }
        float ta = (box.lo[a] - origin[a]) / direction[a], tb = (box.hi[a] - origin[a]) / direction[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 <= t1;
}

// §4.3: "Direct images from the lens object center tend to work better for reflective objects
// while direct images from the viewpoint are better suited for refractive (transparent) objects."
// A direct image from a viewpoint far from a reflective cup indexes its layer where the viewpoint's
// ray meets the shell, so a nearby object (the teapot, a column) lands in directions where the cup
// never sees it. From the EM origin a direct ray's direction is the texel's own.
TEST(EmBake, ReflectiveSystemsTakeDirectImagesFromTheOrigin) {
    Scene scene = loadSceneFile(test::builtinSceneFile("teapot-lens"), {.loadTextures = false});
    auto systems = findLensSystems(scene);
    ASSERT_EQ(systems[0].name, "teapot");
    ASSERT_EQ(systems[1].name, "cup");
    EXPECT_EQ(directImageSourceFor(scene, systems[0], DirectImageSource::Automatic), DirectImageSource::Viewpoint) << "glass refracts";
    EXPECT_EQ(directImageSourceFor(scene, systems[1], DirectImageSource::Automatic), DirectImageSource::Origin) << "the cup only reflects";
    EXPECT_EQ(directImageSourceFor(scene, systems[1], DirectImageSource::Viewpoint), DirectImageSource::Viewpoint);
    EXPECT_EQ(directImageSourceNamed("origin"), DirectImageSource::Origin);
    EXPECT_THROW(directImageSourceNamed("centre"), std::invalid_argument);

    EmBakeSettings settings = smallBake();
    settings.viewpoints.maxSamples = 2;
    settings.inference.size = 16;
    settings.originImages = false;  // the direct images alone
    EmBakeStats stats;
    settings.directImageSource = DirectImageSource::Viewpoint;
    const LayeredEm fromViewpoint = bakeLayeredEm(scene, systems[1], settings, stats);
    settings.directImageSource = DirectImageSource::Automatic;
    const LayeredEm fromOrigin = bakeLayeredEm(scene, systems[1], settings, stats);
    EXPECT_NE(layeredEmCacheKey(scene, systems[1], settings), layeredEmCacheKey(scene, systems[1], [&] {
                  EmBakeSettings v = settings;
                  v.directImageSource = DirectImageSource::Viewpoint;
                  return v;
              }()));
    ASSERT_EQ(fromViewpoint.layers.size(), fromOrigin.layers.size());
    // Level-0 texels of the nearest layer that are opaque although the ray from the EM origin along
    // the texel passes nowhere near the layer's objects (their boxes grown by about two texels).
    const int size = settings.inference.size;
    std::size_t originOpaque = 0;
    auto misplaced = [&](const LayeredEm& em, std::size_t& opaque) {
        const EmLayer& layer = em.layers[0];
        std::size_t count = 0;
        opaque = 0;
        for (std::uint32_t t = 0; t < cubeMapLevelOffset(size, 1); ++t) {
            if (em.viewpoints[0].maps[0].texels[t].a < 0.5f) continue;
            ++opaque;
            const glm::vec3 d = glm::normalize(cubeMapTexelDirection(t, size));
            bool explained = false;
            for (std::uint32_t o : layer.objects) {
                const Aabb box = scene.objectBounds(o, 0.0);
                const float margin = glm::length(box.center() - em.center) * 2.0f * glm::half_pi<float>() / static_cast<float>(size);
                explained = explained || rayMeetsBox(em.center, d, box, margin);
            }
            count += !explained;
        }
        return count;
    };
    std::size_t viewpointOpaque = 0;
    const std::size_t viewpointMisplaced = misplaced(fromViewpoint, viewpointOpaque), originMisplaced = misplaced(fromOrigin, originOpaque);
    RecordProperty("misplaced_texels_viewpoint", std::to_string(viewpointMisplaced) + " of " + std::to_string(viewpointOpaque));
    RecordProperty("misplaced_texels_origin", std::to_string(originMisplaced) + " of " + std::to_string(originOpaque));
    // The texels along which the origin sees the layer's objects first (the teapot, column-0).
    const LensSystem system(scene, systems[1]);
    std::size_t covered = 0;
    for (std::uint32_t t = 0; t < cubeMapLevelOffset(size, 1); ++t) {
        SurfaceHit hit;
        if (!system.environmentRays().intersect({fromOrigin.center, glm::normalize(cubeMapTexelDirection(t, size))}, 0.0f,
                                                 std::numeric_limits<float>::infinity(), hit))
            continue;
        const std::vector<std::uint32_t>& objects = fromOrigin.layers[0].objects;
        covered += std::find(objects.begin(), objects.end(), system.environmentObject(hit.object)) != objects.end();
    }
    RecordProperty("texels_the_origin_sees_the_layer_in", std::to_string(covered));
    EXPECT_GT(covered, 20u) << "the layer holds the teapot and a column";
    EXPECT_GT(originOpaque * 10, covered * 8) << "what the origin sees of the layer is opaque";
    EXPECT_LT(originMisplaced * 10, originOpaque);
    EXPECT_GT(viewpointMisplaced, 10 * originMisplaced);
}

TEST(EmBake, CacheRoundTripsAndKeysFollowSettings) {
    Scene scene = loadSceneFile(test::builtinSceneFile("teapot-lens"), {.loadTextures = false});
    auto systems = findLensSystems(scene);
    EmBakeSettings settings = smallBake();
    settings.viewpoints.maxSamples = 2;
    settings.width = 24;
    settings.height = 18;
    settings.layers = 2;
    EmBakeStats stats;
    LayeredEm em = bakeLayeredEm(scene, systems[1], settings, stats);
    ASSERT_EQ(em.viewpoints.size(), 2u);
    test::TempDir dir;
    const std::string key = layeredEmCacheKey(scene, systems[1], settings);
    EmBakeSettings other = settings;
    other.inference.size = 16;
    EXPECT_NE(key, layeredEmCacheKey(scene, systems[1], other));
    other = settings;
    other.originImages = false;
    EXPECT_NE(key, layeredEmCacheKey(scene, systems[1], other));
    EXPECT_NE(key, layeredEmCacheKey(scene, systems[0], settings));
    EXPECT_EQ(key, layeredEmCacheKey(scene, systems[1], settings));
    const auto file = dir / (key + ".hlem");
    const CachedLayeredEm absent = readLayeredEm(file, scene, systems[1], settings);
    EXPECT_FALSE(absent.em.has_value());
    EXPECT_EQ(absent.problem, "") << "no file is a plain miss";
    writeLayeredEm(file, em);
    const CachedLayeredEm cached = readLayeredEm(file, scene, systems[1], settings);
    ASSERT_TRUE(cached.em.has_value()) << "a bake passes the cache's check of its entry: " << cached.problem;
    const LayeredEm& back = *cached.em;
    EXPECT_EQ(back.system, "cup");
    ASSERT_EQ(back.layers.size(), em.layers.size());
    EXPECT_EQ(back.layers[1].objects, em.layers[1].objects);
    EXPECT_EQ(back.layers[0].shell.radius, em.layers[0].shell.radius);
    ASSERT_EQ(back.viewpoints.size(), 2u);
    EXPECT_EQ(back.viewpoints[1].maps[1].texels, em.viewpoints[1].maps[1].texels);
    EXPECT_EQ(back.viewpoints[1].camera.position, em.viewpoints[1].camera.position);
    EmBakeSettings larger = settings;
    larger.inference.size = 16;
    EXPECT_FALSE(readLayeredEm(file, scene, systems[1], larger).em.has_value()) << "an entry of 8-texel maps is no 16-texel bake";
}

}  // namespace
}  // namespace hybridlab

namespace hybridlab {
namespace {

TEST(EmBake, BakeEmCommandBakesCachesAndRejectsBadInput) {
    test::TempDir dir;
    const std::string cache = (dir / "cache").string();
    const std::vector<std::string> quick = {"bake-em", "--scene", "teapot-lens", "--system", "cup", "--cache", cache,
                                            "--width", "32", "--height", "24", "--supersampling", "1", "--em-size", "4",
                                            "--max-viewpoints", "2", "--layers", "2"};
    auto results = test::runHybridlabAll({{quick, {}},
                                          {{"bake-em", "--scene", "teapot-lens", "--system", "vase", "--cache", cache}, {}},
                                          {{"bake-em", "--scene", "whitted-classic", "--cache", cache}, {}},
                                          {{"bake-em", "--scene", "teapot-lens", "--em-size", "1", "--cache", cache}, {}},
                                          {{"bake-em", "--scene", "teapot-lens", "--direct-images", "centre", "--cache", cache}, {}}});
    EXPECT_EQ(results[0].exitStatus, 0) << results[0].err;
    EXPECT_CONTAINS(results[0].out, "lens system cup (1 objects)");
    EXPECT_CONTAINS(results[0].out, "stage inference");
    EXPECT_CONTAINS(results[0].out, "full ray tree");
    EXPECT_CONTAINS(results[0].out, "direct images from the EM origin (a reflective system)");
    // Without a terminal, a progress line a step, saying what it bakes: each viewpoint sample's
    // records, then its inference.
    EXPECT_CONTAINS(results[0].err, "bake step 1/4 (left ?): lens system cup, records of viewpoint sample 1/2\n");
    EXPECT_CONTAINS(results[0].err, "bake step 4/4");
    EXPECT_CONTAINS(results[0].err, "lens system cup, inference of viewpoint sample 2/2\n");
    EXPECT_EQ(results[1].exitStatus, 2);
    EXPECT_CONTAINS(results[1].err, "has no lens system 'vase'");
    EXPECT_EQ(results[2].exitStatus, 2);
    EXPECT_CONTAINS(results[2].err, "the scene has no lens objects");
    EXPECT_EQ(results[3].exitStatus, 2);
    EXPECT_EQ(results[4].exitStatus, 2);
    EXPECT_CONTAINS(results[4].err, "--direct-images");
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(cache), std::filesystem::directory_iterator()), 1)
        << "one entry; bad input writes nothing";
    // The second run finds the entry, and writes a chosen viewpoint sample's cube maps; one that
    // is not a sample writes nothing.
    const std::string images = (dir / "images").string();
    std::vector<std::string> second = quick, past = quick;
    second.insert(second.end(), {"--images", images, "--images-viewpoint", "1"});
    past.insert(past.end(), {"--images", images, "--images-viewpoint", "2"});
    auto again = test::runHybridlabAll({{past, {}}, {second, {}}});
    EXPECT_EQ(again[0].exitStatus, 2);
    EXPECT_CONTAINS(again[0].err, "--images-viewpoint: 2 is not a viewpoint sample of lens system 'cup', which has 2 (0 to 1)");
    EXPECT_EQ(again[1].exitStatus, 0) << again[1].err;
    EXPECT_CONTAINS(again[1].out, "in the cache: 2 layers, 2 viewpoints");
    for (const char* layer : {"L1", "L2"}) EXPECT_TRUE(std::filesystem::exists(dir / "images" / (std::string("cup-v1-") + layer + ".exr"))) << layer;
}

}  // namespace
}  // namespace hybridlab

namespace hybridlab {
namespace {

TEST(EmBake, ViewpointSamplesCircleTheLensOrFollowACameraPath) {
    test::SceneBuilder b;
    b.object("ball", makeSphere(8, 4), b.material(test::matte(glm::vec3(0.5f))));
    Scene& s = b.scene();
    s.camera.position = {1.0f, 2.0f, 5.0f};
    s.camera.fovYDegrees = 33.0f;
    const glm::vec3 center(1.0f, 0.5f, 1.0f);
    auto circle = viewpointSamples(s, center, {});
    ASSERT_EQ(circle.size(), 45u) << "every 8 degrees";
    EXPECT_VEC_NEAR(circle[0].position, s.camera.position, 1e-5f) << "starts at the scene camera's bearing";
    for (const Camera& c : circle) {
        EXPECT_NEAR(std::hypot(c.position.x - center.x, c.position.z - center.z), 4.0f, 1e-4f);
        EXPECT_NEAR(c.position.y, 2.0f, 1e-6f);
        EXPECT_VEC_NEAR(c.forward(), glm::normalize(center - c.position), 1e-5f);
        EXPECT_EQ(c.fovYDegrees, 33.0f);
    }
    const glm::vec3 a = circle[1].position - center, c0 = circle[0].position - center;
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(glm::normalize(glm::vec2(a.x, a.z)), glm::normalize(glm::vec2(c0.x, c0.z))))), 8.0f, 1e-3f);

    ViewpointSettings v;
    v.stepDegrees = 90.0f;
    v.radius = 2.0f;
    v.height = -1.0f;
    v.heightSet = true;
    v.maxSamples = 3;
    auto few = viewpointSamples(s, center, v);
    ASSERT_EQ(few.size(), 3u);
    EXPECT_FALSE(v.closed()) << "a cut circle does not wrap around";
    EXPECT_VEC_NEAR(few[1].position, glm::vec3(3.0f, -1.0f, 1.0f), 1e-5f);

    CameraPath path;
    path.name = "line";
    path.interpolation = Interpolation::Linear;
    path.times = {0.0, 1.0};
    path.positions = {{0, 1, 5}, {4, 1, 5}};
    path.targets = {{0, 0, 0}, {0, 0, 0}};
    path.framesPerSecond = 4.0;
    s.cameraPaths.push_back(path);
    ViewpointSettings onPath;
    onPath.cameraPath = "line";
    onPath.frameStride = 2;
    auto frames = viewpointSamples(s, center, onPath);
    ASSERT_EQ(frames.size(), 3u) << "frames 0, 2, 4 of 5";
    EXPECT_VEC_NEAR(frames[1].position, glm::vec3(2, 1, 5), 1e-5f);
    onPath.cameraPath = "circle";
    EXPECT_THROW(viewpointSamples(s, center, onPath), InputError);
}

}  // namespace
}  // namespace hybridlab
