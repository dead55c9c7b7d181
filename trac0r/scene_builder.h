// Scenes built in code: materials, shapes (planes, boxes, spheres, meshes
// from arrays, mesh files), the camera, the environment and lamps, each
// checked as the scene format checks it (docs/scene-format.md) and refused
// with its words. The JSON loader builds every scene through a
// SceneBuilder, so a value a file may not hold cannot be added in code
// either; docs/library.md shows it in use.
#ifndef TRAC0R_SCENE_BUILDER_H
#define TRAC0R_SCENE_BUILDER_H

#include "trac0r/mesh_arrays.h"
#include "trac0r/model_defects.h"
#include "trac0r/scene.h"
#include "trac0r/scene_loader.h"

#include <glm/glm.hpp>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace trac0r {

// A value the scene cannot hold. what() is "OBJECT: FIELD: PROBLEM", for
// example `material "red": roughness: expected a number in [0, 1], got
// 1.5`; the JSON loader puts the file and JSON pointer in front of
// PROBLEM instead.
class SceneValueError : public std::invalid_argument {
  public:
    SceneValueError(const std::string& object, std::string field, std::string expected,
                    std::string problem);
    // The scene format's key that is wrong ("roughness", "color",
    // "material"); "" when the object as a whole is (a shape with no
    // triangle left).
    const std::string& field() const { return field_; }
    // For a value out of its range, what the key must hold in the scene
    // format's words ("a number in [0, 1]"); else "".
    const std::string& expected() const { return expected_; }
    // The message without the object and field ("expected a number in
    // [0, 1], got 1.5").
    const std::string& problem() const { return problem_; }

  private:
    std::string field_;
    std::string expected_;
    std::string problem_;
};

// Where a plane, box or sphere goes, as a scene file's shape says it.
struct ShapePlacement {
    std::string material;         // a material of the scene by name; "": as MeshPlacement's
    glm::dvec3 position{0.0};     // in the file's coordinates (Scene::origin subtracted)
    glm::vec3 orientation{0.0f};  // radians, about x, y, z
};

// A mesh file placed as a scene file's "mesh" shape (its keys, same names).
struct MeshFilePlacement {
    std::string material;  // faces without a file material; "": as MeshPlacement's
    glm::dvec3 position{0.0};
    glm::vec3 orientation{0.0f};
    glm::vec3 scale{1.0f};
    bool smooth = true;
    float smooth_angle = -1.0f;  // degrees in [0, 180]; below 0: none
    bool file_materials = true;
};

class SceneBuilder {
  public:
    // Adds to `scene`, whose materials so far are known by name. Mesh files
    // are read as `options` says (strict, isolate_readers); their warnings
    // go to Scene::warnings after those it has.
    explicit SceneBuilder(Scene& scene, const LoadOptions& options = LoadOptions());

    // Adds a material and returns its index. Refused: no name, a name the
    // scene has, a number outside its type's range (the scene format's
    // table), an unknown metal, a texture index past Scene::textures,
    // emission above max_emitted_radiance.
    int add_material(const Material& material);

    // Primitives, as the scene format's "plane" (size in x and z), "box"
    // and "icosphere" (subdivisions 0 to 7). Refused: an unknown material,
    // a size or radius not finite and positive, a position or orientation
    // not finite, no triangle left in float.
    void add_plane(const ShapePlacement& placement, const glm::vec2& size);
    void add_box(const ShapePlacement& placement, const glm::vec3& size);
    void add_icosphere(const ShapePlacement& placement, float radius, int subdivisions = 2);
    // A mesh from arrays (mesh_arrays.h has what is refused).
    void add_mesh(const MeshArrays& mesh, const MeshPlacement& placement);
    // A mesh file (.obj, .ply, .gltf, .glb) with its materials and
    // textures. A file that cannot be read: std::runtime_error naming it.
    void add_mesh_file(const std::string& path, const MeshFilePlacement& placement);

    // Refused: camera_problem's conditions.
    void set_camera(const Camera& camera);
    // A constant colour, or a map (read_environment_map, then strength and
    // rotation set). Refused: a negative or non-finite colour or strength,
    // a non-finite rotation, a map whose texels are not width x height,
    // radiance above max_emitted_radiance.
    void set_environment(Environment environment);
    // A point, spot or sun lamp (Lamp::position relative to Scene::origin).
    // Refused: a negative or non-finite colour or power, a zero or
    // non-finite direction (it is made unit), a spot's angle outside
    // (0, 180], a sun's outside [0, 90], blend outside [0, 1], radiance
    // above max_emitted_radiance.
    void add_lamp(Lamp lamp);

    Scene& scene() { return scene_; }

  private:
    int material_index(const std::string& name, const std::string& object);
    void read_mesh_file(const std::string& path, const MeshFilePlacement& placement,
                        const std::string& object);
    static void check_usable(const std::vector<Shape>& shapes, const std::string& object);
    void add_primitive(Shape shape, const ShapePlacement& placement, const std::string& object);

    Scene& scene_;
    LoadOptions options_;
    std::map<std::string, int> material_index_;  // the scene's own, by name
    // A file's material (its path and name) -> its index in materials.
    std::map<std::string, int> file_material_index_;
    int default_material_ = -1;  // default_mesh_material's index once added
    std::vector<std::string> warnings_before_;
    ModelDefects defects_;
};

}  // namespace trac0r

#endif
