#pragma once
// EM inference (Hakura & Snyder 2001 §4.3): the layer cube map x, its whole MIP chain ("entire
// MIPMAPs are inferred", Figure 7), that, applied by the renderer, best matches the ray tracer's
// layer images in the confidence-weighted least-squares sense, A x = b over every observation at
// once (both terms, several nearby viewpoints, direct images of the environment), solved by
// conjugate gradient (Eigen's least-squares CG) over the texels the images read, a ring around
// them and their neighbours in the chain (solving the whole cube cost up to 20 times more for
// texels no view reads; they stay empty, alpha 0: no image saw anything of the layer there, and
// filling them from their neighbours drew phantom layers where novel views read them, e.g. the
// cup's lid seen from above the viewpoint samples, lens SSIM 0.796 -> 0.842), with a small
// smoothness term between neighbouring texels, a small pyramid term tying each texel to the mean
// of the finer texels it covers (so the levels no image reads agree with those it does), a small
// damping of each observed texel towards the mean of the targets that read it (Tikhonov
// regularisation: the plain least-squares solution swings weakly observed texels far outside
// [0, 1]), all relative to the data's weight, and a stopping rule on the relative residual; the
// solution is then clamped to what a texture holds (alpha in [0, 1], colour >= 0).
#include <cstdint>
#include <vector>

#include <Eigen/SparseCore>
#include <glm/vec4.hpp>

#include "common/scene/camera.h"
#include "techniques/layered_em/em_cube_map.h"
#include "techniques/layered_em/layer_shells.h"
#include "techniques/layered_em/lens_raster.h"

namespace hybridlab {

// Rows of the rendering matrix and their targets: one row per pixel an image holds.
struct EmObservation {
    std::vector<CubeMapLookup> lookups;  // what the renderer reads at the pixel
    std::vector<glm::vec4> targets;      // b: premultiplied colour and alpha of the layer at the pixel
    std::vector<float> confidence;       // row weight
    std::vector<std::uint32_t> pixels;   // the pixel of each row (for images and tests)
};

// A lens image of one term: a row for every covered pixel whose confidence is positive.
// `targets` and `confidence` are per pixel of the raster.
EmObservation lensObservation(const LensRaster& raster, const std::vector<glm::uvec3>& triangles, const LayerTextureIndex& index,
                              const std::vector<glm::vec4>& targets, const std::vector<float>& confidence, int size);

// A direct image of the environment without the lens (§4.3): the pixel's own camera ray indexes
// the shell, at the level of detail of the angle between neighbouring pixels' indices.
EmObservation directObservation(const Camera& camera, int width, int height, const Shell& shell,
                                const std::vector<glm::vec4>& targets, const std::vector<float>& confidence, int size);

// The (unweighted) rendering matrix of an observation: row r holds the lookup weights of its pixel.
Eigen::SparseMatrix<double, Eigen::RowMajor> renderingMatrix(const EmObservation& observation, int size);

// What the renderer draws for one term and layer with `em` (per pixel; zero where uncovered).
std::vector<glm::vec4> drawLayer(const LensRaster& raster, const std::vector<glm::uvec3>& triangles, const LayerTextureIndex& index,
                                 const LayerCubeMap& em);

struct EmInferenceSettings {
    int size = 32;                    // texels a cube face side
    // Regularising weights, relative to the mean diagonal of the data rows' A^T A.
    double smoothness = 1e-3;         // weight of (x_i - x_j)^2 between neighbouring texels of a level-0 face
    double pyramid = 1e-2;            // weight of (x_parent - mean of its finer texels)^2
    double damping = 1.0;             // weight of (x_i - the mean of the targets that read texel i)^2 (0.3 -> 1, display bake:
                                      // lens SSIM above the samples' plane 0.782 -> 0.796, same elsewhere)
    double tolerance = 1e-6;          // stop at this relative residual (of the normal equations)
    int maxIterations = 1000;
    int ring = 2;                     // texels around the observed ones that the solve carries (the rest stay empty)
    int finerLevels = 2;              // and levels below the observed ones (a display up to 4x finer than the bake)
    double observedWeight = 0.25;     // a texel is observed when its confidence-weighted lookup weights
                                      // over all rows sum to at least this (a quarter of a pixel)
};

struct EmInferenceResult {
    LayerCubeMap em;
    std::vector<bool> observed;       // per texel of the chain: read with at least observedWeight in all
    std::size_t observedTexels = 0;
    std::size_t activeTexels = 0;     // the unknowns of the solve
    int iterations = 0;               // the largest over the four channels
    double relativeResidual = 0.0;    // the largest over the four channels
    std::size_t rows = 0;
};

// `holds`, when not empty, is per texel of the chain whether the layer's impostor can hold it (a
// quad only its rectangle); the others stay empty, and rows that read them read zero.
EmInferenceResult inferLayerEm(const std::vector<EmObservation>& observations, const EmInferenceSettings& settings,
                               const std::vector<bool>& holds = {});

}  // namespace hybridlab
