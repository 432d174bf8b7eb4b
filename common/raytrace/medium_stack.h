#pragma once
// The media a ray travels in, and Beer-Lambert absorption along it. The rule, the same for every
// tracer (the reference, the hybrids' traced rays, the two-term lens paths; a GPU port mirrors
// these few lines):
//
//   * A path starts in the ambient medium (nothing absorbs). A refracted ray that enters an object
//     through its front face pushes (object, absorption); one that leaves through a back face pops
//     that object's entry, wherever it is in the stack (touching and overlapping objects). A
//     reflected ray keeps its parent's stack.
//   * A segment of length d carries exp(-A d), A the SUM of the absorption coefficients of every
//     medium in the stack (overlapping media add, as POV-Ray's media of nested hollow objects do;
//     a segment in an opaque object nested in a glass ball is inside the glass only).
//   * Eye-path segments are attenuated up to the surface they end on, whatever it is. A ray that
//     leaves the scene (the sky) is not attenuated: an unbounded segment inside a closed object
//     cannot happen, and an open one is not a medium.
//   * A shadow ray from a point inside the stack's media to a light at distance D carries
//     exp(-tau) with tau = A_start D + sum over crossings i of +-a_i (D - t_i): + where it enters
//     object i (front face), - where it leaves it (back face). That is the integral of A along
//     the ray whatever order the crossings come in (Embree reports them in any order); towards a
//     directional light (D infinite) tau = sum over crossings of -+a_i t_i (the light lies outside
//     every medium).
//   * A ray that leaves a medium it never entered (overlapping or open meshes), or enters more
//     than kCapacity nested media, keeps its stack unchanged and is counted (RayStats::mediumErrors).
//
// Hakura & Snyder 2001's G (Kay & Greenberg's transparency) is this term along each lens path.
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

#include "common/shading/absorption.h"

namespace hybridlab {

class MediumStack {
public:
    static constexpr int kCapacity = 8;

    // The ambient medium (nothing entered). Entries past depth() are never read, so neither this
    // nor a copy touches them: a camera ray's empty stack, passed at every recursion, costs its
    // size and absorption alone rather than a fill and copy of every entry.
    MediumStack() {}
    MediumStack(const MediumStack& other) : size_(other.size_), absorption_(other.absorption_) {
        for (int i = 0; i < size_; ++i) entries_[i] = other.entries_[i];
    }
    MediumStack& operator=(const MediumStack& other) {
        size_ = other.size_;
        absorption_ = other.absorption_;
        for (int i = 0; i < size_; ++i) entries_[i] = other.entries_[i];
        return *this;
    }
    // The stack of a camera ray, shared: default arguments take it instead of a temporary.
    static const MediumStack kAmbient;

    // Sum of the absorption coefficients of the media the ray is in.
    const glm::vec3& absorption() const { return absorption_; }
    bool absorbs() const { return absorption_.x > 0.0f || absorption_.y > 0.0f || absorption_.z > 0.0f; }
    int depth() const { return size_; }

    // The stack of a ray that entered `object` (absorption `a`); false (stack unchanged) when full.
    bool enter(std::uint32_t object, glm::vec3 a) {
        if (size_ == kCapacity) return false;
        entries_[size_++] = {object, a};
        absorption_ += a;
        return true;
    }
    // The stack of a ray that left `object`; false (stack unchanged) when it was never entered.
    bool leave(std::uint32_t object) {
        for (int i = size_ - 1; i >= 0; --i) {
            if (entries_[i].object != object) continue;
            for (int j = i; j + 1 < size_; ++j) entries_[j] = entries_[j + 1];
            --size_;
            absorption_ = glm::vec3(0.0f);  // re-summed, so that no rounding accumulates along a path
            for (int j = 0; j < size_; ++j) absorption_ += entries_[j].absorption;
            return true;
        }
        return false;
    }

private:
    struct Entry {
        std::uint32_t object;
        glm::vec3 absorption;
    };
    Entry entries_[kCapacity];
    int size_ = 0;
    glm::vec3 absorption_{0.0f};
};

inline const MediumStack MediumStack::kAmbient;

// Beer-Lambert transmittance of a segment (common/shading/absorption.h, written once for both ray
// backends with a shadow ray's optical depth at a crossing).
using shading_language::crossingOpticalDepth;
using shading_language::segmentTransmittance;
using shading_language::shadowRayTransmittance;

}  // namespace hybridlab
