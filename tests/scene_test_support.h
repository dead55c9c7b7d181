// What the scene loader's tests and the readers' tests share: a minimal
// valid scene to swap parts of, strict loading, and the error a scene
// file's loading throws.
#ifndef TRAC0R_TESTS_SCENE_TEST_SUPPORT_H
#define TRAC0R_TESTS_SCENE_TEST_SUPPORT_H

#include <catch2/catch.hpp>

#include "trac0r/scene_loader.h"

#include <glm/glm.hpp>

#include <string>

namespace trac0r_scene_test {

// A minimal valid scene: one diffuse material, one plane. Tests swap one
// part for a broken one.
const std::string white_material = R"("white": {"type": "diffuse", "color": [0.5, 0.5, 0.5]})";
const std::string plane_shape = R"({"type": "plane", "size": [1, 1], "material": "white"})";

inline std::string scene_json(const std::string& materials = white_material,
                              const std::string& shapes = plane_shape,
                              const std::string& extra = "") {
    return "{" + extra + (extra.empty() ? "" : ", ") + R"("materials": {)" + materials +
           R"(}, "shapes": [)" + shapes + "]}";
}

inline std::string with_shape(const std::string& shape) {
    return scene_json(white_material, shape);
}

// Strict loading: a model file's defects are errors, with the messages
// these tests check (lenient loading's warnings: test_model_defects.cpp).
inline trac0r::LoadOptions strict() {
    trac0r::LoadOptions options;
    options.strict = true;
    return options;
}

// The message of the SceneError that loading the scene file `path` throws
// (strictly).
inline std::string scene_file_error(const std::string& path) {
    try {
        trac0r::load_scene_file(path, strict());
    } catch (const trac0r::SceneError& e) {
        return e.what();
    }
    FAIL("no SceneError for " << path);
    return "";
}

inline bool same_vec3(const glm::vec3& a, const glm::vec3& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

}  // namespace trac0r_scene_test

#endif
