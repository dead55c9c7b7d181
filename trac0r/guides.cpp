#include "trac0r/guides.h"

#include "trac0r/kernel/bundle.h"
#include "trac0r/kernel/guides.h"
#include "trac0r/kernel/lamp_edge.h"
#include "trac0r/kernel/tile_grid.h"
#include "trac0r/packed_scene.h"

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <limits>
#include <stdexcept>
#include <utility>

namespace trac0r {

namespace {

// The first hits of camera rays rays[0, n), which all start at the
// camera's position: with `bundled` (the BVH, a pinhole or thin-lens
// camera's centre), bounded together and found among the few leaves they
// share (kernel/bundle.h), the same hits as through the tree (but where two
// triangles of different leaves are hit within rounding, as at a shared
// edge, which bundle.h explains); else each through the scene.
void first_hits(const kernel::SceneView& view, bool bundled, const glm::vec3& origin,
                const kernel::Ray* rays, int n, kernel::Hit* hits) {
    int count = -1;
    kernel::LeafCandidate leaves[T0_BUNDLE_LEAVES];
    if (bundled) {
        kernel::RayBundle bundle;
        kernel::bundle_start(&bundle, origin);
        for (int k = 0; k < n; ++k) {
            if (!rays[k].any_parallel) {
                kernel::bundle_add(&bundle, rays[k].inv_direction);
            }
        }
        count = kernel::bundle_finish_leaves(&view, &bundle, leaves);
    }
    for (int k = 0; k < n; ++k) {
        hits[k] = kernel::camera_hit(&view, &rays[k], leaves, count);
    }
}

// Whether a view's camera rays may be bundled (first_hits).
bool bundles_camera_rays(const kernel::SceneView& view, const kernel::CameraRecord& camera) {
    return T0_HAS_FEATURE(&view, T0_FEATURE_BVH) && !kernel::camera_is_orthographic(camera);
}

// Rays first to last - 1 of pixel (x, y)'s r2_point sequence, as
// kernel::pixel_emission_rays traces them, their first hits found
// together (first_hits): adds to *sum the radiance of the pure emitters
// they meet first and to *hits how many meet one.
void bundled_emission_rays(const kernel::SceneView& view, const kernel::CameraRecord& camera,
                           bool bundled, std::uint32_t x, std::uint32_t y, int first, int last,
                           glm::vec3* sum, int* hits) {
    kernel::Ray rays[T0_GUIDE_EMISSION_RAYS] = {};
    kernel::Hit found[T0_GUIDE_EMISSION_RAYS] = {};
    const int n = last - first;
    for (int k = 0; k < n; ++k) {
        rays[k] = kernel::pixel_emission_ray(camera, x, y, first + k);
    }
    first_hits(view, bundled, glm::vec3(camera.position), rays, n, found);
    for (int k = 0; k < n; ++k) {
        glm::vec3 emitted;
        const kernel::GuidePixel g =
            kernel::guide_ray_from(&view, camera, rays[k], found[k], &emitted);
        kernel::add_emission_ray(g, emitted, sum, hits);
    }
}

}  // namespace

GuideImages render_guides(const PackedScene& packed, const kernel::CameraRecord& camera) {
    GuideImages g = render_surface_guides(packed, camera);
    add_lamp_edges(packed, camera, &g);
    return g;
}

GuideImages render_surface_guides(const PackedScene& packed, const kernel::CameraRecord& camera) {
    GuideImages g;
    render_surface_guides(packed, camera, &g);
    return g;
}

void render_surface_guides(const PackedScene& packed, const kernel::CameraRecord& camera,
                           GuideImages* into) {
    GuideImages& g = *into;
    const std::size_t pixels = static_cast<std::size_t>(camera.size.x) * camera.size.y;
    try {
        g.albedo.resize(pixels);
        g.normal.resize(pixels);
        g.depth.resize(pixels);
        g.emitter.resize(pixels);
        g.emission.resize(pixels);
    } catch (...) {
        g = GuideImages();  // empty, not another view's images of this size
        throw;
    }
    g.width = static_cast<int>(camera.size.x);
    g.height = static_cast<int>(camera.size.y);
    g.lamp_edges = false;
    g.lamp_edge_pixels = 0;
    g.lamp_edge_traced = 0;
    g.lamp_edge_straight = 0;
    const kernel::SceneView view = packed.view();
    const kernel::CameraRecord scaled = scaled_camera(camera, packed.scale);
    const int height = g.height;
    const int width = g.width;
    // By tiles, as the frame's camera rays: a tile's centre rays find
    // their first hits together (first_hits).
    const bool bundled = bundles_camera_rays(view, scaled);
    const std::uint32_t w = static_cast<std::uint32_t>(width);
    const std::uint32_t h = static_cast<std::uint32_t>(height);
    const int tiles = static_cast<int>(kernel::tile_count(w, h));
#pragma omp parallel for schedule(dynamic, 4)
    for (int tile = 0; tile < tiles; ++tile) {
        const kernel::TileRect r = kernel::tile_rect(static_cast<std::uint32_t>(tile), w, h);
        kernel::Ray rays[T0_TILE * T0_TILE];
        kernel::Hit found[T0_TILE * T0_TILE];
        int n = 0;
        for (std::uint32_t y = r.y0; y < r.y1; ++y) {
            for (std::uint32_t x = r.x0; x < r.x1; ++x, ++n) {
                rays[n] = kernel::camera_ray(scaled, static_cast<float>(x), static_cast<float>(y),
                                             0.5f, 0.5f);
            }
        }
        first_hits(view, bundled, glm::vec3(scaled.position), rays, n, found);
        n = 0;
        for (std::uint32_t y = r.y0; y < r.y1; ++y) {
            for (std::uint32_t x = r.x0; x < r.x1; ++x, ++n) {
                glm::vec3 emitted;
                const kernel::GuidePixel p =
                    kernel::guide_ray_from(&view, scaled, rays[n], found[n], &emitted);
                const std::size_t i = static_cast<std::size_t>(y) * width + x;
                g.emission[i] = glm::vec4(emitted, p.normal.w > 0.0f ? 1.0f : 0.0f);
                g.albedo[i] = glm::vec3(p.albedo);
                g.normal[i] = glm::vec3(p.normal);
                g.emitter[i] = p.normal.w > 0.0f ? 1 : 0;
                g.depth[i] = p.albedo.w >= T0_NO_HIT ? std::numeric_limits<float>::infinity()
                                                     : p.albedo.w / packed.scale;
            }
        }
    }
}

void add_lamp_edges(const PackedScene& packed, const kernel::CameraRecord& camera,
                    GuideImages* guides) {
    GuideImages& g = *guides;
    if (g.lamp_edges) {
        return;
    }
    if (g.width != static_cast<int>(camera.size.x) || g.height != static_cast<int>(camera.size.y)) {
        throw std::invalid_argument("add_lamp_edges: the guides are not of this camera's size");
    }
    const int height = g.height;
    const int width = g.width;
    const kernel::SceneView view = packed.view();
    const kernel::CameraRecord scaled = scaled_camera(camera, packed.scale);
    const bool bundled = bundles_camera_rays(view, scaled);
    // Along a lamp's edge, the share of each pixel that sees it: where the
    // centre rays of the pixel and its eight neighbours disagree (emitter
    // or not), a lamp's edge may run through the pixel. Those pixels are
    // listed, so that the work on them is shared evenly between the threads
    // (they lie on a few rows): each thread lists those of its rows. (The
    // order does not matter: each pixel's share is made alone.) Where a
    // list cannot grow, the failure is rethrown after the parallel region,
    // out of which nothing may throw.
    const int threads = omp_get_max_threads();
    std::vector<std::vector<int>> listed_by_thread(static_cast<std::size_t>(threads));
    std::vector<std::vector<unsigned char>> columns(static_cast<std::size_t>(threads),
                                                    std::vector<unsigned char>(width));
    std::exception_ptr failure;
#pragma omp parallel num_threads(threads)
    {
        const std::size_t own = static_cast<std::size_t>(omp_get_thread_num());
        std::vector<int> mine;
        bool failed = false;
        // Per row: the emitters in each column of the rows around it, then
        // over the columns around each pixel.
        unsigned char* const column = columns[own].data();
#pragma omp for schedule(static)
        for (int y = 0; y < height; ++y) {
            if (failed) {
                continue;
            }
            const int y0 = std::max(y - 1, 0);
            const int y1 = std::min(y + 1, height - 1);
            std::fill(column, column + width, static_cast<unsigned char>(0));
            for (int qy = y0; qy <= y1; ++qy) {
                const unsigned char* row = &g.emitter[static_cast<std::size_t>(qy) * width];
                for (int x = 0; x < width; ++x) {
                    column[x] = static_cast<unsigned char>(column[x] + row[x]);
                }
            }
            const int rows = y1 - y0 + 1;
            try {
                for (int x = 0; x < width; ++x) {
                    const int x0 = std::max(x - 1, 0);
                    const int x1 = std::min(x + 1, width - 1);
                    const int emitters = column[x0] + (x1 > x0 ? column[x0 + 1] : 0) +
                                         (x1 > x0 + 1 ? column[x1] : 0);
                    if (emitters > 0 && emitters < rows * (x1 - x0 + 1)) {
                        mine.push_back(y * width + x);
                    }
                }
            } catch (...) {
                failed = true;
#pragma omp critical(t0_lamp_edge_failure)
                failure = std::current_exception();
            }
        }
        listed_by_thread[own] = std::move(mine);
    }
    if (failure) {
        std::rethrow_exception(failure);
    }
    std::size_t listed_total = 0;
    for (const std::vector<int>& some : listed_by_thread) {
        listed_total += some.size();
    }
    std::vector<int> listed;
    listed.reserve(listed_total);
    for (std::vector<int>& some : listed_by_thread) {
        listed.insert(listed.end(), some.begin(), some.end());
        std::vector<int>().swap(some);
    }
    // Their corners, each once, in order: corner (x, y) is the top left one
    // of pixel (x, y); a pixel finds its corners' rays by binary search.
    const int corner_columns = width + 1;
    std::vector<int> corners;
    corners.reserve(4 * listed.size());
    for (const int i : listed) {
        const int c = i / width * corner_columns + i % width;
        for (const int k : {c, c + 1, c + corner_columns, c + corner_columns + 1}) {
            corners.push_back(k);
        }
    }
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    std::vector<unsigned char> corner_emitter(corners.size());
    const auto corner_slot = [&](int c) {
        return static_cast<std::size_t>(std::lower_bound(corners.begin(), corners.end(), c) -
                                        corners.begin());
    };
    // Most of those pixels it does not cross: a straight edge that crosses
    // a pixel leaves one of its corners on each side (a half-plane that
    // meets a square holds one of its corners), so where the four corners'
    // rays agree with the centre's, so do T0_GUIDE_PROBE_RAYS rays over the
    // pixel (for a lamp's corner poking in, or a thin lamp), the pixel is
    // taken as its centre ray sees it. Of the others, where one straight
    // edge crosses the pixel its share is the area beside the edge's line
    // (kernel::straight_edge_emission: about 40 rays, to about 5e-4 of the
    // pixel); the rest get the full count.
    const int corner_count = static_cast<int>(corners.size());
#pragma omp parallel for schedule(dynamic, 16)
    for (int k = 0; k < corner_count; ++k) {
        const int c = corners[static_cast<std::size_t>(k)];
        glm::vec3 emitted;
        const kernel::GuidePixel p =
            kernel::guide_ray(&view, scaled, static_cast<std::uint32_t>(c % corner_columns),
                              static_cast<std::uint32_t>(c / corner_columns), 0.0f, 0.0f, &emitted);
        corner_emitter[static_cast<std::size_t>(k)] = p.normal.w > 0.0f ? 1 : 0;
    }
    int split = 0;
    int straight = 0;
    const int listed_count = static_cast<int>(listed.size());
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : split, straight)
    for (int k = 0; k < listed_count; ++k) {
        const std::size_t i = static_cast<std::size_t>(listed[k]);
        const int x = static_cast<int>(i % static_cast<std::size_t>(width));
        const int y = static_cast<int>(i / static_cast<std::size_t>(width));
        const unsigned char centre = g.emitter[i];
        const int c = y * corner_columns + x;
        const std::uint32_t ux = static_cast<std::uint32_t>(x);
        const std::uint32_t uy = static_cast<std::uint32_t>(y);
        glm::vec3 sum(0.0f);
        int hits = 0;
        int traced = 0;
        // The corners in pixel_corner's order, round the pixel; the one
        // right of a listed corner is the next listed one.
        const std::size_t top = corner_slot(c);
        const std::size_t bottom = corner_slot(c + corner_columns);
        const int round = corner_emitter[top] | corner_emitter[top + 1] << 1 |
                          corner_emitter[bottom + 1] << 2 | corner_emitter[bottom] << 3;
        if (round == (centre ? 15 : 0)) {
            // The probes: the first rays of the full count, kept for it.
            bundled_emission_rays(view, scaled, bundled, ux, uy, 0, T0_GUIDE_PROBE_RAYS, &sum,
                                  &hits);
            traced = T0_GUIDE_PROBE_RAYS;
            if (hits == (centre ? T0_GUIDE_PROBE_RAYS : 0)) {
                continue;  // no edge crosses it: its centre's value stands
            }
        } else {
            glm::vec4 e;
            if (kernel::straight_edge_emission(&view, scaled, ux, uy, round, centre, &e)) {
                g.emission[i] = e;  // one straight edge crosses it
                ++split;
                ++straight;
                continue;
            }
        }
        bundled_emission_rays(view, scaled, bundled, ux, uy, traced, T0_GUIDE_EMISSION_RAYS, &sum,
                              &hits);
        g.emission[i] = kernel::pixel_emission_of(sum, hits, T0_GUIDE_EMISSION_RAYS);
        ++split;
    }
    g.lamp_edge_pixels = listed_count;
    g.lamp_edge_traced = split;
    g.lamp_edge_straight = straight;
    g.lamp_edges = true;
}

std::vector<float> mean_variance(const std::vector<kernel::AccumPixel>& accumulator) {
    std::vector<float> v(accumulator.size());
    for (std::size_t i = 0; i < accumulator.size(); ++i) {
        const double n = accumulator[i].moments.z;
        v[i] = n < 2.0 ? std::numeric_limits<float>::infinity()
                       : static_cast<float>(accumulator[i].moments.y / (n - 1.0) / n);
    }
    return v;
}

std::vector<ExrChannel> exr_layers(const ExrLayerChoice& choice, const GuideImages& guides,
                                   const std::vector<kernel::AccumPixel>& accumulator) {
    std::vector<ExrChannel> out;
    const auto add_vec3 = [&](const std::string& layer, const char* axes,
                              const std::vector<glm::vec3>& values) {
        for (int c = 0; c < 3; ++c) {
            ExrChannel channel;
            channel.name = layer + "." + axes[c];
            channel.values.reserve(values.size());
            for (const glm::vec3& v : values) {
                channel.values.push_back(v[c]);
            }
            out.push_back(std::move(channel));
        }
    };
    if (choice.albedo) {
        add_vec3("albedo", "RGB", guides.albedo);
    }
    if (choice.normal) {
        add_vec3("normal", "XYZ", guides.normal);
    }
    if (choice.depth) {
        out.push_back({"Z", guides.depth});
    }
    if (choice.variance) {
        out.push_back({"variance.Y", mean_variance(accumulator)});
    }
    return out;
}

}  // namespace trac0r
