// A scene as authored: camera, render settings, materials and shapes.
#ifndef TRAC0R_SCENE_H
#define TRAC0R_SCENE_H

#include "trac0r/camera.h"
#include "trac0r/material.h"
#include "trac0r/shape.h"

#include <string>
#include <vector>

namespace trac0r {

struct RenderSettings {
    int width = 800;
    int height = 600;
    int max_depth = 5;
};

struct Scene {
    Camera camera;
    RenderSettings render;
    std::vector<Material> materials;
    std::vector<Shape> shapes;

    std::size_t triangle_count() const;
};

}  // namespace trac0r

#endif
