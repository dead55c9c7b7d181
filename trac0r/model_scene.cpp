#include "trac0r/model_scene.h"

#include "trac0r/gltf_json.h"
#include "trac0r/gltf_view.h"
#include "trac0r/input_checks.h"
#include "trac0r/input_file.h"
#include "trac0r/isolated_call.h"

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>

namespace trac0r {

namespace {

nlohmann::json vec3_json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// A lamp as the scene file writes it.
nlohmann::json lamp_json(const Lamp& lamp) {
    nlohmann::json out = {{"type", to_string(lamp.type)},
                          {"color", vec3_json(glm::dvec3(lamp.color))}};
    if (lamp.type == LampType::sun) {
        out["direction"] = vec3_json(glm::dvec3(lamp.direction));
        out["irradiance"] = lamp.power;
        out["angle"] = lamp.angle;
        return out;
    }
    out["position"] = vec3_json(glm::dvec3(lamp.position));
    out["intensity"] = lamp.power;
    if (lamp.type == LampType::spot) {
        out["direction"] = vec3_json(glm::dvec3(lamp.direction));
        out["angle"] = lamp.angle;
        out["blend"] = lamp.blend;
    }
    return out;
}

// The scene-file JSON around the model, with `camera` and `render` where
// given, lit by `lamps`, or by a white sky where there are none.
nlohmann::json scene_json(const std::string& model, const nlohmann::json* camera,
                          const nlohmann::json* render, const std::vector<Lamp>& lamps) {
    nlohmann::json scene;
    if (camera != nullptr) {
        scene["camera"] = *camera;
    }
    if (render != nullptr) {
        scene["render"] = *render;
    }
    // default_mesh_material, as a scene file writes it.
    scene["materials"]["default"] = {{"type", "diffuse"}, {"color", {0.8, 0.8, 0.8}}};
    if (lamps.empty()) {
        scene["environment"] = {{"color", {1, 1, 1}}};
    } else {
        scene["lights"] = nlohmann::json::array();
        for (const Lamp& lamp : lamps) {
            scene["lights"].push_back(lamp_json(lamp));
        }
    }
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
    const ReaderIsolation isolation(options.isolate_readers);
    const std::string model = absolute_path(model_path);
    // A glTF's own camera and lights.
    GltfView view;
    const bool glb = has_extension(model_path, ".glb");
    if (glb || has_extension(model_path, ".gltf")) {
        std::string text;
        try {
            text = read_input_file(model_path, "mesh");
        } catch (const std::runtime_error& e) {
            throw SceneError(e.what());
        }
        try {
            view = gltf_view(gltf_json_text(text, glb), model_path);
        } catch (const std::runtime_error& e) {
            throw SceneError(e.what());
        }
    }
    // Loaded once without a camera (the default's, near the origin), for
    // the model's bounds in the file's coordinates.
    Scene scene = parse_scene(scene_json(model, nullptr, nullptr, view.lamps).dump(), model_path,
                              "", options);
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
    nlohmann::json camera = {{"position", {position.x, position.y, position.z}},
                             {"direction", {-from.x, -from.y, -from.z}},
                             {"world_up", {0, 1, 0}},
                             {"vertical_fov", fov}};
    nlohmann::json render = nullptr;
    if (view.has_camera) {
        camera = {{"position", vec3_json(view.position)},
                  {"direction", vec3_json(view.direction)},
                  {"world_up", vec3_json(view.up)}};
        if (view.orthographic) {
            camera["projection"] = "orthographic";
            camera["view_height"] = view.view_height;
        } else {
            camera["vertical_fov"] = view.vertical_fov;
        }
        if (view.aspect > 0.0) {
            // 600 rows, as the default's, and the camera's aspect.
            const double width = std::round(600.0 * view.aspect);
            render = {{"width", static_cast<int>(std::min(16384.0, std::max(1.0, width)))},
                      {"height", 600}};
        }
    }
    const glm::dvec3 eye = view.has_camera ? view.position : position;
    const nlohmann::json full =
        scene_json(model, &camera, render.is_null() ? nullptr : &render, view.lamps);
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
    if (local_origin(eye) == scene.origin && render.is_null()) {
        scene.camera = placed;
        return scene;
    }
    return parse_scene(full.dump(), model_path, "", options);
}

Scene open_scene(const std::string& path, const LoadOptions& options) {
    return is_model_path(path) ? model_scene(path, options) : load_scene_file(path, options);
}

}  // namespace trac0r
