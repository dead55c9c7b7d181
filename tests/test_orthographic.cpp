// The orthographic camera rendered: a lamp shows at its own size, in
// metres of the view's height, at any distance (no perspective), and the
// OpenCL backend draws what the CPU one does.
#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/renderer.h"
#include "trac0r/scene.h"
#include "trac0r/shape.h"

#include <cmath>
#include <memory>

using namespace trac0r;

namespace {

const float half_pi = 1.5707963f;
const int width = 64;
const int height = 48;

// A square lamp of radiance 1, 1 m on a side, facing the camera at
// `depth`, centred on its axis; nothing else. The camera at the origin
// looks along -z, orthographic, 2 m high: a pixel is 2 / 48 m, so the lamp
// covers the 24 x 24 pixels from (20, 12) to (43, 35), its edges on pixel
// edges.
Scene lamp_scene(float depth) {
    Scene scene;
    Material lamp;
    lamp.name = "lamp";
    lamp.type = MaterialType::emissive;
    lamp.color = glm::vec3(1.0f);
    lamp.emittance = 1.0f;
    scene.materials = {lamp};
    // A plane's normal is local +y: turned by pi/2 about x it is +z.
    scene.shapes.push_back(make_plane(glm::vec3(0.0f, 0.0f, -depth), glm::vec3(half_pi, 0.0f, 0.0f),
                                      glm::vec2(1.0f), 0));
    scene.camera.position = glm::vec3(0.0f);
    scene.camera.direction = glm::vec3(0.0f, 0.0f, -1.0f);
    scene.camera.projection = Projection::orthographic;
    scene.camera.view_height = 2.0f;
    scene.render.width = width;
    scene.render.height = height;
    scene.render.max_depth = 1;
    return scene;
}

Image render(const Scene& scene, Accel accel) {
    PackOptions options;
    options.accel = accel;
    Renderer r(scene, std::make_unique<CpuBackend>(), 5, options);
    for (int i = 0; i < 4; ++i) {
        r.render_frame();
    }
    return r.image();
}

}  // namespace

TEST_CASE("an orthographic view shows a lamp at its size in metres, at any distance",
          "[camera][orthographic]") {
    for (const Accel accel : {Accel::flat, Accel::bvh}) {
        for (const float depth : {0.5f, 3.0f, 40.0f}) {
            CAPTURE(static_cast<int>(accel), depth);
            const Image image = render(lamp_scene(depth), accel);
            double sum = 0.0;
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const float v = image.pixels[static_cast<std::size_t>(y) * width + x].x;
                    sum += v;
                    CAPTURE(x, y, v);
                    // Every sample of a pixel inside the square meets the
                    // lamp, every one outside misses it; a pixel on its
                    // border may lose a sample that lands exactly on the edge.
                    const bool inside = x >= 20 && x <= 43 && y >= 12 && y <= 35;
                    const bool border = inside && (x == 20 || x == 43 || y == 12 || y == 35);
                    if (inside && !border) {
                        REQUIRE(v == 1.0f);
                    } else if (!inside) {
                        REQUIRE(v == 0.0f);
                    }
                }
            }
            // 24 x 24 pixels of radiance 1: a lost edge sample costs 1/4.
            CHECK(sum == Approx(24.0 * 24.0).margin(1.0));
        }
    }
}
