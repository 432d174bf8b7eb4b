// libFuzzer target: the scene-file reader (common/scene/scene_file.h), textures and models included
// (the seeds name built-in ones; a model or texture path the fuzzer makes up names nothing).
#include "common/scene/scene_file.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = hybridlab::fuzz::inputFile(data, size, "scene.toml");
    return hybridlab::fuzz::loadOrRefuse([&] { hybridlab::loadSceneFile(file); });
}
