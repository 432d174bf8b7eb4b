// EM inference (Hakura & Snyder 2001 §4.3): the rendering matrix reproduces what the renderer
// draws from the tessellated lens, and inference recovers a known environment: a mirror sphere in
// an environment that is exactly a smoothly textured sphere at the shell radius.
#include <array>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "techniques/layered_em/em_inference.h"
#include "techniques/layered_em/outgoing_records.h"
#include "tests/support/lens_test_scenes.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

// The known environment: premultiplied RGBA by direction from the EM origin.
glm::vec4 environmentTexture(glm::vec3 d) {
    d = glm::normalize(d);
    return {0.5f + 0.35f * std::sin(1.5f * d.x) * std::cos(1.2f * d.y), 0.5f + 0.3f * d.z * d.y,
            0.4f + 0.3f * std::cos(2.0f * d.x + d.z), 1.0f};
}

struct MirrorSetup {
    Scene scene;
    std::unique_ptr<LensSystem> system;
    Camera camera = test::lookingAt({0, 0.5f, 4}, {0, 0, 0}, 35.0f);
    int width = 64, height = 64;
    TessellatedLens lens;
    LensRaster raster;
    Shell shell;

    MirrorSetup() {
        test::SceneBuilder b;
        Material mirror;
        mirror.reflectivity = 1.0f;
        b.object("ball", makeSphere(32, 16), b.material(mirror), test::placed({0, 0, 0}, glm::vec3(2.0f)));
        b.scene().objects[0].lens = true;
        scene = b.scene();
        system = std::make_unique<LensSystem>(scene, findLensSystems(scene).at(0));
        TessellationSettings ts;
        ts.tauPixels = 2.0f;
        lens = tessellateLens(*system, buildLensMesh(*system), camera, width, height, ts);
        raster = rasterizeLens(positionsOf(lens), lens.triangles, camera, width, height);
        shell.center = system->center();
        shell.radius = 5.0f;
    }
    static std::vector<glm::vec3> positionsOf(const TessellatedLens& l) {
        std::vector<glm::vec3> p;
        for (const LensVertex& v : l.vertices) p.push_back(v.position);
        return p;
    }
};

TEST(EmInference, RenderingMatrixReproducesTheRenderer) {
    MirrorSetup s;
    const int size = 16;
    const LayerTextureIndex dirs = vertexTextureIndex(s.lens, PathTerm::Reflection, s.shell,
                                                      textureLodEdges(s.lens, PathTerm::Reflection, lensVertexPixels(s.lens, s.camera, s.width, s.height)), size);
    std::vector<glm::vec4> zero(s.raster.triangle.size(), glm::vec4(0.0f));
    std::vector<float> ones(s.raster.triangle.size(), 1.0f);
    EmObservation o = lensObservation(s.raster, s.lens.triangles, dirs, zero, ones, size);
    std::size_t covered = 0;
    for (std::size_t i = 0; i < s.raster.triangle.size(); ++i) covered += s.raster.covered(i);
    EXPECT_EQ(o.lookups.size(), covered);
    EXPECT_GT(covered, 1000u);

    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    LayerCubeMap em(size);
    for (glm::vec4& t : em.texels) t = {u(rng), u(rng), u(rng), u(rng)};
    Eigen::SparseMatrix<double, Eigen::RowMajor> a = renderingMatrix(o, size);
    std::vector<glm::vec4> drawn = drawLayer(s.raster, s.lens.triangles, dirs, em);
    for (int c = 0; c < 4; ++c) {
        Eigen::VectorXd x(static_cast<Eigen::Index>(em.texels.size()));
        for (std::size_t t = 0; t < em.texels.size(); ++t) x[static_cast<Eigen::Index>(t)] = em.texels[t][c];
        Eigen::VectorXd ax = a * x;
        double maxDiff = 0.0;
        for (std::size_t r = 0; r < o.pixels.size(); ++r) maxDiff = std::max(maxDiff, std::abs(ax[static_cast<Eigen::Index>(r)] - drawn[o.pixels[r]][c]));
        EXPECT_LT(maxDiff, 1e-4) << "channel " << c;
    }
}

TEST(EmInference, RecoversAKnownEnvironment) {
    MirrorSetup s;
    const int size = 16;
    // b: the supersampled two-term image of the mirror with the outgoing rays looked up in the
    // known environment where they meet the sphere of radius 5.
    LayerImageAccumulator acc(s.width, s.height);
    LensRayCounter counter;
    const float aspect = 1.0f;
    for (int y = 0; y < s.height; ++y) {
        for (int x = 0; x < s.width; ++x) {
            for (int k = 0; k < 9; ++k) {
                glm::vec2 ndc = subpixelNdc(x, y, k, 3, s.width, s.height);
                TwoTermPaths p;
                if (!traceTwoTermPaths(s.system->lensRays(), s.camera.rayThroughNdc(ndc, aspect), {}, counter, p)) continue;
                const LensPath& r = p.reflection();
                glm::vec3 hit = shellPoint(s.shell, r.exitOrigin, r.exitDirection);
                acc.add(x, y, r.exitDirection, environmentTexture(hit - s.shell.center));
            }
        }
    }
    std::vector<glm::vec4> b;
    std::vector<float> confidence;
    acc.finish(b, confidence);
    const LayerTextureIndex dirs = vertexTextureIndex(s.lens, PathTerm::Reflection, s.shell,
                                                      textureLodEdges(s.lens, PathTerm::Reflection, lensVertexPixels(s.lens, s.camera, s.width, s.height)), size);
    EmInferenceSettings settings;
    settings.size = size;
    EmInferenceResult r = inferLayerEm({lensObservation(s.raster, s.lens.triangles, dirs, b, confidence, size)}, settings);
    EXPECT_LT(r.relativeResidual, 1e-5);
    // A direction is seen when a texel covering it is observed at some level (the ball minifies its
    // environment towards the silhouette, where the coarser levels hold the rows).
    std::size_t seenDirections = 0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                bool seen = false;
                for (int k = 0; k < cubeMapLevels(size); ++k) seen = seen || r.observed[cubeMapTexelIndex({k, f, i >> k, j >> k}, size)];
                seenDirections += seen;
            }
    EXPECT_GT(seenDirections, 6u * size * size / 4) << "a mirror ball shows much of its environment";
    double se = 0.0;
    std::size_t n = 0;
    for (std::size_t t = 0; t < r.em.texels.size(); ++t) {
        if (!r.observed[t]) continue;
        glm::vec4 d = r.em.texels[t] - environmentTexture(cubeMapTexelDirection(static_cast<std::uint32_t>(t), size));
        se += glm::dot(d, d) / 4.0;
        ++n;
    }
    const double rmse = std::sqrt(se / static_cast<double>(n));
    EXPECT_LT(rmse, 0.02);
    RecordProperty("rmse", std::to_string(rmse));
    RecordProperty("observed_texels", std::to_string(r.observedTexels));
    RecordProperty("iterations", r.iterations);
}

// Two rows: texel A alone (target 0.5), and A with a 5% bilinear share of texel B (target 0.8).
// Plain least squares fits both exactly with B = (0.8 - 0.95 * 0.5) / 0.05 = 6.5, a value no
// texture holds; damping towards the mean target of each texel keeps B near what reads it, and the
// clamp keeps alpha a coverage.
TEST(EmInference, DampingKeepsAWeaklyObservedTexelNearItsTargets) {
    const int size = 2;
    EmObservation o;
    auto row = [&](std::array<CubeMapTap, 2> taps, float target) {
        CubeMapLookup l;
        l.taps[0] = taps[0];
        l.taps[1] = taps[1];
        o.lookups.push_back(l);
        o.targets.push_back(glm::vec4(target));
        o.confidence.push_back(1.0f);
        o.pixels.push_back(static_cast<std::uint32_t>(o.pixels.size()));
    };
    row({CubeMapTap{0, 1.0f}, CubeMapTap{1, 0.0f}}, 0.5f);
    row({CubeMapTap{0, 0.95f}, CubeMapTap{1, 0.05f}}, 0.8f);
    EmInferenceSettings settings;
    settings.size = size;
    settings.tolerance = 1e-12;
    settings.maxIterations = 10000;
    settings.smoothness = 0.0;
    settings.pyramid = 0.0;
    settings.damping = 0.0;
    EmInferenceResult plain = inferLayerEm({o}, settings);
    EXPECT_NEAR(plain.em.texels[0].r, 0.5f, 1e-3f);
    EXPECT_GT(plain.em.texels[1].r, 6.0f) << "least squares alone swings the weak texel";
    EXPECT_FLOAT_EQ(plain.em.texels[1].a, 1.0f) << "alpha clamped to a coverage";

    settings.damping = EmInferenceSettings{}.damping;
    EmInferenceResult damped = inferLayerEm({o}, settings);
    EXPECT_NEAR(damped.em.texels[0].r, 0.65f, 0.15f);
    EXPECT_NEAR(damped.em.texels[1].r, 0.8f, 0.3f);
}

TEST(EmInference, SolvesOnlyNearWhatTheImagesSeeAndLeavesTheRestEmpty) {
    // A uniform environment seen in a small cone: the solve carries a small part of the chain, which
    // takes that colour; texels far from every row stay transparent.
    const int size = 32;
    const glm::vec4 colour(0.2f, 0.4f, 0.6f, 1.0f);
    EmObservation o;
    for (int y = 0; y < 12; ++y) {
        for (int x = 0; x < 12; ++x) {
            o.lookups.push_back(cubeMapLookup(glm::vec3(0.02f * static_cast<float>(x - 6), 0.02f * static_cast<float>(y - 6), 1.0f), size, 0.0f));
            o.targets.push_back(colour);
            o.confidence.push_back(1.0f);
            o.pixels.push_back(static_cast<std::uint32_t>(o.pixels.size()));
        }
    }
    EmInferenceSettings settings;
    settings.size = size;
    const EmInferenceResult r = inferLayerEm({o}, settings);
    EXPECT_GT(r.activeTexels, r.observedTexels);
    EXPECT_LT(r.activeTexels, cubeMapTexelCount(size) / 20);
    float worstSeen = 0.0f;
    for (std::size_t t = 0; t < r.observed.size(); ++t) {
        if (r.observed[t]) worstSeen = std::max(worstSeen, glm::length(r.em.texels[t] - colour));
    }
    EXPECT_LT(worstSeen, 1e-3f);
    EXPECT_EQ(r.em.texels[cubeMapTexelIndex({0, 1, 16, 16}, size)], glm::vec4(0.0f)) << "-X, never seen";
    EXPECT_EQ(r.em.texels[cubeMapTexelIndex({0, 4, 0, 0}, size)], glm::vec4(0.0f)) << "+Z corner, beyond the ring";

    // Texels the impostor cannot hold (a quad outside its rectangle) stay empty even where rows
    // read them; the rest still take the colour.
    std::vector<bool> holds(cubeMapTexelCount(size), true);
    std::size_t dropped = 0;
    for (std::size_t t = 0; t < holds.size(); ++t) {
        if (r.observed[t] && cubeMapTexelDirection(static_cast<std::uint32_t>(t), size).x > 0.0f) {
            holds[t] = false;
            ++dropped;
        }
    }
    ASSERT_GT(dropped, 0u);
    const EmInferenceResult held = inferLayerEm({o}, settings, holds);
    for (std::size_t t = 0; t < holds.size(); ++t) {
        if (!holds[t]) {
            ASSERT_EQ(held.em.texels[t], glm::vec4(0.0f)) << t;
        }
    }
    EXPECT_LT(held.activeTexels, r.activeTexels);
    EXPECT_LT(glm::length(held.em.texels[cubeMapTexelIndex({0, 4, 14, 16}, size)] - colour), 0.1f)
        << "+Z, left of the centre: held (a little off the colour: its rows and smoothness reach the empty half)";

    // A layer no image of the window saw (rows of no pixel): an empty map, nothing to solve.
    const EmInferenceResult none = inferLayerEm({EmObservation{}}, settings);
    EXPECT_EQ(none.activeTexels, 0u);
    EXPECT_EQ(none.rows, 0u);
    for (const glm::vec4& t : none.em.texels) ASSERT_EQ(t, glm::vec4(0.0f));
}

TEST(EmInference, ConfidenceAngleIsThePapersScaledToTheBakesLines) {
    EXPECT_FLOAT_EQ(confidenceAngle(0.0f, 480), 5.0f);  // §4.3 at the paper's 640 x 480
    EXPECT_NEAR(confidenceAngle(0.0f, 180), 13.333f, 1e-3f);
    EXPECT_FLOAT_EQ(confidenceAngle(7.0f, 180), 7.0f);
    EXPECT_FLOAT_EQ(rayConfidence(0.0f, 0.1f), 1.0f);
    EXPECT_NEAR(rayConfidence(0.05f, 0.1f), 0.75f, 1e-6f);
    EXPECT_FLOAT_EQ(rayConfidence(0.2f, 0.1f), 0.0f);
}

}  // namespace
}  // namespace hybridlab
