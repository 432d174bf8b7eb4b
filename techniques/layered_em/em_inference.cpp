#include "techniques/layered_em/em_inference.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

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

EmObservation lensObservation(const LensRaster& raster, const std::vector<glm::uvec3>& triangles, const LayerTextureIndex& index,
                              const std::vector<glm::vec4>& targets, const std::vector<float>& confidence, int size) {
    EmObservation o;
    for (std::size_t i = 0; i < raster.triangle.size(); ++i) {
        if (!raster.covered(i) || confidence[i] <= 0.0f) continue;
        addRow(o, pixelCubeMapLookup(raster, i, triangles, index, size), targets[i], confidence[i],
               static_cast<std::uint32_t>(i));
    }
    return o;
}

EmObservation directObservation(const Camera& camera, int width, int height, const Shell& shell,
                                const std::vector<glm::vec4>& targets, const std::vector<float>& confidence, int size) {
    EmObservation o;
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    // Each pixel centre's index once, with a row and a column beyond the image for the neighbours.
    const int gw = width + 1, gh = height + 1;
    std::vector<glm::vec3> index(static_cast<std::size_t>(gw) * static_cast<std::size_t>(gh));
    for (int y = 0; y < gh; ++y) {
        for (int x = 0; x < gw; ++x) {
            const Ray ray = camera.rayThroughNdc(pixelCenterNdc(x, y, width, height), aspect);
            index[static_cast<std::size_t>(y * gw + x)] = glm::normalize(shellTextureDirection(shell, ray.origin, ray.direction));
        }
    }
    auto angle = [](glm::vec3 a, glm::vec3 b) { return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f)); };
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
            if (confidence[i] <= 0.0f) continue;
            const std::size_t g = static_cast<std::size_t>(y * gw + x);
            const glm::vec3 d = index[g];
            const float rate = std::max(angle(d, index[g + 1]), angle(d, index[g + static_cast<std::size_t>(gw)]));
            addRow(o, cubeMapLookup(d, size, cubeMapLod(rate, size)), targets[i], confidence[i], static_cast<std::uint32_t>(i));
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

std::vector<glm::vec4> drawLayer(const LensRaster& raster, const std::vector<glm::uvec3>& triangles, const LayerTextureIndex& index,
                                 const LayerCubeMap& em) {
    std::vector<glm::vec4> image(raster.triangle.size(), glm::vec4(0.0f));
    for (std::size_t i = 0; i < image.size(); ++i) {
        if (raster.covered(i)) image[i] = em.sample(pixelCubeMapLookup(raster, i, triangles, index, em.size));
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
    std::vector<glm::dvec4> splat(static_cast<std::size_t>(texels), glm::dvec4(0.0));  // weighted sum of the targets reading a texel

    // Stack the confidence-weighted rows of every observation, then the regularising rows.
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
                splat[t.texel] += c * static_cast<double>(t.weight) * glm::dvec4(o.targets[r]);
            }
            rhs.push_back(c * glm::dvec4(o.targets[r]));
        }
    }
    result.rows = static_cast<std::size_t>(row);
    // Smoothness between neighbouring texels of a level-0 face; the pyramid carries it to the coarser
    // levels (smoothness there would pull them away from the mean of what they cover).
    const double s = std::sqrt(settings.smoothness);
    auto addPair = [&](Eigen::Index a, Eigen::Index b, double weight) {
        entries.emplace_back(row, a, weight);
        entries.emplace_back(row, b, -weight);
        rhs.push_back(glm::dvec4(0.0));
        ++row;
    };
    for (int f = 0; f < 6; ++f) {
        for (int j = 0; j < size; ++j) {
            for (int i = 0; i < size; ++i) {
                const Eigen::Index t = (f * size + j) * size + i;  // level 0 starts the chain
                if (i + 1 < size) addPair(t, t + 1, s);
                if (j + 1 < size) addPair(t, t + size, s);
            }
        }
    }
    // Damping towards the splat (the weighted mean of the targets that read the texel): a texel that
    // rows touch only with small bilinear weights would otherwise take extreme values (alpha far
    // outside [0, 1], negative colours) to fix other texels' residuals, and "over" amplifies them.
    const double d = std::sqrt(settings.damping);
    for (Eigen::Index t = 0; t < texels && d > 0.0; ++t) {
        const double w = observedWeight[static_cast<std::size_t>(t)];
        if (w <= 0.0) continue;
        entries.emplace_back(row, t, d);
        rhs.push_back(d * splat[static_cast<std::size_t>(t)] / w);
        ++row;
    }
    // The pyramid: each texel of level k >= 1 against the mean of the level k - 1 texels it covers.
    const double p = std::sqrt(settings.pyramid);
    for (int level = 1; level < cubeMapLevels(size); ++level) {
        const int fine = cubeMapLevelSize(size, level - 1), coarse = cubeMapLevelSize(size, level);
        std::vector<std::vector<std::uint32_t>> children(6u * static_cast<std::size_t>(coarse * coarse));
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < fine; ++j)
                for (int i = 0; i < fine; ++i)
                    children[static_cast<std::size_t>((f * coarse + j * coarse / fine) * coarse + i * coarse / fine)].push_back(
                        cubeMapTexelIndex({level - 1, f, i, j}, size));
        const Eigen::Index first = static_cast<Eigen::Index>(cubeMapLevelOffset(size, level));
        for (std::size_t parent = 0; parent < children.size(); ++parent) {
            entries.emplace_back(row, first + static_cast<Eigen::Index>(parent), p);
            for (std::uint32_t c : children[parent]) entries.emplace_back(row, c, -p / static_cast<double>(children[parent].size()));
            rhs.push_back(glm::dvec4(0.0));
            ++row;
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
    // What a texture can hold: premultiplied colour is not negative and alpha is a coverage in
    // [0, 1]; "over" with alpha outside it subtracts the layers behind (the projection of the
    // damped solution onto that set).
    for (glm::vec4& t : result.em.texels) t = glm::vec4(glm::max(glm::vec3(t), glm::vec3(0.0f)), std::clamp(t.a, 0.0f, 1.0f));
    for (std::size_t t = 0; t < result.observed.size(); ++t) {
        result.observed[t] = observedWeight[t] >= settings.observedWeight;
        result.observedTexels += result.observed[t] ? 1 : 0;
    }
    return result;
}

}  // namespace hybridlab
