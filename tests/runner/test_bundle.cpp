// `hybridlab bundle`: the bundle runs from a folder outside the checkout with LD_LIBRARY_PATH
// pointed at it alone, the dynamic linker resolves every library in it but the base ones, it
// renders the same image as the program in the build folder, and it carries the models of the
// config's scenes.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/image/image_io.h"
#include "experiments/runner/portable_bundle.h"
#include "tests/support/cli_runner.h"
#include "tests/support/shell_command.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

// A shell command run in `cwd` with the library path set to `libraries` alone, and no scene or
// asset folder from the environment.
std::string inFolder(const fs::path& cwd, const fs::path& libraries, const std::string& command) {
    return "cd " + quoted(cwd) + " && env -u HYBRIDLAB_ASSETS -u HYBRIDLAB_SCENES LD_LIBRARY_PATH=" + quoted(libraries) + " " + command + " 2>&1";
}

TEST(PortableBundle, RunsFromAnotherFolderOnItsOwnLibrariesAndScenes) {
    test::TempDir dir;
    const fs::path bundle = dir / "bundle", config = dir / "bundled.toml";
    // teapot-lens reads a model (scenes/assets/teapot); the bundle must carry it, and no other.
    test::writeTextFile(config, R"(
[experiment]
name = "bundled"
warmup_frames = 0
repeats = 1
[[scenes]]
scene = "teapot-lens"
resolutions = [[32, 18]]
[[techniques]]
name = "whitted"
)");
    const test::CliResult made = test::runHybridlab({"bundle", "--out", bundle.string(), "--config", config.string()});
    ASSERT_EQ(made.exitStatus, 0) << made.err;
    EXPECT_CONTAINS(made.out, "bundle in " + bundle.string() + ": ");
    for (const char* file : {"hybridlab", "bin/hybridlab", "README.txt", "lib/libembree3.so.3", "lib/libvulkan.so.1",
                             "scenes/whitted-classic.toml", "scenes/teapot-lens.toml", "configs/bundled.toml"})
        EXPECT_TRUE(fs::is_regular_file(bundle / file)) << file;
    EXPECT_TRUE(fs::is_directory(bundle / "scenes" / "assets" / "teapot"));
    EXPECT_FALSE(fs::exists(bundle / "scenes" / "assets" / "sponza")) << "only the config's scenes' models";
    EXPECT_FALSE(fs::exists(bundle / "lib" / "libc.so.6"));

    // The dynamic linker's view: every library in lib/ but the documented base ones.
    const test::CommandOutput ldd = test::commandOutput(inFolder(dir.path(), bundle / "lib", "ldd " + quoted(bundle / "bin" / "hybridlab")));
    ASSERT_EQ(ldd.exitStatus, 0) << ldd.out;
    std::istringstream lines(ldd.out);
    std::size_t inside = 0;
    for (std::string line; std::getline(lines, line);) {
        const std::size_t arrow = line.find(" => ");
        if (arrow == std::string::npos) continue;
        const std::string soname = line.substr(line.find_first_not_of(" \t"), arrow - line.find_first_not_of(" \t"));
        const std::string file = line.substr(arrow + 4, line.rfind(" (") - arrow - 4);
        if (fs::path(file).parent_path() == bundle / "lib") ++inside;
        else EXPECT_TRUE(isBaseLibrary(soname)) << line;
    }
    EXPECT_GT(inside, 10u) << ldd.out;  // Embree, OpenEXR, libpng, TBB, ... and what they load

    // What a bundle holds is what the program links: image formats on their own libraries keep it
    // small enough to copy to a GPU machine whole (about 76 MB here, 18 MB as a .tar.xz).
    std::uintmax_t libraryBytes = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(bundle / "lib")) libraryBytes += e.file_size();
    EXPECT_LT(libraryBytes, 150u << 20) << "lib/ holds " << (libraryBytes >> 20) << " MiB";

    // Renders from another folder, with Embree, with the rasterizer and with rays on the Vulkan
    // device (lavapipe here): the images the program in the build folder renders.
    const fs::path elsewhere = dir / "elsewhere";
    fs::create_directories(elsewhere);
    const std::vector<std::pair<std::string, std::string>> renders = {
        {"whitted", "--technique whitted"}, {"raster", "--technique raster"}, {"whitted-vulkan", "--technique whitted --param rays=vulkan"}};
    for (const auto& [name, technique] : renders) {
        SCOPED_TRACE(name);
        const std::string render = " render --scene whitted-classic --width 32 --height 18 " + technique + " --out ";
        const test::CommandOutput bundled = test::commandOutput(
            inFolder(elsewhere, bundle / "lib", "HYBRIDLAB_VULKAN_DEVICE=llvmpipe " + quoted(bundle / "hybridlab") + render + name + ".exr"));
        ASSERT_EQ(bundled.exitStatus, 0) << bundled.out;
        std::vector<std::string> args = {"render", "--scene", "whitted-classic", "--width", "32", "--height", "18", "--out",
                                         (dir / (name + "-direct.exr")).string()};
        std::istringstream words(technique);
        for (std::string w; words >> w;) args.push_back(w);
        const test::CliResult direct = test::runHybridlab(args, {{"HYBRIDLAB_VULKAN_DEVICE", "llvmpipe"}});
        ASSERT_EQ(direct.exitStatus, 0) << direct.err;
        const Image image = readImage(elsewhere / (name + ".exr")), expected = readImage(dir / (name + "-direct.exr"));
        ASSERT_EQ(image.width(), 32);
        ASSERT_EQ(image.height(), 18);
        double sum = 0.0;
        for (int y = 0; y < image.height(); ++y) {
            for (int x = 0; x < image.width(); ++x) {
                for (int c = 0; c < 3; ++c) {
                    ASSERT_TRUE(std::isfinite(image.at(x, y)[c]));
                    sum += image.at(x, y)[c];
                }
                ASSERT_EQ(image.at(x, y), expected.at(x, y)) << x << "," << y;
            }
        }
        EXPECT_GT(sum, 0.0);
        EXPECT_TRUE(fs::exists(elsewhere / (name + ".png")));
    }

    // The config, from the bundle: its scene loads with the bundle's model (a dry run loads the
    // scenes and writes nothing).
    const test::CommandOutput plan = test::commandOutput(
        inFolder(elsewhere, bundle / "lib", quoted(bundle / "hybridlab") + " run " + quoted(bundle / "configs" / "bundled.toml") + " --dry-run --cache cache"));
    ASSERT_EQ(plan.exitStatus, 0) << plan.out;
    EXPECT_CONTAINS(plan.out, "experiment bundled (" + (bundle / "configs" / "bundled.toml").string() + ", ");
}

// Several configs (a campaign of experiments for one machine): each config, and every one's models.
TEST(PortableBundle, CarriesEveryConfigAndItsModels) {
    test::TempDir dir;
    const auto config = [&](const fs::path& file, const std::string& scene) {
        fs::create_directories(file.parent_path());
        test::writeTextFile(file, "[experiment]\nname = \"" + file.stem().string() + "\"\n[[scenes]]\nscene = \"" + scene +
                                      "\"\nresolutions = [[32, 18]]\n[[techniques]]\nname = \"whitted\"\n");
    };
    config(dir / "lens.toml", "teapot-lens");
    config(dir / "bunnies.toml", "bunnies-falling-5");
    config(dir / "other" / "lens.toml", "whitted-classic");
    const fs::path bundle = dir / "bundle";
    const test::CliResult made =
        test::runHybridlab({"bundle", "--out", bundle.string(), "--config", (dir / "lens.toml").string(), "--config", (dir / "bunnies.toml").string()});
    ASSERT_EQ(made.exitStatus, 0) << made.err;
    for (const char* file : {"configs/lens.toml", "configs/bunnies.toml"}) EXPECT_TRUE(fs::is_regular_file(bundle / file)) << file;
    for (const char* model : {"teapot", "bunny"}) EXPECT_TRUE(fs::is_directory(bundle / "scenes" / "assets" / model)) << model;
    EXPECT_FALSE(fs::exists(bundle / "scenes" / "assets" / "sponza"));
    EXPECT_CONTAINS(test::readTextFile(bundle / "README.txt"), "./hybridlab run configs/bunnies.toml --out DIR");

    // Two configs that would be one configs/lens.toml: refused, nothing written.
    const fs::path clash = dir / "clash";
    const test::CliResult refused = test::runHybridlab(
        {"bundle", "--out", clash.string(), "--config", (dir / "lens.toml").string(), "--config", (dir / "other" / "lens.toml").string()});
    EXPECT_EQ(refused.exitStatus, 2) << refused.err;
    EXPECT_CONTAINS(refused.err, "is already bundled (both would be configs/lens.toml); rename one");
    EXPECT_FALSE(fs::exists(clash));

    // The README's own example, its scene beside it and its model the program's: the bundle runs it.
    const fs::path example = dir / "example";
    const test::CliResult bundled =
        test::runHybridlab({"bundle", "--out", example.string(), "--config", (test::sourceDir() / "examples" / "mirror-bunny" / "experiment.toml").string()});
    ASSERT_EQ(bundled.exitStatus, 0) << bundled.err;
    const test::CommandOutput planned =
        test::commandOutput(inFolder(example, example / "lib", "./hybridlab run configs/experiment.toml --out " + quoted(dir / "out") + " --dry-run"));
    EXPECT_EQ(planned.exitStatus, 0) << planned.out;
    EXPECT_CONTAINS(planned.out, "mirror-bunny  camera");
}

TEST(PortableBundle, BadInputIsRefusedAndLeavesNothing) {
    test::TempDir dir;
    const fs::path full = dir / "full";
    fs::create_directories(full);
    test::writeTextFile(full / "keep.txt", "mine");
    const auto refused = test::runHybridlab({"bundle", "--out", full.string()});
    EXPECT_EQ(refused.exitStatus, 2) << refused.err;
    EXPECT_CONTAINS(refused.err, full.string() + ": exists and is not an empty folder; choose another --out");
    EXPECT_EQ(test::readTextFile(full / "keep.txt"), "mine");

    const auto missing = test::runHybridlab({"bundle", "--out", (dir / "b").string(), "--config", (dir / "missing.toml").string()});
    EXPECT_EQ(missing.exitStatus, 2) << missing.err;
    EXPECT_CONTAINS(missing.err, (dir / "missing.toml").string());

    // A folder that cannot be made: under a regular file.
    const auto unwritable = test::runHybridlab({"bundle", "--out", (full / "keep.txt" / "bundle").string()});
    EXPECT_EQ(unwritable.exitStatus, 3) << unwritable.err;
    EXPECT_CONTAINS(unwritable.err, (full / "keep.txt").string());

    // Nothing of any of them: only the folder the test made.
    std::vector<std::string> left;
    for (const auto& e : fs::recursive_directory_iterator(dir.path())) left.push_back(fs::relative(e.path(), dir.path()).string());
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<std::string>{"full", "full/keep.txt"}));
}

}  // namespace
}  // namespace hybridlab
