#include "trac0r/scene_builder.h"

#include "trac0r/auto_smooth.h"
#include "trac0r/isolated_call.h"
#include "trac0r/json_diagnostics.h"
#include "trac0r/material_schema.h"
#include "trac0r/shape.h"
#include "trac0r/texture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace trac0r {

SceneValueError::SceneValueError(const std::string& object, std::string field, std::string expected,
                                 std::string problem)
    : std::invalid_argument(object + ": " + (field.empty() ? "" : field + ": ") + problem),
      field_(std::move(field)),
      expected_(std::move(expected)),
      problem_(std::move(problem)) {}

namespace {

using json_diagnostics::expectation;
using json_diagnostics::NumberRule;
using json_diagnostics::satisfies;

std::string number_text(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

std::string vector_text(const glm::dvec3& v) {
    return "[" + number_text(v.x) + ", " + number_text(v.y) + ", " + number_text(v.z) + "]";
}

[[noreturn]] void refuse(const std::string& object, const std::string& field,
                         const std::string& expected, const std::string& got) {
    throw SceneValueError(object, field, expected, "expected " + expected + ", got " + got);
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void check_number(const std::string& object, const std::string& field, float x, NumberRule rule) {
    if (!std::isfinite(x) || !satisfies(rule, x)) {
        refuse(object, field, expectation(rule), number_text(x));
    }
}

void check_vec3(const std::string& object, const std::string& field, const glm::dvec3& v,
                NumberRule rule) {
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(v[i]) || !satisfies(rule, static_cast<float>(v[i]))) {
            refuse(object, field, expectation(rule, 3), vector_text(v));
        }
    }
}

// Degrees in [lowest, highest] (`low_closed`: the low end included).
void check_degrees(const std::string& object, const std::string& field, float degrees, float lowest,
                   bool low_closed, float highest) {
    if (!(low_closed ? degrees >= lowest : degrees > lowest) || !(degrees <= highest)) {
        char text[96];
        std::snprintf(text, sizeof text, "a number of degrees in %c%g, %g]", low_closed ? '[' : '(',
                      static_cast<double>(lowest), static_cast<double>(highest));
        refuse(object, field, text, number_text(degrees));
    }
}

// colour x amount within what a pixel's float sum can hold.
void check_radiance(const std::string& object, const std::string& field, const glm::vec3& color,
                    float amount, const std::string& what) {
    const double peak = static_cast<double>(amount) * std::max({color.x, color.y, color.z});
    if (peak > static_cast<double>(max_emitted_radiance)) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", peak);
        throw SceneValueError(object, field, "",
                              "the colour times the " + what + " is " + text +
                                  " in a channel, above 1e30, the most the renderer can sum "
                                  "over a pixel's samples in float");
    }
}

void check_emission(const std::string& object, const Material& m) {
    const bool principled = m.type == MaterialType::principled;
    const double emitted =
        principled ? std::max({m.emission.x, m.emission.y, m.emission.z})
                   : static_cast<double>(m.emittance) * std::max({m.color.x, m.color.y, m.color.z});
    if (emitted > static_cast<double>(max_emitted_radiance)) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", emitted);
        throw SceneValueError(
            object, principled ? "emission" : "emittance", "",
            std::string(principled ? "the emission" : "the colour times the emittance") + " is " +
                text +
                " in a channel, above 1e30, the most the renderer can "
                "sum over a pixel's samples in float: scale the scene's "
                "emission down");
    }
}

void check_placement(const std::string& object, const glm::dvec3& position,
                     const glm::vec3& orientation) {
    check_vec3(object, "position", position, NumberRule::finite);
    check_vec3(object, "orientation", glm::dvec3(orientation), NumberRule::finite);
}

const char* const texture_field_names[] = {"texture",          "roughness_texture",
                                           "metallic_texture", "normal_texture",
                                           "alpha_texture",    "emission_texture"};

}  // namespace

SceneBuilder::SceneBuilder(Scene& scene, const LoadOptions& options)
    : scene_(scene), options_(options), warnings_before_(scene.warnings), defects_(options.strict) {
    for (std::size_t i = 0; i < scene_.materials.size(); ++i) {
        const Material& m = scene_.materials[i];
        if (m.file.empty()) {
            material_index_.emplace(m.name, static_cast<int>(i));
        } else {
            file_material_index_.emplace(m.file + "\n" + m.name, static_cast<int>(i));
        }
    }
}

// ---- Materials ---------------------------------------------------------------

int SceneBuilder::add_material(const Material& m) {
    const std::string object = "material \"" + m.name + "\"";
    if (m.name.empty()) {
        throw SceneValueError(object, "", "", "a material needs a name");
    }
    if (material_index_.count(m.name) != 0) {
        throw SceneValueError(object, "", "", "the scene has a material of this name already");
    }
    check_vec3(object, "color", glm::dvec3(m.color), material_color_rule(m.type));
    for (const MaterialKey& k : material_keys()) {
        if (k.type == m.type) {
            check_number(object, k.key, m.*k.field, k.rule);
        }
    }
    if (!m.metal.empty() && (m.type != MaterialType::conductor || find_metal(m.metal) == nullptr)) {
        const std::vector<std::string> names = metal_names();
        throw SceneValueError(object, "metal", "",
                              m.type != MaterialType::conductor
                                  ? "only a conductor has a named metal"
                                  : "unknown metal \"" + m.metal + "\" (known metals: " +
                                        json_diagnostics::join(names, "\"") + ")");
    }
    if (m.type == MaterialType::principled) {
        check_vec3(object, "emission", glm::dvec3(m.emission), NumberRule::non_negative);
    }
    check_number(object, "alpha", m.alpha, NumberRule::unit_interval);
    check_number(object, "alpha_cutoff", m.alpha_cutoff, NumberRule::unit_interval);
    check_number(object, "normal_scale", m.normal_scale, NumberRule::finite);
    const std::array<int, 6> textures = texture_fields(m);
    for (std::size_t i = 0; i < textures.size(); ++i) {
        if (textures[i] < -1 || textures[i] >= static_cast<int>(scene_.textures.size())) {
            refuse(object, texture_field_names[i],
                   "-1 or an index into the scene's " + std::to_string(scene_.textures.size()) +
                       " textures",
                   std::to_string(textures[i]));
        }
    }
    if (m.alpha_channel < 0 || m.alpha_channel > 3) {
        refuse(object, "alpha_channel", "an integer in [0, 3]", std::to_string(m.alpha_channel));
    }
    check_emission(object, m);
    const int index = static_cast<int>(scene_.materials.size());
    scene_.materials.push_back(m);
    material_index_.emplace(m.name, index);
    return index;
}

// The material a shape names; "" for the scene's "default", else
// default_mesh_material, added once.
int SceneBuilder::material_index(const std::string& name, const std::string& object) {
    if (name.empty()) {
        if (default_material_ < 0) {
            const auto own = material_index_.find("default");
            if (own != material_index_.end()) {
                default_material_ = own->second;
            } else {
                default_material_ = static_cast<int>(scene_.materials.size());
                scene_.materials.push_back(default_mesh_material());
                material_index_.emplace(scene_.materials.back().name, default_material_);
            }
        }
        return default_material_;
    }
    const auto found = material_index_.find(name);
    if (found != material_index_.end()) {
        return found->second;
    }
    // The first names only: a scene may have thousands.
    const std::size_t shown = 20;
    std::vector<std::string> names;
    for (const auto& entry : material_index_) {
        if (names.size() == shown) {
            break;
        }
        names.push_back(entry.first);
    }
    const std::string more =
        material_index_.size() > shown
            ? " and " + std::to_string(material_index_.size() - shown) + " more"
            : "";
    throw SceneValueError(object, "material", "",
                          "unknown material " + json_diagnostics::describe(name) +
                              " (known materials: " +
                              json_diagnostics::join(names, "\"") + more + ")");
}

// ---- Shapes ------------------------------------------------------------------

// Each number was in range, but the triangles are made in float: a shape
// of size 1e-20, or at 3e38, would silently vanish.
void SceneBuilder::check_usable(const std::vector<Shape>& shapes, const std::string& object) {
    std::size_t count = 0;
    bool any_usable = false;
    for (const Shape& shape : shapes) {
        count += shape.triangles.size();
        any_usable = any_usable ||
                     std::any_of(shape.triangles.begin(), shape.triangles.end(), usable_triangle);
    }
    if (!any_usable) {
        throw SceneValueError(object, "", "",
                              "no triangle of the shape can be rendered (of " +
                                  std::to_string(count) +
                                  ", each has in float arithmetic an area of zero or below "
                                  "float's smallest normal, or a vertex that is not finite: "
                                  "degenerate faces, or a size, scale or position too small "
                                  "or too large)");
    }
}

// A primitive: usable, then its material (a refused one adds no default
// material).
void SceneBuilder::add_primitive(Shape shape, const ShapePlacement& p, const std::string& object) {
    check_usable({shape}, object);
    shape.material = material_index(p.material, object);
    scene_.shapes.push_back(std::move(shape));
}

void SceneBuilder::add_plane(const ShapePlacement& p, const glm::vec2& size) {
    const std::string object = "plane";
    check_placement(object, p.position, p.orientation);
    if (!std::isfinite(size.x) || !std::isfinite(size.y) || !(size.x > 0.0f) || !(size.y > 0.0f)) {
        refuse(object, "size", expectation(NumberRule::positive, 2),
               "[" + number_text(size.x) + ", " + number_text(size.y) + "]");
    }
    add_primitive(make_plane(glm::vec3(p.position - scene_.origin), p.orientation, size, 0), p,
                  object);
}

void SceneBuilder::add_box(const ShapePlacement& p, const glm::vec3& size) {
    const std::string object = "box";
    check_placement(object, p.position, p.orientation);
    check_vec3(object, "size", glm::dvec3(size), NumberRule::positive);
    add_primitive(make_box(glm::vec3(p.position - scene_.origin), p.orientation, size, 0), p,
                  object);
}

void SceneBuilder::add_icosphere(const ShapePlacement& p, float radius, int subdivisions) {
    const std::string object = "icosphere";
    check_placement(object, p.position, p.orientation);
    check_number(object, "radius", radius, NumberRule::positive);
    if (subdivisions < 0 || subdivisions > 7) {
        refuse(object, "subdivisions", "an integer in [0, 7]", std::to_string(subdivisions));
    }
    add_primitive(make_icosphere(glm::vec3(p.position - scene_.origin), p.orientation, radius,
                                 subdivisions, 0),
                  p, object);
}

void SceneBuilder::add_mesh_file(const std::string& path, const MeshFilePlacement& p) {
    const std::string object = "mesh \"" + path + "\"";
    check_placement(object, p.position, p.orientation);
    check_vec3(object, "scale", glm::dvec3(p.scale), NumberRule::non_zero);
    // Blender's auto smooth, for files with neither normals nor groups.
    const bool auto_smoothed = !(p.smooth_angle < 0.0f);
    if (auto_smoothed && !(p.smooth_angle <= 180.0f)) {
        refuse(object, "smooth_angle", "degrees in [0, 180]", number_text(p.smooth_angle));
    }
    // What a refusal takes back: the builder appends materials and
    // textures, and notes the default and the file's materials.
    const std::size_t materials_before = scene_.materials.size();
    const std::size_t textures_before = scene_.textures.size();
    const int default_before = default_material_;
    const std::map<std::string, int> index_before = material_index_;
    const std::map<std::string, int> file_index_before = file_material_index_;
    const ModelDefects defects_before = defects_;
    try {
        read_mesh_file(path, p, object);
    } catch (...) {
        scene_.materials.erase(
            scene_.materials.begin() + static_cast<std::ptrdiff_t>(materials_before),
            scene_.materials.end());
        scene_.textures.erase(
            scene_.textures.begin() + static_cast<std::ptrdiff_t>(textures_before),
            scene_.textures.end());
        default_material_ = default_before;
        material_index_ = index_before;
        file_material_index_ = file_index_before;
        defects_ = defects_before;
        throw;
    }
    scene_.warnings = warnings_before_;
    const std::vector<std::string> lines = defects_.lines();
    scene_.warnings.insert(scene_.warnings.end(), lines.begin(), lines.end());
}

void SceneBuilder::read_mesh_file(const std::string& path, const MeshFilePlacement& p,
                                  const std::string& object) {
    const int material = material_index(p.material, object);
    const ReaderIsolation isolation(options_.isolate_readers);
    // The file's textures are counted against the scene's room before they
    // are decoded (a small file may name many huge images).
    MeshParts mesh = load_mesh_parts(
        path, glm::vec3(p.position - scene_.origin), p.orientation, p.scale, material, p.smooth,
        p.file_materials, scene_texel_budget() - texel_count(scene_.textures), &defects_);
    std::vector<Material>& materials = scene_.materials;
    std::vector<Texture>& textures = scene_.textures;
    // The file's textures that its materials use, moved into the scene's on
    // first use: by index in mesh.textures.
    std::vector<int> texture_in_scene(mesh.textures.size(), -1);
    std::vector<Shape> shapes;
    for (MeshPart& part : mesh.parts) {
        if (part.material >= 0) {
            // The scene's material of the same name, else the file's, added
            // once for each file and name (so files whose materials share a
            // name, or have none, stay apart).
            Material m = mesh.materials[static_cast<std::size_t>(part.material)];
            const auto own = material_index_.find(m.name);
            if (!m.name.empty() && own != material_index_.end()) {
                part.shape.material = own->second;
            } else {
                if (m.name.empty()) {
                    m.name = path + " #" + std::to_string(part.material);
                }
                const std::string key = path + "\n" + m.name;
                const auto found = file_material_index_.find(key);
                if (found != file_material_index_.end()) {
                    part.shape.material = found->second;
                } else {
                    part.shape.material = static_cast<int>(materials.size());
                    file_material_index_[key] = part.shape.material;
                    // The mesh's textures this material uses, moved into
                    // the scene's once each.
                    for (int* texture : texture_fields(m)) {
                        if (*texture < 0) {
                            continue;
                        }
                        int& index = texture_in_scene[static_cast<std::size_t>(*texture)];
                        if (index < 0) {
                            index = static_cast<int>(textures.size());
                            textures.push_back(
                                std::move(mesh.textures[static_cast<std::size_t>(*texture)]));
                            const std::uint64_t texels = texel_count(textures);
                            if (texels > scene_texel_budget()) {
                                throw std::runtime_error(
                                    path + ": its textures bring the scene's to " +
                                    std::to_string(texels) + " texels, over the " +
                                    std::to_string(scene_texel_budget()) +
                                    " a scene may have on this machine");
                            }
                        }
                        *texture = index;
                    }
                    m.file = path;
                    materials.push_back(m);
                }
            }
        }
        part.shape.source = path;
        shapes.push_back(std::move(part.shape));
    }
    if (!(p.smooth_angle < 0.0f) && p.smooth) {
        auto_smooth(shapes, p.smooth_angle);
    }
    check_usable(shapes, object);
    for (Shape& shape : shapes) {
        scene_.shapes.push_back(std::move(shape));
    }
}

// ---- Camera and light --------------------------------------------------------

void SceneBuilder::set_camera(const Camera& camera) {
    if (const char* problem = camera_problem(camera)) {
        throw SceneValueError("camera", "", "", problem);
    }
    scene_.camera = camera;
}

void SceneBuilder::set_environment(Environment e) {
    const std::string object = "environment";
    check_number(object, "strength", e.strength, NumberRule::non_negative);
    check_number(object, "rotation", e.rotation, NumberRule::finite);
    glm::vec3 peak(0.0f);
    if (e.texels.empty()) {
        check_vec3(object, "color", glm::dvec3(e.color), NumberRule::non_negative);
        peak = e.color;
    } else {
        const std::size_t expected =
            e.width > 0 && e.height > 0
                ? static_cast<std::size_t>(e.width) * static_cast<std::size_t>(e.height)
                : 0;
        if (expected == 0 || e.texels.size() != expected) {
            throw SceneValueError(object, "map", "",
                                  "a map of " + std::to_string(e.width) + " x " +
                                      std::to_string(e.height) + " texels holds " +
                                      std::to_string(e.texels.size()));
        }
        for (const glm::vec3& t : e.texels) {
            if (!finite(glm::dvec3(t)) || t.x < 0.0f || t.y < 0.0f || t.z < 0.0f) {
                throw SceneValueError(
                    object, "map", "",
                    "a texel is negative or not finite: " + vector_text(glm::dvec3(t)));
            }
            peak = glm::max(peak, t);
        }
    }
    check_radiance(object, "strength", peak, e.strength, "strength");
    e.present = true;
    scene_.environment = std::move(e);
}

void SceneBuilder::add_lamp(Lamp lamp) {
    const std::string object = std::string(to_string(lamp.type)) + " light";
    const bool sun = lamp.type == LampType::sun;
    const char* power = sun ? "irradiance" : "intensity";
    check_vec3(object, "color", glm::dvec3(lamp.color), NumberRule::non_negative);
    check_number(object, power, lamp.power, NumberRule::non_negative);
    if (lamp.type != LampType::point) {
        const float length = glm::length(lamp.direction);
        if (!finite(glm::dvec3(lamp.direction)) || !(length > 0.0f) || !std::isfinite(length)) {
            refuse(object, "direction",
                   std::string("a direction (3 finite numbers, not all zero): ") +
                       (sun ? "towards the sun" : "where the spot points"),
                   vector_text(glm::dvec3(lamp.direction)));
        }
        lamp.direction /= length;
    }
    if (!sun) {
        check_vec3(object, "position", glm::dvec3(lamp.position), NumberRule::finite);
    }
    if (sun) {
        check_degrees(object, "angle", lamp.angle, 0.0f, true, 90.0f);
        // The sun's radiance is its irradiance over its disc's pi sin^2.
        const float radius = glm::radians(0.5f * lamp.angle);
        const float radiance_factor =
            lamp.angle > 0.0f ? 1.0f / (3.14159265f * std::sin(radius) * std::sin(radius)) : 1.0f;
        check_radiance(object, power, lamp.color, lamp.power * radiance_factor,
                       "irradiance over the sun's disc");
    } else {
        if (lamp.type == LampType::spot) {
            check_degrees(object, "angle", lamp.angle, 0.0f, false, 180.0f);
            check_number(object, "blend", lamp.blend, NumberRule::unit_interval);
        }
        check_radiance(object, power, lamp.color, lamp.power, "intensity");
    }
    scene_.lamps.push_back(lamp);
}

}  // namespace trac0r
