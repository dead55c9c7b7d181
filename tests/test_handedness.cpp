// The camera is right-handed, as glTF, Blender and OBJ exporters: from +z
// looking along -z, +x is on the image's right and a texture reads as
// drawn. The scene is benchmarks/handedness/scene.json, which Blender
// renders the same way round (benchmarks/handedness/run.sh): a quad whose
// texture has a blue corner at its top left (u = 0, v = 1) and a red cube
// at x = +1.4.
#include <catch2/catch.hpp>

#include "trac0r/cpu_backend.h"
#include "trac0r/renderer.h"
#include "trac0r/scene_loader.h"

#include <memory>
#include <string>

using namespace trac0r;

namespace {

struct Centroid {
    double x = 0.0, y = 0.0;
    long count = 0;
};

template <typename Test>
Centroid centroid_of(const Image& image, Test is) {
    Centroid c;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            if (is(image.pixels[static_cast<std::size_t>(y) * image.width + x])) {
                c.x += x + 0.5;
                c.y += y + 0.5;
                ++c.count;
            }
        }
    }
    if (c.count > 0) {
        c.x /= c.count;
        c.y /= c.count;
    }
    return c;
}

}  // namespace

TEST_CASE("from +z looking along -z, +x is right and a texture reads as drawn",
          "[camera][texture]") {
    Scene scene =
        load_scene_file(std::string(TRAC0R_SOURCE_DIR) + "/benchmarks/handedness/scene.json");
    REQUIRE(scene.camera.direction == glm::vec3(0.0f, 0.0f, -1.0f));
    scene.render.width = 160;
    scene.render.height = 120;
    PackOptions options;
    options.integrator = Integrator::nee;
    Renderer r(scene, std::make_unique<CpuBackend>(), 1, options);
    for (int i = 0; i < 16; ++i) {
        r.render_frame();
    }
    const Image image = r.image();
    // The red cube: strongly red pixels.
    const Centroid red = centroid_of(image, [](const glm::vec3& c) {
        return c.x > 0.1f && c.x > 3.0f * c.y && c.x > 3.0f * c.z;
    });
    // The quad: bright, nearly grey pixels (the texture's white ground).
    const Centroid quad = centroid_of(image, [](const glm::vec3& c) {
        return c.y > 0.2f && std::abs(c.x - c.y) < 0.1f * c.y && std::abs(c.z - c.y) < 0.1f * c.y;
    });
    // The texture's top-left corner: blue.
    const Centroid blue = centroid_of(image, [](const glm::vec3& c) {
        return c.z > 0.05f && c.z > 2.0f * c.x && c.z > 2.0f * c.y;
    });
    CAPTURE(red.x, red.count, quad.x, quad.y, quad.count, blue.x, blue.y, blue.count);
    REQUIRE(red.count > 50);
    REQUIRE(quad.count > 500);
    REQUIRE(blue.count > 10);
    CHECK(red.x > 0.75 * image.width);  // the cube at +x: on the right
    CHECK(std::abs(quad.x - 0.5 * image.width) < 4.0);  // the quad at x = 0: centred
    CHECK(blue.x < quad.x - 10.0);  // the corner at u = 0: the quad's left
    CHECK(blue.y < quad.y - 10.0);  // and v = 1: its top
}
