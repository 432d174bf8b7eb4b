#pragma once
// Tests of the raster core need a Vulkan device; on a machine without one (no loader, no
// lavapipe) they skip with the reason. setup.sh installs lavapipe, so in CI they run.
#include <memory>

#include <gtest/gtest.h>

#include "common/raster/rasterizer.h"
#include "common/raster/vulkan_device.h"
#include "common/raster/vulkan_error.h"

// Declares `std::unique_ptr<Rasterizer> var` for `scene`, or skips the test when no Vulkan device
// can be created.
#define RASTERIZER_OR_SKIP(var, scene)                                            \
    std::unique_ptr<::hybridlab::Rasterizer> var;                                 \
    try {                                                                         \
        var = std::make_unique<::hybridlab::Rasterizer>(scene);                   \
    } catch (const ::hybridlab::VulkanUnavailable& e) {                           \
        GTEST_SKIP() << "no Vulkan device, raster tests skipped: " << e.what();   \
    }

// The ray-tracing device, or a skip when the machine has none (Mesa older than 25, no Vulkan).
#define REQUIRE_RAY_TRACING_DEVICE()                                      \
    try {                                                                 \
        ::hybridlab::VulkanDevice::shared({.rayTracing = true});          \
    } catch (const ::hybridlab::VulkanUnavailable& e) {                   \
        GTEST_SKIP() << "no ray-tracing Vulkan device: " << e.what();     \
    }
