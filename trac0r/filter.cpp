#include "trac0r/filter.h"

#include "trac0r/backend.h"

#include "trac0r/kernel/filter.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>

// The row loop's `#pragma omp simd` is a hint: Clang (the fuzz and
// sanitizer builds) may decline it, saying so with -Wpass-failed (at the
// loop or at its function), which -Werror would make an error.
#if defined(__clang__)
#pragma clang diagnostic ignored "-Wpass-failed"
#endif

namespace trac0r {

namespace {

// Pixels row to row + n - 1 of `plane`: value(k) for the k-th. One plane
// at a time, one stream of stores (FilterWorkspace::set_guides).
template <class Value>
void set_plane_row(std::vector<float>* plane, std::size_t row, int n, Value value) {
    float* const out = plane->data() + row;
    for (int k = 0; k < n; ++k) {
        out[k] = value(k);
    }
}

// The CPU's passes keep their per-pixel values in planes, one float a
// pixel each, which the compiler loads for neighbouring pixels at once: the
// guides as the passes read them (kernel::FilterTap), and a pass's image
// and its noise (kernel::FilterPixel, kernel::FilterNoise).
// `centre` is the centre tap's weight where the pixel's values are finite
// (centre_weight): of the guides alone.
// span_begin and span_end: per row, from its first pixel that is not kept
// as it is to one past its last (begin == end: all kept).
struct TapPlanes {
    void resize(std::size_t n, int rows) {
        for (std::vector<float>* v :
             {&nx, &ny, &nz, &nw, &depth, &by_depth, &share, &kept, &centre}) {
            v->resize(n);
        }
        span_begin.resize(static_cast<std::size_t>(rows));
        span_end.resize(static_cast<std::size_t>(rows));
    }
    // Pixels row to row + n - 1 from their taps and centre weights, plane
    // by plane.
    void set_row(std::size_t row, const kernel::FilterTap* t, const float* centres, int n) {
        set_plane_row(&nx, row, n, [t](int k) { return t[k].normal.x; });
        set_plane_row(&ny, row, n, [t](int k) { return t[k].normal.y; });
        set_plane_row(&nz, row, n, [t](int k) { return t[k].normal.z; });
        set_plane_row(&nw, row, n, [t](int k) { return t[k].normal.w; });
        set_plane_row(&depth, row, n, [t](int k) { return t[k].params.x; });
        set_plane_row(&by_depth, row, n, [t](int k) { return t[k].params.y; });
        set_plane_row(&share, row, n, [t](int k) { return t[k].params.z; });
        set_plane_row(&kept, row, n, [t](int k) { return t[k].params.w; });
        set_plane_row(&centre, row, n, [centres](int k) { return centres[k]; });
    }
    // Row y's span, from its pixels' `kept`, once they are set.
    void set_span(int y, int width) {
        const float* const row = kept.data() + static_cast<std::size_t>(y) * width;
        int begin = 0;
        int end = width;
        while (begin < end && row[begin] > 0.0f) {
            ++begin;
        }
        while (end > begin && row[end - 1] > 0.0f) {
            --end;
        }
        span_begin[y] = begin;
        span_end[y] = end;
    }
    std::vector<float> nx, ny, nz, nw, depth, by_depth, share, kept, centre;
    std::vector<int> span_begin, span_end;
};

// A pixel's weight as its own centre tap (kernel::tap_weight with the tap
// the pixel itself), where its values are finite. Then the tap's distance
// is zero whatever they are: its depths and luminances are the same. So
// it is of the guides alone, the same every pass.
float centre_weight(const kernel::FilterTap& t) {
    return kernel::tap_weight(t.normal.x, t.normal.y, t.normal.z, t.normal.w, t.params.x, 0.0f,
                              1.0f, 1.0f, t.normal.x, t.normal.y, t.normal.z, t.normal.w,
                              t.params.x, t.params.z, 0.0f, 1.0f, 0.0f,
                              kernel::wavelet_weight(0, 0), kernel::tap_reach(0, 0));
}

// What the first pass's input and the filtered pixel take of the guides
// (kernel::FilterScale), one plane per component.
struct ScalePlanes {
    void resize(std::size_t n) {
        for (std::vector<float>* v : {&dr, &dg, &db, &dl, &lr, &lg, &lb}) {
            v->resize(n);
        }
    }
    // Pixels row to row + n - 1, plane by plane.
    void set_row(std::size_t row, const kernel::FilterScale* s, int n) {
        set_plane_row(&dr, row, n, [s](int k) { return s[k].divisor.x; });
        set_plane_row(&dg, row, n, [s](int k) { return s[k].divisor.y; });
        set_plane_row(&db, row, n, [s](int k) { return s[k].divisor.z; });
        set_plane_row(&dl, row, n, [s](int k) { return s[k].luminance_divisor; });
        set_plane_row(&lr, row, n, [s](int k) { return s[k].lamp.x; });
        set_plane_row(&lg, row, n, [s](int k) { return s[k].lamp.y; });
        set_plane_row(&lb, row, n, [s](int k) { return s[k].lamp.z; });
    }
    std::vector<float> dr, dg, db, dl, lr, lg, lb;
};

// ScalePlanes read through their pointers, taken before a loop (so that no
// store in it may change them, and the compiler vectorizes it).
struct ScaleRows {
    explicit ScaleRows(const ScalePlanes& s)
        : dr(s.dr.data()),
          dg(s.dg.data()),
          db(s.db.data()),
          dl(s.dl.data()),
          lr(s.lr.data()),
          lg(s.lg.data()),
          lb(s.lb.data()) {}
    kernel::FilterScale at(std::size_t i) const {
        kernel::FilterScale s;
        s.divisor = glm::vec3(dr[i], dg[i], db[i]);
        s.luminance_divisor = dl[i];
        s.lamp = glm::vec3(lr[i], lg[i], lb[i]);
        return s;
    }
    const float* dr;
    const float* dg;
    const float* db;
    const float* dl;
    const float* lr;
    const float* lg;
    const float* lb;
};

struct PixelPlanes {
    void resize(std::size_t n) {
        for (std::vector<float>* v : {&r, &g, &b, &variance, &l, &by_noise}) {
            v->resize(n);
        }
    }
    std::vector<float> r, g, b, variance, l, by_noise;
};

// Where a pixel's taps are: per row of taps (above, on, below) the offset
// of that row from the pixel's and whether it is inside the image (1) or
// not (0, weight zero); likewise per column.
struct TapPlaces {
    std::ptrdiff_t row[3];
    float row_inside[3];
    std::ptrdiff_t column[3];
    float column_inside[3];
};

// Pixel i of a pass, as kernel::atrous_pixel makes it, written as scalar
// code with no branches, so that the compiler vectorizes a loop of it over
// a row: the same tap_weight, atrous_keeps and sums in the same order, so
// the same result. Taps outside the image read a pixel inside and weigh
// zero.
inline void atrous_at(const TapPlanes& t, const PixelPlanes& in, std::ptrdiff_t i,
                      const TapPlaces& at, float by_depth, PixelPlanes* out) {
    const float* const r = in.r.data();
    const float* const g = in.g.data();
    const float* const b = in.b.data();
    const float* const variance = in.variance.data();
    const float* const l = in.l.data();
    const float* const by_noise = in.by_noise.data();
    const float cnx = t.nx[i], cny = t.ny[i], cnz = t.nz[i], cnw = t.nw[i];
    const float cdepth = t.depth[i];
    const float cl = l[i];
    const float cby_noise = by_noise[i];
    const float centre = t.centre[i];
    float sr = 0.0f, sg = 0.0f, sb = 0.0f, sv = 0.0f, total = 0.0f;
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
#pragma GCC unroll 3
        for (int j = 0; j < 3; ++j) {
            const std::ptrdiff_t q = i + at.row[k] + at.column[j];
            const float p_sum = r[q] + g[q] + b[q] + variance[q];
            // The centre's weight is of the guides alone (centre_weight).
            float w = kernel::is_finite_f(p_sum) ? centre : 0.0f;
            if (k != 1 || j != 1) {
                w = at.row_inside[k] * at.column_inside[j] *
                    kernel::tap_weight(cnx, cny, cnz, cnw, cdepth, cl, cby_noise, by_depth, t.nx[q],
                                       t.ny[q], t.nz[q], t.nw[q], t.depth[q], t.share[q], l[q],
                                       by_noise[q], p_sum, kernel::wavelet_weight(j - 1, k - 1),
                                       kernel::tap_reach(j - 1, k - 1));
            }
            const bool use = w > 0.0f;
            sr += use ? r[q] * w : 0.0f;
            sg += use ? g[q] * w : 0.0f;
            sb += use ? b[q] * w : 0.0f;
            sv += use ? w * w * variance[q] : 0.0f;
            total += use ? w : 0.0f;
        }
    }
    const bool keep = kernel::atrous_keeps(t.kept[i], total);
    const float nr = keep ? r[i] : sr / total;
    const float ng = keep ? g[i] : sg / total;
    const float nb = keep ? b[i] : sb / total;
    const float nv = keep ? variance[i] : sv / (total * total);
    out->r[i] = nr;
    out->g[i] = ng;
    out->b[i] = nb;
    out->variance[i] = nv;
    out->l[i] = kernel::luminance_rgb(nr, ng, nb);
    out->by_noise[i] = kernel::by_noise_of(nv);
}

// x86-64: the row's loop compiled for AVX-512, AVX2 and the baseline,
// chosen at run time (GCC's and Clang's function multiversioning); other
// targets compile it once.
#if defined(__x86_64__)
#define T0_ROW_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define T0_ROW_CLONES
#endif

// Before a loop whose iterations are independent (no store in it changes
// what another reads), which the compiler could not prove: GCC's ivdep,
// Clang's assume_safety.
#if defined(__clang__)
#define T0_INDEPENDENT _Pragma("clang loop vectorize(assume_safety)")
#else
#define T0_INDEPENDENT _Pragma("GCC ivdep")
#endif

// Row y's pixels outside its span (TapPlanes), which every pass keeps as
// they are: copied from `from` to `to` once, after the input, so that
// both planes the passes take turns with hold them and no pass copies
// them again (on cornell_diffuse.json 62 % of the view sees nothing).
void copy_kept_ends(const TapPlanes& t, const PixelPlanes& from, int y, int width,
                    PixelPlanes* to) {
    const std::ptrdiff_t start = static_cast<std::ptrdiff_t>(y) * width;
    const int begin = t.span_begin[y];
    const int end = t.span_end[y];
    for (std::vector<float> PixelPlanes::*plane :
         {&PixelPlanes::r, &PixelPlanes::g, &PixelPlanes::b, &PixelPlanes::variance,
          &PixelPlanes::l, &PixelPlanes::by_noise}) {
        const float* in = (from.*plane).data() + start;
        float* out = ((*to).*plane).data() + start;
        std::copy(in, in + begin, out);
        std::copy(in + end, in + width, out + end);
    }
}

// Row y of pass `pass`: its pixels from the first to the last one that is
// not kept as it is (TapPlanes' span; those outside it are in `out`
// already, copy_kept_ends), the inner ones (all their taps in the image's
// columns) in a vectorized loop, AVX2 where the CPU has it, the few at its
// ends one by one (the same atrous_at: the same result).
T0_ROW_CLONES void atrous_row(const TapPlanes& t, const PixelPlanes& in, int width, int height,
                              int y, int pass, PixelPlanes* out) {
    const std::ptrdiff_t start = static_cast<std::ptrdiff_t>(y) * width;
    const int begin = t.span_begin[y];
    const int end = t.span_end[y];
    if (begin >= end) {
        return;
    }
    const int step = 1 << pass;
    TapPlaces at;
    for (int k = 0; k < 3; ++k) {
        const int qy = y + (k - 1) * step;
        at.row_inside[k] = qy >= 0 && qy < height ? 1.0f : 0.0f;
        at.row[k] = static_cast<std::ptrdiff_t>(qy >= 0 && qy < height ? qy - y : 0) * width;
        at.column[k] = (k - 1) * step;
        at.column_inside[k] = 1.0f;
    }
    // The inner pixels of the span, [lo, hi); those before and after it
    // one by one.
    const int lo = std::max(begin, std::min(step, width));
    const int hi = std::max(lo, std::min(end, width - step));
    const float* const by_depth = t.by_depth.data();
    const float steps = static_cast<float>(step);
#pragma omp simd
    for (int x = lo; x < hi; ++x) {
        atrous_at(t, in, start + x, at, by_depth[start + x] / steps, out);
    }
    const auto one_by_one = [&](int x) {
        TapPlaces edge = at;
        for (int j = 0; j < 3; ++j) {
            const int qx = x + (j - 1) * step;
            edge.column_inside[j] = qx >= 0 && qx < width ? 1.0f : 0.0f;
            edge.column[j] = qx >= 0 && qx < width ? (j - 1) * step : 0;
        }
        atrous_at(t, in, start + x, edge, by_depth[start + x] / steps, out);
    };
    for (int x = begin; x < std::min(lo, end); ++x) {
        one_by_one(x);
    }
    for (int x = hi; x < end; ++x) {
        one_by_one(x);
    }
}

// The first pass's input for the `count` pixels from `start`
// (kernel::filter_input_scaled and filter_noise). In chunks: the
// accumulator's fields that it reads are first copied into arrays, so that
// the arithmetic (ten divisions a pixel) runs in a loop the compiler
// vectorizes (a 48-byte AccumPixel is no access group it can load as
// vectors).
T0_ROW_CLONES void input_row(const kernel::AccumPixel* accumulator, const ScalePlanes& scale,
                             std::size_t start, int count, PixelPlanes* out) {
    const ScaleRows sc(scale);
    float* const r = out->r.data();
    float* const g = out->g.data();
    float* const b = out->b.data();
    float* const variance = out->variance.data();
    float* const l = out->l.data();
    float* const by_noise = out->by_noise.data();
    constexpr int chunk = 256;
    float sum[3][chunk], compensation[3][chunk], squares[chunk], samples[chunk];
    for (int x0 = 0; x0 < count; x0 += chunk) {
        const int n = std::min(chunk, count - x0);
        const kernel::AccumPixel* const px = accumulator + start + x0;
        for (int k = 0; k < n; ++k) {
            for (int c = 0; c < 3; ++c) {
                sum[c][k] = px[k].sum[c];
                compensation[c][k] = px[k].compensation[c];
            }
            squares[k] = px[k].moments.y;
            samples[k] = px[k].moments.z;
        }
        const std::size_t first = start + static_cast<std::size_t>(x0);
        T0_INDEPENDENT
        for (int k = 0; k < n; ++k) {
            const std::size_t i = first + static_cast<std::size_t>(k);
            kernel::AccumPixel a;
            a.sum = glm::vec4(sum[0][k], sum[1][k], sum[2][k], 0.0f);
            a.compensation =
                glm::vec4(compensation[0][k], compensation[1][k], compensation[2][k], 0.0f);
            a.moments = glm::vec4(0.0f, squares[k], samples[k], 0.0f);
            const kernel::FilterPixel p = kernel::filter_input_scaled(a, sc.at(i));
            const kernel::FilterNoise noise = kernel::filter_noise(p);
            r[i] = p.value.x;
            g[i] = p.value.y;
            b[i] = p.value.z;
            variance[i] = p.value.w;
            l[i] = noise.value.x;
            by_noise[i] = noise.value.y;
        }
    }
}

// The filtered pixels of the `count` from `start`
// (kernel::filter_output_scaled).
T0_ROW_CLONES void output_row(const PixelPlanes& in, const ScalePlanes& scale, std::size_t start,
                              int count, glm::vec3* out) {
    const ScaleRows sc(scale);
    const float* const r = in.r.data();
    const float* const g = in.g.data();
    const float* const b = in.b.data();
    T0_INDEPENDENT
    for (int x = 0; x < count; ++x) {
        const std::size_t i = start + static_cast<std::size_t>(x);
        kernel::FilterPixel p;
        p.value = glm::vec4(r[i], g[i], b[i], 0.0f);
        out[i] = kernel::filter_output_scaled(p, sc.at(i));
    }
}

}  // namespace

std::vector<kernel::FilterGuide> filter_guides(const GuideImages& guides) {
    std::vector<kernel::FilterGuide> out;
    filter_guides(guides, &out);
    return out;
}

void filter_guides(const GuideImages& guides, std::vector<kernel::FilterGuide>* into) {
    if (!guides.lamp_edges) {
        throw std::invalid_argument(
            "filter_guides: the guides have no lamp-edge split (add_lamp_edges, or render_guides)");
    }
    const int width = guides.width;
    const int height = guides.height;
    const std::size_t pixels = static_cast<std::size_t>(std::max(width, 0)) *
                               static_cast<std::size_t>(std::max(height, 0));
    if (width < 0 || height < 0 || guides.albedo.size() != pixels ||
        guides.normal.size() != pixels || guides.depth.size() != pixels ||
        guides.emitter.size() != pixels ||
        (!guides.emission.empty() && guides.emission.size() != pixels)) {
        throw std::invalid_argument("filter_guides: the guides' images are not all " +
                                    std::to_string(width) + " x " + std::to_string(height));
    }
    std::vector<kernel::FilterGuide>& out = *into;
    out.resize(pixels);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < out.size(); ++i) {
        const int x = static_cast<int>(i % static_cast<std::size_t>(width));
        const int y = static_cast<int>(i / static_cast<std::size_t>(width));
        const glm::vec4 e = guides.emission.empty() ? glm::vec4(0.0f) : guides.emission[i];
        // The surface the pixel shows: its centre's, or where the centre
        // is on a lamp whose edge runs through the pixel, the surface
        // beside the lamp, which goes on under the edge: a 4-neighbour's
        // that is no lamp.
        std::size_t s = i;
        if (guides.emitter[i] != 0 && e.w < 1.0f) {
            const int nx[4] = {x - 1, x + 1, x, x};
            const int ny[4] = {y, y, y - 1, y + 1};
            for (int k = 0; k < 4 && s == i; ++k) {
                const std::size_t q = static_cast<std::size_t>(ny[k]) * width + nx[k];
                if (nx[k] >= 0 && nx[k] < width && ny[k] >= 0 && ny[k] < height &&
                    guides.emitter[q] == 0 && std::isfinite(guides.depth[q])) {
                    s = q;
                }
            }
        }
        // A pixel (almost) all lamp is kept as it is; where an edge runs
        // through it, the lamps' part is set apart from the surface's.
        const bool kept = guides.emitter[s] != 0 || e.w > 0.95f;
        const float depth = guides.depth[s];
        out[i].albedo = glm::vec4(guides.albedo[s], std::isfinite(depth) ? depth : T0_NO_HIT);
        out[i].normal = glm::vec4(guides.normal[s], kept ? 1.0f : 0.0f);
        out[i].emission = kept ? glm::vec4(0.0f) : e;
    }
}

struct FilterWorkspace::Buffers {
    int width = 0;
    int height = 0;
    bool has_guides = false;
    std::vector<kernel::FilterGuide> guides;  // set_guides(GuideImages)'s
    // set_guides' scratch: a row for each thread.
    std::vector<kernel::FilterTap> row_taps;
    std::vector<float> row_centres;
    std::vector<kernel::FilterScale> row_scales;
    TapPlanes taps;
    ScalePlanes scale;
    PixelPlanes a;
    PixelPlanes b;
};

FilterWorkspace::FilterWorkspace() : buffers_(new Buffers()) {}
FilterWorkspace::~FilterWorkspace() = default;

void FilterWorkspace::set_guides(const std::vector<kernel::FilterGuide>& guides, int width,
                                 int height) {
    const std::size_t pixels = static_cast<std::size_t>(std::max(width, 0)) *
                               static_cast<std::size_t>(std::max(height, 0));
    if (width < 0 || height < 0 || guides.size() != pixels) {
        throw std::invalid_argument(
            "FilterWorkspace::set_guides: " + std::to_string(guides.size()) +
            " guides for an image of " + std::to_string(width) + " x " + std::to_string(height));
    }
    Buffers& b = *buffers_;
    b.has_guides = false;
    b.taps.resize(pixels, height);
    b.scale.resize(pixels);
    // A row's taps and scales made first, into a row of scratch for each
    // thread (made here: nothing in the parallel region may throw), then
    // written plane by plane, one stream of stores at a time: at 320 x 240
    // to 800 x 600 that took half the time of storing each pixel into the
    // sixteen planes at once (at 160 x 120, 1.4 times as long).
    const std::size_t row_length = static_cast<std::size_t>(std::max(width, 0));
    const std::size_t threads = static_cast<std::size_t>(omp_get_max_threads());
    b.row_taps.resize(threads * row_length);
    b.row_centres.resize(threads * row_length);
    b.row_scales.resize(threads * row_length);
#pragma omp parallel num_threads(static_cast <int>(threads))
    {
        const std::size_t own = static_cast<std::size_t>(omp_get_thread_num()) * row_length;
        kernel::FilterTap* const taps = b.row_taps.data() + own;
        float* const centres = b.row_centres.data() + own;
        kernel::FilterScale* const scales = b.row_scales.data() + own;
#pragma omp for schedule(dynamic, 16)
        for (int y = 0; y < height; ++y) {
            const std::size_t row = static_cast<std::size_t>(y) * width;
            for (int x = 0; x < width; ++x) {
                taps[x] = kernel::filter_tap(guides.data(), width, height, x, y);
                centres[x] = centre_weight(taps[x]);
                scales[x] = kernel::filter_scale(guides[row + x]);
            }
            b.taps.set_row(row, taps, centres, width);
            b.scale.set_row(row, scales, width);
            b.taps.set_span(y, width);
        }
    }
    b.width = width;
    b.height = height;
    b.has_guides = true;
}

void FilterWorkspace::set_guides(const GuideImages& guides) {
    filter_guides(guides, &buffers_->guides);
    set_guides(buffers_->guides, guides.width, guides.height);
}

Image filter_image(const std::vector<kernel::AccumPixel>& accumulator, int width, int height,
                   const std::vector<kernel::FilterGuide>& guides, int passes) {
    FilterWorkspace workspace;
    return filter_image(accumulator, width, height, guides, passes, workspace);
}

Image filter_image(const std::vector<kernel::AccumPixel>& accumulator, int width, int height,
                   const std::vector<kernel::FilterGuide>& guides, int passes,
                   FilterWorkspace& workspace) {
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (accumulator.size() != pixels || guides.size() != pixels) {
        throw std::invalid_argument("filter_image: the accumulator and the guides must have " +
                                    std::to_string(pixels) + " pixels");
    }
    workspace.set_guides(guides, width, height);
    return filter_image(accumulator, passes, workspace);
}

Image filter_image(const std::vector<kernel::AccumPixel>& accumulator, int passes,
                   FilterWorkspace& workspace) {
    FilterWorkspace::Buffers& buffers = workspace.buffers();
    const int width = buffers.width;
    const int height = buffers.height;
    const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (!buffers.has_guides) {
        throw std::invalid_argument("filter_image: the workspace has no guides (set_guides)");
    }
    if (accumulator.size() != pixels) {
        throw std::invalid_argument("filter_image: the accumulator has " +
                                    std::to_string(accumulator.size()) +
                                    " pixels, the workspace's guides " + std::to_string(pixels));
    }
    PixelPlanes& a = buffers.a;
    PixelPlanes& b = buffers.b;
    const TapPlanes& taps = buffers.taps;
    const ScalePlanes& scale = buffers.scale;
    a.resize(pixels);
    b.resize(pixels);
#pragma omp parallel for schedule(static)
    for (int y = 0; y < height; ++y) {
        input_row(accumulator.data(), scale, static_cast<std::size_t>(y) * width, width, &a);
        // Its ends, which no pass changes, into the other plane too.
        copy_kept_ends(taps, a, y, width, &b);
    }
    for (int pass = 0; pass < passes; ++pass) {
#pragma omp parallel for schedule(dynamic, 16)
        for (int y = 0; y < height; ++y) {
            atrous_row(taps, a, width, height, y, pass, &b);
        }
        std::swap(a, b);
    }
    Image out;
    out.width = width;
    out.height = height;
    out.pixels.resize(pixels);
#pragma omp parallel for schedule(static)
    for (int y = 0; y < height; ++y) {
        output_row(a, scale, static_cast<std::size_t>(y) * width, width, out.pixels.data());
    }
    return out;
}

Image Backend::filter_accumulation(const std::vector<kernel::AccumPixel>& accumulator, int width,
                                   int height, const std::vector<kernel::FilterGuide>& guides,
                                   int passes) {
    return filter_image(accumulator, width, height, guides, passes);
}

}  // namespace trac0r
