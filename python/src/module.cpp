// module.cpp — the Python module caustica._caustica (docs/PYTHON.md): scenes, the render session
// and its images as numpy arrays. It turns keyword arguments into render/'s RenderRequest and
// calls render/ (Renderer, and runRender, the command line's loop); no render logic lives here.
// The GIL is released while a step renders; Ctrl-C is seen between steps (PyErr_CheckSignals)
// and raises KeyboardInterrupt there, after the current pass.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <tbb/global_control.h>

#include <atomic>
#include <memory>

#include "py_arrays.h"
#include "py_images.h"
#include "py_options.h"
#include "caustica/io/scene_loader.h"
#include "caustica/parallel/device.h"
#include "caustica/render/render_run.h"
#include "caustica/render/renderer.h"
#include "caustica/render/stereo_outputs.h"
#include "caustica/util/error.h"
#ifdef CAUSTICA_WITH_CUDA
#include "cuda/cuda_backend.h"
#endif

namespace caustica::py {
namespace {

namespace pyb = pybind11;
using namespace pybind11::literals;

void warn(const std::string& message) {
    if (PyErr_WarnEx(PyExc_RuntimeWarning, message.c_str(), 1) != 0) throw pyb::error_already_set();
}

/// A loaded scene; every render copies it, so one scene serves many renders.
struct PyScene {
    std::shared_ptr<const Scene> scene;
    std::map<std::string, std::string> defines;
};

PyScene loadPyScene(const std::string& path, const pyb::kwargs& defines) {
    PyScene s;
    for (const auto& [key, value] : defines) {
        const std::string name = pyb::str(key).cast<std::string>();
        s.defines[name] = valueText(value, name);
    }
    std::vector<std::string> warnings;
    {
        pyb::gil_scoped_release release;
        s.scene = std::make_shared<const Scene>(loadScene(path, s.defines, &warnings));
    }
    for (const std::string& w : warnings) warn(w);
    return s;
}

pyb::dict progressDict(const RenderProgress& p) {
    return pyb::dict("spp"_a = p.samplesPerPixel, "target"_a = p.target, "seconds"_a = p.seconds,
                     "time_limit"_a = p.timeLimit);
}

/// Raises the pending KeyboardInterrupt (or other signal exception) with the GIL held.
void checkSignals() {
    if (PyErr_CheckSignals() != 0) throw pyb::error_already_set();
}

class PyRenderer {
public:
    PyRenderer(const PyScene& scene, const RenderKeywords& keywords, pyb::object progress)
        : request_(renderRequest(keywords, scene.defines)), progress_(std::move(progress)) {
        if (const std::optional<int> n = threadCount(keywords.threads))
            threads_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(*n));
        {
            pyb::gil_scoped_release release;
            renderer_ = std::make_unique<Renderer>(Scene(*scene.scene), request_);
        }
        for (const std::string& w : renderer_->warnings()) warn(w);
    }

    bool finished() const { return renderer_->finished(); }
    bool stereo() const { return renderer_->scene().film.eyeWidth > 0; }

    void step() {
        {
            pyb::gil_scoped_release release;
            renderer_->step();
        }
        checkSignals();
    }

    /// Renders to the budget with the command line's loop; returns whether the progress callback
    /// stopped it early (by returning False).
    bool run(pyb::object progress) {
        if (progress.is_none()) progress = progress_;
        std::atomic<bool> stop{false};
        RunControl control;
        control.quiet = true;
        control.catchInterrupts = false;  // Python's SIGINT handler stays: KeyboardInterrupt
        control.checkpointEvery = 0;
        control.cancel = &stop;
        control.stereo.enabled = stereo();
        control.onStep = [&](const RenderProgress& p) {
            pyb::gil_scoped_acquire acquire;
            checkSignals();
            if (!progress.is_none()) {
                const pyb::object answer = progress(progressDict(p));
                if (pyb::isinstance<pyb::bool_>(answer) && !answer.cast<bool>()) stop = true;
            }
        };
        RunResult result;
        {
            pyb::gil_scoped_release release;
            result = runRender(*renderer_, control);
        }
        return result.cancelled;
    }

    /// (H, W, 3); a stereo render: (left, right).
    pyb::object develop() const {
        if (!renderer_->session().hasImage()) throw Error("develop: the render has no image yet (step() first)");
        Image image;
        {
            pyb::gil_scoped_release release;
            image = renderer_->develop();
        }
        if (!stereo()) return imageArray(image);
        return pyb::make_tuple(imageArray(stereoEyeImage(image, 0)), imageArray(stereoEyeImage(image, 1)));
    }

    pyb::dict aovs() const {
        if (!renderer_->hasAovs()) return pyb::dict();
        AovImage aovs;
        {
            pyb::gil_scoped_release release;
            aovs = renderer_->developAovs();
        }
        return aovArrays(aovs);
    }

    pyb::dict progress() const { return progressDict(renderer_->progress()); }

    pyb::dict stats() const {
        const RenderStats s = renderer_->stats();
        pyb::dict d("seconds"_a = s.seconds, "run_seconds"_a = renderer_->runSeconds(), "spp"_a = s.samplesPerPixel,
                    "samples"_a = s.samples, "rays"_a = s.rays, "invalid_samples"_a = s.invalidSamples,
                    "integrator"_a = renderer_->integrator(), "seed"_a = renderer_->seed(),
                    "device"_a = deviceName(renderer_->device().kind), "accel"_a = renderer_->accelName(),
                    "accel_description"_a = renderer_->accelDescription(),
                    "accel_build_seconds"_a = renderer_->accelBuildSeconds());
        // The integrator's own figures, as the statistics JSON has them (values are JSON text).
        const pyb::object loads = pyb::module_::import("json").attr("loads");
        for (const auto& [key, json] : renderer_->session().statsJson()) d[pyb::str(key)] = loads(json);
        return d;
    }

    void save(const std::string& path) const {
        pyb::gil_scoped_release release;
        renderer_->save(path);
    }
    void load(const std::string& path) {
        pyb::gil_scoped_release release;
        renderer_->load(path);
    }

    const Renderer& renderer() const { return *renderer_; }

private:
    RenderRequest request_;  // outlives the renderer, which was made from it
    std::unique_ptr<tbb::global_control> threads_;
    std::unique_ptr<Renderer> renderer_;
    pyb::object progress_;
};

}  // namespace
}  // namespace caustica::py

PYBIND11_MODULE(_caustica, m) {
    namespace pyb = pybind11;
    using namespace caustica;
    using namespace caustica::py;
#ifdef CAUSTICA_WITH_CUDA
    registerCudaBackend();  // installs the GPU backend's function table; touches no GPU
#endif
    m.doc() = "caustica's render session (docs/PYTHON.md); use the package caustica, not this module";
    pyb::register_exception<Error>(m, "Error", PyExc_RuntimeError);

    pyb::class_<PyScene>(m, "Scene", "A loaded scene (caustica.load_scene); each render copies it.")
        .def_property_readonly("path", [](const PyScene& s) { return s.scene->sourceFile; })
        .def_property_readonly("resolution", [](const PyScene& s) { return pyb::make_tuple(s.scene->film.width, s.scene->film.height); })
        .def_property_readonly("integrator", [](const PyScene& s) { return s.scene->integrator.type; })
        .def_property_readonly("spp", [](const PyScene& s) { return s.scene->sampleCount; })
        .def_property_readonly("seed", [](const PyScene& s) { return s.scene->seed; })
        .def_property_readonly("defines", [](const PyScene& s) { return s.defines; })
        .def("__repr__", [](const PyScene& s) {
            return "<caustica.Scene " + s.scene->sourceFile + " " + std::to_string(s.scene->film.width) + "x" +
                   std::to_string(s.scene->film.height) + ", integrator " + s.scene->integrator.type + ">";
        });

    bindImages(m);

    m.def("load_scene", &loadPyScene, pyb::arg("path"),
          "Loads a Mitsuba 3 XML scene; keyword arguments set its <default> values (the CLI's -D name=value).");

    pyb::class_<PyRenderer>(m, "Renderer")
        .def(pyb::init([](const PyScene& scene, pyb::object integrator, pyb::object spp, pyb::object time,
                          pyb::object device, pyb::object seed, pyb::object resolution, pyb::object aovs,
                          pyb::object stereo, pyb::object progress, pyb::object threads, pyb::object sppPerPass,
                          pyb::kwargs params) {
                 RenderKeywords k{integrator, spp, time, device, seed, resolution, aovs, stereo, threads, sppPerPass,
                                  pyb::dict(params)};
                 return std::make_unique<PyRenderer>(scene, k, progress);
             }),
             pyb::arg("scene"), pyb::kw_only(), pyb::arg("integrator") = pyb::none(), pyb::arg("spp") = pyb::none(),
             pyb::arg("time") = pyb::none(), pyb::arg("device") = "auto", pyb::arg("seed") = pyb::none(),
             pyb::arg("resolution") = pyb::none(), pyb::arg("aovs") = pyb::none(), pyb::arg("stereo") = pyb::none(),
             pyb::arg("progress") = pyb::none(), pyb::arg("threads") = pyb::none(),
             pyb::arg("spp_per_pass") = pyb::none())
        .def_property_readonly("finished", &PyRenderer::finished)
        .def_property_readonly("stereo", &PyRenderer::stereo)
        .def_property_readonly("has_aovs", [](const PyRenderer& r) { return r.renderer().hasAovs(); })
        .def_property_readonly("integrator", [](const PyRenderer& r) { return r.renderer().integrator(); })
        .def_property_readonly("seed", [](const PyRenderer& r) { return r.renderer().seed(); })
        .def_property_readonly("device", [](const PyRenderer& r) { return deviceName(r.renderer().device().kind); })
        .def_property_readonly("description", [](const PyRenderer& r) { return r.renderer().description(); })
        .def("step", &PyRenderer::step, "Renders one pass / iteration (the GIL is released meanwhile).")
        .def("run", &PyRenderer::run, pyb::arg("progress") = pyb::none(),
             "Renders until the budget is spent; returns True when the progress callback stopped it.")
        .def("develop", &PyRenderer::develop)
        .def("aovs", &PyRenderer::aovs)
        .def("progress", &PyRenderer::progress)
        .def("stats", &PyRenderer::stats)
        .def("save", &PyRenderer::save, pyb::arg("path"))
        .def("load", &PyRenderer::load, pyb::arg("path"));
}
