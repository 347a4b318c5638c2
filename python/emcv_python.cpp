// SPDX-License-Identifier: MIT
// The Python module `emcv`: the per-frame adaptive-sampling API of include/emcv/adaptive_sampling.hpp over numpy
// arrays, for replaying captured (f, G) frames and choosing eta, the quality target or the budget in a notebook
// (docs/python.md). Every computation is the C++ library's (plan_frame, sampling_update, budget_solve, the
// port's history states); this file only checks the arrays, holds the histories and releases the GIL around
// the per-pixel loops.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <algorithm>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <emcv/adaptive_sampling.hpp>
#include <emcv/version.hpp>

namespace py = pybind11;

namespace {

using emcv::port::EmcvEmcm2;
using emcv::port::EmcvMovingStats;

// ---- names ----

/// The library's name with '-' as '_': Python spells the estimators as identifiers ("cv_notex").
std::string estimator_name(emcv::sampling_estimator e) {
    std::string name = emcv::sampling_estimator_name(e);
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

emcv::sampling_estimator parse_estimator(const std::string& name) {
    if (const auto e = emcv::parse_sampling_estimator(name)) return *e;
    std::string accepted;
    for (std::size_t i = 0; i < emcv::sampling_estimators.size(); ++i)
        accepted += (i == 0 ? "'" : i + 1 == emcv::sampling_estimators.size() ? " or '" : ", '") +
                    estimator_name(emcv::sampling_estimators[i]) + "'";
    throw py::value_error("emcv: estimator must be " + accepted + ", got '" + name + "'");
}

const char* mode_name(emcv::sampling_mode m) {
    return m == emcv::sampling_mode::budget ? "budget" : "quality_target";
}

emcv::sampling_mode parse_mode(const std::string& name) {
    if (name == "quality_target" || name == "quality") return emcv::sampling_mode::quality_target;
    if (name == "budget") return emcv::sampling_mode::budget;
    throw py::value_error("emcv: mode must be 'quality_target' or 'budget', got '" + name + "'");
}

// ---- SamplingParams: emcv::sampling_params, checked on construction and on every change ----

class sampling_params_py {
public:
    sampling_params_py(const std::string& estimator, const std::string& mode, float target, float budget, int n_min,
                       int n_max, std::optional<float> eta) {
        p_.estimator = parse_estimator(estimator);
        p_.mode = parse_mode(mode);
        p_.target = target;
        p_.budget = budget;
        p_.n_min = n_min;
        p_.n_max = n_max;
        p_.eta = eta;
        emcv::check_sampling_params(p_);
    }

    const emcv::sampling_params& get() const noexcept { return p_; }

    /// Changes one field through a copy: a refused value leaves the parameters as they were.
    template <class Change>
    void change(Change&& c) {
        emcv::sampling_params next = p_;
        c(next);
        emcv::check_sampling_params(next);
        p_ = next;
    }

    std::string repr() const {
        std::ostringstream s;
        s << "SamplingParams(estimator='" << estimator_name(p_.estimator) << "', mode='" << mode_name(p_.mode)
          << "', target=" << p_.target << ", budget=" << p_.budget << ", n_min=" << p_.n_min
          << ", n_max=" << p_.n_max << ", eta=";
        if (p_.eta) s << *p_.eta;
        else s << "None";
        s << ")";
        return s.str();
    }

private:
    emcv::sampling_params p_;
};

// ---- History: the per-pixel states of one estimator over a width x height image ----

class history_py {
public:
    history_py(std::size_t width, std::size_t height, emcv::sampling_estimator estimator)
        : width_(width), height_(height), estimator_(estimator) {
        if (width == 0 || height == 0)
            throw py::value_error("emcv.History: width and height must be >= 1, got " + std::to_string(width) + "x" +
                                  std::to_string(height));
        if (estimator == emcv::sampling_estimator::cv) states_ = std::vector<EmcvEmcm2>(pixels(), emcv::port::emcv_emcm2_init());
        else states_ = std::vector<EmcvMovingStats>(pixels(), emcv::port::emcv_moving_stats_init());
    }

    std::size_t width() const noexcept { return width_; }
    std::size_t height() const noexcept { return height_; }
    std::size_t pixels() const noexcept { return width_ * height_; }
    emcv::sampling_estimator estimator() const noexcept { return estimator_; }

    template <class Visit>
    decltype(auto) visit(Visit&& v) {
        return std::visit(std::forward<Visit>(v), states_);
    }

    void* data() {
        return std::visit([](auto& s) { return static_cast<void*>(s.data()); }, states_);
    }

    /// Resets every pixel (mask None) or those where mask is true: the reprojection step of the recipe.
    void reset(const bool* mask) {
        std::visit(
            [&](auto& states) {
                const auto empty = empty_state(states);
                for (std::size_t i = 0; i < states.size(); ++i)
                    if (mask == nullptr || mask[i]) states[i] = empty;
            },
            states_);
    }

    history_py copy() const { return *this; }

    /// The budget's frame statistics carried from one plan_frame to the next (emcv::budget_prior).
    emcv::budget_prior& prior() noexcept { return prior_; }

private:
    static EmcvEmcm2 empty_state(const std::vector<EmcvEmcm2>&) { return emcv::port::emcv_emcm2_init(); }
    static EmcvMovingStats empty_state(const std::vector<EmcvMovingStats>&) { return emcv::port::emcv_moving_stats_init(); }

    std::size_t width_, height_;
    emcv::sampling_estimator estimator_;
    std::variant<std::vector<EmcvEmcm2>, std::vector<EmcvMovingStats>> states_;
    emcv::budget_prior prior_;  // plan_frame's, under a budget: last frame's statistics
};

// The structured dtypes of the history views: the port's structs, field by field (their layout is checked here,
// so a view can never misread a state).
static_assert(sizeof(EmcvEmcm2) == 32 && offsetof(EmcvEmcm2, mean) == 0 && offsetof(EmcvEmcm2, cov) == 8 &&
                  offsetof(EmcvEmcm2, count) == 20 && offsetof(EmcvEmcm2, rejected) == 24 &&
                  offsetof(EmcvEmcm2, reseeded) == 28,
              "EmcvEmcm2 is (vec2 mean, vec3 cov, uint count, rejected, reseeded), packed");
static_assert(sizeof(EmcvMovingStats) == 20 && offsetof(EmcvMovingStats, mean) == 0 &&
                  offsetof(EmcvMovingStats, variance) == 4 && offsetof(EmcvMovingStats, count) == 8 &&
                  offsetof(EmcvMovingStats, rejected) == 12 && offsetof(EmcvMovingStats, reseeded) == 16,
              "EmcvMovingStats is (float mean, variance, uint count, rejected, reseeded), packed");

py::dtype state_dtype(emcv::sampling_estimator e) {
    py::module_ np = py::module_::import("numpy");
    py::list fields;
    if (e == emcv::sampling_estimator::cv) {
        fields.append(py::make_tuple("mean", "<f4", py::make_tuple(2)));
        fields.append(py::make_tuple("cov", "<f4", py::make_tuple(3)));
    } else {
        fields.append(py::make_tuple("mean", "<f4"));
        fields.append(py::make_tuple("variance", "<f4"));
    }
    fields.append(py::make_tuple("count", "<u4"));
    fields.append(py::make_tuple("rejected", "<u4"));
    fields.append(py::make_tuple("reseeded", "<u4"));
    return py::dtype::from_args(np.attr("dtype")(fields));
}

// ---- array checks: a clear ValueError naming the function, the argument and what was expected ----

std::string shape_text(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

/// The argument must be a numpy array of dtype T, shape (height, width), C-contiguous; returns its data.
template <class T>
const T* checked(const py::handle& object, const char* where, const char* name, const char* dtype_name,
                 std::size_t height, std::size_t width) {
    const std::string expected = std::string(where) + ": " + name + " must be a C-contiguous numpy array of dtype " +
                                 dtype_name + " and shape (" + std::to_string(height) + ", " +
                                 std::to_string(width) + ") (height, width)";
    if (!py::isinstance<py::array>(object))
        throw py::value_error(expected + ", got " + std::string(py::str(py::type::of(object).attr("__name__"))));
    const auto a = py::reinterpret_borrow<py::array>(object);
    const std::string got = ", got dtype " + std::string(py::str(a.dtype())) + " and shape " + shape_text(a);
    if (!a.dtype().is(py::dtype::of<T>()) && !a.dtype().equal(py::dtype::of<T>())) throw py::value_error(expected + got);
    if (a.ndim() != 2 || static_cast<std::size_t>(a.shape(0)) != height || static_cast<std::size_t>(a.shape(1)) != width)
        throw py::value_error(expected + got);
    if (!(a.flags() & py::array::c_style))
        throw py::value_error(expected + got + " (not C-contiguous: pass numpy.ascontiguousarray(" + name + "))");
    return static_cast<const T*>(a.data());
}

/// sub_pixel: uint8 or bool (both one byte, non-zero marks a sub-pixel kernel).
const std::uint8_t* checked_flags(const py::handle& object, const char* where, const char* name, std::size_t height,
                                  std::size_t width) {
    if (py::isinstance<py::array>(object) && py::reinterpret_borrow<py::array>(object).dtype().kind() == 'b')
        return reinterpret_cast<const std::uint8_t*>(checked<bool>(object, where, name, "uint8 or bool", height, width));
    return checked<std::uint8_t>(object, where, name, "uint8 or bool", height, width);
}

void check_estimator(const sampling_params_py& p, const history_py& h, const char* where) {
    if (p.get().estimator != h.estimator())
        throw py::value_error(std::string(where) + ": the history holds " + estimator_name(h.estimator()) +
                              " states but params.estimator is " + estimator_name(p.get().estimator) +
                              " (make the History with the params' estimator)");
}

// ---- the per-frame API ----

py::object plan_frame_py(const sampling_params_py& params, history_py& history, const py::object& material,
                         const py::object& sub_pixel, std::uint32_t frame, std::uint32_t seed) {
    constexpr const char* where = "emcv.plan_frame";
    check_estimator(params, history, where);
    const std::size_t w = history.width(), h = history.height();
    const std::uint32_t* material_data =
        material.is_none() ? nullptr : checked<std::uint32_t>(material, where, "material", "uint32", h, w);
    const std::uint8_t* sub_pixel_data = sub_pixel.is_none() ? nullptr : checked_flags(sub_pixel, where, "sub_pixel", h, w);
    py::array_t<int> counts({h, w});
    py::array_t<float> sigma2({h, w});
    int* counts_data = counts.mutable_data();
    float* sigma2_data = sigma2.mutable_data();
    emcv::frame_plan plan;
    {
        py::gil_scoped_release unlocked;
        plan = history.visit([&](auto& states) {
            return emcv::plan_frame(params.get(), states.data(), history.pixels(), w, material_data, sub_pixel_data,
                                    frame, seed, sigma2_data, counts_data, history.prior());
        });
    }
    py::object frame_plan = py::module_::import("emcv").attr("FramePlan");
    return frame_plan(counts, sigma2, plan.lambda, plan.samples);
}

void sampling_update_py(const sampling_params_py& params, history_py& history, const py::object& f,
                        const py::object& g, const py::object& counts, const py::object& material) {
    constexpr const char* where = "emcv.sampling_update";
    check_estimator(params, history, where);
    const std::size_t w = history.width(), h = history.height();
    const float* f_data = checked<float>(f, where, "f", "float32", h, w);
    const float* g_data = nullptr;
    if (!g.is_none()) g_data = checked<float>(g, where, "g", "float32", h, w);
    else if (params.get().estimator != emcv::sampling_estimator::spvg)
        throw py::value_error(std::string(where) + ": g must be given for cv and cv_notex (None only for spvg)");
    const int* counts_data = checked<int>(counts, where, "counts", "int32", h, w);
    const std::uint32_t* material_data =
        material.is_none() ? nullptr : checked<std::uint32_t>(material, where, "material", "uint32", h, w);
    py::gil_scoped_release unlocked;
    history.visit([&](auto& states) {
        emcv::sampling_update(params.get(), states.data(), history.pixels(), w, material_data, f_data, g_data,
                              counts_data);
    });
}

float budget_solve_py(const sampling_params_py& params, const py::object& sigma2, const py::object& material) {
    constexpr const char* where = "emcv.budget_solve";
    if (!py::isinstance<py::array>(sigma2) || py::reinterpret_borrow<py::array>(sigma2).ndim() != 2)
        throw py::value_error(std::string(where) +
                              ": sigma2 must be a C-contiguous numpy array of dtype float32 and shape (height, width)");
    const auto a = py::reinterpret_borrow<py::array>(sigma2);
    const std::size_t h = static_cast<std::size_t>(a.shape(0)), w = static_cast<std::size_t>(a.shape(1));
    const float* sigma2_data = checked<float>(sigma2, where, "sigma2", "float32", h, w);
    const std::uint32_t* material_data =
        material.is_none() ? nullptr : checked<std::uint32_t>(material, where, "material", "uint32", h, w);
    py::gil_scoped_release unlocked;
    emcv::budget_histogram histogram = emcv::make_budget_histogram();
    emcv::budget_add(histogram, sigma2_data, h * w, material_data);
    return emcv::budget_solve(params.get(), histogram);
}

}  // namespace

PYBIND11_MODULE(emcv, m) {
    m.doc() = "emcv's per-frame adaptive-sampling policy (include/emcv/adaptive_sampling.hpp) over numpy arrays: "
              "docs/python.md";
    m.attr("__version__") = std::to_string(EMCV_VERSION_MAJOR) + "." + std::to_string(EMCV_VERSION_MINOR) + "." +
                            std::to_string(EMCV_VERSION_PATCH);
    m.attr("NO_VARIANCE") = emcv::port::emcv_history_no_variance();
    m.attr("NO_SAMPLES") = emcv::port::emcv_history_no_samples();
    m.attr("TILE_SIZE") = emcv::sampling_tile_size;
    py::module_ collections = py::module_::import("collections");
    m.attr("FramePlan") = collections.attr("namedtuple")("FramePlan", py::make_tuple("counts", "sigma2", "lambda_", "samples"));
    m.attr("FramePlan").attr("__doc__") =
        "What plan_frame decided: counts (int32, height x width: the samples each pixel takes), sigma2 (float32: the "
        "pooled per-sample variance each count came from, or NO_VARIANCE / NO_SAMPLES), lambda_ (budget mode's "
        "solved scale, 0 under a quality target) and samples (the sum of the counts).";

    m.def("default_eta", [](const std::string& estimator) { return emcv::sampling_default_eta(parse_estimator(estimator)); },
          py::arg("estimator"), "The history weight the renderer uses for an estimator (sampling_default_eta).");

    py::class_<sampling_params_py>(m, "SamplingParams",
                                   "emcv::sampling_params: every field is checked on construction and on assignment "
                                   "(ValueError naming the broken requirement; a refused value changes nothing).")
        .def(py::init<const std::string&, const std::string&, float, float, int, int, std::optional<float>>(),
             py::arg("estimator") = "spvg", py::arg("mode") = "quality_target", py::arg("target") = EMCV_HISTORY_TARGET,
             py::arg("budget") = 8.0f, py::arg("n_min") = EMCV_HISTORY_N_MIN, py::arg("n_max") = EMCV_HISTORY_N_MAX,
             py::arg("eta") = py::none())
        .def_property(
            "estimator", [](const sampling_params_py& p) { return estimator_name(p.get().estimator); },
            [](sampling_params_py& p, const std::string& v) {
                p.change([&](emcv::sampling_params& q) { q.estimator = parse_estimator(v); });
            })
        .def_property(
            "mode", [](const sampling_params_py& p) { return mode_name(p.get().mode); },
            [](sampling_params_py& p, const std::string& v) {
                p.change([&](emcv::sampling_params& q) { q.mode = parse_mode(v); });
            })
        .def_property(
            "target", [](const sampling_params_py& p) { return p.get().target; },
            [](sampling_params_py& p, float v) { p.change([&](emcv::sampling_params& q) { q.target = v; }); })
        .def_property(
            "budget", [](const sampling_params_py& p) { return p.get().budget; },
            [](sampling_params_py& p, float v) { p.change([&](emcv::sampling_params& q) { q.budget = v; }); })
        .def_property(
            "n_min", [](const sampling_params_py& p) { return p.get().n_min; },
            [](sampling_params_py& p, int v) { p.change([&](emcv::sampling_params& q) { q.n_min = v; }); })
        .def_property(
            "n_max", [](const sampling_params_py& p) { return p.get().n_max; },
            [](sampling_params_py& p, int v) { p.change([&](emcv::sampling_params& q) { q.n_max = v; }); })
        .def_property(
            "eta", [](const sampling_params_py& p) { return p.get().eta; },
            [](sampling_params_py& p, std::optional<float> v) { p.change([&](emcv::sampling_params& q) { q.eta = v; }); })
        .def_property_readonly(
            "effective_eta", [](const sampling_params_py& p) { return emcv::sampling_eta(p.get()); },
            "eta, or the estimator's default_eta when eta is None")
        .def("__repr__", &sampling_params_py::repr);

    py::class_<history_py>(m, "History",
                           "The per-pixel history states of one estimator over a width x height image (port::EmcvEmcm2 "
                           "for cv, port::EmcvMovingStats for spvg and cv_notex), all empty at first.")
        .def(py::init([](std::size_t width, std::size_t height, const std::string& estimator) {
                 return history_py(width, height, parse_estimator(estimator));
             }),
             py::arg("width"), py::arg("height"), py::arg("estimator"))
        .def_property_readonly("width", &history_py::width)
        .def_property_readonly("height", &history_py::height)
        .def_property_readonly("estimator", [](const history_py& h) { return estimator_name(h.estimator()); })
        .def_property_readonly(
            "state",
            [](py::object self) {
                history_py& h = self.cast<history_py&>();
                return py::array(state_dtype(h.estimator()),
                                 {static_cast<py::ssize_t>(h.height()), static_cast<py::ssize_t>(h.width())}, {},
                                 h.data(), self);
            },
            "A writable (height, width) structured numpy view of the states (no copy; it keeps the History "
            "alive): cv (mean[2], cov[3] = (C_ff, C_fG, C_GG), count, rejected, reseeded), spvg and cv_notex "
            "(mean, variance, count, rejected, reseeded)")
        .def(
            "reset",
            [](history_py& h, const py::object& mask) {
                const bool* data = nullptr;
                if (!mask.is_none()) data = checked<bool>(mask, "emcv.History.reset", "mask", "bool", h.height(), h.width());
                h.reset(data);
            },
            py::arg("mask") = py::none(),
            "Empties every state (mask None) or those where mask is True: where reprojection failed")
        .def("copy", &history_py::copy, "An independent copy of the states");

    m.def("plan_frame", &plan_frame_py, py::arg("params"), py::arg("history"), py::arg("material") = py::none(),
          py::arg("sub_pixel") = py::none(), py::arg("frame") = 0u, py::arg("seed") = 0u,
          "emcv::plan_frame: each pixel's pooled per-sample variance and count for this frame, from the history "
          "before this frame's push. material: uint32 (height, width), 0 where a pixel does not scatter (None: "
          "all scatter, one material); sub_pixel: uint8 or bool, non-zero for sub-pixel kernels (None: none); "
          "frame and seed salt the budget's stochastic rounding. Under a budget each pooled variance is shrunk towards "
          "the statistics of the history's previous plan_frame (kept in the History; none before its first) and "
          "this frame's replace them. Returns FramePlan(counts, sigma2, lambda_, samples).");
    m.def("sampling_update", &sampling_update_py, py::arg("params"), py::arg("history"), py::arg("f"), py::arg("g"),
          py::arg("counts"), py::arg("material") = py::none(),
          "emcv::sampling_update: pushes each pixel's output f (float32, the mean of its counts[i] samples) and "
          "control g (float32; None for spvg only) into the history as a batch of counts[i] (int32); a pixel with "
          "counts <= 0 or material 0 (uint32, as plan_frame's; None: every pixel scatters, one material) is left "
          "as it is, a non-finite value is refused (its `rejected` count grows); cv's noise test pools over each "
          "8x8 tile's scattering pixels.");
    m.def("budget_solve", &budget_solve_py, py::arg("params"), py::arg("sigma2"), py::arg("material") = py::none(),
          "emcv::budget_add + emcv::budget_solve: the budget's lambda over the scattering pixels of a (height, width) "
          "float32 sigma2 of variance codes (plan_frame's sigma2), with params.budget whatever params.mode is.");
}
