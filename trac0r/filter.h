// The edge-preserving filter (kernel/filter.h) over an accumulated image,
// on the CPU: what `--filter` shows and writes. The accumulator is read,
// never changed.
#ifndef TRAC0R_FILTER_H
#define TRAC0R_FILTER_H

#include "trac0r/guides.h"
#include "trac0r/image_io.h"
#include "trac0r/kernel/filter.h"

#include <memory>
#include <vector>

namespace trac0r {

// The filter's guides for the kernel: the camera ray's first non-specular
// surface's albedo, depth and normal (render_guides), as FilterGuide.
// Throws std::invalid_argument for guides without their lamp-edge split
// (render_surface_guides without add_lamp_edges).
std::vector<kernel::FilterGuide> filter_guides(const GuideImages& guides);
// The same into *into, whose storage it reuses. Both throw
// std::invalid_argument as said, and for images of another size than the
// guides' width and height.
void filter_guides(const GuideImages& guides, std::vector<kernel::FilterGuide>* into);

// The CPU filter's working buffers (some 110 bytes a pixel; 160 given
// GuideImages), kept between the filter_image calls that are given it,
// and what it makes of the guides, which stay while the view does: a
// caller that filters every frame (a window) then allocates, and the
// system zeroes, no memory a call, and reads the guides once a view.
class FilterWorkspace {
  public:
    FilterWorkspace();
    ~FilterWorkspace();
    FilterWorkspace(const FilterWorkspace&) = delete;
    FilterWorkspace& operator=(const FilterWorkspace&) = delete;
    // The guides of a width x height image, for the filter_image calls
    // that take none. Throws std::invalid_argument for guides of another
    // size.
    void set_guides(const std::vector<kernel::FilterGuide>& guides, int width, int height);
    // The same for guides with their lamp-edge split (filter_guides, made
    // in a buffer the workspace keeps: a view's guides make no new pages).
    // Throws std::invalid_argument as filter_guides does. After it throws
    // std::invalid_argument (either form), the workspace keeps the guides
    // it had.
    void set_guides(const GuideImages& guides);
    struct Buffers;
    Buffers& buffers() { return *buffers_; }

  private:
    std::unique_ptr<Buffers> buffers_;
};

// The accumulated image filtered: `passes` a-trous passes (0: the image
// as it is; default T0_FILTER_PASSES) with the guides, in the buffers of
// `workspace`, whose guides they replace (the second form: new ones).
// Throws std::invalid_argument for guides of another size than the
// accumulator.
Image filter_image(const std::vector<kernel::AccumPixel>& accumulator, int width, int height,
                   const std::vector<kernel::FilterGuide>& guides, int passes,
                   FilterWorkspace& workspace);
Image filter_image(const std::vector<kernel::AccumPixel>& accumulator, int width, int height,
                   const std::vector<kernel::FilterGuide>& guides, int passes);

// The same with the guides the workspace was last given (set_guides), the
// same image as the forms above with them. Throws std::invalid_argument
// for a workspace without guides or an accumulator of another size.
Image filter_image(const std::vector<kernel::AccumPixel>& accumulator, int passes,
                   FilterWorkspace& workspace);

#ifdef TRAC0R_HAVE_OPENCL
// filter_image on OpenCL device `device_index` (list_opencl_devices): the
// same kernel code, run by the embedded program. Throws OpenClError.
Image opencl_filter_image(int device_index, const std::vector<kernel::AccumPixel>& accumulator,
                          int width, int height, const std::vector<kernel::FilterGuide>& guides,
                          int passes);
#endif

}  // namespace trac0r

#endif
