// `hybridlab bench`: the reference's ray throughput against bare Embree on the same rays
// (the goal: the reference at least 0.75 of bare Embree's rays/s, on sponza-spheres and
// whitted-classic), and the same rays through the reference's own calls with every hit resolved
// and nothing shaded (the most the reference can reach). All run side by side in one process, on
// the same threads, and report medians over repeats. Where a ray-tracing Vulkan device is present,
// a second column: the same rays, by kind, replayed on the device (DeviceRayReplay), its
// acceleration-structure build, and the reference frame with rays = "vulkan". Then, on one thread,
// the reference's frame split by a clock on every Embree call into traversal and the work around
// it, beside the same rays bare. Last, each device trace per ray: rt_only's and the hybrids' ray
// stages (heuristic_rt, ssr_fallback; on both G-buffers) with rays = "vulkan", interleaved round by
// round, their invocations and GPU time per ray beside rt_only's.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "common/core/cli_number_validators.h"
#include "common/core/input_error.h"
#include "common/core/wall_clock.h"
#include "common/device_rays/device_ray_replay.h"
#include "common/raster/vulkan_error.h"
#include "common/raytrace/embree_call_clock.h"
#include "common/raytrace/ray_task_context.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "common/scene/view.h"
#include "experiments/cli/commands.h"
#include "techniques/technique.h"

namespace hybridlab::cli {

namespace {

struct BenchOptions {
    std::string scene = "sponza-spheres";
    std::string cameraPath;
    std::optional<int> frame;
    int width = 1280;
    int height = 720;
    int repeats = 5;
    int threads = 0;
    double budget = 0.0;              // heuristic_rt's in the device traces; 0: 1e6 scaled to the image's area
    bool deviceTracesOnly = false;
    bool embreeOnly = false;
    int wavefrontBlocks = 0;          // > 0: also the shadow rays regrouped by light over this many blocks (shadowsByLight)
    std::string launch = "both";      // the hybrids' launches in the device traces: full, compact or both
};

struct Summary {
    double median, min, max;
};

Summary summarize(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    std::size_t n = v.size();
    double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    return {median, v.front(), v.back()};
}

template <typename F>
double milliseconds(F&& f) {
    const auto start = WallClock::now();
    f();
    return millisecondsSince(start);
}

// Traces every logged ray as the reference traced it, through `trace` (BareEmbree, ResolvedHits): a
// packet where the reference traced camera rays or first-hit shadow rays as coherent packets (a
// packet whose first lane is in a task's range is that task's, whole), else one ray at a time.
// Returns the number of hits so that the work cannot be optimised away.
template <class Trace>
std::size_t replay(const std::vector<LoggedRay>& rays, const Trace& trace) {
    std::atomic<std::size_t> hits{0};
    RayTaskContext context;  // the mode the reference traces in, for a like-for-like throughput
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        std::size_t local = 0;
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            const LoggedRay& lr = rays[i];
            if (lr.packetLane != 0) continue;  // traced with its packet's first lane
            if (lr.packetSize > 1 && lr.shadow) {
                ShadowQuery packetRays[RayScene::kCoherentRays];
                const int count = std::min<int>(lr.packetSize, static_cast<int>(rays.size() - i));
                for (int k = 0; k < count; ++k) packetRays[k] = {rays[i + k].origin, rays[i + k].direction, rays[i + k].tmax};
                local += trace.shadowPacket(packetRays, count);
            } else if (lr.packetSize > 1) {
                Ray packetRays[RayScene::kCoherentRays];
                const int count = std::min<int>(lr.packetSize, static_cast<int>(rays.size() - i));
                for (int k = 0; k < count; ++k) packetRays[k] = {rays[i + k].origin, rays[i + k].direction};
                local += trace.packet(packetRays, count);
            } else {
                local += lr.shadow ? trace.shadow(lr) : trace.single(lr);
            }
        }
        hits += local;
    }, context);
    return hits;
}

// The logged rays with the shadow rays that were traced alone (those of hits past the first)
// regrouped, over each run of `blocks` pixel blocks, into packets by the light they go to, in the
// order of their origins along a Morton curve: what a walk advancing those blocks' trees together
// (a wavefront, tracing its shadow rays a packet a light) could trace as packets, at most, since it
// also groups across depths and ignores what sorting costs. A block starts at its camera packet,
// and a thread's blocks lie in its log in order (32 blocks: a pixel loop's 16 x 16 tile). The light:
// the ray's end (origin + tmax direction) to a millimetre, or its direction where tmax is infinite
// (a light at infinity).
std::vector<LoggedRay> shadowsByLight(const std::vector<LoggedRay>& rays, int blocks) {
    // A shadow ray with its sort key, computed once: its light, then its origin's Morton code over
    // the run's origins' bounds (neighbouring origins in one packet).
    struct Keyed {
        std::array<long, 4> light;
        std::uint64_t morton;
        LoggedRay ray;
    };
    const auto light = [](const LoggedRay& r) {
        const bool infinite = std::isinf(r.tmax);
        const glm::vec3 p = infinite ? r.direction * 1e4f : r.origin + r.direction * r.tmax;
        return std::array<long, 4>{infinite, std::lround(p.x * 1e3f), std::lround(p.y * 1e3f), std::lround(p.z * 1e3f)};
    };
    const auto morton = [](glm::vec3 unit) {
        std::uint64_t code = 0;
        const std::uint32_t q[3] = {static_cast<std::uint32_t>(std::clamp(unit.x, 0.0f, 1.0f) * 1023.0f),
                                    static_cast<std::uint32_t>(std::clamp(unit.y, 0.0f, 1.0f) * 1023.0f),
                                    static_cast<std::uint32_t>(std::clamp(unit.z, 0.0f, 1.0f) * 1023.0f)};
        for (int bit = 9; bit >= 0; --bit)
            for (int a = 0; a < 3; ++a) code = (code << 1) | ((q[a] >> bit) & 1u);
        return code;
    };
    std::vector<LoggedRay> out, run;
    out.reserve(rays.size());
    std::vector<Keyed> keyed;
    const auto flush = [&] {
        if (run.empty()) return;
        glm::vec3 lo(run[0].origin), hi(run[0].origin);
        for (const LoggedRay& r : run) {
            lo = glm::min(lo, r.origin);
            hi = glm::max(hi, r.origin);
        }
        const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-20f));
        keyed.clear();
        for (const LoggedRay& r : run) keyed.push_back({light(r), morton((r.origin - lo) / extent), r});
        std::stable_sort(keyed.begin(), keyed.end(),
                         [](const Keyed& a, const Keyed& b) { return a.light != b.light ? a.light < b.light : a.morton < b.morton; });
        for (std::size_t i = 0; i < keyed.size();) {
            std::size_t n = 1;
            while (n < static_cast<std::size_t>(RayScene::kCoherentRays) && i + n < keyed.size() && keyed[i + n].light == keyed[i].light) ++n;
            for (std::size_t k = 0; k < n; ++k) {
                LoggedRay r = keyed[i + k].ray;
                r.packetSize = static_cast<std::uint8_t>(n);
                r.packetLane = static_cast<std::uint8_t>(k);
                out.push_back(r);
            }
            i += n;
        }
        run.clear();
    };
    int blocksSeen = 0;
    for (const LoggedRay& r : rays) {
        if (r.packetSize > 1 && !r.shadow && r.packetLane == 0 && blocksSeen++ % blocks == 0) flush();
        if (r.shadow && r.packetSize == 1) run.push_back(r);
        else out.push_back(r);
    }
    flush();
    return out;
}

// Bare rtcIntersect8 / rtcOccluded8 / rtcIntersect1 / rtcOccluded1: the traversal alone.
struct BareEmbree {
    RTCScene scene;
    int packet(const Ray* rays, int count) const {
        alignas(32) RTCRayHit8 packet;
        RayScene::traceCoherentPacket(scene, rays, count, packet);
        int hits = 0;
        for (int k = 0; k < count; ++k) hits += packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
        return hits;
    }
    int shadowPacket(const ShadowQuery* rays, int count) const {
        ShadowLane lanes[RayScene::kCoherentRays];
        ShadowRayContext ctx(lanes);
        alignas(32) RTCRay8 packet;
        RayScene::traceShadowPacket(scene, rays, count, ctx, packet);
        int stopped = 0;
        for (int k = 0; k < count; ++k) stopped += packet.tfar[k] < 0.0f;
        return stopped;
    }
    int shadow(const LoggedRay& lr) const {
        ShadowLane lane;
        lane.start(lr.tmax);
        ShadowRayContext ctx(&lane);
        RTCRay ray{lr.origin.x, lr.origin.y, lr.origin.z, lr.tmin, lr.direction.x, lr.direction.y, lr.direction.z,
                   0.0f, lr.tmax, 0xFFFFFFFFu, 0, 0};
        rtcOccluded1(scene, &ctx.base, &ray);
        return ray.tfar < 0.0f;
    }
    int single(const LoggedRay& lr) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh;
        rh.ray = RTCRay{lr.origin.x, lr.origin.y, lr.origin.z, lr.tmin, lr.direction.x, lr.direction.y, lr.direction.z,
                        0.0f, lr.tmax, 0xFFFFFFFFu, 0, 0};
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ctx, &rh);
        return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
};

// The reference's own calls (RayScene::intersectCoherent, intersect, transmittance): the traversal
// and what every shader needs before it starts, each hit resolved to the scene (position, normals,
// uv, material) and each shadow ray's transmittance, with nothing shaded.
struct ResolvedHits {
    const RayScene& scene;
    int packet(const Ray* rays, int count) const {
        SurfaceHit hits[RayScene::kCoherentRays];
        bool found[RayScene::kCoherentRays];
        scene.intersectCoherent(rays, count, hits, found);
        int n = 0;
        for (int k = 0; k < count; ++k) n += found[k] && hits[k].material;
        return n;
    }
    int shadowPacket(const ShadowQuery* rays, int count) const {
        glm::vec3 transmittances[RayScene::kCoherentRays];
        scene.transmittanceCoherent(rays, count, transmittances);
        int stopped = 0;
        for (int k = 0; k < count; ++k) stopped += transmittances[k] == glm::vec3(0.0f);
        return stopped;
    }
    int shadow(const LoggedRay& lr) const { return scene.transmittance(lr.origin, lr.direction, lr.tmax) == glm::vec3(0.0f); }
    int single(const LoggedRay& lr) const {
        SurfaceHit hit;
        return scene.intersect({lr.origin, lr.direction}, lr.tmin, lr.tmax, hit) && hit.material;
    }
};

// The logged rays by kind: primary (radiance rays from the camera's position), secondary (the
// other radiance rays) and shadow rays.
struct RaysByKind {
    const char* name;
    std::vector<LoggedRay> rays;
};

std::vector<RaysByKind> splitByKind(const std::vector<LoggedRay>& logged, glm::vec3 cameraPosition) {
    std::vector<RaysByKind> kinds = {{"primary", {}}, {"shadow", {}}, {"secondary", {}}};
    for (const LoggedRay& r : logged) kinds[r.shadow ? 1 : r.origin == cameraPosition ? 0 : 2].rays.push_back(r);
    return kinds;
}

// The Vulkan column: each kind of ray replayed on the device against bare Embree, side by side.
void benchDevice(const BenchOptions& o, SceneContext& context, const RayScene& rays, const FrameRequest& request,
                 const std::vector<LoggedRay>& logged, double embreeFrameMs) {
    DeviceRayScene* device = nullptr;
    std::unique_ptr<Technique> whitted;
    try {
        whitted = createTechnique("whitted", {{"rays", std::string("vulkan")}});
        whitted->prepare(context);
        device = &context.deviceRayScene(request.time);
    } catch (const InputError& e) {
        std::printf("vulkan: not measured (%s)\n", e.what());
        return;
    }
    std::printf("\nvulkan device %s: acceleration structures %.2f ms (Embree's BVH %.2f ms), %zu triangles, %.1f MiB\n",
                device->device().name().c_str(), device->buildMilliseconds(), rays.buildMilliseconds(), device->triangleCount(),
                static_cast<double>(device->deviceBytes()) / (1 << 20));
    std::printf("%-10s %10s %14s %10s %14s %10s %12s\n", "rays", "count", "embree ms", "Mrays/s", "vulkan ms", "Mrays/s", "vulkan/embree");
    DeviceRayReplay replayer(*device);
    auto row = [&](const char* name, const std::vector<LoggedRay>& list) {
        if (list.empty()) return;
        replayer.setRays(list);
        replayer.trace();  // warm-up
        std::vector<double> embreeMs, deviceMs;
        for (int i = 0; i < o.repeats; ++i) {
            embreeMs.push_back(milliseconds([&] { replay(list, BareEmbree{rays.embreeScene()}); }));
            deviceMs.push_back(milliseconds([&] { replayer.trace(); }));
        }
        const double e = summarize(embreeMs).median, d = summarize(deviceMs).median, n = static_cast<double>(list.size());
        std::printf("%-10s %10zu %14.2f %10.3f %14.2f %10.3f %12.3f\n", name, list.size(), e, n / (e * 1e3), d, n / (d * 1e3), e / d);
    };
    for (const RaysByKind& k : splitByKind(logged, request.camera.position)) row(k.name, k.rays);
    row("all", logged);
    whitted->render(context, request);  // warm-up
    std::vector<double> frameMs;
    for (int i = 0; i < o.repeats; ++i) frameMs.push_back(whitted->render(context, request).totalMilliseconds());
    const double d = summarize(frameMs).median;
    std::printf("reference frame, rays = vulkan %10.2f ms median (embree %.2f ms): %.3f x embree's time\n", d, embreeFrameMs, d / embreeFrameMs);
}

// On one thread, so that the calls' time is a share of the frame's: the reference frame, the part of
// it inside Embree's calls (embree_call_clock.h), and the same rays bare, interleaved; medians.
// Inside and bare agree when the replay measures what the reference's traversal costs.
void benchSplit(const BenchOptions& o, SceneContext& context, Technique& whitted, RayScene& rays, const FrameRequest& request,
                const std::vector<LoggedRay>& logged) {
    std::vector<double> frameMs, insideMs, bareMs, unclockedMs;
    tbb::task_arena oneThread(1);
    oneThread.execute([&] {
        for (int i = 0; i < o.repeats; ++i) {
            unclockedMs.push_back(milliseconds([&] { whitted.render(context, request); }));
            EmbreeCallClock clock;
            rays.setCallClock(&clock);
            std::uint64_t start = 0, end = 0;
            const double frame = milliseconds([&] {
                start = EmbreeCallClock::now();
                whitted.render(context, request);
                end = EmbreeCallClock::now();
            });
            rays.setCallClock(nullptr);
            frameMs.push_back(frame);
            insideMs.push_back(frame * static_cast<double>(clock.ticks()) / static_cast<double>(std::max<std::uint64_t>(end - start, 1)));
            bareMs.push_back(milliseconds([&] { replay(logged, BareEmbree{rays.embreeScene()}); }));
        }
    });
    const double frame = summarize(frameMs).median, inside = summarize(insideMs).median, bare = summarize(bareMs).median;
    const double unclocked = summarize(unclockedMs).median;
    std::printf("one thread: reference frame %.2f ms = %.2f ms inside Embree's calls (%.1f %%) + %.2f ms around them; "
                "the same rays bare %.2f ms; the frame without the clock %.2f ms\n",
                frame, inside, 100.0 * inside / frame, frame - inside, bare, unclocked);
    // A preemption only adds time, and one inside a call lands wholly in the calls' share: on a loaded
    // machine the fastest repeats are the fair comparison of inside and bare.
    std::printf("one thread, fastest repeat: reference frame %.2f ms, inside Embree's calls %.2f ms, the same rays bare %.2f ms\n",
                summarize(frameMs).min, summarize(insideMs).min, summarize(bareMs).min);
}

// A setting of the device-trace table: a technique with rays = "vulkan" and its parameters.
struct DeviceTraceSetting {
    std::string label, technique;
    std::vector<std::pair<std::string, ParamValue>> params;
};

double frameCounter(const FrameResult& f, const std::string& name) {
    const auto it = f.counters.find(name);
    return it == f.counters.end() ? 0.0 : it->second;
}

// By kind: rt_only's time per ray split by regression over the counts of settings 0, 1 and 2
// (rt_only, its camera rays only, its camera and first-hit shadow rays) in the same round (T =
// camera x P + shadow x S + secondary x (reflection + refraction); the shading of each hit falls on
// the ray that found it), and each hybrid's trace from `firstHybrid` on against (1) rt_only's rays
// beyond the camera rays, (T - T_camera-only) / (rays - P), and (2) rt_only's rays at the hybrid's
// own mix of kinds: its shadow and secondary rays at rt_only's costs.
void printByKind(const std::vector<DeviceTraceSetting>& settings, const std::vector<std::vector<FrameResult>>& frames,
                 std::size_t firstHybrid) {
    const auto counter = frameCounter;
    struct ByKind {
        double camera, shadow, secondary, beyondCamera;  // ns per ray
    };
    auto byKind = [&](std::size_t r) {
        const FrameResult &full = frames[0][r], &cameraOnly = frames[1][r], &firstHit = frames[2][r];
        const double tc = counter(cameraOnly, "gpu_trace_ms"), tf = counter(firstHit, "gpu_trace_ms"), t = counter(full, "gpu_trace_ms");
        const double p = counter(full, "rays_primary"), sFirst = counter(firstHit, "rays_shadow"), s = counter(full, "rays_shadow");
        const double secondary = counter(full, "rays_reflection") + counter(full, "rays_refraction");
        ByKind k{};
        k.camera = 1e6 * tc / p;
        k.shadow = sFirst > 0.0 ? 1e6 * (tf - tc) / sFirst : 0.0;
        k.secondary = secondary > 0.0 ? (1e6 * (t - tc) - k.shadow * s) / secondary : 0.0;
        k.beyondCamera = 1e6 * (t - tc) / (s + secondary);
        return k;
    };
    std::vector<ByKind> kinds;
    const std::size_t rounds = frames[0].size();
    for (std::size_t r = 0; r < rounds; ++r) kinds.push_back(byKind(r));
    auto kindSummary = [&](double ByKind::* field) {
        std::vector<double> v;
        for (const ByKind& k : kinds) v.push_back(k.*field);
        return summarize(v);
    };
    const Summary camera = kindSummary(&ByKind::camera), shadow = kindSummary(&ByKind::shadow),
                  secondary = kindSummary(&ByKind::secondary), beyond = kindSummary(&ByKind::beyondCamera);
    std::printf("\nrt_only's rays by kind (ns per ray, median [min, max] over the rounds; by regression over the counts of rt_only, "
                "camera rays only, and camera + shadow rays)\n");
    std::printf("camera %.1f [%.1f, %.1f], shadow %.1f [%.1f, %.1f], secondary %.1f [%.1f, %.1f]; beyond the camera rays %.1f [%.1f, %.1f]\n",
                camera.median, camera.min, camera.max, shadow.median, shadow.min, shadow.max, secondary.median, secondary.min,
                secondary.max, beyond.median, beyond.min, beyond.max);
    std::printf("%-38s %28s %28s\n", "setting", "to rt_only beyond camera", "to rt_only at its ray mix");
    for (std::size_t i = firstHybrid; i < settings.size(); ++i) {
        std::vector<double> toBeyond, toMix;
        for (std::size_t r = 0; r < rounds; ++r) {
            const FrameResult& f = frames[i][r];
            const ByKind& k = kinds[r];
            const double ns = counter(f, "gpu_trace_ns_per_ray");
            toBeyond.push_back(ns / k.beyondCamera);
            // The trace's own rays: no camera rays (a cast G-buffer's are the gbuffer.rays stage's).
            const double s = counter(f, "rays_shadow"), sec = counter(f, "rays_reflection") + counter(f, "rays_refraction");
            toMix.push_back(1e6 * counter(f, "gpu_trace_ms") / (k.shadow * s + k.secondary * sec));
        }
        const Summary a = summarize(toBeyond), b = summarize(toMix);
        std::printf("%-38s %7.3f [%.3f, %.3f]        %7.3f [%.3f, %.3f]\n", settings[i].label.c_str(), a.median, a.min, a.max, b.median, b.min,
                    b.max);
    }
}

// The device traces per ray: every setting rendered once a round (after one warm-up frame each), in
// the same order every round so that a round's load falls on all of them; per setting the medians
// of its trace's GPU time per ray (counter gpu_trace_ns_per_ray) and its ratio to rt_only's in the
// same round (median, min and max over the rounds), with its invocations and rays.
void benchDeviceTraces(const BenchOptions& o, SceneContext& context, const FrameRequest& request) {
    const double budget = o.budget > 0.0 ? o.budget : 1e6 * request.width * request.height / (1280.0 * 720.0);
    const auto vulkan = std::make_pair(std::string("rays"), ParamValue(std::string("vulkan")));
    const auto castGBuffer = std::make_pair(std::string("gbuffer"), ParamValue(std::string("rays")));
    const auto budgetParam = std::make_pair(std::string("budget"), ParamValue(budget));
    std::vector<DeviceTraceSetting> settings = {{"rt_only", "rt_only", {vulkan}}};
    // rt_only cut down to its camera rays, then with their shadow rays: what its rays cost by kind
    // (printByKind).
    const auto depth0 = std::make_pair(std::string("max_depth"), ParamValue(0LL));
    const auto noShadows = std::make_pair(std::string("shadows"), ParamValue(false));
    settings.push_back({"rt_only, camera rays only", "rt_only", {vulkan, depth0, noShadows}});
    settings.push_back({"rt_only, camera + shadow rays", "rt_only", {vulkan, depth0}});
    const std::size_t firstHybrid = settings.size();
    // Each hybrid's ray stage launched over its classified texels and one invocation per texel.
    for (const DeviceTraceSetting& hybrid : std::vector<DeviceTraceSetting>{
             {"heuristic_rt, gbuffer raster", "heuristic_rt", {vulkan, budgetParam}},
             {"heuristic_rt, gbuffer rays", "heuristic_rt", {vulkan, budgetParam, castGBuffer}},
             {"ssr_fallback, gbuffer raster", "ssr_fallback", {vulkan}},
             {"ssr_fallback, gbuffer rays", "ssr_fallback", {vulkan, castGBuffer}}}) {
        for (const char* launch : {"full", "compact"}) {
            if (o.launch != "both" && o.launch != launch) continue;
            DeviceTraceSetting s = hybrid;
            s.label += std::string(", ") + launch;
            s.params.emplace_back("launch", std::string(launch));
            settings.push_back(s);
        }
    }
    std::vector<std::unique_ptr<Technique>> techniques;
    try {
        for (const DeviceTraceSetting& s : settings) {
            techniques.push_back(createTechnique(s.technique, s.params));
            techniques.back()->prepare(context);
            techniques.back()->render(context, request);  // warm-up
        }
    } catch (const InputError& e) {
        std::printf("device traces: not measured (%s)\n", e.what());
        return;
    }
    std::vector<std::vector<FrameResult>> frames(settings.size());
    for (int r = 0; r < o.repeats; ++r)
        for (std::size_t i = 0; i < settings.size(); ++i) frames[i].push_back(techniques[i]->render(context, request));
    const auto counter = frameCounter;
    auto median = [&](std::size_t i, const std::string& name) {
        std::vector<double> v;
        for (const FrameResult& f : frames[i]) v.push_back(counter(f, name));
        return summarize(v).median;
    };
    std::printf("\ndevice traces per ray (rays = vulkan; heuristic_rt budget %.0f; %d rounds; medians; ratio to rt_only's ns/ray paired "
                "by round, median [min, max])\n",
                budget, o.repeats);
    std::printf("%-38s %9s %9s %8s %9s %9s %9s %22s %9s %9s %11s\n", "setting", "launched", "traced", "rays/inv", "rays", "trace ms",
                "ns/ray", "ratio to rt_only", "classify", "composite", "gbuf ns/ray");
    for (std::size_t i = 0; i < settings.size(); ++i) {
        std::vector<double> ratios;
        for (int r = 0; r < o.repeats; ++r) {
            const double base = counter(frames[0][r], "gpu_trace_ns_per_ray");
            ratios.push_back(base > 0.0 ? counter(frames[i][r], "gpu_trace_ns_per_ray") / base : 0.0);
        }
        const Summary ratio = summarize(ratios);
        const FrameResult& last = frames[i].back();
        const double traceRays = counter(last, "trace_rays_per_invocation") * counter(last, "trace_invocations_launched");
        std::printf("%-38s %9.0f %9.0f %8.3f %9.0f %9.3f %9.1f %6.3f [%.3f, %.3f] %9.3f %9.3f %11.1f\n", settings[i].label.c_str(),
                    counter(last, "trace_invocations_launched"), counter(last, "trace_invocations_traced"),
                    counter(last, "trace_rays_per_invocation"), traceRays, median(i, "gpu_trace_ms"), median(i, "gpu_trace_ns_per_ray"),
                    ratio.median, ratio.min, ratio.max, median(i, "gpu_classify_ms"), median(i, "gpu_composite_ms"),
                    median(i, "gpu_gbuffer.rays_ns_per_ray"));
    }
    printByKind(settings, frames, firstHybrid);

    // What the last frame cost the device outside the technique's work (device_frame_work.h).
    std::printf("\ndevice frame outside the technique's work (the last frame)\n");
    std::printf("%-38s %12s %14s %12s %25s\n", "setting", "submissions", "read-back B", "allocations", "diagnostics: subm. / B");
    for (std::size_t i = 0; i < settings.size(); ++i) {
        const FrameResult& last = frames[i].back();
        std::printf("%-38s %12.0f %14.0f %12.0f %12.0f / %10.0f\n", settings[i].label.c_str(), counter(last, "device_submissions"),
                    counter(last, "device_readback_bytes"), counter(last, "device_allocations"),
                    counter(last, "device_diagnostic_submissions"), counter(last, "device_diagnostic_readback_bytes"));
    }

    // The whole frame by stage (wall clock; the device's stages by their GPU timestamps, the rest
    // of each submission's wall clock as overhead): what lies outside the trace.
    std::printf("\nframe stages (medians, ms)\n");
    for (std::size_t i = 0; i < settings.size(); ++i) {
        std::vector<double> frame;
        for (const FrameResult& f : frames[i]) frame.push_back(f.totalMilliseconds());
        std::printf("%-38s frame %9.2f:", settings[i].label.c_str(), summarize(frame).median);
        for (const StageTime& s : frames[i].back().stages) {
            std::vector<double> v;
            for (const FrameResult& f : frames[i]) {
                const auto it = std::find_if(f.stages.begin(), f.stages.end(), [&](const StageTime& t) { return t.name == s.name; });
                v.push_back(it == f.stages.end() ? 0.0 : it->milliseconds);
            }
            std::printf(" %s %.2f", s.name.c_str(), summarize(v).median);
        }
        std::printf("\n");
    }
}

void run(const BenchOptions& o) {
    Scene scene = loadSceneFile(findSceneFile(o.scene));
    View view = resolveView(scene, o.cameraPath, o.frame, std::nullopt);
    std::optional<tbb::global_control> threadLimit;
    if (o.threads > 0) threadLimit.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    if (o.deviceTracesOnly) {
        SceneContext context(scene);
        std::printf("scene %s, %dx%d, view %s\n", scene.name.c_str(), o.width, o.height, view.label.c_str());
        benchDeviceTraces(o, context, {view.camera, view.time, o.width, o.height});
        return;
    }

    SceneContext context(scene);
    auto whitted = createTechnique("whitted", {});
    whitted->prepare(context);
    RayScene& rays = context.rayScene(view.time);
    const FrameRequest request{view.camera, view.time, o.width, o.height};

    // Warm-up frame, recording the rays.
    RayLog log;
    rays.setRayLog(&log);
    FrameResult first = whitted->render(context, request);
    rays.setRayLog(nullptr);
    const std::vector<LoggedRay> logged = log.collect();
    const double rayCount = first.counters.at("rays_total");

    const bool wavefront = o.wavefrontBlocks > 0;
    const std::vector<LoggedRay> regrouped = wavefront ? shadowsByLight(logged, o.wavefrontBlocks) : std::vector<LoggedRay>{};
    std::vector<double> referenceMs, embreeMs, resolvedMs, regroupedMs;
    std::size_t loggedHits = 0, regroupedHits = 0;  // hits and stopped shadow rays of the bare replays
    for (int i = 0; i < o.repeats; ++i) {
        // Interleaved, so that all see the same machine load.
        referenceMs.push_back(whitted->render(context, request).totalMilliseconds());
        embreeMs.push_back(milliseconds([&] { loggedHits = replay(logged, BareEmbree{rays.embreeScene()}); }));
        resolvedMs.push_back(milliseconds([&] { replay(logged, ResolvedHits{rays}); }));
        if (wavefront) regroupedMs.push_back(milliseconds([&] { regroupedHits = replay(regrouped, BareEmbree{rays.embreeScene()}); }));
    }
    Summary ref = summarize(referenceMs), raw = summarize(embreeMs), resolved = summarize(resolvedMs);
    const double refRate = rayCount / (ref.median * 1e3), rawRate = static_cast<double>(logged.size()) / (raw.median * 1e3);
    const double resolvedRate = static_cast<double>(logged.size()) / (resolved.median * 1e3);
    std::printf("scene %s, %dx%d, view %s, %d threads, %d repeats\n", scene.name.c_str(), o.width, o.height, view.label.c_str(),
                o.threads > 0 ? o.threads : tbb::info::default_concurrency(), o.repeats);
    std::printf("bvh build                %10.2f ms\n", rays.buildMilliseconds());
    std::printf("rays per frame           %10.0f (primary %.0f, shadow %.0f, reflection %.0f, refraction %.0f); logged %zu\n", rayCount,
                first.counters.at("rays_primary"), first.counters.at("rays_shadow"), first.counters.at("rays_reflection"),
                first.counters.at("rays_refraction"), logged.size());
    std::printf("reference frame          %10.2f ms median (min %.2f, max %.2f)   %8.3f Mrays/s\n", ref.median, ref.min, ref.max, refRate);
    std::printf("bare Embree, same rays   %10.2f ms median (min %.2f, max %.2f)   %8.3f Mrays/s\n", raw.median, raw.min, raw.max, rawRate);
    std::printf("hits resolved, unshaded  %10.2f ms median (min %.2f, max %.2f)   %8.3f Mrays/s\n", resolved.median, resolved.min,
                resolved.max, resolvedRate);
    if (wavefront) {
        const Summary g = summarize(regroupedMs);
        std::size_t packets = 0, inPackets = 0;
        for (const LoggedRay& r : regrouped)
            if (r.shadow && r.packetSize > 1) {
                packets += r.packetLane == 0;
                ++inPackets;
            }
        // The same rays, only grouped otherwise: as many, with as many hits and stopped shadow rays.
        std::printf("bare Embree, wavefront   %10.2f ms median (min %.2f, max %.2f)   shadow rays a packet a light over %d blocks: "
                    "%zu in %zu packets; %zu rays, %zu hits and stops (alone: %zu, %zu)\n", g.median, g.min, g.max, o.wavefrontBlocks,
                    inPackets, packets, regrouped.size(), regroupedHits, logged.size(), loggedHits);
    }
    std::printf("reference / bare Embree  %10.1f %%\n", 100.0 * refRate / rawRate);
    // A shader that cost nothing would still resolve every hit: the reference's ceiling.
    std::printf("resolved / bare Embree   %10.1f %% (the reference's ceiling: every hit resolved, nothing shaded)\n",
                100.0 * resolvedRate / rawRate);
    if (o.embreeOnly) return;
    benchSplit(o, context, *whitted, rays, request, logged);
    benchDevice(o, context, rays, request, logged, ref.median);
    benchDeviceTraces(o, context, request);
}

}  // namespace

void addBenchCommand(CLI::App& app) {
    auto o = std::make_shared<BenchOptions>();
    auto* cmd = app.add_subcommand("bench", "Reference ray throughput against bare Embree on the same rays, and on the Vulkan device by kind "
                                            "(medians over repeats)");
    cmd->add_option("--scene", o->scene, "Scene file or name")->capture_default_str();
    cmd->add_option("--camera-path", o->cameraPath, "Camera path (default: the scene camera)");
    cmd->add_option("--frame", o->frame, "Frame on the camera path");
    cmd->add_option("--width", o->width, "Image width")->check(CLI::Range(1, 16384))->capture_default_str();
    cmd->add_option("--height", o->height, "Image height")->check(CLI::Range(1, 16384))->capture_default_str();
    cmd->add_option("--repeats", o->repeats, "Timed repeats of each")->check(CLI::Range(1, 1000))->capture_default_str();
    cmd->add_option("--threads", o->threads, "Worker threads (default: every core)")->check(CLI::Range(1, 1024));
    cmd->add_option("--budget", o->budget, "heuristic_rt's budget in the device traces (default: 1e6 scaled to the image's area)")
        ->check(numberIn(1.0, 1e18));
    cmd->add_option("--wavefront-bound", o->wavefrontBlocks,
                    "Also bare Embree with the shadow rays in packets by light over runs of this many 4x2 pixel blocks (32: a 16x16 "
                    "tile): what a wavefront walk could save, at most")
        ->check(CLI::Range(1, 1 << 30));
    auto* deviceTracesOnly =
        cmd->add_flag("--device-traces-only", o->deviceTracesOnly, "Only the device traces per ray (no Embree measurements)");
    // For a drift check between commits (experiments/drift_check.py): minutes of lavapipe spared.
    cmd->add_flag("--embree-only", o->embreeOnly,
                  "Only the reference against bare Embree and its ceiling (no one-thread split, no Vulkan device)")
        ->excludes(deviceTracesOnly);
    cmd->add_option("--launch", o->launch, "The hybrids' launches in the device traces: full (one invocation a texel), compact, or both")
        ->check(CLI::IsMember({"both", "full", "compact"}))
        ->capture_default_str();
    cmd->callback([o] { run(*o); });
}

}  // namespace hybridlab::cli
