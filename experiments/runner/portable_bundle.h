#pragma once
// `hybridlab bundle`: a relocatable folder that runs hybridlab on a machine without the packages it
// links against (a cluster node):
//   hybridlab        launcher: sets LD_LIBRARY_PATH to lib/ and HYBRIDLAB_SCENES to scenes/, then
//                    runs bin/hybridlab (shaders are embedded in it)
//   bin/hybridlab    this program
//   lib/             every shared library it loads, as the dynamic linker resolves them (ldd), but
//                    the base set below
//   scenes/          the built-in scene files, and the models and textures a config's scenes read
//   configs/         the configs, with scene files they name by path
//   README.txt       what the node must provide, and where each library came from
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace hybridlab {

// Libraries every node has, left out of bundles: glibc's (the dynamic linker, libc, libm,
// libpthread, libdl, librt, libresolv, libutil, libanl, libmvec), and the GCC runtime of a
// minimal Debian (debootstrap minbase: libstdc++, libgcc_s), which a node's Vulkan driver loads
// too and must not be handed an older copy of.
bool isBaseLibrary(const std::string& soname);

struct SharedLibrary {
    std::string soname;
    std::filesystem::path file;  // where the dynamic linker found it
};

// The shared libraries `binary` loads, direct and indirect, as `ldd` lists them (this process's
// LD_LIBRARY_PATH applies). Throws std::runtime_error when ldd fails or a library is not found.
std::vector<SharedLibrary> sharedLibraries(const std::filesystem::path& binary);

struct BundleContents {
    std::size_t libraries = 0;
    std::uintmax_t bytes = 0;  // the whole folder
};

// Writes the bundle of `binary` into `out` (new, or an empty folder), with the scenes and assets of
// the experiment `configs` (none, one, or several: a campaign of experiments on one machine). Built
// beside `out` under a temporary name and renamed when complete: nothing is left at `out` on
// failure. Throws InputError for an `out` that exists and is not an empty folder, a bad config, or
// two configs of one file name (nothing written); IoError when a file cannot be written.
BundleContents writeBundle(const std::filesystem::path& binary, const std::filesystem::path& out,
                           const std::vector<std::filesystem::path>& configs);

}  // namespace hybridlab
