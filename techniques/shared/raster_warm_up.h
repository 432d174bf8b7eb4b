#pragma once
// Untimed frames that bring a rasterizing technique to its steady state before it is timed:
// lavapipe compiles shaders at the first draw, and targets of a new size cost page faults and
// allocations that later frames do not pay.
#include "techniques/technique.h"

namespace hybridlab {

class RasterWarmUp {
public:
    // The frame prepare() renders once, for the shaders: the scene's camera, small. The first
    // timed frame still warms up at its own size.
    static FrameRequest preparing(const Scene& scene) { return {scene.camera, 0.0, 64, 36}; }

    // Calls render(frame) unless the last frame this warmed up had frame's size.
    template <class Render>
    void atSizeOf(const FrameRequest& frame, Render&& render) {
        if (frame.width == width_ && frame.height == height_) return;
        render(frame);
        width_ = frame.width;
        height_ = frame.height;
    }

private:
    int width_ = 0, height_ = 0;
};

}  // namespace hybridlab
