// SPDX-License-Identifier: MIT
// One row per frame and method (metrics.csv / metrics.json), and writing them so that a crash leaves no
// half-written file. Column names are a contract: the evaluation and outside checks read them.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace emcv::demo::app {

struct metrics_row {
    int frame = 0;
    std::string method;
    double sss_ms = 0.0;
    double frame_ms = 0.0;
    double mean_spp = 0.0;
    int max_spp = 0;
    std::optional<double> psnr_db;         ///< +inf for the reference itself; empty: undefined
    std::optional<double> psnr_sss_db;     ///< empty when no SSS pixel is visible
    double rel_mse = 0.0;
    std::optional<double> temporal_error;  ///< empty on the first frame (no previous frame)
    /// The same three of the image the frame shows after its temporal resolve (--resolve taa; the reference
    /// shows its raw image): empty under --resolve none.
    std::optional<double> psnr_resolved_db;
    std::optional<double> psnr_sss_resolved_db;
    std::optional<double> temporal_error_resolved;
    /// Mean over the SSS pixels of (y - y_ref)^2, y the value the adaptive methods track (gamma-space luminance
    /// of albedo * scattered irradiance * exposure) and y_ref the reference's: the measure --target-variance V
    /// bounds (each SSS pixel's output variance, docs/renderer.md). Empty when the method's SSS passes did not
    /// run (diffuse) or no SSS pixel is visible.
    std::optional<double> tracked_mse;
    /// Each recorded pass's name and time in ms, in recording order (metrics.json only; sss_ms and frame_ms
    /// are sums of these).
    std::vector<std::pair<std::string, double>> passes;
};

inline constexpr std::array<const char*, 14> metrics_columns = {
    "frame", "method", "sss_ms", "frame_ms", "mean_spp", "max_spp", "psnr_db", "psnr_sss_db", "rel_mse",
    "temporal_error", "psnr_resolved_db", "psnr_sss_resolved_db", "temporal_error_resolved", "tracked_mse"};

/// Writing an output failed; what() names the file.
class output_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// CSV text: the header line, then one line per row. An undefined value is an empty field; +inf is "inf".
std::string metrics_csv(const std::vector<metrics_row>& rows);

/// JSON text: {"columns": [...], "rows": [{column: value, ..., "passes": [{"name", "ms"}, ...]}, ...]},
/// "sampling" (the adaptive methods' mode, e.g. "budget 8 spp" or "target variance 0.0001") and "timing" (the
/// clock of the times: "gpu" or "wall") when given. JSON has no infinity: +inf and undefined values are null
/// (the reference's PSNR against itself; see docs/demo.md). "resolve" ("taa", "taa+jitter" or "none") when given.
std::string metrics_json(const std::vector<metrics_row>& rows, const std::string& sampling = {},
                         const std::string& timing = {}, const std::string& resolve = {});

/// Writes `text` to `path` through a temporary sibling and a rename. Throws output_error.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace emcv::demo::app
