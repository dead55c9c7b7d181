// Tone-maps a linear PFM to PNG exactly as trac0r_viewer --output does.
//
//   build/benchmarks/tonemap IN.pfm OUT.png [EXPOSURE]
#include "cli.h"

#include "trac0r/input_checks.h"
#include "trac0r/image_io.h"

#include <cstdio>
#include <string>
#include <vector>

namespace {

using trac0r_bench::UsageError;

const char* const description =
    "Tone-maps the linear RGB image IN.pfm to the 8-bit sRGB image OUT.png, as trac0r_viewer "
    "--output does for a .png: each channel times EXPOSURE, clamped to [0, 1], then the sRGB "
    "curve.";

const double min_exposure = 1e-6;
const double max_exposure = 1e6;

int run(int argc, char** argv) {
    std::string in_arg;
    std::string out_arg;
    std::string exposure_arg;
    std::size_t extras = 0;
    trac0r_cli::CommandLine cl("tonemap", "tonemap IN.pfm OUT.png [EXPOSURE]", description, 14);
    cl.positional("IN.pfm", &in_arg, "a linear PFM image (e.g. trac0r_viewer --output x.pfm)");
    cl.positional("OUT.png", &out_arg,
                  "the PNG to write (a name ending in .png; not IN.pfm itself)");
    cl.positional("EXPOSURE", &exposure_arg, "a number in [1e-06, 1e+06] (default 1)");
    cl.on_extra([&extras](const std::string&) { ++extras; });
    if (!cl.parse_or_print(argc, argv)) {
        return 0;
    }
    // The positionals fill in order: those given, then any extras.
    std::vector<std::string> args = {in_arg, out_arg, exposure_arg};
    while (!args.empty() && cl.app().count(args.size() == 3   ? "EXPOSURE"
                                           : args.size() == 2 ? "OUT.png"
                                                              : "IN.pfm") == 0) {
        args.pop_back();
    }
    const std::size_t given = args.size() + extras;
    if (given < 2 || given > 3) {
        throw UsageError("expected IN.pfm OUT.png [EXPOSURE], got " + std::to_string(given) +
                         " argument" + (given == 1 ? "" : "s") + " (see --help)");
    }
    const std::string& in = args[0];
    const std::string& out = args[1];
    if (trac0r::same_file(in, out)) {
        throw UsageError("OUT.png '" + out + "' is the input file: it would be overwritten");
    }
    if (!trac0r::is_png_path(out)) {
        throw UsageError("OUT.png '" + out + "': expected a file name ending in .png");
    }
    const std::string reason = trac0r::unwritable_reason(out);
    if (!reason.empty()) {
        throw UsageError("OUT.png '" + out + "': cannot be written (" + reason + ")");
    }
    const float exposure = args.size() == 3 ? static_cast<float>(trac0r_bench::parse_number(
                                                  "EXPOSURE", args[2], min_exposure, max_exposure))
                                            : 1.0f;
    trac0r::write_png(out, trac0r::read_pfm(in), exposure);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return trac0r_bench::run_main("tonemap", [&] { return run(argc, argv); });
}
