// The smallest program on trac0r: load a scene (or the built-in Cornell
// box), render N samples per pixel on the CPU, write the image.
//   minimal [SCENE.json] [SPP] [OUTPUT.png|.pfm]
#include <trac0r/trac0r.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>

int main(int argc, char** argv) {
    try {
        const std::string scene_path = argc > 1 ? argv[1] : "";
        const int spp = argc > 2 ? std::atoi(argv[2]) : 16;
        const std::string output = argc > 3 ? argv[3] : "minimal.png";
        if (spp < 1) {
            std::fprintf(stderr, "minimal: SPP: expected a positive integer, got '%s'\n", argv[2]);
            return 2;
        }
        const trac0r::Scene scene =
            scene_path.empty() ? trac0r::builtin_scene() : trac0r::load_scene_file(scene_path);
        trac0r::Renderer renderer(scene, std::make_unique<trac0r::CpuBackend>());
        trac0r::BatchOptions options;
        options.stop.spp = spp;  // also: .seconds, .target_error
        const trac0r::BatchResult result = trac0r::render_batch(renderer, options);
        trac0r::write_image(output, result.image);
        std::printf("%s: %d spp of %dx%d written to %s\n", trac0r::version_line().c_str(), spp,
                    renderer.width(), renderer.height(), output.c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "minimal: %s\n", e.what());
        return 1;
    }
}
