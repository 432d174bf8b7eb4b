#include "experiments/runner/portable_bundle.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "common/core/atomic_file.h"
#include "common/core/input_error.h"
#include "common/core/io_error.h"
#include "common/core/program_version.h"
#include "common/scene/assets.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "experiments/runner/experiment_config.h"

namespace hybridlab {
namespace fs = std::filesystem;

bool isBaseLibrary(const std::string& soname) {
    static const std::set<std::string> base = {"libc.so.6",     "libm.so.6",    "libpthread.so.0", "libdl.so.2",
                                               "librt.so.1",    "libresolv.so.2", "libutil.so.1",  "libanl.so.1",
                                               "libmvec.so.1",  "libstdc++.so.6", "libgcc_s.so.1"};
    // glvnd's dispatch libraries: a GPU's Vulkan driver loads the node's own, and a copy of another
    // version breaks it ("libGLdispatch ABI version is incompatible with libEGL", NVIDIA's driver).
    static const std::set<std::string> glvnd = {"libGLdispatch.so.0", "libGLX.so.0", "libGL.so.1", "libEGL.so.1",
                                                "libOpenGL.so.0",     "libGLESv2.so.2"};
    return base.count(soname) || glvnd.count(soname) || soname.rfind("ld-linux", 0) == 0 || soname.rfind("linux-vdso", 0) == 0;
}

std::vector<SharedLibrary> sharedLibraries(const fs::path& binary) {
    const std::string command = "ldd '" + binary.string() + "' 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) throw std::runtime_error("cannot run ldd on " + binary.string());
    std::string text;
    std::array<char, 4096> chunk{};
    while (std::size_t n = std::fread(chunk.data(), 1, chunk.size(), pipe)) text.append(chunk.data(), n);
    if (::pclose(pipe) != 0) throw std::runtime_error("ldd " + binary.string() + " failed: " + text);
    // "\tsoname => /path/file (0x...)"; the dynamic linker and the vDSO have no "=>" and are base.
    std::vector<SharedLibrary> out;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t arrow = line.find(" => ");
        if (arrow == std::string::npos) continue;
        const std::string soname = line.substr(line.find_first_not_of(" \t"), arrow - line.find_first_not_of(" \t"));
        std::string file = line.substr(arrow + 4);
        if (file.rfind("not found", 0) == 0) throw std::runtime_error(binary.string() + ": the dynamic linker does not find " + soname);
        file = file.substr(0, file.rfind(" ("));
        out.push_back({soname, file});
    }
    return out;
}

namespace {

// fs::copy_file, failing with IoError naming the target.
void copyFile(const fs::path& from, const fs::path& to) {
    createDirectories(to.parent_path());
    std::error_code ec;
    fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
    if (ec) throw IoError::fromErrno(to, "write", ec.value());
}

bool isUnder(const fs::path& file, const fs::path& dir) {
    const fs::path rel = file.lexically_relative(dir);
    return !rel.empty() && *rel.begin() != "..";
}

fs::path canonicalOr(const fs::path& p) {
    std::error_code ec;
    const fs::path c = fs::weakly_canonical(p, ec);
    return ec ? p : c;
}

// Where a file a config's scene reads goes in the bundle: a model or texture under scenes/assets/,
// a scene file under scenes/ or, named by path, under configs/ where the config finds it.
fs::path placeInBundle(const fs::path& file, const fs::path& sceneFile, const fs::path& configFile) {
    const fs::path f = canonicalOr(file);
    const fs::path assets = canonicalOr(assetsRoot(sceneFile)), scenes = canonicalOr(scenesDirectory()),
                   configDir = canonicalOr(configFile.parent_path());
    if (isUnder(f, assets)) return fs::path("scenes") / "assets" / f.lexically_relative(assets);
    if (isUnder(f, scenes)) return fs::path("scenes") / f.lexically_relative(scenes);
    if (isUnder(f, configDir)) return fs::path("configs") / f.lexically_relative(configDir);
    throw InputError(configFile.string() + ": scene " + sceneFile.string() + " reads " + file.string() +
                     ", which is neither in the scenes folder (" + scenes.string() + ") nor under the config's folder (" +
                     configDir.string() + "): the bundle has no place for it that the config would find");
}

const char* kLauncher = R"sh(#!/bin/sh
# hybridlab from a bundle (`hybridlab bundle`): the libraries in lib/, the scenes in scenes/.
here=$(cd "$(dirname "$0")" && pwd -P)
LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
HYBRIDLAB_SCENES="$here/scenes"
export LD_LIBRARY_PATH HYBRIDLAB_SCENES
exec "$here/bin/hybridlab" "$@"
)sh";

std::string readme(const std::vector<SharedLibrary>& bundled, const std::vector<SharedLibrary>& base,
                   const std::vector<fs::path>& configs) {
    std::ostringstream s;
    s << "hybridlab " << programVersion() << ", bundled by `hybridlab bundle`.\n\n"
      << "Run ./hybridlab (the launcher) as the program, from any folder: it sets LD_LIBRARY_PATH to lib/ and\n"
      << "HYBRIDLAB_SCENES to scenes/, then runs bin/hybridlab.";
    for (const fs::path& config : configs) s << "\nThe experiment: ./hybridlab run configs/" << config.filename().string() << " --out DIR";
    s << "\n\nThe node must provide:\n"
      << "- Linux x86-64 with these libraries, which every node has and the bundle leaves out (glibc's, and\n"
      << "  the GCC runtime of a minimal Debian, which the node's Vulkan driver loads too, and glvnd's\n"
      << "  dispatch libraries, which a GPU's driver needs in the node's own version; Debian and Ubuntu:\n"
      << "  libglvnd0 libgl1 libglx0 libegl1 libopengl0 libgles2):\n";
    for (const auto& l : base) s << "    " << l.soname << "\n";
    s << "  glibc and libstdc++ at least as new as the build machine's (Debian 12: glibc 2.36, GCC 12).\n"
      << "- For the techniques that rasterize or trace rays on Vulkan (raster, heuristic_rt, ssr_fallback,\n"
      << "  layered_em, rays = \"vulkan\"): a Vulkan driver (ICD, registered in /usr/share/vulkan/icd.d):\n"
      << "  a GPU vendor's driver, or Mesa's lavapipe (Debian: mesa-vulkan-drivers; 25 or newer for ray\n"
      << "  tracing, from bookworm-backports on Debian 12). The Vulkan loader (libvulkan.so.1) is bundled.\n"
      << "  whitted and rt_only with Embree need no Vulkan device.\n"
      << "A driver that fails to load naming a library in lib/ (the bundle's copy shadows the node's one\n"
      << "for the driver too) is fixed by deleting that file from lib/.\n\n"
      << "Bundled libraries (" << bundled.size() << "), each from:\n";
    for (const auto& l : bundled) s << "    " << l.soname << "  <-  " << l.file.string() << "\n";
    return s.str();
}

std::uintmax_t folderBytes(const fs::path& dir) {
    std::uintmax_t n = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) n += e.file_size();
    return n;
}

}  // namespace

BundleContents writeBundle(const fs::path& binary, const fs::path& out, const std::vector<fs::path>& configs) {
    if (fs::exists(out) && (!fs::is_directory(out) || !fs::is_empty(out)))
        throw InputError(out.string() + ": exists and is not an empty folder; choose another --out");
    // Every file the config's scenes read, before anything is written.
    std::map<fs::path, fs::path> files;  // in the bundle <- from
    for (const fs::path& config : configs) {
        const ExperimentConfig experiment = loadExperimentConfig(config);
        const auto [placed, fresh] = files.emplace(fs::path("configs") / config.filename(), config);
        if (!fresh)
            throw InputError(config.string() + ": a config of the same file name as " + placed->second.string() +
                             " is already bundled (both would be configs/" + config.filename().string() + "); rename one");
        for (const SceneSpec& spec : experiment.scenes) {
            const Scene scene = loadSceneFile(spec.file);
            files[placeInBundle(spec.file, spec.file, config)] = spec.file;
            for (const fs::path& source : scene.sourceFiles) files[placeInBundle(source, spec.file, config)] = source;
        }
    }
    for (const fs::path& scene : listSceneFiles()) files.try_emplace(fs::path("scenes") / scene.filename(), scene);

    std::vector<SharedLibrary> bundled, base;
    for (auto& l : sharedLibraries(binary)) (isBaseLibrary(l.soname) ? base : bundled).push_back(std::move(l));
    for (const auto& l : bundled) files[fs::path("lib") / l.soname] = l.file;
    files[fs::path("bin") / "hybridlab"] = binary;

    // Built under a temporary name beside `out`, renamed when complete.
    writeFolderAtomically(out, [&](const fs::path& staging) {
        for (const auto& [to, from] : files) copyFile(from, staging / to);
        writeFileAtomically(staging / "hybridlab", kLauncher);
        writeFileAtomically(staging / "README.txt", readme(bundled, base, configs));
        std::error_code ec;
        fs::permissions(staging / "hybridlab", fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                                    fs::perms::others_read | fs::perms::others_exec, ec);
        if (ec) throw IoError::fromErrno(staging / "hybridlab", "make executable", ec.value());
    });
    return {bundled.size(), folderBytes(out.has_filename() ? out : out.parent_path())};
}

}  // namespace hybridlab
