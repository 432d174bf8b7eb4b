#include "techniques/layered_em/em_inference.h"

#include <algorithm>
#include <cmath>

#include <Eigen/IterativeLinearSolvers>

namespace hybridlab {
namespace {

using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;

void addRow(EmObservation& o, const CubeMapLookup& l, glm::vec4 target, float confidence, std::uint32_t pixel) {
    o.lookups.push_back(l);
    o.targets.push_back(target);
    o.confidence.push_back(confidence);
    o.pixels.push_back(pixel);
}

}  // namespace

EmObservation lensObservation(const LensRaster& raster, const std::vector<glm::uvec3>& triangles,
                              const std::vector<glm::vec3>& vertexDirections, const std::vector<glm::vec4>& targets,
                              const std::vector<float>& confidence, int size) {
    EmObservation o;
    for (std::size_t i = 0; i < raster.triangle.size(); ++i) {
        if (!raster.covered(i) || confidence[i] <= 0.0f) continue;
        addRow(o, pixelCubeMapLookup(raster, i, triangles, vertexDirections, size), targets[i], confidence[i],
               static_cast<std::uint32_t>(i));
    }
    return o;
}

EmObservation directObservation(const Camera& camera, int width, int height, const Shell& shell,
                                const std::vector<glm::vec4>& targets, const std::vector<float>& confidence, int size) {
    EmObservation o;
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
            if (confidence[i] <= 0.0f) continue;
            Ray ray = camera.rayThroughNdc(pixelCenterNdc(x, y, width, height), aspect);
            addRow(o, cubeMapLookup(shellTextureDirection(shell, ray.origin, ray.direction), size), targets[i], confidence[i],
                   static_cast<std::uint32_t>(i));
        }
    }
    return o;
}

SparseRows renderingMatrix(const EmObservation& observation, int size) {
    std::vector<Eigen::Triplet<double>> entries;
    for (std::size_t r = 0; r < observation.lookups.size(); ++r) {
        for (const CubeMapTap& t : observation.lookups[r].taps) {
            if (t.weight != 0.0f) entries.emplace_back(static_cast<int>(r), static_cast<int>(t.texel), t.weight);
        }
    }
    SparseRows a(static_cast<Eigen::Index>(observation.lookups.size()), static_cast<Eigen::Index>(cubeMapTexelCount(size)));
    a.setFromTriplets(entries.begin(), entries.end());  // duplicate taps (clamped edges) add up
    return a;
}

std::vector<glm::vec4> drawLayer(const LensRaster& raster, const std::vector<glm::uvec3>& triangles,
                                 const std::vector<glm::vec3>& vertexDirections, const LayerCubeMap& em) {
    std::vector<glm::vec4> image(raster.triangle.size(), glm::vec4(0.0f));
    for (std::size_t i = 0; i < image.size(); ++i) {
        if (raster.covered(i)) image[i] = em.sample(pixelCubeMapLookup(raster, i, triangles, vertexDirections, em.size));
    }
    return image;
}

EmInferenceResult inferLayerEm(const std::vector<EmObservation>& observations, const EmInferenceSettings& settings) {
    const int size = settings.size;
    const Eigen::Index texels = static_cast<Eigen::Index>(cubeMapTexelCount(size));
    EmInferenceResult result;
    result.em = LayerCubeMap(size);
    result.observed.assign(static_cast<std::size_t>(texels), false);
    std::vector<double> observedWeight(static_cast<std::size_t>(texels), 0.0);

    // Stack the confidence-weighted rows of every observation, then the smoothness rows.
    std::vector<Eigen::Triplet<double>> entries;
    std::vector<glm::dvec4> rhs;
    Eigen::Index row = 0;
    for (const EmObservation& o : observations) {
        for (std::size_t r = 0; r < o.lookups.size(); ++r, ++row) {
            const double c = o.confidence[r];
            for (const CubeMapTap& t : o.lookups[r].taps) {
                if (t.weight == 0.0f) continue;
                entries.emplace_back(row, static_cast<Eigen::Index>(t.texel), c * t.weight);
                observedWeight[t.texel] += c * t.weight;
            }
            rhs.push_back(c * glm::dvec4(o.targets[r]));
        }
    }
    result.rows = static_cast<std::size_t>(row);
    const double s = std::sqrt(settings.smoothness);
    const int perFace = size * size;
    for (int f = 0; f < 6; ++f) {
        for (int j = 0; j < size; ++j) {
            for (int i = 0; i < size; ++i) {
                const int t = f * perFace + j * size + i;
                for (int n : {i + 1 < size ? t + 1 : -1, j + 1 < size ? t + size : -1}) {
                    if (n < 0) continue;
                    entries.emplace_back(row, t, s);
                    entries.emplace_back(row, n, -s);
                    rhs.push_back(glm::dvec4(0.0));
                    ++row;
                }
            }
        }
    }
    SparseRows a(row, texels);
    a.setFromTriplets(entries.begin(), entries.end());
    Eigen::LeastSquaresConjugateGradient<SparseRows> solver;
    solver.setTolerance(settings.tolerance);
    solver.setMaxIterations(settings.maxIterations);
    solver.compute(a);
    for (int channel = 0; channel < 4; ++channel) {
        Eigen::VectorXd b(row);
        for (Eigen::Index r = 0; r < row; ++r) b[r] = rhs[static_cast<std::size_t>(r)][channel];
        Eigen::VectorXd x = solver.solve(b);
        result.iterations = std::max(result.iterations, static_cast<int>(solver.iterations()));
        result.relativeResidual = std::max(result.relativeResidual, solver.error());
        for (Eigen::Index t = 0; t < texels; ++t) result.em.texels[static_cast<std::size_t>(t)][channel] = static_cast<float>(x[t]);
    }
    for (std::size_t t = 0; t < result.observed.size(); ++t) {
        result.observed[t] = observedWeight[t] >= settings.observedWeight;
        result.observedTexels += result.observed[t] ? 1 : 0;
    }
    return result;
}

}  // namespace hybridlab
