// A scene as authored: camera, render settings, materials, shapes, and
// the light that is not a surface's (environment, lamps).
#ifndef TRAC0R_SCENE_H
#define TRAC0R_SCENE_H

#include "trac0r/camera.h"
#include "trac0r/lights.h"
#include "trac0r/material.h"
#include "trac0r/shape.h"
#include "trac0r/view_transform.h"

#include <cstdint>
#include <string>
#include <vector>

namespace trac0r {

struct RenderSettings {
    int width = 800;
    int height = 600;
    int max_depth = 5;
    // How the window and PNG outputs show the render (not in scene_digest:
    // it changes no sample).
    ViewTransform view = ViewTransform::standard;
};

struct Scene {
    // Where the scene's own coordinate (0, 0, 0) lies in the file's
    // coordinates: every position below (camera, shapes) is relative to it.
    // The loader chooses it in double near the camera (local_origin), so
    // that a room far from the file's origin keeps its shape in float.
    glm::dvec3 origin{0.0};
    Camera camera;
    RenderSettings render;
    std::vector<Material> materials;
    std::vector<Shape> shapes;
    std::vector<Texture> textures;  // the materials' base-colour textures (Material::texture)
    Environment environment;        // none unless present
    std::vector<Lamp> lamps;        // positions relative to origin, as the shapes'
    // What loading passed over in its model files (ModelDefects::lines),
    // for the program to show; empty when strict or when there was none.
    std::vector<std::string> warnings;

    std::size_t triangle_count() const;
};

// The local origin for a camera at `position` (in the file's coordinates,
// in double): each component rounded to a multiple of 1024, so that in the
// scene's coordinates the camera is within 512 of the origin on each axis
// and a scene near the file's origin (|x| < 512) keeps its coordinates
// exactly. What is near the camera then has float's precision at 512 or
// less (2^-15) wherever the file puts it, up to where double's own spacing
// (2^-52 of the distance) matters: about 1e12 for millimetre detail.
glm::dvec3 local_origin(const glm::dvec3& position);

// A 64-bit FNV-1a hash of everything that decides the image: the origin,
// camera, render settings, materials, every triangle's vertices, the
// environment and the lamps, field by field (no padding bytes). Equal
// scenes hash equal on every machine of the same byte order; trac0r_mpi's
// ranks compare theirs.
std::uint64_t scene_digest(const Scene& scene);

}  // namespace trac0r

#endif
