#include "trac0r/model_scene.h"

#include "trac0r/input_checks.h"

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <climits>
#include <cmath>
#include <cstdlib>

namespace trac0r {

namespace {

// The scene-file JSON around the model, with `camera` where given.
nlohmann::json scene_json(const std::string& model, const nlohmann::json* camera) {
    nlohmann::json scene;
    if (camera != nullptr) {
        scene["camera"] = *camera;
    }
    // default_mesh_material, as a scene file writes it.
    scene["materials"]["default"] = {{"type", "diffuse"}, {"color", {0.8, 0.8, 0.8}}};
    scene["environment"] = {{"color", {1, 1, 1}}};
    scene["shapes"] = nlohmann::json::array({{{"type", "mesh"}, {"file", model}}});
    return scene;
}

// The absolute path of `path` (as given, where it cannot be resolved:
// loading then names it).
std::string absolute_path(const std::string& path) {
    char resolved[PATH_MAX];
    return realpath(path.c_str(), resolved) != nullptr ? std::string(resolved) : path;
}

}  // namespace

bool is_model_path(const std::string& path) {
    return has_extension(path, ".obj") || has_extension(path, ".ply") ||
           has_extension(path, ".gltf") || has_extension(path, ".glb");
}

Scene model_scene(const std::string& model_path, const LoadOptions& options, std::string* json) {
    const std::string model = absolute_path(model_path);
    // Loaded once without a camera (the default's, near the origin), for
    // the model's bounds in the file's coordinates.
    Scene scene = parse_scene(scene_json(model, nullptr).dump(), model_path, "", options);
    glm::dvec3 low(0.0);
    glm::dvec3 high(0.0);
    bool any = false;
    for (const Shape& s : scene.shapes) {
        if (s.aabb.empty()) {
            continue;
        }
        low = any ? glm::min(low, glm::dvec3(s.aabb.min)) : glm::dvec3(s.aabb.min);
        high = any ? glm::max(high, glm::dvec3(s.aabb.max)) : glm::dvec3(s.aabb.max);
        any = true;
    }
    low += scene.origin;
    high += scene.origin;
    const glm::dvec3 centre = 0.5 * (low + high);
    double radius = 0.5 * glm::length(high - low);
    if (!(radius > 0.0) || !std::isfinite(radius)) {
        radius = 1.0;
    }
    const double fov = 45.0;
    const double distance = 1.05 * radius / std::sin(0.5 * fov * 3.14159265358979323846 / 180.0);
    const glm::dvec3 from = glm::normalize(glm::dvec3(0.55, 0.4, 1.0));
    const glm::dvec3 position = centre + from * distance;
    const nlohmann::json camera = {{"position", {position.x, position.y, position.z}},
                                   {"direction", {-from.x, -from.y, -from.z}},
                                   {"world_up", {0, 1, 0}},
                                   {"vertical_fov", fov}};
    const nlohmann::json full = scene_json(model, &camera);
    if (json != nullptr) {
        // One line a top-level key, for a reader to edit.
        std::string text = "{";
        for (auto it = full.begin(); it != full.end(); ++it) {
            text += std::string(it == full.begin() ? "\n" : ",\n") + "  " +
                    nlohmann::json(it.key()).dump() + ": " + it.value().dump();
        }
        *json = text + "\n}\n";
    }
    // The scene as the JSON loads: where its camera keeps the origin, the
    // model as loaded (the same numbers); else loaded again about it.
    const std::string camera_text = nlohmann::json({{"camera", camera}}).dump();
    const Camera placed = parse_camera_block(camera_text, model_path, scene.origin);
    if (local_origin(position) == scene.origin) {
        scene.camera = placed;
        return scene;
    }
    return parse_scene(full.dump(), model_path, "", options);
}

}  // namespace trac0r
