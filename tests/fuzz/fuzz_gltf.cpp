// libFuzzer target: the glTF loader (common/scene/gltf_loader.h), as text (.gltf) or binary (.glb,
// chosen by the binary container's magic "glTF" at the start, as a file's extension would).
#include <cstring>

#include "common/scene/gltf_loader.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const auto file = hybridlab::fuzz::inputFile(data, size, binary ? "model.glb" : "model.gltf");
    return hybridlab::fuzz::loadOrRefuse([&] { hybridlab::loadGltf(file, {}); });
}
