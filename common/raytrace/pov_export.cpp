// POV-Ray 3.7 export. How the shading model of shading.h becomes POV-Ray SDL (the POV-Ray
// behaviour cited is that of its 3.7 trace.cpp: ComputeLightedTexture, ComputeDiffuseColour,
// ComputeSpecularColour, ComputeReflectivity, ComputeShadowTexture, Attenuate_Light):
//
// Geometry. POV-Ray is left-handed: every point, normal and direction is mirrored in z
// (x, y, -z); the mirrored camera's right x up = direction, which is POV-Ray's own convention, so
// the image is not mirrored. Meshes are mesh2 in world space (the object's matrix at the export
// time baked in) with our vertex normals, which POV-Ray interpolates barycentrically as we do.
//
// Camera. Perspective: direction = forward * 0.5 / tan(fov_y / 2), up = up (length 1), right =
// right * W / H; with antialiasing off POV-Ray shoots one ray through each pixel centre, as we do.
//
// A surface, in POV-Ray, at one hit: with a layered texture (top layer first) each layer adds
// filCol * opacity * (pigment * (ambient * ambient_light + emission) + lights), where filCol is
// the product of the layers above of (filter * pigment + transmit), times (1 - reflection) when a
// layer has conserve_energy; every layer adds reflection * M, unfiltered; the transmitted ray adds
// filCol * R. Specular highlights are not multiplied by the layer's opacity (only by filCol).
// Our rule is  o_m M + (1 - o_m) (o_r R + (1 - o_r) C). So a material is two layers:
//   top ("reflection" layer, only when the material reflects): pigment rgbt 1 (adds no colour,
//     lets everything through), finish reflection { o_m } or reflection { 0, 1 fresnel on }, and
//     conserve_energy: it adds o_m M and leaves (1 - o_m) for the layer below and the refraction.
//     POV-Ray's Fresnel reflectivity is the exact unpolarised dielectric term for the relative
//     index of the interfaces it tracks, as ours (shading normal, both sides).
//   bottom ("surface" layer): pigment D*T (normalised, see below) with transmit o_r, so R gets
//     (1 - o_m) o_r and the layer's own colour is scaled by opacity 1 - o_r; its finish makes that
//     colour exactly C: diffuse / ambient / emission relative to the pigment, specular times
//     (1 - o_r) because POV-Ray does not scale highlights by opacity.
// Total internal reflection: POV-Ray then adds the reflected ray with weight 1 and skips the
// layers' own reflection. With Fresnel that is our rule (o_m = 1); for a transparent material
// with a constant reflectivity ours weights M by o_m + (1 - o_m) o_r < 1: not exportable exactly.
//
// Local colour C = emission + ambient * scene_ambient * T + sum of lights. The pigment is
// P = Dn * T / s with Dn = diffuse / max(diffuse) (white when diffuse is black) and s >= 1 only
// when Dn * T exceeds 1 somewhere; then finish diffuse = max(diffuse) * s, ambient (a colour,
// ambient_light 1) = A * scene_ambient * s / Dn and emission = E * s / Dn, channel by channel.
// Exact except where Dn has a zero channel but ambient or emission does not, and for emission on a
// textured material (POV-Ray multiplies emission by the pigment, we do not).
// Blinn-Phong specular: POV-Ray's `specular k roughness r` adds k (N.H)^(1/r) times the light,
// with H the normalised half vector and only where N.L > 0: k = mean of our specular colour
// (exact for grey specular, as in every built-in scene), r = 1 / exponent.
//
// Lights. Point and spot: POV-Ray's fade multiplies by 2 / (1 + (d / fade_distance)^2); with
// fade_distance f = 1e-3 and colour I / (2 f^2) that is I / (d^2 + f^2), inverse-square to a
// relative 1e-6 / d^2. Spot: radius = inner cone, falloff = outer cone, tightness 0; POV-Ray's
// cubic_spline(cos outer, cos inner, cos angle) is (3 - 2x) x^2 on x = (cos angle - cos outer) /
// (cos inner - cos outer): our smoothstep exactly. Directional: a parallel light placed outside
// the scene's bounds, no fade. Lights that cast no shadow are shadowless, and POV-Ray adds no
// specular highlight from a shadowless light (an approximation, listed when it occurs).
//
// Shadows. POV-Ray lets a shadow ray through a surface times that surface's (filter * pigment +
// transmit) at each crossing; ours multiplies by (1 - opacity) * diffuse at each crossing. For an
// opaque material the visible object gives that (0). A transparent material's visible object
// has no_shadow, and a shadow copy (the same mesh, no_image no_reflection, pigment rgbf <diffuse,
// 1 - opacity>) casts the shadow instead: exactly our transmittance, untextured as ours. Materials
// that cast no shadow get no_shadow and no shadow copy.
//
// Interior: ior = material ior / scene ambient ior (POV-Ray's surrounding medium has index 1 and
// it uses only ratios); absorption as media absorption, which POV-Ray computes only inside hollow
// objects (hence `hollow on`). POV-Ray keeps the list of interiors a ray is in and integrates the
// media of all of them along every segment, eye rays and (with `media_attenuation on` on each
// light, and the interior on the shadow copy, since shadow rays skip the no_shadow visible object)
// shadow rays: the rule of medium_stack.h. Where transparent objects nest or overlap,
// POV-Ray refracts at their shared surfaces with the ratio of the two indices, ours against the
// ambient index (listed when two transparent objects' bounds overlap); a camera inside a medium
// starts, in ours, outside every medium (listed).
// Sky: background colour; misses return it unchanged (no ambient). Depth: max_trace_level 11
// (POV-Ray counts the camera ray as level 1 and returns black past the limit, so a depth-10 hit
// gives its local colour without what would come from further rays: the reference's
// depth_limit = "weighted", its default; "local" differs there); adc_bailout 0 (no ray is cut for
// low weight); assumed_gamma 1.
#include "common/raytrace/pov_export.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <system_error>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vector_relational.hpp>

#include "common/core/atomic_file.h"
#include "common/core/input_error.h"
#include "common/core/io_error.h"
#include "common/image/image_io.h"
#include "common/raytrace/whitted_tracer.h"

namespace hybridlab {

namespace fs = std::filesystem;

namespace {

constexpr double kFadeDistance = 1e-3;

// ---- SDL text --------------------------------------------------------------------------------

std::string num(double v) {
    if (v == 0.0 || !std::isfinite(v)) return "0";  // no "-0"; callers never pass non-finite values
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

std::string vec(glm::dvec3 v) { return "<" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ">"; }

// Full double precision, for the camera's vectors: rounded to 9 digits an orthogonal basis is no
// longer orthogonal to POV-Ray's tolerance, and it warns that they are not perpendicular.
std::string exactVec(glm::dvec3 v) {
    auto exact = [](double x) {
        if (x == 0.0) return std::string("0");
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", x);
        return std::string(buf);
    };
    return "<" + exact(v.x) + ", " + exact(v.y) + ", " + exact(v.z) + ">";
}

// Right-handed (ours) to left-handed (POV-Ray): mirror z.
glm::dvec3 pov(glm::dvec3 v) { return {v.x, v.y, -v.z}; }

// A string as an SDL comment body (one line).
std::string commentText(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
}

// ---- materials ----------------------------------------------------------------------------------

struct MaterialPlan {
    bool used = false;
    bool reflects = false;       // has the top reflection layer
    bool transparent = false;    // o_r > 0
    bool shadowCopy = false;     // a transparent shadow caster: the copy casts its shadow
    bool noShadow = false;       // the visible object casts no shadow
    bool textured = false;
    bool absorbs = false;        // media absorption inside: the object must be hollow
    Image pigmentImage;          // textured: Dn * T / s, linear
    double pigmentScale = 1.0;   // s >= 1: the peak of Dn * T when it exceeds 1
    std::string pngName;         // textured: file name beside the .pov file
};

double maxComponent(glm::dvec3 v) { return std::max({v.x, v.y, v.z}); }

std::string finish(glm::dvec3 ambient, glm::dvec3 emission, double diffuse, double specular, double roughness,
                   const std::string& reflection, bool conserveEnergy) {
    std::string s = "finish {\n";
    s += "    ambient rgb " + vec(ambient) + "\n";
    s += "    emission rgb " + vec(emission) + "\n";
    s += "    diffuse " + num(diffuse) + "\n";
    s += "    brilliance 1\n";
    s += "    crand 0\n";
    s += "    phong 0\n";
    s += "    specular " + num(specular) + "\n";
    s += "    roughness " + num(roughness) + "\n";
    s += "    metallic 0\n";
    s += "    reflection { " + reflection + " }\n";
    if (conserveEnergy) s += "    conserve_energy\n";
    s += "  }";
    return s;
}

std::string materialId(std::size_t i) { return "HL_Material_" + std::to_string(i); }

// The #declares of one material: its surface layer, reflection layer, shadow copy texture and
// interior. Appends what cannot be exact to `approximations`.
std::string materialSdl(const Scene& scene, std::size_t index, const MaterialPlan& plan, std::vector<std::string>& approximations) {
    const Material& m = scene.materials[index];
    const std::string id = materialId(index);
    const std::string who = "material '" + m.name + "'";
    const double orr = 1.0 - static_cast<double>(m.opacity);
    const double att = 1.0 - orr;  // POV-Ray's opacity of the surface layer
    const glm::dvec3 D(m.diffuse), A(m.ambient), E(m.emission), S(m.specular), sceneAmbient(scene.ambient);

    std::string sdl = "// " + commentText(who) + "\n";

    // Surface layer.
    const double g = maxComponent(D);
    const glm::dvec3 Dn = g > 0.0 ? D / g : glm::dvec3(1.0);
    const double s = plan.pigmentScale;  // P = Dn * T / s
    glm::dvec3 ambient(0.0), emission(0.0);
    double diffuse = 0.0, specular = 0.0;
    if (att > 0.0) {
        diffuse = g * s;  // (1 - o_r) / att = 1
        specular = orr < 1.0 ? (1.0 - orr) * (S.x + S.y + S.z) / 3.0 : 0.0;
        const glm::dvec3 ambientWanted = A * sceneAmbient;
        for (int c = 0; c < 3; ++c) {
            if (Dn[c] > 0.0) {
                ambient[c] = ambientWanted[c] * s / Dn[c];
                emission[c] = E[c] * s / Dn[c];
            } else if (ambientWanted[c] > 0.0 || E[c] > 0.0) {
                approximations.push_back(who + ": ambient or emission in a colour channel where the diffuse colour is 0 "
                                               "is lost (POV-Ray multiplies both by the pigment)");
            }
        }
        if (plan.textured && maxComponent(E) > 0.0) {
            approximations.push_back(who + ": emission on a textured material is multiplied by the texture in POV-Ray");
        }
        if (S.x != S.y || S.y != S.z) {
            approximations.push_back(who + ": coloured specular exported as its mean " + num(specular / (1.0 - orr)) +
                                     " (POV-Ray's specular is a scalar)");
        }
    }
    if (m.normalTexture != kNoTexture) approximations.push_back(who + ": normal map not exported (vertex normals only)");

    std::string pigment;
    if (plan.textured) {
        // uv: ours has (0, 0) at the image's top-left and samples at uv * tiling + offset; POV-Ray's
        // image_map has (0, 0) at the bottom-left and evaluates the pattern at M^-1(p) for
        // `translate a scale b` = p / b - a. With b = (1 / tx, -1 / ty, 1), a = (-ox, oy - 1, 0)
        // that is (u tx + ox, 1 - (v ty + oy)).
        const glm::dvec2 tiling(m.textureTiling), offset(m.textureOffset);
        pigment = "pigment {\n    uv_mapping\n    image_map { png \"" + plan.pngName + "\" gamma 1.0 interpolate 2 transmit all " +
                  num(orr) + " }\n    translate " + vec({-offset.x, offset.y - 1.0, 0.0}) + "\n    scale " +
                  vec({1.0 / tiling.x, -1.0 / tiling.y, 1.0}) + "\n  }";
    } else {
        pigment = "pigment { rgbt <" + num(Dn.x) + ", " + num(Dn.y) + ", " + num(Dn.z) + ", " + num(orr) + "> }";
    }
    sdl += "#declare " + id + "_Surface = texture {\n  " + pigment + "\n  " +
           finish(ambient, emission, diffuse, specular, 1.0 / std::max(1e-6, static_cast<double>(m.specularExponent)), "rgb 0",
                  false) +
           "\n};\n";

    // Reflection layer.
    const bool canTir = plan.transparent && m.ior > scene.ambientIor;  // leaving it, rays can be reflected totally
    if (plan.reflects) {
        const std::string reflection =
            m.fresnel ? "rgb 0, rgb 1 fresnel on falloff 1 exponent 1 metallic 0"
                      : "rgb " + num(m.reflectivity) + " falloff 1 exponent 1 metallic 0";
        sdl += "#declare " + id + "_Reflection = texture {\n  pigment { rgbt <1, 1, 1, 1> }\n  " +
               finish(glm::dvec3(0.0), glm::dvec3(0.0), 0.0, 0.0, 1.0, reflection, true) + "\n};\n";
        if (canTir && !m.fresnel && m.reflectivity + (1.0f - m.reflectivity) * static_cast<float>(orr) < 1.0f) {
            approximations.push_back(who + ": under total internal reflection POV-Ray weights the reflected ray by 1, "
                                           "ours by reflectivity + (1 - reflectivity) * (1 - opacity)");
        }
    } else if (canTir) {
        approximations.push_back(who + ": under total internal reflection POV-Ray weights the reflected ray by 1, ours by "
                                       "1 - opacity");
    }

    // Shadow copy: lets (1 - opacity) * diffuse through at each crossing, untextured.
    if (plan.shadowCopy) {
        sdl += "#declare " + id + "_Shadow = texture {\n  pigment { rgbf <" + num(D.x) + ", " + num(D.y) + ", " + num(D.z) + ", " +
               num(orr) + "> }\n  " + finish(glm::dvec3(0.0), glm::dvec3(0.0), 0.0, 0.0, 1.0, "rgb 0", false) + "\n};\n";
    }

    // Interior.
    sdl += "#declare " + id + "_Interior = interior {\n  ior " + num(m.ior / scene.ambientIor) + "\n";
    const glm::dvec3 absorption(m.absorption);
    if (plan.absorbs) {
        sdl += "  media { absorption rgb " + vec(absorption) + " }\n";
    }
    sdl += "};\n\n";
    return sdl;
}

// ---- geometry ---------------------------------------------------------------------------------

void writeMesh(std::ostream& os, const std::string& id, const Mesh& mesh, const glm::mat4& toWorld, bool withUvs) {
    const glm::dmat4 m(toWorld);
    const glm::dmat3 nm(normalMatrix(toWorld));
    os << "#declare " << id << " = mesh2 {\n  vertex_vectors {\n    " << mesh.positions.size();
    for (const auto& p : mesh.positions) os << ",\n    " << vec(pov(glm::dvec3(m * glm::dvec4(glm::dvec3(p), 1.0))));
    os << "\n  }\n";
    if (mesh.normals.size() == mesh.positions.size()) {  // loaded meshes always have them
        os << "  normal_vectors {\n    " << mesh.normals.size();
        for (const auto& n : mesh.normals) {
            glm::dvec3 w = nm * glm::dvec3(n);
            const double len = glm::length(w);
            os << ",\n    " << vec(pov(len > 0.0 ? w / len : glm::dvec3(0.0, 1.0, 0.0)));
        }
        os << "\n  }\n";
    }
    if (withUvs) {
        // Meshes without uvs sample the texture at uv (0, 0), as the tracer does.
        os << "  uv_vectors {\n    " << mesh.positions.size();
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            const glm::dvec2 uv = mesh.uvs.empty() ? glm::dvec2(0.0) : glm::dvec2(mesh.uvs[i]);
            os << ",\n    <" << num(uv.x) << ", " << num(uv.y) << ">";
        }
        os << "\n  }\n";
    }
    os << "  face_indices {\n    " << mesh.triangles.size();
    for (const auto& t : mesh.triangles) os << ",\n    <" << t.x << ", " << t.y << ", " << t.z << ">";
    os << "\n  }\n}\n";
}

// ---- files ------------------------------------------------------------------------------------

// Removes the temporary files on failure.
// Per material: whether the scene uses it, how POV-Ray expresses it, and its pigment image (for a
// textured one, the diffuse colour times the texture, scaled into [0, 1]).
std::vector<MaterialPlan> planMaterials(const Scene& scene, const std::string& stem) {
    std::vector<MaterialPlan> plans(scene.materials.size());
    for (const auto& o : scene.objects)
        for (auto meshIndex : o.meshes) plans[scene.meshes[meshIndex].material].used = true;

    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        MaterialPlan& p = plans[i];
        if (!p.used) continue;
        p.reflects = m.fresnel || m.reflectivity > 0.0f;
        p.transparent = m.opacity < 1.0f;
        p.noShadow = !m.castsShadows || p.transparent;
        p.shadowCopy = m.castsShadows && p.transparent;
        p.textured = m.diffuseTexture != kNoTexture;
        p.absorbs = maxComponent(glm::dvec3(m.absorption)) > 0.0;
        if (!p.textured) continue;
        if (m.textureTiling.x == 0.0f || m.textureTiling.y == 0.0f) {
            throw InputError(scene.file.string() + ": material '" + m.name + "': a texture tiling of 0 cannot be exported to POV-Ray");
        }
        const Image& tex = scene.textures.at(static_cast<std::size_t>(m.diffuseTexture)).image;
        if (tex.empty()) throw InputError(scene.file.string() + ": material '" + m.name + "': its texture was not loaded");
        const double g = maxComponent(glm::dvec3(m.diffuse));
        const glm::vec3 Dn = g > 0.0 ? glm::vec3(glm::dvec3(m.diffuse) / g) : glm::vec3(1.0f);
        p.pigmentImage = Image(tex.width(), tex.height());
        float peak = 0.0f;
        for (std::size_t k = 0; k < tex.pixelCount(); ++k) {
            glm::vec3 c = Dn * glm::vec3(tex.data()[k]);
            p.pigmentImage.data()[k] = glm::vec4(c, 1.0f);
            peak = std::max({peak, c.r, c.g, c.b});
        }
        if (peak > 1.0f) {
            p.pigmentScale = peak;
            for (std::size_t k = 0; k < tex.pixelCount(); ++k) p.pigmentImage.data()[k] /= glm::vec4(glm::vec3(peak), 1.0f);
        }
        p.pngName = stem + ".mat" + std::to_string(i) + ".png";
    }
    return plans;
}

// The file's header comment (how to render it) and POV-Ray's global settings and background.
void writeSdlHeader(std::ostream& sdl, const Scene& scene, double time, int width, int height, const fs::path& out) {
    const std::string stem = out.stem().string();
    sdl << "// POV-Ray 3.7 scene exported by `hybridlab export-pov` (common/raytrace/pov_export.cpp says how each\n"
        << "// term of hybridlab's shading model is expressed here).\n"
        << "// scene: " << commentText(scene.name) << " (" << commentText(scene.file.string()) << "), time " << num(time) << " s\n"
        << "// render: povray";
    for (const auto& a : povrayArguments(out.filename(), fs::path(stem + ".png"), width, height)) sdl << " " << a;
    sdl << "\n#version 3.7;\n\n";

    const int maxTraceLevel = WhittedSettings{}.maxDepth + 1;
    sdl << "global_settings {\n  assumed_gamma 1.0\n  max_trace_level " << maxTraceLevel
        << "\n  adc_bailout 0\n  ambient_light rgb <1, 1, 1>\n}\n\n";
    sdl << "background { rgb " << vec(glm::dvec3(scene.sky.color)) << " }\n\n";
}

void writeSdlCamera(std::ostream& sdl, const Camera& camera, int width, int height) {
    const double aspect = static_cast<double>(width) / height;
    // An exactly orthonormal basis (POV-Ray warns about vectors that are not perpendicular).
    const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.forward()));
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(camera.up())));
    const glm::dvec3 up = glm::cross(right, forward);
    if (camera.projection == Camera::Projection::Perspective) {
        const double halfTan = std::tan(glm::radians(static_cast<double>(camera.fovYDegrees)) * 0.5);
        sdl << "camera {\n  perspective\n  location " << vec(pov(glm::dvec3(camera.position))) << "\n  direction "
            << exactVec(pov(forward * (0.5 / halfTan))) << "\n  right " << exactVec(pov(right * aspect)) << "\n  up " << exactVec(pov(up))
            << "\n}\n\n";
    } else {
        const double h = camera.orthoHeight;
        sdl << "camera {\n  orthographic\n  location " << vec(pov(glm::dvec3(camera.position))) << "\n  direction "
            << exactVec(pov(forward)) << "\n  right " << exactVec(pov(right * (h * aspect))) << "\n  up " << exactVec(pov(up * h)) << "\n}\n\n";
    }

}

// The lights; what POV-Ray cannot express exactly is added to `approximations`.
void writeSdlLights(std::ostream& sdl, const Scene& scene, double time, std::vector<std::string>& approximations) {
    const Aabb bounds = scene.bounds(time);
    const glm::dvec3 centre = bounds.valid() ? glm::dvec3(bounds.center()) : glm::dvec3(0.0);
    const double radius = bounds.valid() ? 0.5 * glm::length(glm::dvec3(bounds.extent())) : 1.0;
    for (const auto& l : scene.lights) {
        const glm::dvec3 e = glm::dvec3(l.color) * static_cast<double>(l.intensity);
        const glm::dvec3 dir = glm::normalize(glm::dvec3(l.direction));
        sdl << "// light '" << commentText(l.name) << "' (" << lightTypeName(l.type) << ")\nlight_source {\n";
        if (l.type == Light::Type::Directional) {
            const glm::dvec3 from = centre - dir * (2.0 * radius + 1.0);
            sdl << "  " << vec(pov(from)) << "\n  color rgb " << vec(e) << "\n  parallel\n  point_at " << vec(pov(from + dir)) << "\n";
        } else {
            const double scale = 1.0 / (2.0 * kFadeDistance * kFadeDistance);
            const glm::dvec3 p(l.position);
            sdl << "  " << vec(pov(p)) << "\n  color rgb " << vec(e * scale) << "\n";
            if (l.type == Light::Type::Spot) {
                const double inner = std::min(l.innerConeDegrees, l.outerConeDegrees);
                sdl << "  spotlight\n  point_at " << vec(pov(p + dir)) << "\n  radius " << num(inner) << "\n  falloff "
                    << num(l.outerConeDegrees) << "\n  tightness 0\n";
                if (l.innerConeDegrees >= 90.0f || l.outerConeDegrees >= 90.0f) {
                    approximations.push_back("light '" + l.name + "': POV-Ray's spot light cones end at 90 degrees");
                }
            }
            sdl << "  fade_distance " << num(kFadeDistance) << "\n  fade_power 2\n";
        }
        // Shadow rays through absorbing media are attenuated, as ours (medium_stack.h).
        sdl << "  media_attenuation on\n";
        if (!l.castsShadows) {
            sdl << "  shadowless\n";
            approximations.push_back("light '" + l.name + "' casts no shadows: POV-Ray's shadowless lights add no "
                                            "specular highlights");
        }
        sdl << "}\n\n";
    }

}

// Objects: one mesh2 per mesh, in world space.
void writeSdlObjects(std::ostream& sdl, const Scene& scene, const std::vector<MaterialPlan>& plans, double time) {
    std::size_t meshCount = 0;
    for (const auto& o : scene.objects) {
        const glm::mat4 toWorld = o.worldMatrix(time);
        for (auto meshIndex : o.meshes) {
            Mesh deformedMesh;
            if (o.isDeforming()) {  // the surface at `time`, as the renderers see it (deformation.h)
                DeformedVertices d;
                deformMesh(o.deformation, scene.meshes[meshIndex], time, d);
                deformedMesh = scene.meshes[meshIndex];
                deformedMesh.positions = std::move(d.positions);
                deformedMesh.normals = std::move(d.normals);
                deformedMesh.tangents = std::move(d.tangents);
            }
            const Mesh& mesh = o.isDeforming() ? deformedMesh : scene.meshes[meshIndex];
            if (mesh.triangles.empty()) continue;
            const MaterialPlan& p = plans[mesh.material];
            const std::string id = "HL_Mesh_" + std::to_string(meshCount++);
            const std::string mat = materialId(mesh.material);
            sdl << "// object '" << commentText(o.name) << "', mesh '" << commentText(mesh.name) << "', material '"
                << commentText(scene.materials[mesh.material].name) << "'\n";
            writeMesh(sdl, id, mesh, toWorld, p.textured);
            sdl << "object {\n  " << id << "\n  texture { " << mat << "_Surface }\n";
            if (p.reflects) sdl << "  texture { " << mat << "_Reflection }\n";
            sdl << "  interior { " << mat << "_Interior }\n";
            if (p.noShadow) sdl << "  no_shadow\n";
            // POV-Ray computes interior media only along rays inside hollow objects.
            if (p.absorbs) sdl << "  hollow on\n";
            sdl << "}\n";
            if (p.shadowCopy) {
                // POV-Ray's shadow rays skip no_shadow objects, interiors included: the copy carries the
                // media that absorb them.
                sdl << "object { " << id << " texture { " << mat << "_Shadow }";
                if (p.absorbs) sdl << " interior { " << mat << "_Interior } hollow on";
                sdl << " no_image no_reflection }\n";
            }
            sdl << "\n";
        }
    }
}

// Media: what the interior list of POV-Ray does that ours does not (see the top of this file).
void addMediaApproximations(const Scene& scene, const std::vector<MaterialPlan>& plans, const Camera& camera, double time,
                            std::vector<std::string>& approximations) {
    auto overlap = [](const Aabb& a, const Aabb& b) {
        return a.valid() && b.valid() && glm::all(glm::lessThanEqual(a.lo, b.hi)) && glm::all(glm::lessThanEqual(b.lo, a.hi));
    };
    auto absorbs = [&](std::size_t o) {
        for (auto meshIndex : scene.objects[o].meshes)
            if (plans[scene.meshes[meshIndex].material].absorbs) return true;
        return false;
    };
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        if (!scene.objectIsRefractive(i)) continue;
        const Aabb bi = scene.objectBounds(i, time);
        if (absorbs(i) && bi.valid() && glm::all(glm::lessThanEqual(bi.lo, camera.position)) &&
            glm::all(glm::lessThanEqual(camera.position, bi.hi))) {
            approximations.push_back("the camera is inside the bounds of absorbing object '" + scene.objects[i].name +
                                            "': if inside the object, POV-Ray absorbs along camera rays from the start, ours "
                                            "starts them outside every medium");
        }
        for (std::size_t j = i + 1; j < scene.objects.size(); ++j) {
            if (!scene.objectIsRefractive(j) || !overlap(bi, scene.objectBounds(j, time))) continue;
            approximations.push_back("transparent objects '" + scene.objects[i].name + "' and '" + scene.objects[j].name +
                                            "' have overlapping bounds: where one nests in or overlaps the other, POV-Ray "
                                            "refracts at their shared surfaces with the ratio of their indices, ours each "
                                            "against the ambient index");
        }
    }

}

// Writes the SDL and the pigment images under temporary names, then renames them: no partial output.
// Returns the files written.
std::vector<fs::path> writeExportFiles(const fs::path& out, const std::string& sdl, const std::vector<MaterialPlan>& plans) {
    const fs::path dir = out.parent_path();
    if (!dir.empty()) createDirectories(dir);
    FileGroup files;
    files.write(out, sdl);
    for (const auto& p : plans) {
        if (!p.used || !p.textured) continue;
        const std::vector<unsigned char> png = pngFileBytes(p.pigmentImage, 16);
        files.write(dir / p.pngName, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    }
    return files.commit();
}

}  // namespace

PovExport writePovScene(const Scene& scene, const Camera& camera, double time, int width, int height, const fs::path& out) {
    // Everything that can be wrong with the input is checked before anything is written.
    if (width <= 0 || height <= 0) throw InputError("POV-Ray export: image size must be positive");
    if (out.extension() != ".pov") throw InputError(out.string() + ": expected a .pov file name");
    if (scene.sky.hasCubeMap()) throw InputError(scene.file.string() + ": cube-map skies are not exported to POV-Ray");
    if (!std::isfinite(scene.ambientIor) || scene.ambientIor <= 0.0f) throw InputError(scene.file.string() + ": ambient ior must be positive");
    const std::vector<MaterialPlan> plans = planMaterials(scene, out.stem().string());

    PovExport result;
    std::ostringstream sdl;
    writeSdlHeader(sdl, scene, time, width, height, out);
    writeSdlCamera(sdl, camera, width, height);
    writeSdlLights(sdl, scene, time, result.approximations);
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
        if (plans[i].used) sdl << materialSdl(scene, i, plans[i], result.approximations);
    writeSdlObjects(sdl, scene, plans, time);
    addMediaApproximations(scene, plans, camera, time, result.approximations);

    // One note per distinct approximation.
    std::sort(result.approximations.begin(), result.approximations.end());
    result.approximations.erase(std::unique(result.approximations.begin(), result.approximations.end()), result.approximations.end());
    if (!result.approximations.empty()) {
        sdl << "// Not exact in POV-Ray:\n";
        for (const auto& a : result.approximations) sdl << "//   " << commentText(a) << "\n";
    }

    result.files = writeExportFiles(out, sdl.str(), plans);
    return result;
}

std::vector<std::string> povrayArguments(const fs::path& pov, const fs::path& png, int width, int height) {
    return {"+W" + std::to_string(width), "+H" + std::to_string(height), "-D", "-A", "File_Gamma=1.0", "+FN16",
            "+I" + pov.string(), "+O" + png.string()};
}

}  // namespace hybridlab
