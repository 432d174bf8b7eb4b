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

// What the data rows tell of every texel of the chain.
struct TexelData {
    std::vector<double> observedWeight;  // sum of confidence * tap weight
    std::vector<double> normalDiagonal;  // diagonal of A^T A over the data rows
    std::vector<glm::dvec4> splat;       // weighted sum of the targets reading a texel
};

TexelData texelData(const std::vector<EmObservation>& observations, std::size_t texels) {
    TexelData d{std::vector<double>(texels, 0.0), std::vector<double>(texels, 0.0), std::vector<glm::dvec4>(texels, glm::dvec4(0.0))};
    for (const EmObservation& o : observations) {
        for (std::size_t r = 0; r < o.lookups.size(); ++r) {
            const double c = o.confidence[r];
            for (const CubeMapTap& t : o.lookups[r].taps) {
                if (t.weight == 0.0f) continue;
                d.observedWeight[t.texel] += c * t.weight;
                d.normalDiagonal[t.texel] += (c * t.weight) * (c * t.weight);
                d.splat[t.texel] += c * static_cast<double>(t.weight) * glm::dvec4(o.targets[r]);
            }
        }
    }
    return d;
}

// The regularising weights are relative to the data's mean diagonal of A^T A, so scaling every
// confidence alike does not change the solution (the paper multiplies both sides by it).
double meanDiagonal(const std::vector<double>& normalDiagonal) {
    double sum = 0.0;
    std::size_t count = 0;
    for (double v : normalDiagonal) {
        sum += v;
        count += v > 0.0 ? 1 : 0;
    }
    return count > 0 ? sum / static_cast<double>(count) : 1.0;
}

// The stacked least-squares system over the active texels (the unknowns, numbered in chain order
// by `column`, -1 for the rest): its entries and right-hand sides, row after row.
class StackedRows {
public:
    explicit StackedRows(const std::vector<Eigen::Index>& column) : column_(column) {}

    // The confidence-weighted rows of every observation.
    void addData(const std::vector<EmObservation>& observations) {
        for (const EmObservation& o : observations) {
            for (std::size_t r = 0; r < o.lookups.size(); ++r, ++row_) {
                const double c = o.confidence[r];
                for (const CubeMapTap& t : o.lookups[r].taps) {
                    if (t.weight != 0.0f && column_[t.texel] >= 0) entries_.emplace_back(row_, column_[t.texel], c * t.weight);
                }
                rhs_.push_back(c * glm::dvec4(o.targets[r]));
            }
        }
    }

    // Smoothness between neighbouring active texels of a level-0 face, weight s; the pyramid carries
    // it to the coarser levels (smoothness there would pull them away from the mean of what they cover).
    void addSmoothness(const std::vector<bool>& active, int size, double s) {
        auto addPair = [&](std::size_t a, std::size_t b) {
            if (column_[a] < 0 || column_[b] < 0) return;
            entries_.emplace_back(row_, column_[a], s);
            entries_.emplace_back(row_, column_[b], -s);
            rhs_.push_back(glm::dvec4(0.0));
            ++row_;
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
    }

    // Damping towards the splat (the weighted mean of the targets that read the texel), weight d: a
    // texel that rows touch only with small bilinear weights would otherwise take extreme values
    // (alpha far outside [0, 1], negative colours) to fix other texels' residuals, and "over"
    // amplifies them.
    void addDamping(const TexelData& data, double d) {
        for (std::size_t t = 0; t < column_.size() && d > 0.0; ++t) {
            const double w = data.observedWeight[t];
            if (w <= 0.0 || column_[t] < 0) continue;
            entries_.emplace_back(row_, column_[t], d);
            rhs_.push_back(d * data.splat[t] / w);
            ++row_;
        }
    }

    // The pyramid, weight p: each active texel of level k >= 1 against the mean of its active children.
    void addPyramid(const std::vector<bool>& active, const std::vector<std::uint32_t>& parents, double p) {
        const std::size_t texels = column_.size();
        std::vector<std::vector<std::uint32_t>> children(texels);
        for (std::size_t t = 0; t < texels; ++t) {
            if (active[t] && parents[t] != kNoParent) children[parents[t]].push_back(static_cast<std::uint32_t>(t));
        }
        for (std::size_t parent = 0; parent < texels; ++parent) {
            if (children[parent].empty()) continue;
            entries_.emplace_back(row_, column_[parent], p);
            for (std::uint32_t c : children[parent]) entries_.emplace_back(row_, column_[c], -p / static_cast<double>(children[parent].size()));
            rhs_.push_back(glm::dvec4(0.0));
            ++row_;
        }
    }

    Eigen::Index rows() const { return row_; }

    // Solves the system channel by channel (LSCG) into the active texels of `result.em`.
    void solve(Eigen::Index unknowns, const EmInferenceSettings& settings, EmInferenceResult& result) const {
        SparseRows a(row_, unknowns);
        a.setFromTriplets(entries_.begin(), entries_.end());
        Eigen::LeastSquaresConjugateGradient<SparseRows> solver;
        solver.setTolerance(settings.tolerance);
        solver.setMaxIterations(settings.maxIterations);
        solver.compute(a);
        for (int channel = 0; channel < 4; ++channel) {
            Eigen::VectorXd b(row_);
            for (Eigen::Index r = 0; r < row_; ++r) b[r] = rhs_[static_cast<std::size_t>(r)][channel];
            Eigen::VectorXd x = solver.solve(b);
            result.iterations = std::max(result.iterations, static_cast<int>(solver.iterations()));
            result.relativeResidual = std::max(result.relativeResidual, solver.error());
            for (std::size_t t = 0; t < column_.size(); ++t) {
                if (column_[t] >= 0) result.em.texels[t][channel] = static_cast<float>(x[column_[t]]);
            }
        }
    }

private:
    const std::vector<Eigen::Index>& column_;
    std::vector<Eigen::Triplet<double>> entries_;
    std::vector<glm::dvec4> rhs_;
    Eigen::Index row_ = 0;
};

}  // namespace

EmInferenceResult inferLayerEm(const std::vector<EmObservation>& observations, const EmInferenceSettings& settings,
                               const std::vector<bool>& holds) {
    const int size = settings.size;
    const std::size_t texels = cubeMapTexelCount(size);
    EmInferenceResult result;
    result.em = LayerCubeMap(size);
    result.observed.assign(texels, false);
    const TexelData data = texelData(observations, texels);
    // The unknowns: the active texels, numbered in chain order.
    const std::vector<std::uint32_t> parents = cubeMapParents(size);
    std::vector<bool> active = activeTexels(data.observedWeight, parents, size, settings.ring, settings.finerLevels);
    if (!holds.empty()) {
        for (std::size_t t = 0; t < texels; ++t) active[t] = active[t] && holds[t];
    }
    std::vector<Eigen::Index> column(texels, -1);
    Eigen::Index unknowns = 0;
    for (std::size_t t = 0; t < texels; ++t) {
        if (active[t]) column[t] = unknowns++;
    }

    // The confidence-weighted rows of every observation, then the regularising rows.
    StackedRows system(column);
    system.addData(observations);
    result.rows = static_cast<std::size_t>(system.rows());
    const double mean = meanDiagonal(data.normalDiagonal);
    system.addSmoothness(active, size, std::sqrt(settings.smoothness * mean));
    system.addDamping(data, std::sqrt(settings.damping * mean));
    system.addPyramid(active, parents, std::sqrt(settings.pyramid * mean));
    if (unknowns == 0) return result;  // no image saw the layer: it stays empty
    system.solve(unknowns, settings, result);
    // What a texture can hold: premultiplied colour is not negative and alpha is a coverage in
    // [0, 1]; "over" with alpha outside it subtracts the layers behind (the projection of the
    // damped solution onto that set).
    for (glm::vec4& t : result.em.texels) t = glm::vec4(glm::max(glm::vec3(t), glm::vec3(0.0f)), std::clamp(t.a, 0.0f, 1.0f));
    for (std::size_t t = 0; t < result.observed.size(); ++t) {
        result.observed[t] = data.observedWeight[t] >= settings.observedWeight;
        result.observedTexels += result.observed[t] ? 1 : 0;
    }
    result.activeTexels = static_cast<std::size_t>(unknowns);
    return result;
}

}  // namespace hybridlab
