// A seeded random mutator over the readers of outside input: scene files, experiment configs and
// glTF models. Each mutant must load or be refused with an InputError (exit status 2 in the CLI);
// any other exception, a crash or a hang is a finding. The seeds are files in the repository
// (fixtures/minimal.toml, two built-in scenes, the quick experiment) and a glTF written by
// GltfBuilder; the mutations are the mistakes people and broken tools make: flipped or dropped
// bytes, cut files, duplicated lines, and numbers replaced by extreme ones (NaN, 2^32, 1e309,
// negatives). Bounded by a count of mutants and a time limit each, so that CI stays fast.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/core/input_error.h"
#include "common/scene/gltf_loader.h"
#include "common/scene/scene_file.h"
#include "experiments/runner/experiment_config.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kExtremeNumbers = {"nan", "inf", "-inf", "1e309", "-1", "0", "4294967296", "4294967360",
                                                  "9223372036854775807", "-9223372036854775808", "1e-320", "300000", "1e6",
                                                  "18446744073709551616", "0.0", "-0.0", "2147483648"};

// One mutation of `text`.
std::string mutate(std::string text, std::mt19937& random) {
    auto pick = [&](std::size_t n) { return n == 0 ? std::size_t{0} : static_cast<std::size_t>(random() % n); };
    switch (random() % 6) {
    case 0: {  // a number replaced by an extreme one
        std::vector<std::size_t> starts;
        for (std::size_t i = 0; i < text.size(); ++i)
            if (std::isdigit(static_cast<unsigned char>(text[i])) && (i == 0 || !std::isalnum(static_cast<unsigned char>(text[i - 1]))))
                starts.push_back(i);
        if (starts.empty()) break;
        const std::size_t at = starts[pick(starts.size())];
        std::size_t end = at;
        while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '.' || text[end] == '-' || text[end] == '+')) ++end;
        text.replace(at, end - at, kExtremeNumbers[pick(kExtremeNumbers.size())]);
        break;
    }
    case 1:  // a flipped byte
        if (!text.empty()) text[pick(text.size())] = static_cast<char>(random() % 256);
        break;
    case 2: {  // a cut file
        text.resize(pick(text.size() + 1));
        break;
    }
    case 3: {  // a dropped range
        const std::size_t at = pick(text.size() + 1);
        text.erase(at, pick(40));
        break;
    }
    case 4: {  // a duplicated line
        const std::size_t at = text.rfind('\n', pick(text.size() + 1));
        const std::size_t from = at == std::string::npos ? 0 : at + 1;
        const std::size_t to = text.find('\n', from);
        const std::string line = text.substr(from, to == std::string::npos ? std::string::npos : to - from + 1);
        text.insert(from, line);
        break;
    }
    default: {  // an inserted structural character
        static const std::string kChars = "[]{}=\",.\n#'\\";
        text.insert(pick(text.size() + 1), 1, kChars[pick(kChars.size())]);
    }
    }
    return text;
}

struct FuzzOutcome {
    int loaded = 0, refused = 0;
};

// Loads `mutants` mutants of each seed with `load` (given the mutant's path), up to `limit` in all.
FuzzOutcome fuzz(const std::vector<std::string>& seeds, const fs::path& file, const std::function<void(const fs::path&)>& load, int mutants,
                 std::chrono::seconds limit, std::uint32_t seed) {
    std::mt19937 random(seed);
    FuzzOutcome outcome;
    const auto deadline = std::chrono::steady_clock::now() + limit;
    for (int i = 0; i < mutants && std::chrono::steady_clock::now() < deadline; ++i) {
        std::string text = seeds[random() % seeds.size()];
        const int rounds = 1 + static_cast<int>(random() % 3);
        for (int r = 0; r < rounds; ++r) text = mutate(std::move(text), random);
        test::writeTextFile(file, text);
        try {
            load(file);
            ++outcome.loaded;
        } catch (const InputError&) {
            ++outcome.refused;
        } catch (const std::exception& e) {
            ADD_FAILURE() << "mutant " << i << " (seed " << seed << "): not an InputError: " << e.what() << "\n--- input ---\n" << text;
            return outcome;
        }
    }
    return outcome;
}

// CI's bound; HYBRIDLAB_FUZZ_MUTANTS and HYBRIDLAB_FUZZ_SECONDS run longer by hand.
int envOr(const char* name, int fallback) {
    const char* v = std::getenv(name);
    return v && *v ? std::atoi(v) : fallback;
}
const int kMutants = envOr("HYBRIDLAB_FUZZ_MUTANTS", 1500);
const std::chrono::seconds kLimit{envOr("HYBRIDLAB_FUZZ_SECONDS", 20)};

TEST(InputFuzz, SceneFilesLoadOrAreRefusedWithAnInputError) {
    test::TempDir dir;
    std::vector<std::string> seeds;
    for (const fs::path& p : {test::fixturesDir() / "minimal.toml", test::builtinSceneFile("whitted-classic"), test::builtinSceneFile("cornell-mirror-glass")})
        seeds.push_back(test::readTextFile(p));
    const FuzzOutcome o = fuzz(seeds, dir / "scene.toml", [](const fs::path& f) { loadSceneFile(f, {.loadTextures = false}); }, kMutants, kLimit, 1);
    std::printf("[ fuzz     ] scene files: %d loaded, %d refused\n", o.loaded, o.refused);
    EXPECT_GT(o.refused, 0);
}

TEST(InputFuzz, ExperimentConfigsLoadOrAreRefusedWithAnInputError) {
    test::TempDir dir;
    const std::vector<std::string> seeds = {test::readTextFile(test::sourceDir() / "experiments" / "configs" / "quick.toml"),
                                            "[experiment]\nrepeats = 2\n[[scenes]]\nscene = \"whitted-classic\"\nresolutions = [[32, 24], [64, 48]]\n"
                                            "[[scenes.views]]\npath = \"orbit\"\nframes = [0, 10]\nstride = 5\n"
                                            "[[techniques]]\nname = \"whitted\"\nparams = { max_depth = [1, 2] }\n"};
    const FuzzOutcome o = fuzz(seeds, dir / "config.toml", [](const fs::path& f) { loadExperimentConfig(f); }, kMutants, kLimit, 2);
    std::printf("[ fuzz     ] experiment configs: %d loaded, %d refused\n", o.loaded, o.refused);
    EXPECT_GT(o.refused, 0);
}

TEST(InputFuzz, GltfModelsLoadOrAreRefusedWithAnInputError) {
    test::TempDir dir;
    test::GltfBuilder b;
    const int pos = b.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
    const int nrm = b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int idx = b.addIndices({0, 1, 2, 0, 2, 3});
    const int mat = b.addMaterial("red", {1.0, 0.0, 0.0, 1.0});
    const int root = b.addNode({{"mesh", b.addMesh("quad", pos, nrm, idx, mat)}, {"translation", {0.0, 1.0, 0.0}}});
    b.addChild(root, b.addNode({{"camera", b.addPerspectiveCamera(0.8, 0.1, 100.0, 1.5)}}));
    b.setRoots({root});
    const std::vector<std::string> seeds = {b.gltfText()};
    GltfLoadOptions options;
    const FuzzOutcome o = fuzz(seeds, dir / "model.gltf", [&](const fs::path& f) { loadGltf(f, options); }, kMutants, kLimit, 3);
    std::printf("[ fuzz     ] glTF models: %d loaded, %d refused\n", o.loaded, o.refused);
    EXPECT_GT(o.refused, 0);
}

}  // namespace
}  // namespace hybridlab
