#include "common/raytrace/ray_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "common/core/wall_clock.h"
#include "common/raytrace/medium_stack.h"
#include "common/raytrace/shading.h"

namespace hybridlab {

namespace {

void checkDevice(RTCDevice device, const char* what) {
    RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree error ") + std::to_string(e) + " while " + what);
}

// Any-hit program of shadow rays (Walewski 2019 Listing 8b): attached only to geometry whose
// material lets light through or casts no shadow, so opaque casters end the ray at once.
void shadowFilter(const RTCFilterFunctionNArguments* args) {
    auto* ctx = reinterpret_cast<ShadowRayContext*>(args->context);
    for (unsigned k = 0; k < args->N; ++k) {
        if (!args->valid[k]) continue;
        ShadowLane& lane = ctx->lanes[RTCRayN_id(args->ray, args->N, k)];
        const unsigned geom = RTCHitN_geomID(args->hit, args->N, k), inst = RTCHitN_instID(args->hit, args->N, k, 0);
        const float t = RTCRayN_tfar(args->ray, args->N, k);
        bool counted = false;
        for (int i = 0; i < lane.crossings && !counted; ++i)
            counted = lane.geometry[i] == geom && lane.instance[i] == inst && std::abs(lane.distance[i] - t) <= 1e-5f * t;
        if (counted) {
            args->valid[k] = 0;  // the same surface crossing, seen through its other triangle
            continue;
        }
        if (lane.crossings < ShadowLane::kMaxCrossings) {
            lane.geometry[lane.crossings] = geom;
            lane.instance[lane.crossings] = inst;
            lane.distance[lane.crossings] = t;
            ++lane.crossings;
        }
        const Material& m = *static_cast<const Material*>(args->geometryUserPtr);
        if (m.absorption != glm::vec3(0.0f)) {
            // Ray and normal are in the same (instance) space; the normal follows the winding as
            // SurfaceHit::geometricNormal does, so a negative cosine is a front face: entering.
            const float cosine = RTCRayN_dir_x(args->ray, args->N, k) * RTCHitN_Ng_x(args->hit, args->N, k) +
                                 RTCRayN_dir_y(args->ray, args->N, k) * RTCHitN_Ng_y(args->hit, args->N, k) +
                                 RTCRayN_dir_z(args->ray, args->N, k) * RTCHitN_Ng_z(args->hit, args->N, k);
            const bool entering = cosine < 0.0f;
            lane.opticalDepth += crossingOpticalDepth(m.absorption, entering, t, std::isfinite(lane.tmax) ? lane.tmax : -1.0f);
        }
        lane.transmittance *= occluderTransmittance(m);
        if (lane.transmittance.r > 0.0f || lane.transmittance.g > 0.0f || lane.transmittance.b > 0.0f) args->valid[k] = 0;
    }
}

// Lane k of a packet: a ray from tnear 0 to `tfar`, with `id`.
void setPacketLane(RTCRay8& packet, int k, const glm::vec3& origin, const glm::vec3& direction, float tfar, unsigned id) {
    packet.org_x[k] = origin.x, packet.org_y[k] = origin.y, packet.org_z[k] = origin.z;
    packet.dir_x[k] = direction.x, packet.dir_y[k] = direction.y, packet.dir_z[k] = direction.z;
    packet.tnear[k] = 0.0f;
    packet.tfar[k] = tfar;
    packet.time[k] = 0.0f;
    packet.mask[k] = 0xFFFFFFFFu;
    packet.id[k] = id;
    packet.flags[k] = 0;
}

// A traced shadow ray's transmittance from its lane's state: 0 where Embree accepted a hit (tfar
// -inf: an opaque caster, or the transmittance used up).
glm::vec3 laneTransmittance(const ShadowLane& lane, float tfar, const glm::vec3& startAbsorption) {
    if (tfar == -std::numeric_limits<float>::infinity()) return glm::vec3(0.0f);
    return shadowRayTransmittance(lane.transmittance, lane.opticalDepth, startAbsorption, std::isfinite(lane.tmax) ? lane.tmax : -1.0f);
}

// What depends on a triangle alone (world-space vertices p0, p1, p2): its unit geometric normal by
// the winding, and ray cones' Delta_0 = 0.5 log2(uv area / world area) (ray_cone.h; -inf without uvs).
struct TriangleTerms {
    glm::vec3 geometricNormal;
    float uvDensityLod = -std::numeric_limits<float>::infinity();
};

TriangleTerms triangleTerms(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, const glm::vec2* uv) {
    TriangleTerms terms;
    terms.geometricNormal = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    if (uv) {
        const glm::vec2 a = uv[1] - uv[0], b = uv[2] - uv[0];
        const float uvArea = std::abs(a.x * b.y - a.y * b.x);
        const float worldArea = glm::length(glm::cross(p1 - p0, p2 - p0));
        if (uvArea > 0.0f && worldArea > 0.0f) terms.uvDensityLod = 0.5f * std::log2(uvArea / worldArea);
    }
    return terms;
}

}  // namespace

RTCGeometry RayScene::makeTriangleGeometry(const Mesh& mesh, const std::vector<glm::vec3>& positions, const glm::mat4* toWorld,
                                           bool refit) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          positions.size()));
    for (std::size_t i = 0; i < positions.size(); ++i) {
        glm::vec3 p = toWorld ? glm::vec3(*toWorld * glm::vec4(positions[i], 1.0f)) : positions[i];
        v[3 * i] = p.x, v[3 * i + 1] = p.y, v[3 * i + 2] = p.z;
    }
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                               mesh.triangles.size()));
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        idx[3 * i] = mesh.triangles[i].x, idx[3 * i + 1] = mesh.triangles[i].y, idx[3 * i + 2] = mesh.triangles[i].z;
    }
    const Material& m = scene_.materials[mesh.material];
    rtcSetGeometryUserData(g, const_cast<Material*>(&m));
    if (m.isRefractive() || !m.castsShadows) rtcSetGeometryOccludedFilterFunction(g, shadowFilter);
    if (refit) rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_REFIT);
    rtcCommitGeometry(g);
    return g;
}

void RayScene::deformObject(std::size_t object, double time) {
    const std::vector<std::uint32_t>& meshes = scene_.objects[object].meshes;
    const std::vector<DeformedVertices>& deformed = deformedMeshes_->vertices(object, time, DeformedMeshCache::kRayScene);
    for (std::uint32_t k = 0; k < meshes.size(); ++k) {
        DeformedVertices& d = deformed_[meshes[k]];
        d = deformed[k];
        RTCGeometry g = rtcGetGeometry(objectScenes_[object], k);
        if (!g) continue;
        auto* v = static_cast<float*>(rtcGetGeometryBufferData(g, RTC_BUFFER_TYPE_VERTEX, 0));
        for (std::size_t i = 0; i < d.positions.size(); ++i) v[3 * i] = d.positions[i].x, v[3 * i + 1] = d.positions[i].y, v[3 * i + 2] = d.positions[i].z;
        rtcUpdateGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0);
        rtcCommitGeometry(g);
    }
}

std::vector<RayScene::StaticTriangle> RayScene::worldTriangles(const Mesh& m, const glm::mat4& toWorld, const glm::mat3& normalToWorld) {
    std::vector<glm::vec3> positions, normals;
    for (const auto& p : m.positions) positions.push_back(glm::vec3(toWorld * glm::vec4(p, 1.0f)));
    for (const auto& nrm : m.normals) normals.push_back(normalToWorld * nrm);
    std::vector<StaticTriangle> triangles(m.triangles.size());
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        StaticTriangle& t = triangles[i];
        t.vertices = m.triangles[i];
        for (int k = 0; k < 3; ++k) {
            t.position[k] = positions[t.vertices[k]];
            t.normal[k] = normals[t.vertices[k]];
            t.uv[k] = m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[t.vertices[k]];
        }
        const TriangleTerms terms = triangleTerms(t.position[0], t.position[1], t.position[2], m.uvs.empty() ? nullptr : t.uv);
        t.geometricNormal = terms.geometricNormal;
        t.uvDensityLod = terms.uvDensityLod;
    }
    return triangles;
}

RayScene::RayScene(const Scene& scene, double time, DeformedMeshCache* deformedMeshes) : scene_(scene), time_(time) {
    auto start = WallClock::now();
    if (!deformedMeshes) ownDeformedMeshes_ = std::make_unique<DeformedMeshCache>(scene);
    deformedMeshes_ = deformedMeshes ? deformedMeshes : ownDeformedMeshes_.get();
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("cannot create an Embree device");
    textureMips_.reserve(scene.textures.size());
    for (const Texture& t : scene.textures) textureMips_.emplace_back(t.image);
    for (const Material& m : scene.materials) diffuseTextures_.push_back(makeDiffuseTexture(m, textureMips(m.diffuseTexture)));
    const std::size_t n = scene.objects.size();
    toWorld_.resize(n);
    normalToWorld_.resize(n);
    objectScenes_.assign(n, nullptr);
    instanceGeometry_.assign(n, RTC_INVALID_GEOMETRY_ID);
    bool anyAnimated = false;
    for (std::size_t o = 0; o < n; ++o) {
        toWorld_[o] = scene.objects[o].worldMatrix(time);
        normalToWorld_[o] = normalMatrix(toWorld_[o]);
        anyAnimated |= scene.objects[o].isDynamic();
        triangles_ += scene.objectTriangleCount(o);
    }
    deformed_.resize(scene.meshes.size());

    static_ = rtcNewScene(device_);
    for (std::size_t o = 0; o < n; ++o) {
        if (scene.objects[o].isDynamic()) continue;
        for (std::uint32_t mesh : scene.objects[o].meshes) {
            const Mesh& m = scene.meshes[mesh];
            RTCGeometry g = makeTriangleGeometry(m, m.positions, &toWorld_[o], false);
            rtcAttachGeometryByID(static_, g, static_cast<unsigned>(staticGeometry_.size()));
            rtcReleaseGeometry(g);
            staticGeometry_.push_back({static_cast<std::uint32_t>(o), mesh, &scene.materials[m.material], !m.uvs.empty(),
                                       worldTriangles(m, toWorld_[o], normalToWorld_[o])});
        }
    }
    // Spatial splits: built once per scene (about 120 ms for sponza-spheres, twice the default's),
    // traced in every frame (its bare traversal 0.89-0.93 of the default's time).
    rtcSetSceneBuildQuality(static_, RTC_BUILD_QUALITY_HIGH);
    rtcCommitScene(static_);

    if (!anyAnimated) {
        top_ = static_;
    } else {
        top_ = rtcNewScene(device_);
        RTCGeometry inst = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(inst, static_);
        glm::mat4 identity(1.0f);
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &identity[0][0]);
        rtcCommitGeometry(inst);
        unsigned staticInstance = rtcAttachGeometry(top_, inst);
        rtcReleaseGeometry(inst);
        instanceObject_.resize(staticInstance + 1, std::numeric_limits<std::uint32_t>::max());
        for (std::size_t o = 0; o < n; ++o) {
            const SceneObject& object = scene.objects[o];
            if (!object.isDynamic()) continue;
            RTCScene s = rtcNewScene(device_);
            const bool deforming = object.isDeforming();
            if (deforming) {
                // A two-level build whose per-geometry BVHs refit when only the vertices change.
                rtcSetSceneFlags(s, RTC_SCENE_FLAG_DYNAMIC);
                rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_LOW);
                deformingTriangles_ += scene.objectTriangleCount(o);
            } else {
                rigidMovingTriangles_ += scene.objectTriangleCount(o);
            }
            const std::vector<DeformedVertices>* deformed =
                deforming ? &deformedMeshes_->vertices(o, time, DeformedMeshCache::kRayScene) : nullptr;
            for (std::uint32_t k = 0; k < object.meshes.size(); ++k) {
                const std::uint32_t mesh = object.meshes[k];
                const Mesh& m = scene.meshes[mesh];
                if (deforming) deformed_[mesh] = (*deformed)[k];
                RTCGeometry g = makeTriangleGeometry(m, deforming ? deformed_[mesh].positions : m.positions, nullptr, deforming);
                rtcAttachGeometryByID(s, g, k);
                rtcReleaseGeometry(g);
            }
            rtcCommitScene(s);
            objectScenes_[o] = s;
            RTCGeometry i = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(i, s);
            rtcSetGeometryTransform(i, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &toWorld_[o][0][0]);
            rtcCommitGeometry(i);
            unsigned id = rtcAttachGeometry(top_, i);
            rtcReleaseGeometry(i);
            instanceGeometry_[o] = id;
            if (instanceObject_.size() <= id) instanceObject_.resize(id + 1, std::numeric_limits<std::uint32_t>::max());
            instanceObject_[id] = static_cast<std::uint32_t>(o);
        }
        rtcCommitScene(top_);
    }
    checkDevice(device_, "building the scene");
    buildMs_ = millisecondsSince(start);
}

RayScene::~RayScene() {
    for (RTCScene s : objectScenes_)
        if (s) rtcReleaseScene(s);
    if (top_ != static_) rtcReleaseScene(top_);
    if (static_) rtcReleaseScene(static_);
    if (device_) rtcReleaseDevice(device_);
}

void RayScene::setTime(double time) {
    auto start = WallClock::now();
    time_ = time;
    bool changed = false;
    for (std::size_t o = 0; o < scene_.objects.size(); ++o) {
        if (!scene_.objects[o].isDynamic()) continue;
        if (scene_.objects[o].isDeforming()) {
            deformObject(o, time);
            rtcCommitScene(objectScenes_[o]);  // refits the object's BVH
        }
        toWorld_[o] = scene_.objects[o].worldMatrix(time);
        normalToWorld_[o] = normalMatrix(toWorld_[o]);
        RTCGeometry inst = rtcGetGeometry(top_, instanceGeometry_[o]);
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, &toWorld_[o][0][0]);
        rtcCommitGeometry(inst);
        changed = true;
    }
    if (changed) rtcCommitScene(top_);
    updateMs_ = millisecondsSince(start);
}

bool RayScene::intersect(const Ray& ray, float tmin, float tmax, SurfaceHit& hit) const {
    if (log_) log_->record({ray.origin, ray.direction, tmin, tmax, false});
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = ray.origin.x, rh.ray.org_y = ray.origin.y, rh.ray.org_z = ray.origin.z;
    rh.ray.dir_x = ray.direction.x, rh.ray.dir_y = ray.direction.y, rh.ray.dir_z = ray.direction.z;
    rh.ray.tnear = tmin;
    rh.ray.tfar = tmax;
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    timedEmbreeCall(callClock_, [&] { rtcIntersect1(top_, &ctx, &rh); });
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    resolveHit(rh, hit);
    return true;
}

void RayScene::traceCoherentPacket(RTCScene scene, const Ray* rays, int count, RTCRayHit8& packet) {
    if (count < 1 || count > kCoherentRays) throw std::logic_error("RayScene: a coherent packet holds 1 to kCoherentRays rays");
    alignas(32) int valid[kCoherentRays];
    for (int k = 0; k < kCoherentRays; ++k) {
        const Ray& ray = rays[std::min(k, count - 1)];  // idle lanes repeat the last ray, masked off
        valid[k] = k < count ? -1 : 0;
        setPacketLane(packet.ray, k, ray.origin, ray.direction, std::numeric_limits<float>::infinity(), 0);
        packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect8(valid, scene, &ctx, &packet);
}

void RayScene::intersectCoherent(const Ray* rays, int count, SurfaceHit* hits, bool* found) const {
    alignas(32) RTCRayHit8 packet;
    timedEmbreeCall(callClock_, [&] { traceCoherentPacket(top_, rays, count, packet); });
    for (int k = 0; k < count; ++k) {
        if (log_) {
            log_->record({rays[k].origin, rays[k].direction, 0.0f, std::numeric_limits<float>::infinity(), false,
                          static_cast<std::uint8_t>(count), static_cast<std::uint8_t>(k)});
        }
        found[k] = packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
        if (!found[k]) continue;
        RTCRayHit rh;
        rh.ray.tfar = packet.ray.tfar[k];
        rh.hit.u = packet.hit.u[k], rh.hit.v = packet.hit.v[k];
        rh.hit.geomID = packet.hit.geomID[k], rh.hit.primID = packet.hit.primID[k];
        rh.hit.instID[0] = packet.hit.instID[0][k];
        resolveHit(rh, hits[k]);
    }
}

glm::vec3 RayScene::transmittance(const glm::vec3& origin, const glm::vec3& dir, float tmax, const glm::vec3& startAbsorption) const {
    if (log_) log_->record({origin, dir, 0.0f, tmax, true});
    ShadowLane lane;
    lane.start(tmax);
    ShadowRayContext ctx(&lane);
    RTCRay r;
    r.org_x = origin.x, r.org_y = origin.y, r.org_z = origin.z;
    r.dir_x = dir.x, r.dir_y = dir.y, r.dir_z = dir.z;
    r.tnear = 0.0f;
    r.tfar = tmax;
    r.time = 0.0f;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
    timedEmbreeCall(callClock_, [&] { rtcOccluded1(top_, &ctx.base, &r); });
    return laneTransmittance(lane, r.tfar, startAbsorption);
}

void RayScene::traceShadowPacket(RTCScene scene, const ShadowQuery* rays, int count, ShadowRayContext& context, RTCRay8& packet) {
    if (count < 1 || count > kCoherentRays) throw std::logic_error("RayScene: a coherent packet holds 1 to kCoherentRays rays");
    alignas(32) int valid[kCoherentRays];
    for (int k = 0; k < kCoherentRays; ++k) {
        const ShadowQuery& ray = rays[std::min(k, count - 1)];  // idle lanes repeat the last ray, masked off
        valid[k] = k < count ? -1 : 0;
        setPacketLane(packet, k, ray.origin, ray.direction, ray.tmax, static_cast<unsigned>(k));  // id: its lane in the context
        context.lanes[k].start(ray.tmax);
    }
    context.base.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcOccluded8(valid, scene, &context.base, &packet);
}

void RayScene::transmittanceCoherent(const ShadowQuery* rays, int count, glm::vec3* transmittances) const {
    ShadowLane lanes[kCoherentRays];
    ShadowRayContext ctx(lanes);
    alignas(32) RTCRay8 packet;
    timedEmbreeCall(callClock_, [&] { traceShadowPacket(top_, rays, count, ctx, packet); });
    for (int k = 0; k < count; ++k) {
        if (log_) {
            log_->record({rays[k].origin, rays[k].direction, 0.0f, rays[k].tmax, true, static_cast<std::uint8_t>(count),
                          static_cast<std::uint8_t>(k)});
        }
        transmittances[k] = laneTransmittance(lanes[k], packet.tfar[k], rays[k].startAbsorption);
    }
}

void RayScene::resolveHit(const RTCRayHit& rh, SurfaceHit& hit) const {
    const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
    const bool instance = top_ != static_ && rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID &&
                          instanceObject_[rh.hit.instID[0]] != std::numeric_limits<std::uint32_t>::max();
    hit.t = rh.ray.tfar;
    hit.primitive = rh.hit.primID;
    glm::uvec3 tri;
    if (!instance) {
        // A static geometry's record is the hit's one likely cache miss: its address first, and
        // nothing read from the Mesh.
        const GeometryRef& ref = staticGeometry_[rh.hit.geomID];
        const StaticTriangle& st = ref.triangles[rh.hit.primID];
        hit.object = ref.object;
        hit.mesh = ref.mesh;
        hit.material = ref.material;
        tri = st.vertices;
        hit.shadingNormal = glm::normalize(w * st.normal[0] + u * st.normal[1] + v * st.normal[2]);
        hit.position = w * st.position[0] + u * st.position[1] + v * st.position[2];
        hit.geometricNormal = st.geometricNormal;
        if (ref.hasUvs) {
            hit.uv = w * st.uv[0] + u * st.uv[1] + v * st.uv[2];
            hit.uvDensityLod = st.uvDensityLod;
        }
    } else {
        // An instance: the object-space vertices, deformed at time_ for a deforming object.
        const std::uint32_t object = instanceObject_[rh.hit.instID[0]];
        const std::uint32_t mesh = scene_.objects[object].meshes[rh.hit.geomID];
        const Mesh& m = scene_.meshes[mesh];
        const glm::mat4& M = toWorld_[object];
        const glm::mat3& N = normalToWorld_[object];
        hit.object = object;
        hit.mesh = mesh;
        hit.material = &scene_.materials[m.material];
        tri = m.triangles[rh.hit.primID];
        const DeformedVertices& d = deformed_[mesh];
        const bool deformed = !d.positions.empty();
        const std::vector<glm::vec3>& positions = deformed ? d.positions : m.positions;
        const std::vector<glm::vec3>& normals = deformed ? d.normals : m.normals;
        const glm::vec3 p0 = glm::vec3(M * glm::vec4(positions[tri.x], 1.0f));
        const glm::vec3 p1 = glm::vec3(M * glm::vec4(positions[tri.y], 1.0f));
        const glm::vec3 p2 = glm::vec3(M * glm::vec4(positions[tri.z], 1.0f));
        hit.shadingNormal = glm::normalize(N * (w * normals[tri.x] + u * normals[tri.y] + v * normals[tri.z]));
        hit.position = w * p0 + u * p1 + v * p2;
        const glm::vec2 uv[3] = {m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[tri.x], m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[tri.y],
                                 m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[tri.z]};
        const TriangleTerms terms = triangleTerms(p0, p1, p2, m.uvs.empty() ? nullptr : uv);
        hit.geometricNormal = terms.geometricNormal;
        if (!m.uvs.empty()) {
            hit.uv = w * uv[0] + u * uv[1] + v * uv[2];
            hit.uvDensityLod = terms.uvDensityLod;
        }
    }
    const Material& mat = *hit.material;
    if (mat.normalTexture == kNoTexture) return;
    const Mesh& m = scene_.meshes[hit.mesh];
    if (!m.tangents.empty() && !m.uvs.empty()) {
        const glm::mat4& M = toWorld_[hit.object];
        const std::vector<glm::vec4>& tangents = deformed_[hit.mesh].tangents.empty() ? m.tangents : deformed_[hit.mesh].tangents;
        glm::vec4 t4 = w * tangents[tri.x] + u * tangents[tri.y] + v * tangents[tri.z];
        glm::vec3 t = glm::normalize(glm::mat3(M) * glm::vec3(t4));
        t = glm::normalize(t - hit.shadingNormal * glm::dot(hit.shadingNormal, t));
        glm::vec3 b = glm::cross(hit.shadingNormal, t) * (t4.w < 0.0f ? -1.0f : 1.0f);
        glm::vec2 tc = hit.uv * mat.textureTiling + mat.textureOffset;
        glm::vec3 tn = glm::vec3(scene_.textures[mat.normalTexture].image.sampleBilinearWrap(tc.x, tc.y)) * 2.0f - 1.0f;
        hit.shadingNormal = glm::normalize(t * tn.x + b * tn.y + hit.shadingNormal * tn.z);
    }
}

}  // namespace hybridlab
