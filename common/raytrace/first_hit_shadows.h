#pragma once
// The shadow rays of a block of pixels' first hits, traced light by light as coherent packets
// (RayScene::transmittanceCoherent) before each pixel's ray tree is walked one hit at a time. The
// walk's backend (embree_tree_backend.h) takes a first hit's shadow ray from here when one equal
// to it bit for bit was traced, and traces it itself otherwise: the walk decides which rays it
// needs, as on the device, and a ray traced here that it does not ask for is only time lost.
#include <glm/vec3.hpp>

#include "common/raytrace/ray_scene.h"

namespace hybridlab {

struct FirstHitShadows {
    // Lights beyond these are traced one ray at a time by the walk.
    static constexpr int kMaxLights = 8;

    struct Traced {
        ShadowQuery ray;
        glm::vec3 transmittance;
    };
    int count = 0;
    Traced rays[kMaxLights];  // in the lights' order, as the walk asks for them

    // The transmittance of the traced ray equal to this one, searched from `next` on (which it
    // advances past the match); null when none is.
    const glm::vec3* find(const glm::vec3& origin, const glm::vec3& direction, float tmax, const glm::vec3& startAbsorption,
                          int& next) const {
        for (int i = next; i < count; ++i) {
            const ShadowQuery& r = rays[i].ray;
            if (r.origin == origin && r.direction == direction && r.tmax == tmax && r.startAbsorption == startAbsorption) {
                next = i + 1;
                return &rays[i].transmittance;
            }
        }
        return nullptr;
    }
};

}  // namespace hybridlab
