// trac0r_mpi: trac0r_viewer's batch render split across MPI ranks
// (docs/mpi.md). Every rank loads the scene and renders the frames r, r + N,
// ...; rank 0 merges the accumulators, prints the progress and writes.
#include "headless.h"
#include "mpi_cluster.h"
#include "options.h"
#include "startup.h"

#include "trac0r/opencl_backend.h"
#include "trac0r/scene.h"
#include "trac0r/version.h"

#include <mpi.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <string>

namespace {

using trac0r_viewer::Options;
using trac0r_viewer::UsageError;

const char* const mpi_description =
    "trac0r_viewer's batch render (--headless) split across MPI ranks: rank r of N renders the "
    "frames r, r + N, r + 2N, ... of the same render, rank 0 merges the per-pixel sums, prints "
    "the progress and writes the outputs. The image is the one trac0r_viewer renders with the "
    "same seed and spp, to float rounding. --spp, --seconds and --target-error count every "
    "rank's samples; all ranks stop after the same round. --threads N sets the CPU threads a "
    "rank (or OMP_NUM_THREADS); --backend opencl gives the ranks on a node its OpenCL devices "
    "in turn (one GPU a rank), --device D all the same one. Every rank must load the same "
    "scene with the same options (checked: a digest). The window, --benchmark, --replay and "
    "--list-devices are trac0r_viewer's.";

void refuse_window_options(const Options& o) {
    if (o.benchmark_frames > 0 || !o.replay_path.empty() || o.list_devices) {
        throw UsageError(
            "--benchmark, --replay and --list-devices are trac0r_viewer's: trac0r_mpi renders "
            "in batch only");
    }
    if (o.outputs.empty()) {
        throw UsageError(
            "nothing to do; give --output FILE (.png, .pfm or .exr): rank 0 writes it");
    }
}

// The options that decide the image or the rounds: ranks that differ in
// one would render another image, or wait for each other forever. Their
// bytes, so that 1e-7 and 2e-7 differ.
std::uint64_t options_digest(const Options& o) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    const auto add = [&h](const void* data, std::size_t size) {
        const unsigned char* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) {
            h = (h ^ p[i]) * 0x100000001b3ull;
        }
    };
    add(&o.seed, sizeof o.seed);
    add(&o.spp, sizeof o.spp);
    add(&o.seconds, sizeof o.seconds);
    add(&o.target_error, sizeof o.target_error);
    add(o.integrator.data(), o.integrator.size());
    add(o.sampler.data(), o.sampler.size());
    return h;
}

// --backend opencl without --device: the ranks on one node take the
// node's devices in turn (one GPU per rank), by their rank within the node;
// -1 (the CPU's fallback, said) where there is none.
int device_for_local_rank(int local_rank) {
#ifdef TRAC0R_HAVE_OPENCL
    const int devices = static_cast<int>(trac0r::list_opencl_devices().size());
    return devices == 0 ? -1 : local_rank % devices;
#else
    (void)local_rank;
    return -1;
#endif
}

void copy_message(const std::string& from, char (&to)[2048]) {
    const std::size_t n = std::min(from.size(), sizeof to - 1);
    std::memcpy(to, from.data(), n);
    to[n] = '\0';
}

int run(int argc, char** argv) {
    trac0r_viewer::MpiCluster cluster;
    const int rank = cluster.rank();
    const int ranks = cluster.size();
    const bool first = rank == 0;
    trac0r_viewer::Startup startup(first);
    Options options;
    std::unique_ptr<trac0r::Renderer> renderer;
    // Every rank reaches the start exchange, failed or not, so that none
    // waits there for one that has gone.
    trac0r_viewer::StartReport mine;
    try {
        options = trac0r_viewer::parse_options(argc, argv);
        if (options.help || options.version) {
            mine.help = options.help ? 1 : 2;
        } else {
            options.headless = true;
            refuse_window_options(options);
            startup.prepare(options, first);  // only rank 0 writes
            if (options.backend == "opencl" && options.device < 0) {
                options.device = device_for_local_rank(cluster.local_rank());
            }
            const trac0r::Scene& scene = startup.load(options);
            renderer = startup.make_renderer(options);
            mine.digest = trac0r::scene_digest(scene) ^ options_digest(options);
        }
    } catch (...) {
        const trac0r_viewer::Failure failure = startup.failure(std::current_exception());
        mine.code = failure.code;
        copy_message(failure.message, mine.message);
    }
    const std::vector<trac0r_viewer::StartReport> all = cluster.start(mine);
    for (int r = 0; r < ranks; ++r) {
        if (all[r].code != 0) {
            // One message: the first failing rank's, or every rank's when
            // all failed alike (a bad command line given to all).
            const bool alike = std::all_of(all.begin(), all.end(), [&](const auto& s) {
                return std::strcmp(s.message, all[r].message) == 0;
            });
            if (first && alike && ranks > 1) {
                std::fprintf(stderr, "trac0r_mpi: every rank: %s\n", all[r].message);
            } else if (first) {
                std::fprintf(stderr, "trac0r_mpi: rank %d of %d: %s\n", r, ranks, all[r].message);
            }
            return all[r].code;
        }
    }
    if (std::any_of(all.begin(), all.end(), [](const auto& s) { return s.help != 0; })) {
        if (first && mine.help == 2) {
            std::printf("trac0r_mpi %s\n", trac0r::version_line().c_str());
        } else if (first) {
            std::fputs(trac0r_viewer::help_text(
                           "mpirun -n N trac0r_mpi [SCENE.json] --output FILE [options]",
                           mpi_description, "")
                           .c_str(),
                       stdout);
        }
        return 0;
    }
    for (int r = 1; r < ranks; ++r) {
        if (all[r].digest != all[0].digest) {
            if (first) {
                std::fprintf(stderr,
                             "trac0r_mpi: rank %d's scene or options differ from rank 0's "
                             "(digest %016llx, rank 0's %016llx): every rank must load the "
                             "same scene files, with the same size, depth, --seed, "
                             "--integrator, --sampler, --spp, --seconds and --target-error\n",
                             r, static_cast<unsigned long long>(all[r].digest),
                             static_cast<unsigned long long>(all[0].digest));
            }
            return 1;
        }
    }
    if (first && options.verbose) {
        std::fprintf(stderr, "trac0r_mpi: %d ranks, scene digest %016llx\n", ranks,
                     static_cast<unsigned long long>(all[0].digest));
    }
    try {
        return trac0r_viewer::run_batch(*renderer, options, cluster);
    } catch (...) {
        const trac0r_viewer::Failure failure = startup.failure(std::current_exception());
        std::fprintf(stderr, "trac0r_mpi: rank %d of %d: %s\n", rank, ranks,
                     failure.message.c_str());
        if (!cluster.merged() && ranks > 1) {
            // The others wait for this rank's next report: end them all.
            MPI_Abort(MPI_COMM_WORLD, failure.code);
        }
        return failure.code;
    }
}

}  // namespace

int main(int argc, char** argv) {
    // As trac0r_viewer: a write over a file-size limit fails with a message.
    std::signal(SIGXFSZ, SIG_IGN);
    trac0r_viewer::set_program_name("trac0r_mpi");
    if (MPI_Init(&argc, &argv) != MPI_SUCCESS) {
        std::fprintf(stderr, "trac0r_mpi: MPI_Init failed (run it with mpirun -n N)\n");
        return 1;
    }
    const int code = run(argc, argv);
    MPI_Finalize();
    return code;
}
