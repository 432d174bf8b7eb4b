#pragma once
// Per-object cost and relevance of Walewski 2019 §3.2 (eqs. 1-3, Listing 6, Table 3).
#include <cstdint>

#include <glm/vec2.hpp>

namespace hybridlab {

// What the heuristic needs to know about one visible object this frame.
struct ObjectObservation {
    std::uint32_t object = 0;
    double visiblePixels = 0.0;          // A: pixels of the object in the object-id target
    glm::vec2 boundsCenterNdc{0.0f};     // its bounding-box centre in NDC
    double distance = 1.0;               // D: bounding-box centre to the camera
    bool reflective = false;
    bool refractive = false;
    double staticRelevance = 1.0;        // K (scene file: relevance)
    double estimatedCost = 1.0;          // E (scene file: cost)
    bool selectedLastFrame = false;      // S
};

struct ObjectScore {
    double P = 0.0;  // centrality, in [0.01, 1]
    double V = 0.0;  // visibility, eq. (1)
    double Q = 0.0;  // estimated rays per pixel
    double C = 0.0;  // cost, eq. (2)
    double R = 0.0;  // relevance, eq. (3)
};

// The secondary effects the heuristic selects (per object, or per object and effect).
enum class Effect { Shadows = 0, Reflection = 1, Refraction = 2 };
inline constexpr int kEffectCount = 3;

// Q's terms (Walewski 2019 §3.2, eq. 2): L shadow rays per pixel; a reflection adds L + 1 (the
// reflected ray and its hit's shadow rays), a refraction L + 4.
double raysPerPixel(Effect effect, int lightCount);

// P = max(1 - |bb|, 0) * 0.99 + 0.01; V = A P / D; Q = L (+ L + 1 if reflective) (+ L + 4 if
// refractive); C = A Q E; R = (S I + V) K, with L lights and I the importance of last frame's
// selection.
ObjectScore scoreObject(const ObjectObservation& o, int lightCount, double previousSelectionImportance);

}  // namespace hybridlab
