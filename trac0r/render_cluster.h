// The processes one batch render (batch.h) is split across: one, or the
// MPI ranks of trac0r_mpi (its mpi_cluster.h). render_batch asks it what
// the others did after every round of frames, so that every rank decides
// the same, and merges the accumulators at the end.
#ifndef TRAC0R_RENDER_CLUSTER_H
#define TRAC0R_RENDER_CLUSTER_H

#include "trac0r/kernel_fwd.h"

#include <cstdint>
#include <vector>

namespace trac0r {

// What a rank tells the others after a round of frames.
struct RoundReport {
    std::int32_t cancel = 0;      // non-zero: asked to stop (BatchOptions::cancel's code)
    std::int32_t overflowed = 0;  // its noise estimate has overflowed float
    std::int64_t frames = 0;      // frames it has rendered
    double elapsed = 0.0;         // seconds since its render started
    double estimate = 0.0;        // its noise estimate, where the round asks for one
};

class Cluster {
  public:
    virtual ~Cluster() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;
    // Every rank's report, in rank order, on every rank (a collective: each
    // rank calls it once a round).
    virtual std::vector<RoundReport> exchange(const RoundReport& mine) = 0;
    // Rank 0's `accumulator` becomes the merge of every rank's (in rank
    // order, accumulator_merge.h); the other ranks' are sent and left as
    // they were. A collective.
    virtual void merge_to_first(std::vector<kernel::AccumPixel>& accumulator) = 0;
};

// One process: the render as it always was.
class SingleProcess : public Cluster {
  public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    std::vector<RoundReport> exchange(const RoundReport& mine) override { return {mine}; }
    void merge_to_first(std::vector<kernel::AccumPixel>&) override {}
};

}  // namespace trac0r

#endif
