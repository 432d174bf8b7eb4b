#include <cstdlib>

#include <gtest/gtest.h>

int main(int argc, char** argv) {
    // The tests' thresholds were calibrated on lavapipe, whose results are deterministic: select it by
    // name (the program itself prefers a GPU when one is present), unless the caller chose a device.
    // The programs the tests start inherit it.
    setenv("HYBRIDLAB_VULKAN_DEVICE", "llvmpipe", 0);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
