// The MPI ranks of MPI_COMM_WORLD as run_batch's cluster (trac0r_mpi).
// MPI_Init must have been called. Reports travel as bytes: the ranks run
// the same program on machines of the same byte order.
#ifndef TRAC0R_VIEWER_MPI_CLUSTER_H
#define TRAC0R_VIEWER_MPI_CLUSTER_H

#include "trac0r/render_cluster.h"

#include <cstdint>
#include <string>
#include <vector>

namespace trac0r_viewer {

// What a rank says once it has started (or failed to).
struct StartReport {
    std::int32_t code = 0;     // 0: ready; else the exit code of its failure
    std::int32_t help = 0;     // 1: --help, 2: --version; print it and exit 0
    std::uint64_t digest = 0;  // of the scene and the options that decide the image
    char message[2048] = {};   // its failure, cut to fit
};

class MpiCluster : public trac0r::Cluster {
  public:
    // Collective: every rank makes one first, before anything can fail.
    MpiCluster();
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    // The rank among the ranks on this node (MPI_COMM_TYPE_SHARED).
    int local_rank() const { return local_rank_; }
    std::vector<trac0r::RoundReport> exchange(const trac0r::RoundReport& mine) override;
    // In chunks of 16,384 pixels (768 KiB a rank), so that rank 0 needs
    // memory for its own image and one chunk of each rank's, not N images.
    void merge_to_first(std::vector<trac0r::kernel::AccumPixel>& accumulator) override;

    // Every rank's start report, in rank order, on every rank.
    std::vector<StartReport> start(const StartReport& mine);
    // Whether merge_to_first has run: from then on the ranks wait for no
    // one, and a failure needs no MPI_Abort to end the job.
    bool merged() const { return merged_; }

  private:
    int rank_ = 0;
    int size_ = 1;
    int local_rank_ = 0;
    bool merged_ = false;
};

}  // namespace trac0r_viewer

#endif
