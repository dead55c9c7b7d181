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

const char* const usage = R"(Usage: tonemap IN.pfm OUT.png [EXPOSURE]

Tone-maps the linear RGB image IN.pfm to the 8-bit sRGB image OUT.png, as
trac0r_viewer --output does for a .png: each channel times EXPOSURE, clamped
to [0, 1], then the sRGB curve.

  IN.pfm      a linear PFM image (e.g. trac0r_viewer --output x.pfm)
  OUT.png     the PNG to write (a name ending in .png; not IN.pfm itself)
  EXPOSURE    a number in [1e-06, 1e+06] (default 1)
  -h, --help  this text
)";

const double min_exposure = 1e-6;
const double max_exposure = 1e6;

int run(int argc, char** argv) {
    std::vector<std::string> args;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (trac0r_bench::is_help(a)) {
            std::fputs(usage, stdout);
            return 0;
        }
        if (a.size() > 2 && a.compare(0, 2, "--") == 0) {
            throw UsageError(a + ": unknown option (see --help)");
        }
        args.push_back(a);
    }
    if (args.size() < 2 || args.size() > 3) {
        throw UsageError("expected IN.pfm OUT.png [EXPOSURE], got " + std::to_string(args.size()) +
                         " argument" + (args.size() == 1 ? "" : "s") + " (see --help)");
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
