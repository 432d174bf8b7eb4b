// The layer cube maps' MIP chain (Hakura & Snyder 2001 §4.3, Figure 7: "entire MIPMAPs are
// inferred"): the chain's layout, the trilinear lookup shared by the rendering matrix and the
// renderer, the per-vertex level of detail against the analytic rate of a planar mirror, and the
// pyramid term that ties the levels no image reads to those it does.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "techniques/layered_em/em_inference.h"
#include "tests/support/lens_test_scenes.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

TEST(EmMipChain, LevelsAreStoredOneAfterAnother) {
    EXPECT_EQ(cubeMapLevels(16), 5);
    EXPECT_EQ(cubeMapLevelOffset(16, 1), 6u * 256u);
    EXPECT_EQ(cubeMapLevelOffset(16, 4), 6u * (256u + 64u + 16u + 4u));
    EXPECT_EQ(cubeMapTexelCount(16), 6u * (256u + 64u + 16u + 4u + 1u));
    // Not a power of two: 24, 12, 6, 3, 1.
    EXPECT_EQ(cubeMapLevels(24), 5);
    EXPECT_EQ(cubeMapLevelSize(24, 3), 3);
    EXPECT_EQ(cubeMapLevelSize(24, 4), 1);
    for (int size : {16, 24}) {
        for (std::uint32_t t = 0; t < cubeMapTexelCount(size); ++t) {
            const CubeMapTexel c = cubeMapTexelAt(t, size);
            ASSERT_EQ(cubeMapTexelIndex(c, size), t) << "size " << size;
            ASSERT_LT(c.column, cubeMapLevelSize(size, c.level));
        }
    }
}

TEST(EmMipChain, LookupBlendsTheTwoNearestLevels) {
    const int size = 16;
    LayerCubeMap map(size);
    for (std::uint32_t t = 0; t < map.texels.size(); ++t) map.texels[t] = glm::vec4(static_cast<float>(cubeMapTexelAt(t, size).level));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (float lod : {-1.0f, 0.0f, 0.25f, 1.5f, 3.75f, 4.0f, 9.0f}) {
        for (int k = 0; k < 20; ++k) {
            const CubeMapLookup l = cubeMapLookup({u(rng), u(rng), u(rng)}, size, lod);
            float weights = 0.0f;
            for (const CubeMapTap& t : l.taps) weights += t.weight;
            EXPECT_NEAR(weights, 1.0f, 1e-6f);
            EXPECT_NEAR(map.sample(l).r, std::clamp(lod, 0.0f, 4.0f), 1e-5f) << "lod " << lod;
        }
    }
    // Level of detail: one level per doubling of the pixel's footprint, none below two texels (half
    // the footprint: a bias of -1).
    EXPECT_FLOAT_EQ(cubeMapLod(4.0f / 16.0f, 16), 0.0f);
    EXPECT_NEAR(cubeMapLod(8.0f / 16.0f, 16), 1.0f, 1e-6f);
    EXPECT_NEAR(cubeMapLod(32.0f / 16.0f, 16), 3.0f, 1e-6f);
    EXPECT_FLOAT_EQ(cubeMapLod(0.01f / 16.0f, 16), 0.0f);
}

// A flat mirror facing the camera reflects the camera's rays: from one pixel to the next near the
// image centre its (distant) texture index turns by the camera's angle per pixel, 2 tan(fov / 2) / height.
TEST(EmMipChain, VertexLevelsFollowTheScreenRateOfAPlanarMirror) {
    test::SceneBuilder b;
    Material mirror;
    mirror.reflectivity = 1.0f;
    b.object("mirror", makePlane(), b.material(mirror), test::placed({0, 0, 0}, glm::vec3(3.0f), {90.0f, 0.0f, 0.0f}));
    b.scene().objects[0].lens = true;
    const Scene scene = b.scene();
    const LensSystem system(scene, findLensSystems(scene).at(0));
    const Camera camera = test::lookingAt({0, 0, 4}, {0, 0, 0}, 40.0f);
    const int width = 96, height = 64, size = 1024;
    TessellationSettings ts;
    ts.tauPixels = 4.0f;
    const TessellatedLens lens = tessellateLens(system, buildLensMesh(system), camera, width, height, ts);
    Shell shell;
    shell.center = system.center();
    shell.radius = 1000.0f;
    const LayerTextureIndex index = vertexTextureIndex(lens, PathTerm::Reflection, shell,
                                                          textureLodEdges(lens, PathTerm::Reflection, lensVertexPixels(lens, camera, width, height)), size);
    const float rate = 2.0f * std::tan(glm::radians(20.0f)) / static_cast<float>(height);
    const float expected = std::log2(0.5f * rate * static_cast<float>(size) * 0.5f);
    ASSERT_GT(expected, 1.0f);
    std::size_t near = 0;
    for (std::size_t i = 0; i < lens.vertices.size(); ++i) {
        const glm::vec2 p = projectToPixels(camera, width, height, lens.vertices[i].position);
        if (!lens.vertices[i].traced || glm::length(p - glm::vec2(width / 2, height / 2)) > 8.0f) continue;
        ++near;
        EXPECT_NEAR(index.lods[i], expected, 0.1f) << "vertex at " << p.x << ", " << p.y;
    }
    EXPECT_GE(near, 3u);
}

// Rows that read level 0 only: the pyramid term makes every coarser texel the mean of the finer
// texels it covers; rows that read the coarsest level only: the finer levels the solve carries
// take its value.
TEST(EmMipChain, ThePyramidTermFillsTheLevelsNoRowReads) {
    const int size = 8;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    EmObservation fine;
    for (std::uint32_t t = 0; t < cubeMapLevelOffset(size, 1); ++t) {
        CubeMapLookup l;
        l.taps[0] = {t, 1.0f};
        fine.lookups.push_back(l);
        fine.targets.push_back(glm::vec4(u(rng), u(rng), u(rng), 1.0f));
        fine.confidence.push_back(1.0f);
        fine.pixels.push_back(t);
    }
    EmInferenceSettings settings;
    settings.size = size;
    settings.tolerance = 1e-10;
    const EmInferenceResult r = inferLayerEm({fine}, settings);
    for (std::uint32_t t = static_cast<std::uint32_t>(cubeMapLevelOffset(size, 1)); t < cubeMapTexelCount(size); ++t) {
        const CubeMapTexel c = cubeMapTexelAt(t, size);
        glm::vec4 mean(0.0f);
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) mean += 0.25f * r.em.texels[cubeMapTexelIndex({c.level - 1, c.face, 2 * c.column + i, 2 * c.row + j}, size)];
        EXPECT_LT(glm::length(r.em.texels[t] - mean), 0.02f) << "level " << c.level;
        EXPECT_FALSE(r.observed[t]);
    }

    EmObservation coarse;
    const int last = cubeMapLevels(size) - 1;
    for (int f = 0; f < 6; ++f) {
        CubeMapLookup l;
        l.taps[0] = {cubeMapTexelIndex({last, f, 0, 0}, size), 1.0f};
        coarse.lookups.push_back(l);
        coarse.targets.push_back(glm::vec4(0.1f * static_cast<float>(f + 1)));
        coarse.confidence.push_back(1.0f);
        coarse.pixels.push_back(static_cast<std::uint32_t>(f));
    }
    // The solve carries finerLevels levels below what rows read (the default: a display up to 4x
    // finer than the bake); below that the chain stays empty.
    const EmInferenceResult c = inferLayerEm({coarse}, settings);
    for (std::uint32_t t = 0; t < cubeMapLevelOffset(size, last); ++t) {
        const CubeMapTexel texel = cubeMapTexelAt(t, size);
        if (texel.level >= last - settings.finerLevels) {
            EXPECT_NEAR(c.em.texels[t].r, 0.1f * static_cast<float>(texel.face + 1), 0.01f) << "level " << texel.level;
        } else {
            EXPECT_EQ(c.em.texels[t], glm::vec4(0.0f)) << "level " << texel.level;
        }
    }
    settings.finerLevels = last;
    const EmInferenceResult whole = inferLayerEm({coarse}, settings);
    for (std::uint32_t t = 0; t < cubeMapLevelOffset(size, 1); ++t) {
        EXPECT_NEAR(whole.em.texels[t].r, 0.1f * static_cast<float>(cubeMapTexelAt(t, size).face + 1), 0.01f);
    }
}

}  // namespace
}  // namespace hybridlab
