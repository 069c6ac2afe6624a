// nxrender.render.

#include "apps/python/py_render.h"

#include <pybind11/numpy.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

#include "apps/python/py_arguments.h"
#include "apps/python/py_arrays.h"
#include "apps/python/py_gradients.h"
#include "apps/python/py_image.h"
#include "apps/python/py_relight.h"
#include "apps/python/py_scene.h"
#include "apps/render_job.h"
#include "core/error.h"
#include "core/memory.h"
#include "integrators/scene_reader.h"

namespace nxpy {
namespace {

// A command-line option's Python parameter name: "--light-sampling" -> "light_sampling".
std::string pythonName(const std::string& option) {
  std::string name = option.rfind("--", 0) == 0 ? option.substr(2) : option;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

// The scene argument: an nxrender.Scene, a scene file's name, or scene text.
struct SceneSource {
  nx::SceneDesc desc;
  std::string name;  ///< recorded as nxrender.scene
  std::string edits; ///< Scene edits, or ""
};

SceneSource sceneArgument(const py::handle& scene) {
  SceneSource src;
  if (py::isinstance<PyScene>(scene)) {
    const SceneState& st = *scene.cast<const PyScene&>().state;
    src.desc = sceneForRendering(st);
    src.name = st.desc.file;
    src.edits = editsText(st);
    return src;
  }
  if (py::isinstance<py::str>(scene)) {
    const std::string text = scene.cast<std::string>();
    const size_t first = text.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && text[first] == '<') {
      src.name = "<string>";
      src.desc = nx::parseScene(text, src.name);
      return src;
    }
  } else if (!py::hasattr(scene, "__fspath__")) {
    throw py::type_error("scene: expected an nxrender.Scene, a scene file name or scene text "
                         "(XML), found " +
                         typeName(scene));
  }
  src.name = pathArgument(scene, "scene");
  std::error_code ec;
  if (!std::filesystem::exists(src.name, ec)) {
    PyErr_SetString(PyExc_FileNotFoundError, (src.name + ": no such scene file").c_str());
    throw py::error_already_set();
  }
  py::gil_scoped_release release;
  src.desc = nx::loadScene(src.name);
  return src;
}

std::string optionString(const py::object& value, const char* param) {
  return stringArgument(value, param);
}

// render()'s arguments, as Python gave them.
struct RenderArguments {
  py::object spp, seed, bands, sensor, sppRange, sampler, lightSampling, lightSelection, density;
  bool fluorescence;
  py::object aovs, targetError, errorOf, timeLimit;
  bool adaptive, relightable;
  py::object relightStep;
};

// Refuses a strategy name the command line would refuse, naming Python's parameter.
void checkStrategyNames(const nx::RenderChoices& choices) {
  for (const nx::StrategyOption& o : nx::strategyOptions()) {
    const std::string& value = choices.*o.field;
    std::string list;
    bool ok = false;
    for (const std::string& n : o.values) {
      ok = ok || value == n;
      list += (list.empty() ? "'" : ", '") + n + "'";
    }
    if (!ok)
      throw py::value_error(pythonName(o.option) + ": expected one of " + list + ", found '" +
                            value + "'");
  }
}

// The layers `aovs` names (a list of names) added to `choices`; TypeError or ValueError naming
// the argument for anything else.
void addAovs(nx::RenderChoices& choices, const py::object& aovs) {
  if (py::isinstance<py::str>(aovs) || !py::hasattr(aovs, "__iter__"))
    throw py::type_error("aovs: expected a list of " + nx::aovOptionList("'", ", ") + ", found " +
                         typeName(aovs));
  for (const py::handle aov : aovs) {
    const std::string name = stringArgument(aov, "aovs");
    if (!nx::addAov(choices, name))
      throw py::value_error("aovs: expected " + nx::aovOptionList("'", " or ") + ", found '" +
                            name + "'");
  }
}

// The render's choices from its arguments, each checked (before the possibly long build).
nx::RenderChoices choicesFrom(const RenderArguments& a) {
  nx::RenderChoices choices;
  if (!a.spp.is_none() && !a.sppRange.is_none())
    throw py::value_error("spp, spp_range: give one of them");
  if (!a.spp.is_none())
    choices.samples = static_cast<int>(integerArgument(a.spp, "spp", 1, 1 << 30));
  if (!a.sppRange.is_none()) {
    const auto r = integersArgument(a.sppRange, "spp_range", 2);
    if (r[0] < 0 || r[1] <= r[0] || r[1] > (1LL << 30))
      throw py::value_error("spp_range: expected (a, b) with 0 <= a < b <= 2**30, found (" +
                            std::to_string(r[0]) + ", " + std::to_string(r[1]) + ")");
    choices.firstSample = static_cast<int>(r[0]);
    choices.samples = static_cast<int>(r[1] - r[0]);
    choices.sampleRange = true;
  }
  if (!a.seed.is_none())
    choices.seed = static_cast<uint32_t>(integerArgument(a.seed, "seed", 0, 2147483647));
  if (!a.bands.is_none() && !a.sensor.is_none())
    throw py::value_error("bands, sensor: give one of them");
  if (!a.bands.is_none()) {
    if (py::isinstance<py::str>(a.bands)) {
      choices.bands = nx::Sensor(nx::SpectralBands::parse(a.bands.cast<std::string>()));
    } else {
      const auto v = numbersArgument(a.bands, "bands", 3);
      nx::SpectralBands b{v[0], v[1], v[2]};
      choices.bands = nx::Sensor(nx::SpectralBands::parse(b.toString()));
    }
  }
  if (!a.sensor.is_none())
    choices.bands = nx::sensorFromOption(pathArgument(a.sensor, "sensor"), "sensor");
  choices.sampler = optionString(a.sampler, "sampler");
  choices.lightSampling = optionString(a.lightSampling, "light_sampling");
  choices.lightSelection = optionString(a.lightSelection, "light_selection");
  choices.density = optionString(a.density, "wavelength_density");
  choices.noFluorescence = !a.fluorescence;
  choices.relightable = a.relightable;
  if (!a.relightStep.is_none()) {
    if (!a.relightable)
      throw py::value_error("relight_step: only with relightable=True (the grid it keeps)");
    choices.relightStepNm = numberArgument(a.relightStep, "relight_step", 1e-9, 1e9);
    try {
      nx::checkRelightStep(choices.relightStepNm, "relight_step");
    } catch (const nx::Error& e) {
      throw py::value_error(e.what());
    }
  }
  addAovs(choices, a.aovs);
  if (!a.targetError.is_none())
    choices.targetError = numberArgument(a.targetError, "target_error", 1e-9, 1e9);
  choices.errorOf = optionString(a.errorOf, "error_of");
  if (!a.timeLimit.is_none())
    choices.timeLimit = numberArgument(a.timeLimit, "time_limit", 1e-3, 1e12);
  choices.adaptive = a.adaptive;
  if (a.adaptive && a.targetError.is_none())
    throw py::value_error("adaptive: expected a target_error to aim at, found none");
  checkStrategyNames(choices);
  return choices;
}

// The crop (x0, y0, x1, y1) checked against the image's size.
nx::PixelRect cropRect(const std::vector<long long>& c, int width, int height) {
  if (c[0] < 0 || c[1] < 0 || c[2] > width || c[3] > height || c[2] <= c[0] || c[3] <= c[1])
    throw py::value_error("crop: expected (x0, y0, x1, y1) with 0 <= x0 < x1 <= " +
                          std::to_string(width) + " and 0 <= y0 < y1 <= " + std::to_string(height) +
                          ", found (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " +
                          std::to_string(c[2]) + ", " + std::to_string(c[3]) + ")");
  return nx::PixelRect{static_cast<int>(c[0]), static_cast<int>(c[1]), static_cast<int>(c[2]),
                       static_cast<int>(c[3])};
}

// Renders on a worker thread in its own arena of `threads`; this thread waits with the GIL
// released, and every 50 ms takes it to run Python's signal handlers (Ctrl-C) and the
// progress callback, so both run on the caller's thread and never inside a TBB task. A
// Python error (Ctrl-C, the callback's) stops the render and is raised.
nx::RenderOutput renderWaiting(const nx::RenderScene& scene, nx::RenderOptions& options,
                               int threads, const py::object& progress) {
  std::atomic<bool> stop{false};
  std::atomic<int64_t> done{0}, total{0};
  options.stop = &stop;
  options.progress = [&](int64_t d, int64_t t) {
    total.store(t);
    done.store(d);
  };
  std::mutex mutex;
  std::condition_variable finishedCv;
  bool finished = false;
  std::optional<nx::RenderOutput> result;
  std::exception_ptr renderError;
  std::thread worker([&] {
    try {
      tbb::task_arena arena(threads);
      arena.execute([&] { result.emplace(nx::render(scene, options)); });
    } catch (...) {
      renderError = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex);
    finished = true;
    finishedCv.notify_all();
  });
  std::optional<py::error_already_set> pythonError;
  int64_t reported = -1;
  for (bool end = false; !end;) {
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(mutex);
      finishedCv.wait_for(lock, std::chrono::milliseconds(50), [&] { return finished; });
      end = finished;
    }
    if (pythonError) continue;
    if (PyErr_CheckSignals() != 0) {
      pythonError.emplace();
      stop.store(true);
      continue;
    }
    const int64_t d = done.load();
    if (!progress.is_none() && d != reported && total.load() > 0) {
      reported = d;
      try {
        progress(d, total.load());
      } catch (py::error_already_set& e) {
        pythonError.emplace(std::move(e));
        stop.store(true);
      }
    }
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (pythonError) throw std::move(*pythonError);
  if (renderError) std::rethrow_exception(renderError);
  return std::move(*result);
}

// Reverse mode's result: d loss / d parameter per name (a number, or one per component) and
// their variances. A non-finite one (an adjoint so large that its products with the radiance
// overflow single precision) is refused, naming the adjoint's largest magnitude.
py::object gradientsByName(const GradientRequest& request, const nx::RenderOutput& result,
                           const std::vector<float>& adjoint) {
  for (const GradientParameter& p : request.parameters)
    for (uint32_t k = p.firstSlot; k < p.firstSlot + (p.indexed ? p.slots : 1u); ++k)
      if (!std::isfinite(result.gradient[k]) || !std::isfinite(result.gradientVariance[k])) {
        float largest = 0;
        for (float a : adjoint) largest = std::max(largest, std::abs(a));
        throw py::value_error(
            "adjoint: expected values whose products with the radiance stay finite, found the "
            "gradient of " +
            p.name + " non-finite (the adjoint's largest magnitude is " + nx::numberText(largest) +
            "; scale the loss down)");
      }
  py::dict grads, variances;
  for (const GradientParameter& p : request.parameters) {
    auto pick = [&](const std::vector<double>& v) -> py::object {
      if (!p.indexed) return py::float_(v[p.firstSlot]);
      py::array_t<double> a(static_cast<py::ssize_t>(p.slots));
      std::copy(v.begin() + p.firstSlot, v.begin() + p.firstSlot + p.slots, a.mutable_data());
      if (p.shape.empty()) return a;
      py::list shape;
      for (long n : p.shape) shape.append(n);
      return a.attr("reshape")(py::tuple(shape));
    };
    grads[py::str(p.name)] = pick(result.gradient);
    variances[py::str(p.name)] = pick(result.gradientVariance);
  }
  return py::make_tuple(grads, variances);
}

py::object render(const py::object& sceneArg, const py::object& spp, const py::object& seed,
                  const py::object& threads, const py::object& bands, const py::object& sensor,
                  const py::object& crop, const py::object& sppRange, const py::object& progress,
                  const py::object& sampler, const py::object& lightSampling,
                  const py::object& lightSelection, const py::object& density, bool fluorescence,
                  const py::object& aovs, const py::object& targetError, const py::object& errorOf,
                  const py::object& timeLimit, bool adaptive, bool relightable,
                  const py::object& relightStep, const py::object& relightFor,
                  const py::object& gradients, const py::object& adjoint) {
  // Every argument is checked before the (possibly long) scene build.
  nx::RenderChoices choices = choicesFrom(
      {spp, seed, bands, sensor, sppRange, sampler, lightSampling, lightSelection, density,
       fluorescence, aovs, targetError, errorOf, timeLimit, adaptive, relightable, relightStep});
  const int nThreads = threads.is_none()
                           ? tbb::info::default_concurrency()
                           : static_cast<int>(integerArgument(threads, "threads", 1, 4096));
  std::optional<std::vector<long long>> cropBox;
  if (!crop.is_none()) cropBox = integersArgument(crop, "crop", 4);
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw py::type_error("progress: expected a callable progress(done, total), found " +
                         typeName(progress));

  std::vector<nx::RelightTargetDesc> targets;
  if (!relightFor.is_none()) {
    if (!relightable)
      throw py::value_error("relight_for: only with relightable=True (the targets it draws for)");
    targets = relightTargetsArgument(relightFor);
  }
  SceneSource src = sceneArgument(sceneArg);
  if (!src.desc.warnings.empty()) {
    const py::object warn = py::module_::import("warnings").attr("warn");
    for (const auto& w : src.desc.warnings) warn(w);
  }
  if (!fluorescence) nx::removeFluorescence(src.desc);
  src.desc.relightable = relightable;
  src.desc.relightTargets = std::move(targets);
  std::optional<nx::RenderScene> scene;
  {
    py::gil_scoped_release release;
    scene.emplace(nx::buildRenderScene(src.desc));
  }
  for (const auto& w : scene->warnings) py::module_::import("warnings").attr("warn")(w);
  const int width = scene->settings.width, height = scene->settings.height;
  if (cropBox) choices.crop = cropRect(*cropBox, width, height);
  // A differentiated render: the slots of the parameters asked for, and their tangents.
  if (!adjoint.is_none() && gradients.is_none())
    throw py::value_error("adjoint: only with gradients=[names] (d loss / d image for reverse "
                          "mode, as nxrender.backward takes it), found an adjoint without them");
  std::optional<GradientRequest> request;
  std::vector<float> adjointValues;
  if (!gradients.is_none()) {
    py::object pyScene = sceneArg;
    if (!py::isinstance<PyScene>(sceneArg)) {
      const py::object cls = py::module_::import("nxrender").attr("Scene");
      pyScene =
          src.name == "<string>" ? cls.attr("from_text")(sceneArg, "<string>") : cls(src.name);
    }
    request.emplace(gradientRequest(pyScene, gradients, *scene, fluorescence));
    for (const std::string& w : request->warnings) py::module_::import("warnings").attr("warn")(w);
  }
  std::optional<nx::RenderJob> jobHolder;
  try {
    jobHolder.emplace(*scene, src.name, choices);
  } catch (const nx::Error& e) {
    // The job's checks name the command line's options (--error-of); say Python's (error_of).
    std::string message = e.what();
    const size_t colon = message.find(':');
    if (message.rfind("--", 0) == 0 && colon != std::string::npos)
      message = pythonName(message.substr(0, colon)) + message.substr(colon);
    throw py::value_error(message);
  }
  nx::RenderJob& job = *jobHolder;
  // Tables and EEM windows that end inside the range this render traces (as nxrender warns).
  for (const std::string& w : nx::extrapolationWarnings(*scene, nx::Film::tracedMinNm(job.bands()),
                                                        nx::Film::tracedMaxNm(job.bands())))
    py::module_::import("warnings").attr("warn")(w);
  const nx::PixelRect r = job.rect();
  nx::requireMemory(nx::renderBufferBytes(r.width(), r.height(), job.bands().count()), src.name,
                    "a render",
                    std::to_string(r.width()) + "x" + std::to_string(r.height()) + " with " +
                        std::to_string(job.bands().count()) + " bands");
  nx::RenderOptions& options = job.options();
  if (request) {
    options.gradients = &request->tangents;
    if (!adjoint.is_none()) {
      // d loss / d image: (H, W, bands) over the rendered pixels, as the radiance; real numbers
      // float32 keeps, as an image's arrays (complex, str, bool and object arrays were cast,
      // 1e-50 became 0).
      adjointValues = pixelsArgument<float>(adjoint, "adjoint", r.height(), r.width(),
                                            job.bands().count(), -FLT_MAX, FLT_MAX);
      options.adjoint = &adjointValues;
    }
  }
  std::optional<nx::RenderOutput> result = renderWaiting(*scene, options, nThreads, progress);
  // An adaptive image keeps its range (counts differ per pixel: sample_count).
  if (!adaptive && (result->stats.reachedTarget || result->stats.reachedTimeLimit))
    job.setSamplesReached(result->stats.samplesReached);
  nx::requireSomeFiniteSamples(result->stats, src.name);
  for (const std::string& w : nx::warningsOf(result->stats))
    if (request) py::module_::import("warnings").attr("warn")(w);
  if (request && !adjoint.is_none()) return gradientsByName(*request, *result, adjointValues);
  PyImage out;
  out.image = job.image(result->film, result->stats.seconds);
  if (request) {
    std::string list;
    for (uint32_t k = 0; k < request->tangents.slots(); ++k)
      list += (k ? ";" : "") + std::string("gradient.") + std::to_string(k) + "=" +
              request->tangents.slotNames[k];
    out.image.attributes["nxrender.gradients"] = list;
    out.gradients = request->parameters;
  }
  if (!src.edits.empty()) out.image.attributes["nxrender.sceneEdits"] = src.edits;
  if (!request)
    for (const std::string& w : nx::warningsOf(result->stats))
      py::module_::import("warnings").attr("warn")(w);
  return py::cast(std::move(out));
}

} // namespace

void bindRender(py::module_& m) {
  // The strategies' defaults as the command line's (RenderChoices, apps/render_job.h).
  const nx::RenderChoices defaults;
  m.def("render", &render, py::arg("scene"), py::arg("spp") = py::none(),
        py::arg("seed") = py::none(), py::arg("threads") = py::none(),
        py::arg("bands") = py::none(), py::arg("sensor") = py::none(), py::arg("crop") = py::none(),
        py::arg("spp_range") = py::none(), py::arg("progress") = py::none(),
        py::arg("sampler") = defaults.sampler, py::arg("light_sampling") = defaults.lightSampling,
        py::arg("light_selection") = defaults.lightSelection,
        py::arg("wavelength_density") = defaults.density, py::arg("fluorescence") = true,
        py::arg("aovs") = py::tuple(), py::arg("target_error") = py::none(),
        py::arg("error_of") = "luminance", py::arg("time_limit") = py::none(),
        py::arg("adaptive") = false, py::arg("relightable") = false,
        py::arg("relight_step") = py::none(), py::arg("relight_for") = py::none(),
        py::arg("gradients") = py::none(), py::arg("adjoint") = py::none(),
        "Renders a scene (an nxrender.Scene, a scene file name, or scene XML text) and returns "
        "an nxrender.Image, the same bit for bit as nxrender's EXR for the same scene, seed and "
        "samples. The GIL is released while rendering; Ctrl-C raises KeyboardInterrupt after "
        "the worker threads stopped; progress(done, total) is called on the calling thread as "
        "tiles finish. Options as nxrender's (docs/python.md). gradients=[names]: also "
        "d radiance / d parameter per name in image.gradients (forward mode, docs/inverse.md).");
  m.def(
      "check_aovs",
      [](const py::object& aovs) {
        nx::RenderChoices choices;
        addAovs(choices, aovs);
      },
      py::arg("aovs"),
      "Raises TypeError or ValueError, as render(aovs=...) would, for layer names it does not "
      "take");
  m.def(
      "backward",
      [](const py::object& scene, const py::object& adjoint, const py::object& gradients,
         const py::object& spp, const py::object& seed, const py::object& threads,
         const py::object& bands, const py::object& sensor, const py::object& crop,
         const py::object& sampler, const py::object& lightSampling,
         const py::object& lightSelection, const py::object& density, bool fluorescence) {
        if (adjoint.is_none()) throw py::value_error("adjoint: expected d loss / d image");
        if (gradients.is_none()) throw py::value_error("gradients: expected parameter names");
        return render(scene, spp, seed, threads, bands, sensor, crop, py::none(), py::none(),
                      sampler, lightSampling, lightSelection, density, fluorescence, py::tuple(),
                      py::none(), py::str("luminance"), py::none(), false, false, py::none(),
                      py::none(), gradients, adjoint);
      },
      py::arg("scene"), py::arg("adjoint"), py::arg("gradients"), py::arg("spp") = py::none(),
      py::arg("seed") = py::none(), py::arg("threads") = py::none(), py::arg("bands") = py::none(),
      py::arg("sensor") = py::none(), py::arg("crop") = py::none(),
      py::arg("sampler") = defaults.sampler, py::arg("light_sampling") = defaults.lightSampling,
      py::arg("light_selection") = defaults.lightSelection,
      py::arg("wavelength_density") = defaults.density, py::arg("fluorescence") = true,
      "Reverse mode (docs/inverse.md): the gradient of a scalar loss with respect to every "
      "parameter named in `gradients`, given adjoint = d loss / d image (the shape of the "
      "radiance), in one pass; returns (gradients, variances): dicts name -> a number, or an "
      "array per component for spectra and colours. Use another seed than the image the loss "
      "was computed from.");
}

} // namespace nxpy
