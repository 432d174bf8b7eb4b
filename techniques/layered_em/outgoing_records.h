#pragma once
// Compiling the outgoing rays (Hakura & Snyder 2001 §4.1): per viewpoint sample, a supersampled
// image of the lens system through the two-term model; every outgoing ray is followed into the
// environment (the scene without the lens system) and records every front-facing intersection,
// not only the first (ray continuation, Figure 4c); incoming rays are traced against the lens
// system alone, so parts of the lens hidden behind environment objects still produce records
// (Figure 4b). Each record keeps the environment's radiance there as the reference tracer shades
// it. Also: the direct images of the environment (§4.3) and the per-pixel layer images b and
// confidence that inference matches.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/raytrace/whitted_tracer.h"
#include "common/scene/camera.h"
#include "techniques/layered_em/layer_shells.h"
#include "techniques/shared/lens_paths.h"
#include "techniques/shared/lens_system.h"

namespace hybridlab {

// NDC of subsample k of an n x n stratified grid in pixel (x, y).
glm::vec2 subpixelNdc(int x, int y, int k, int n, int width, int height);

// §4.3: 1 - min(theta_m^2, theta_c^2) / theta_c^2 for the largest angle theta_m between the
// outgoing rays of a pixel (radians).
float rayConfidence(float maxAngle, float thetaC);

// theta_c in degrees for lens images `height` pixels high: `degrees`, or when it is 0 the paper's
// 5 degrees (a 640 x 480 display, §6) times 480 / height.
float confidenceAngle(float degrees, int height);

struct OutgoingRecord {
    std::uint32_t pixel = 0;     // y * width + x
    std::uint32_t ray = 0;       // ((pixel * n^2 + subsample) * 2 + term): unique within the viewpoint
    std::uint16_t order = 0;     // 0: the outgoing ray's first environment intersection
    std::uint8_t term = 0;       // PathTerm
    std::uint32_t object = 0;    // scene object index
    float distance = 0.0f;       // from the lens centre
    glm::vec3 position{0.0f};
    glm::vec3 radiance{0.0f};
};

struct RecordSettings {
    int supersampling = 3;           // n x n incoming rays a pixel (§4.1: 3 x 3)
    int maxHitsPerRay = 8;           // intersections recorded along one outgoing ray
    bool continueRays = true;        // §4.1 continuation; false: first hits only, incoming rays stop at occluders
    float confidenceAngleDegrees = 0.0f;  // theta_c; 0: the paper's 5 degrees at its 480 lines, scaled to the
                                          // bake's (confidenceAngle): a pixel's rays spread with its size
    LensPathSettings paths;
};

struct ViewpointRecords {
    Camera camera;
    int width = 0, height = 0, supersampling = 1;
    std::vector<OutgoingRecord> records;
    // Per (pixel, subsample, term) ray: whether the path exists, and its exit direction.
    std::vector<std::uint8_t> rayExists;
    std::vector<glm::vec3> rayDirection;
    std::vector<OutgoingRay> rays;  // exit origin and direction, same indexing
    // Per ray: whether it reached the sky with every surface along it recorded, so that a layer
    // without a record of it is empty along it (not merely hidden behind what it met).
    std::vector<std::uint8_t> rayEscaped;
    std::uint64_t lensQueries = 0, environmentQueries = 0;
};

// `shading` traces the full scene (what the reference sees at an environment point).
ViewpointRecords compileOutgoingRecords(const LensSystem& system, const WhittedTracer& shading, const Camera& camera,
                                        int width, int height, const RecordSettings& settings);

// Direct image of the environment from the viewpoint (no lens), with continuation as above.
// Records have term 0 and one ray per pixel (supersampling 1).
ViewpointRecords compileDirectRecords(const LensSystem& system, const WhittedTracer& shading, const Camera& camera, int width,
                                      int height, const RecordSettings& settings);

// Per-pixel accumulation of one term and layer: the premultiplied mean of the layer colour over
// the pixel's rays that have the term (alpha: the fraction of them that met the layer), and the
// confidence from the spread of their outgoing directions.
class LayerImageAccumulator {
public:
    LayerImageAccumulator(int width, int height, float confidenceAngleDegrees = 5.0f);
    void addRay(int x, int y, glm::vec3 outgoingDirection);   // a ray of the pixel with this term
    void addColor(int x, int y, glm::vec4 premultiplied);      // its first intersection in the layer
    void add(int x, int y, glm::vec3 outgoingDirection, glm::vec4 premultiplied) {
        addRay(x, y, outgoingDirection);
        addColor(x, y, premultiplied);
    }
    void finish(std::vector<glm::vec4>& b, std::vector<float>& confidence) const;

private:
    int width_;
    float thetaC_;
    std::vector<glm::vec4> sum_;
    std::vector<std::vector<glm::vec3>> directions_;
};

}  // namespace hybridlab
