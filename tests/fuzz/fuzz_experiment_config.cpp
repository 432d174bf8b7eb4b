// libFuzzer target: the experiment-config reader (experiments/runner/experiment_config.h), which
// also reads the scene files the config names and plans its runs.
#include "experiments/runner/experiment_config.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = hybridlab::fuzz::inputFile(data, size, "config.toml");
    return hybridlab::fuzz::loadOrRefuse([&] { hybridlab::planRuns(hybridlab::loadExperimentConfig(file)); });
}
