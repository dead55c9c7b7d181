#include "trac0r/accumulator_merge.h"

namespace trac0r {

void merge_accumulators(const std::vector<const kernel::AccumPixel*>& parts, std::size_t pixels,
                        kernel::AccumPixel* out) {
    for (std::size_t i = 0; i < pixels; ++i) {
        double sum[3] = {0.0, 0.0, 0.0};
        double mean = 0.0;
        double m2 = 0.0;
        double n = 0.0;
        double dropped = 0.0;
        for (const kernel::AccumPixel* part : parts) {
            const kernel::AccumPixel& p = part[i];
            // A part's sum is sum - compensation (accumulated_mean's).
            sum[0] += static_cast<double>(p.sum.x) - static_cast<double>(p.compensation.x);
            sum[1] += static_cast<double>(p.sum.y) - static_cast<double>(p.compensation.y);
            sum[2] += static_cast<double>(p.sum.z) - static_cast<double>(p.compensation.z);
            dropped += p.moments.w;
            const double nb = p.moments.z;
            if (nb > 0.0) {
                const double total = n + nb;
                const double delta = static_cast<double>(p.moments.x) - mean;
                mean += delta * nb / total;
                m2 += static_cast<double>(p.moments.y) + delta * delta * n * nb / total;
                n = total;
            }
        }
        kernel::AccumPixel& o = out[i];
        const float rounded[3] = {static_cast<float>(sum[0]), static_cast<float>(sum[1]),
                                  static_cast<float>(sum[2])};
        o.sum = kernel::make_float4(rounded[0], rounded[1], rounded[2], 0.0f);
        // What the rounding added, as Kahan's compensation holds it.
        o.compensation = kernel::make_float4(static_cast<float>(rounded[0] - sum[0]),
                                             static_cast<float>(rounded[1] - sum[1]),
                                             static_cast<float>(rounded[2] - sum[2]), 0.0f);
        o.moments = kernel::make_float4(static_cast<float>(mean), static_cast<float>(m2),
                                        static_cast<float>(n), static_cast<float>(dropped));
    }
}

}  // namespace trac0r
