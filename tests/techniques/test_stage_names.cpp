// The stage vocabulary (techniques/stage_names.h): every technique in the registry, at its
// defaults and with each parameter that changes its stages (the G-buffer from rays, occlusion
// queries, rays on the Vulkan device, the G-buffer from rays on that device, lighting on the CPU),
// names its frame's stages from it, once each; the report's reader (report/results.py) reads
// the same vocabulary, and old result sets under it, and experiments/README.md lists it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <string>

#include "common/core/input_error.h"
#include "common/raster/vulkan_error.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "techniques/stage_names.h"
#include "tests/support/technique_test_support.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

TEST(StageNames, NamesWithADetailBelongToTheirKind) {
    EXPECT_TRUE(isStageName("gbuffer"));
    EXPECT_TRUE(isStageName("gbuffer.rays"));
    EXPECT_EQ(stageKind("trace.lens_vertices"), "trace");
    EXPECT_FALSE(isStageName("raster"));
    EXPECT_FALSE(isStageName("gbuffer."));
    EXPECT_FALSE(isStageName(".rays"));
    EXPECT_FALSE(isStageName("gbuffer_rays"));
}

TEST(StageNames, EveryTechniqueNamesItsStagesFromTheVocabulary) {
    // A scene with a lens object (layered_em's lens stages), mirrors and glass.
    const Scene scene = loadSceneFile(findSceneFile("em-disocclusion"));
    struct Case {
        std::string technique;
        test::TechniqueParams params;
    };
    std::vector<Case> cases;
    for (const TechniqueInfo& info : registeredTechniques()) {
        test::TechniqueParams defaults;
        // layered_em: a small bake of its own, not the cache's.
        if (info.name == "layered_em")
            defaults = {{"em_size", 16LL}, {"bake_width", 32LL}, {"bake_height", 24LL}, {"viewpoints", 2LL}, {"layers", 1LL}, {"em_cache", false}};
        cases.push_back({info.name, defaults});
        bool castsGBuffer = false, tracesOnDevice = false;
        for (const ParamSpec& p : info.parameters) {
            test::TechniqueParams variant = defaults;
            if (p.name == "gbuffer") variant.push_back({"gbuffer", std::string("rays")});
            else if (p.name == "visible_pixels") variant.push_back({"visible_pixels", std::string("queries")});
            else if (p.name == "rays") variant.push_back({"rays", std::string("vulkan")});
            else if (p.name == "lighting")
                variant.insert(variant.end(), {{"gbuffer", std::string("rays")}, {"lighting", std::string("cpu")},
                                               {"raster_shadows", std::string("rays")}});
            else continue;
            castsGBuffer |= p.name == "gbuffer";
            tracesOnDevice |= p.name == "rays";
            cases.push_back({info.name, variant});
        }
        // The G-buffer from primary rays on the Vulkan device.
        if (castsGBuffer && tracesOnDevice) {
            test::TechniqueParams variant = defaults;
            variant.push_back({"gbuffer", std::string("rays")});
            variant.push_back({"rays", std::string("vulkan")});
            cases.push_back({info.name, variant});
        }
    }
    std::set<std::string> kinds;
    for (const Case& c : cases) {
        std::string label = c.technique;
        for (const auto& [k, v] : c.params) label += " " + k;
        SCOPED_TRACE(label);
        FrameResult r;
        try {
            r = test::renderFrame(scene, c.technique, c.params, 32, 18);
        } catch (const VulkanUnavailable& e) {
            std::printf("[ skipped  ] %s: no Vulkan device (%s)\n", label.c_str(), e.what());
            continue;
        } catch (const InputError& e) {
            if (c.params.empty() || c.technique == "layered_em") throw;
            std::printf("[ skipped  ] %s: %s\n", label.c_str(), e.what());  // no ray-tracing device
            continue;
        }
        std::set<std::string> seen;
        std::string names;
        ASSERT_FALSE(r.stages.empty());
        for (const StageTime& s : r.stages) {
            EXPECT_TRUE(isStageName(s.name)) << s.name;
            EXPECT_TRUE(seen.insert(s.name).second) << s.name << " twice";
            EXPECT_GE(s.milliseconds, 0.0) << s.name;
            kinds.insert(std::string(stageKind(s.name)));
            names += " " + s.name;
        }
        std::printf("[ stages   ] %s:%s\n", label.c_str(), names.c_str());
        // gbuffer = "rays" replaces the G-buffer pass with the primary rays' stage.
        const bool cast = std::any_of(c.params.begin(), c.params.end(), [](const auto& p) { return p.first == "gbuffer"; });
        if (cast) {
            EXPECT_TRUE(seen.count("gbuffer.rays"));
            EXPECT_FALSE(seen.count("gbuffer"));
        }
        if (c.technique == "layered_em") {
            for (const char* s : {"trace.lens_vertices", "lens.tessellation", "lens.texture_coordinates", "lens.draw", "gbuffer", "blend"})
                EXPECT_TRUE(seen.count(s)) << s;
        }
    }
    // Every kind of work but the rasterizer's is some technique's (shadow maps: the default's "map").
    for (const StageName& s : kStageNames) {
        if (kinds.empty()) break;  // no Vulkan device: only the ray tracers ran
        EXPECT_TRUE(kinds.count(s.name)) << s.name << ": no technique does this work";
    }
}

// What report/results.py prints running `code` (Debian's python3, as the report).
std::string resultsPy(const std::string& code) {
    const std::string command = "cd '" + (test::sourceDir() / "report").string() + "' && /usr/bin/python3 -c 'import results; " + code + "'";
    FILE* pipe = ::popen(command.c_str(), "r");
    EXPECT_NE(pipe, nullptr);
    if (!pipe) return "";
    std::string out;
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
    EXPECT_EQ(::pclose(pipe), 0) << command;
    return out;
}

TEST(StageNames, TheReportReadsTheSameVocabulary) {
    std::string expected;
    for (const StageName& s : kStageNames) expected += (expected.empty() ? "" : " ") + std::string(s.name);
    EXPECT_EQ(resultsPy("print(\" \".join(results.STAGE_KINDS))"), expected + "\n");
    // And experiments/README.md lists it.
    const std::string readme = test::readTextFile(test::sourceDir() / "experiments" / "README.md");
    for (const StageName& s : kStageNames) EXPECT_NE(readme.find("| `" + std::string(s.name) + "` | "), std::string::npos) << s.name;
}

// A record of a result set written before the vocabulary: migrated, its one-to-one renamed stages
// are read under the new names; the hybrids' lumped `raster` counts as the rasterizer's time.
TEST(StageNames, OldResultSetsAreReadUnderTheNewNames) {
    const std::string record =
        "{\"stages\": {\"raster\": {\"median\": 4.0}, \"gbuffer_rays\": {\"median\": 2.0}, \"seam_blur\": {\"median\": 0.5}, "
        "\"composite\": {\"median\": 0.25}, \"vertex_ray_tracing\": {\"median\": 1.0}, \"rayt\": {\"median\": 8.0}}}";
    const std::string out = resultsPy("r = results.migrate(" + record +
                                      "); k = results.stage_kinds(r); print(sorted(k.items()), results.raster_ms(r), results.stage(r, \"blend\"))");
    EXPECT_EQ(out, "[('blend', 0.75), ('gbuffer', 2.0), ('raster', 4.0), ('trace', 9.0)] 4.0 0.25\n");
}

}  // namespace
}  // namespace hybridlab
