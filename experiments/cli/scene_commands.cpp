// `hybridlab scenes` and `hybridlab scene-info`: what a scene holds (Walewski 2019 Table 4's rows).
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "common/core/input_error.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "experiments/cli/commands.h"

namespace hybridlab::cli {

namespace {

// The triangles of the objects that move or deform: de Macedo & Rodrigues Tables I-II's "dynamic
// triangles", what a ray scene updates each frame.
std::size_t dynamicTriangleCount(const Scene& scene) {
    std::size_t triangles = 0;
    for (std::size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].isDynamic()) triangles += scene.objectTriangleCount(i);
    return triangles;
}

void printSceneRow(const std::string& name, const Scene& scene) {
    const SceneStats s = scene.stats();
    std::printf("%-26s %8zu %10zu %10zu %7zu %11zu %11zu %10zu\n", name.c_str(), s.objects, s.vertices, s.triangles, s.lights,
                s.reflectiveObjects, s.refractiveObjects, dynamicTriangleCount(scene));
}

nlohmann::json statsJson(const Scene& scene) {
    const SceneStats s = scene.stats();
    return {{"objects", s.objects}, {"vertices", s.vertices}, {"triangles", s.triangles}, {"lights", s.lights},
            {"reflective", s.reflectiveObjects}, {"refractive", s.refractiveObjects}, {"dynamic_triangles", dynamicTriangleCount(scene)}};
}

nlohmann::json vecJson(glm::vec3 v) { return {v.x, v.y, v.z}; }

nlohmann::json boundsJson(const Aabb& b) { return {{"min", vecJson(b.lo)}, {"max", vecJson(b.hi)}}; }

// `scene-info --json`: the same facts as the text, for scripts.
nlohmann::json sceneInfoJson(const Scene& scene) {
    const Aabb b = scene.bounds(0.0);
    nlohmann::json j = {{"scene", scene.name},
                        {"description", scene.description},
                        {"file", scene.file.string()},
                        {"stats", statsJson(scene)},
                        {"materials", scene.materials.size()},
                        {"textures", scene.textures.size()},
                        {"bounds", boundsJson(b)},
                        {"camera",
                         {{"projection", scene.camera.projection == Camera::Projection::Perspective ? "perspective" : "orthographic"},
                          {"position", vecJson(scene.camera.position)},
                          {"forward", vecJson(scene.camera.forward())}}},
                        {"camera_paths", nlohmann::json::array()},
                        {"objects", nlohmann::json::array()},
                        {"lights", nlohmann::json::array()}};
    for (const auto& p : scene.cameraPaths) {
        j["camera_paths"].push_back({{"name", p.name}, {"keys", p.times.size()}, {"seconds", p.duration()}, {"frames", p.frameCount()},
                                     {"fps", p.framesPerSecond}});
    }
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const auto& o = scene.objects[i];
        j["objects"].push_back({{"name", o.name}, {"triangles", scene.objectTriangleCount(i)}, {"reflective", scene.objectIsReflective(i)},
                                {"refractive", scene.objectIsRefractive(i)}, {"relevance", o.relevance}, {"cost", o.cost},
                                {"animated", o.isAnimated()}, {"deforms", o.isDeforming()}, {"lens", static_cast<bool>(o.lens)},
                                {"bounds", boundsJson(scene.objectBounds(i, 0.0))}});
    }
    for (const auto& l : scene.lights) {
        j["lights"].push_back({{"name", l.name}, {"type", lightTypeName(l.type)}, {"color", vecJson(l.color)}, {"intensity", l.intensity},
                               {"casts_shadows", l.castsShadows}});
    }
    return j;
}

std::string vecString(glm::vec3 v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.4g, %.4g, %.4g)", v.x, v.y, v.z);
    return buf;
}

}  // namespace

void addScenesCommand(CLI::App& app) {
    auto* cmd = app.add_subcommand("scenes", "List the scenes in scenes/ with their object, vertex, triangle, light, "
                                             "reflective and refractive object and dynamic triangle counts");
    auto json = std::make_shared<bool>(false);
    cmd->add_flag("--json", *json, "Print a JSON array of {name, file, stats} (or {name, file, unavailable}) instead");
    cmd->callback([json] {
        if (*json) {
            nlohmann::json out = nlohmann::json::array();
            for (const auto& file : listSceneFiles()) {
                nlohmann::json row = {{"name", file.stem().string()}, {"file", file.string()}};
                try {
                    const Scene scene = loadSceneFile(file, {.loadTextures = false});
                    row["name"] = scene.name;
                    row["stats"] = statsJson(scene);
                } catch (const InputError& e) {
                    row["unavailable"] = e.what();
                }
                out.push_back(row);
            }
            std::printf("%s\n", out.dump(1).c_str());
            return;
        }
        const std::vector<std::filesystem::path> files = listSceneFiles();  // before the header: its folder may be refused
        std::printf("%-26s %8s %10s %10s %7s %11s %11s %10s\n", "scene", "objects", "vertices", "triangles", "lights", "reflective",
                    "refractive", "dynamic");
        for (const auto& file : files) {
            try {
                printSceneRow(file.stem().string(), loadSceneFile(file, {.loadTextures = false}));
            } catch (const InputError& e) {
                // One unavailable scene (say, assets not installed) does not hide the others.
                std::printf("%-26s unavailable: %s\n", file.stem().string().c_str(), e.what());
            }
        }
    });
}

void addSceneInfoCommand(CLI::App& app) {
    auto* cmd = app.add_subcommand("scene-info", "Print one scene's summary and bounds");
    auto file = std::make_shared<std::string>();
    cmd->add_option("scene", *file, "Scene file, or the name of a built-in scene")->required();
    auto json = std::make_shared<bool>(false);
    cmd->add_flag("--json", *json, "Print the summary as a JSON object instead");
    cmd->callback([file, json] {
        Scene scene = loadSceneFile(findSceneFile(*file), {.loadTextures = false});
        if (*json) {
            std::printf("%s\n", sceneInfoJson(scene).dump(1).c_str());
            return;
        }
        SceneStats s = scene.stats();
        Aabb b = scene.bounds(0.0);
        std::printf("scene        %s\n", scene.name.c_str());
        if (!scene.description.empty()) std::printf("description  %s\n", scene.description.c_str());
        std::printf("file         %s\n", scene.file.string().c_str());
        std::printf("objects      %zu (%zu reflective, %zu refractive)\n", s.objects, s.reflectiveObjects, s.refractiveObjects);
        std::printf("triangles    %zu\nvertices     %zu\n", s.triangles, s.vertices);
        std::printf("materials    %zu\ntextures     %zu\n", scene.materials.size(), scene.textures.size());
        std::printf("lights       %zu\n", s.lights);
        std::printf("bounds       %s .. %s (diagonal %.4g)\n", vecString(b.lo).c_str(), vecString(b.hi).c_str(),
                    static_cast<double>(glm::length(b.extent())));
        std::printf("camera       %s at %s looking along %s\n",
                    scene.camera.projection == Camera::Projection::Perspective ? "perspective" : "orthographic",
                    vecString(scene.camera.position).c_str(), vecString(scene.camera.forward()).c_str());
        for (const auto& p : scene.cameraPaths) {
            std::printf("camera path  %s: %zu keys, %.3g s, %d frames at %.3g fps\n", p.name.c_str(), p.times.size(), p.duration(),
                        p.frameCount(), p.framesPerSecond);
        }
        std::printf("\n%-24s %10s %11s %11s %8s %5s %8s\n", "object", "triangles", "reflective", "refractive", "K", "E", "animated");
        for (std::size_t i = 0; i < scene.objects.size(); ++i) {
            const auto& o = scene.objects[i];
            std::printf("%-24s %10zu %11s %11s %8.3g %5.3g %8s%s\n", o.name.c_str(), scene.objectTriangleCount(i),
                        scene.objectIsReflective(i) ? "yes" : "no", scene.objectIsRefractive(i) ? "yes" : "no", o.relevance, o.cost,
                        o.isDeforming() ? "deforms" : o.isAnimated() ? "yes" : "no",
                        o.lens ? "  lens" : "");
        }
        // Where each object stands (at time 0), as placed: what a scene's `fit` tables aim at.
        std::printf("\n%-24s %s\n", "object", "bounds at time 0 (min .. max)");
        for (std::size_t i = 0; i < scene.objects.size(); ++i) {
            const Aabb ob = scene.objectBounds(i, 0.0);
            std::printf("%-24s %s .. %s\n", scene.objects[i].name.c_str(), vecString(ob.lo).c_str(), vecString(ob.hi).c_str());
        }
        std::printf("\n");
        for (const auto& l : scene.lights) {
            std::printf("light        %s (%s) colour %s intensity %.4g%s\n", l.name.c_str(), lightTypeName(l.type),
                        vecString(l.color).c_str(), l.intensity, l.castsShadows ? "" : ", no shadows");
        }
    });
}

}  // namespace hybridlab::cli
