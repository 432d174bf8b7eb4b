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

namespace {

// The texels the solve carries (§4.3 infers what the images see; the rest of the cube stays empty):
// those the rows read, a ring of `ring` texels around them at their level (so smoothness
// reaches a little past the observations, where nearby views read), their descendants a few
// levels down and every ancestor (the pyramid rows tie the chain together).
std::vector<bool> activeTexels(const std::vector<double>& observedWeight, const std::vector<std::uint32_t>& parents, int size, int ring,
                               int finerLevels) {
    std::vector<bool> active(observedWeight.size(), false);
    for (std::size_t t = 0; t < observedWeight.size(); ++t) {
        if (observedWeight[t] <= 0.0) continue;
        const CubeMapTexel c = cubeMapTexelAt(static_cast<std::uint32_t>(t), size);
        const int side = cubeMapLevelSize(size, c.level);
        for (int j = std::max(0, c.row - ring); j <= std::min(side - 1, c.row + ring); ++j)
            for (int i = std::max(0, c.column - ring); i <= std::min(side - 1, c.column + ring); ++i)
                active[cubeMapTexelIndex({c.level, c.face, i, j}, size)] = true;
    }
    // Descendants first, `finerLevels` levels down (a view up to 2^finerLevels times finer than the
    // bake's reads below the levels it observed), then ancestors. Texels are stored level after
    // level, so walking them backwards visits every parent before its children, forwards every
    // child before its parent.
    std::vector<int> depth(active.size(), -1);  // levels of descendants still to mark below a texel
    for (std::size_t t = 0; t < active.size(); ++t) depth[t] = active[t] ? finerLevels : -1;
    for (std::size_t t = active.size(); t-- > 0;) {
        if (parents[t] == kNoParent) continue;
        const int parentDepth = depth[parents[t]];
        if (parentDepth > 0 && depth[t] < parentDepth - 1) {
            depth[t] = parentDepth - 1;
            active[t] = true;
        }
    }
    for (std::size_t t = 0; t < active.size(); ++t) {
        if (active[t] && parents[t] != kNoParent) active[parents[t]] = true;
    }
    return active;
}

}  // namespace

EmInferenceResult inferLayerEm(const std::vector<EmObservation>& observations, const EmInferenceSettings& settings,
                               const std::vector<bool>& holds) {
    const int size = settings.size;
    const std::size_t texels = cubeMapTexelCount(size);
    EmInferenceResult result;
    result.em = LayerCubeMap(size);
    result.observed.assign(texels, false);
    std::vector<double> observedWeight(texels, 0.0);
    std::vector<double> normalDiagonal(texels, 0.0);             // diagonal of A^T A over the data rows
    std::vector<glm::dvec4> splat(texels, glm::dvec4(0.0));      // weighted sum of the targets reading a texel
    for (const EmObservation& o : observations) {
        for (std::size_t r = 0; r < o.lookups.size(); ++r) {
            const double c = o.confidence[r];
            for (const CubeMapTap& t : o.lookups[r].taps) {
                if (t.weight == 0.0f) continue;
                observedWeight[t.texel] += c * t.weight;
                normalDiagonal[t.texel] += (c * t.weight) * (c * t.weight);
                splat[t.texel] += c * static_cast<double>(t.weight) * glm::dvec4(o.targets[r]);
            }
        }
    }
    // The unknowns: the active texels, numbered in chain order.
    const std::vector<std::uint32_t> parents = cubeMapParents(size);
    std::vector<bool> active = activeTexels(observedWeight, parents, size, settings.ring, settings.finerLevels);
    if (!holds.empty()) {
        for (std::size_t t = 0; t < texels; ++t) active[t] = active[t] && holds[t];
    }
    std::vector<Eigen::Index> column(texels, -1);
    Eigen::Index unknowns = 0;
    for (std::size_t t = 0; t < texels; ++t) {
        if (active[t]) column[t] = unknowns++;
    }

    // Stack the confidence-weighted rows of every observation, then the regularising rows.
    std::vector<Eigen::Triplet<double>> entries;
    std::vector<glm::dvec4> rhs;
    Eigen::Index row = 0;
    for (const EmObservation& o : observations) {
        for (std::size_t r = 0; r < o.lookups.size(); ++r, ++row) {
            const double c = o.confidence[r];
            for (const CubeMapTap& t : o.lookups[r].taps) {
                if (t.weight != 0.0f && column[t.texel] >= 0) entries.emplace_back(row, column[t.texel], c * t.weight);
            }
            rhs.push_back(c * glm::dvec4(o.targets[r]));
        }
    }
    result.rows = static_cast<std::size_t>(row);
    // The regularising weights are relative to the data's mean diagonal of A^T A, so scaling every
    // confidence alike does not change the solution (the paper multiplies both sides by it).
    double diagonalSum = 0.0;
    std::size_t diagonalCount = 0;
    for (double v : normalDiagonal) {
        diagonalSum += v;
        diagonalCount += v > 0.0 ? 1 : 0;
    }
    const double meanDiagonal = diagonalCount > 0 ? diagonalSum / static_cast<double>(diagonalCount) : 1.0;
    // Smoothness between neighbouring active texels of a level-0 face; the pyramid carries it to the
    // coarser levels (smoothness there would pull them away from the mean of what they cover).
    const double s = std::sqrt(settings.smoothness * meanDiagonal);
    auto addPair = [&](std::size_t a, std::size_t b) {
        if (column[a] < 0 || column[b] < 0) return;
        entries.emplace_back(row, column[a], s);
        entries.emplace_back(row, column[b], -s);
        rhs.push_back(glm::dvec4(0.0));
        ++row;
    };
    for (int f = 0; f < 6; ++f) {
        for (int j = 0; j < size; ++j) {
            for (int i = 0; i < size; ++i) {
                const std::size_t t = static_cast<std::size_t>((f * size + j) * size + i);  // level 0 starts the chain
                if (!active[t]) continue;
                if (i + 1 < size) addPair(t, t + 1);
                if (j + 1 < size) addPair(t, t + static_cast<std::size_t>(size));
            }
        }
    }
    // Damping towards the splat (the weighted mean of the targets that read the texel): a texel that
    // rows touch only with small bilinear weights would otherwise take extreme values (alpha far
    // outside [0, 1], negative colours) to fix other texels' residuals, and "over" amplifies them.
    const double d = std::sqrt(settings.damping * meanDiagonal);
    for (std::size_t t = 0; t < texels && d > 0.0; ++t) {
        const double w = observedWeight[t];
        if (w <= 0.0 || column[t] < 0) continue;
        entries.emplace_back(row, column[t], d);
        rhs.push_back(d * splat[t] / w);
        ++row;
    }
    // The pyramid: each active texel of level k >= 1 against the mean of its active children.
    const double p = std::sqrt(settings.pyramid * meanDiagonal);
    std::vector<std::vector<std::uint32_t>> children(texels);
    for (std::size_t t = 0; t < texels; ++t) {
        if (active[t] && parents[t] != kNoParent) children[parents[t]].push_back(static_cast<std::uint32_t>(t));
    }
    for (std::size_t parent = 0; parent < texels; ++parent) {
        if (children[parent].empty()) continue;
        entries.emplace_back(row, column[parent], p);
        for (std::uint32_t c : children[parent]) entries.emplace_back(row, column[c], -p / static_cast<double>(children[parent].size()));
        rhs.push_back(glm::dvec4(0.0));
        ++row;
    }
    if (unknowns == 0) return result;  // no image saw the layer: it stays empty
    SparseRows a(row, unknowns);
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
        for (std::size_t t = 0; t < texels; ++t) {
            if (active[t]) result.em.texels[t][channel] = static_cast<float>(x[column[t]]);
        }
    }
    // What a texture can hold: premultiplied colour is not negative and alpha is a coverage in
    // [0, 1]; "over" with alpha outside it subtracts the layers behind (the projection of the
    // damped solution onto that set).
    for (glm::vec4& t : result.em.texels) t = glm::vec4(glm::max(glm::vec3(t), glm::vec3(0.0f)), std::clamp(t.a, 0.0f, 1.0f));
    for (std::size_t t = 0; t < result.observed.size(); ++t) {
        result.observed[t] = observedWeight[t] >= settings.observedWeight;
        result.observedTexels += result.observed[t] ? 1 : 0;
    }
    result.activeTexels = static_cast<std::size_t>(unknowns);
    return result;
}

}  // namespace hybridlab
