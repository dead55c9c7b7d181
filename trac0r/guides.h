// What a denoiser or compositor wants beside the rendered image: per pixel,
// the first surface's depth, the albedo and shading normal of the first
// surface that is not a mirror or glass (kernel/guides.h), and the variance
// of the pixel's mean. The EXR writer stores them as layers.
#ifndef TRAC0R_GUIDES_H
#define TRAC0R_GUIDES_H

#include "trac0r/image_io.h"
#include "trac0r/kernel_fwd.h"

#include <glm/glm.hpp>

#include <vector>

namespace trac0r {

struct GuideImages {
    int width = 0;
    int height = 0;
    // Row-major, row 0 at the top, as Image.
    std::vector<glm::vec3> albedo;       // zero where the ray meets nothing
    std::vector<glm::vec3> normal;       // unit, in world space, facing the camera; zero: nothing
    std::vector<float> depth;            // along the camera's forward axis; +inf: nothing
    std::vector<unsigned char> emitter;  // 1 where the surface is a pure emitter (a lamp)
    // xyz: the mean radiance over the pixel of the pure emitters its rays
    // meet first, w: the share of the pixel that meets one (a box filter,
    // as the render's samples). With lamp_edges, where the centre rays of a
    // pixel and its eight neighbours do not all agree on emitter or not (a
    // lamp's edge runs near) and the rays through its four corners or
    // T0_GUIDE_PROBE_RAYS rays over it disagree with its centre's (the
    // edge crosses it): where one straight edge of one lamp crosses it,
    // from the line through the points where the edge crosses its sides
    // (kernel::straight_edge_emission); else from T0_GUIDE_EMISSION_RAYS
    // rays over the pixel (kernel::pixel_emission). Elsewhere, and
    // everywhere without lamp_edges, from the centre ray.
    std::vector<glm::vec4> emission;
    bool lamp_edges = false;  // add_lamp_edges has made emission's split
    // Of the split: the pixels by a lamp's edge that it tested; those whose
    // share it measured (the rest kept their centre's value: no edge
    // crosses them); and of those, the ones a straight edge crosses.
    int lamp_edge_pixels = 0;
    int lamp_edge_traced = 0;
    int lamp_edge_straight = 0;
};

// One ray through each pixel's centre of `camera` (as the Renderer holds it:
// in the scene's coordinates, before the packed scene's scale), on the CPU
// whatever the backend: the same kernel code, compiled as C++. Then
// add_lamp_edges: what the display filter needs.
GuideImages render_guides(const PackedScene& packed, const kernel::CameraRecord& camera);

// The centre rays alone, without the lamp-edge split: all that temporal
// reuse and the EXR layers read (depth, normal, albedo), at a fraction of
// the cost where lamps' edges cross many pixels.
GuideImages render_surface_guides(const PackedScene& packed, const kernel::CameraRecord& camera);
// The same into *into, whatever view or size it held (its lamp-edge split
// is dropped: add_lamp_edges makes it again), its storage reused: a caller
// that makes guides every frame (a moving window) then allocates, and the
// system zeroes, no memory once it has held guides of this size or larger.
// At 800 x 600 that is 22 MB, which costs about as much as the rays
// themselves. Where it cannot allocate, *into is left empty.
void render_surface_guides(const PackedScene& packed, const kernel::CameraRecord& camera,
                           GuideImages* into);

// The lamp-edge split of guides made by render_surface_guides of the same
// view (nothing when it is made already).
void add_lamp_edges(const PackedScene& packed, const kernel::CameraRecord& camera,
                    GuideImages* guides);

// Per pixel, the variance of its mean luminance: M2 / (n - 1) / n over its
// n accepted samples; +inf where n < 2 (unknown).
std::vector<float> mean_variance(const std::vector<kernel::AccumPixel>& accumulator);

// The layers of an EXR file that a denoiser or compositor reads, in
// OpenEXR's usual names: "albedo.R/G/B", "normal.X/Y/Z", "Z" (depth),
// "variance.Y" (mean_variance); each where asked for (variance needs the
// accumulator, the others the guides).
struct ExrLayerChoice {
    bool albedo = false;
    bool normal = false;
    bool depth = false;
    bool variance = false;
    bool any() const { return albedo || normal || depth || variance; }
};
std::vector<ExrChannel> exr_layers(const ExrLayerChoice& choice, const GuideImages& guides,
                                   const std::vector<kernel::AccumPixel>& accumulator);

}  // namespace trac0r

#endif
