// nxrender: renders a scene file to a spectral OpenEXR and a tone-mapped preview; renders
// parts of an image (crops, sample ranges) for render farms, and survives interruption.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "apps/command_line.h"
#include "apps/program_main.h"
#include "apps/render_job.h"
#include "core/error.h"
#include "core/input_files.h"
#include "core/memory.h"
#include "core/text_table.h"
#include "integrators/relight_targets.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "io/atomic_file.h"
#include "io/envi_export.h"
#include "io/preview_image.h"
#include "io/spectral_exr.h"

namespace {

std::atomic<bool> gStop{false};
std::atomic<int> gSignal{0};

extern "C" void onSignal(int sig) {
  gSignal.store(sig);
  gStop.store(true);
  std::signal(sig, SIG_DFL); // a second signal ends the process at once
}

std::string replaceExtension(const std::string& path, const std::string& ext) {
  return std::filesystem::path(path).replace_extension(ext).string();
}

std::vector<long long> integers(const std::string& text, char sep, size_t count,
                                const std::string& what) {
  std::vector<long long> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, sep)) {
    char* end = nullptr;
    const long long x = std::strtoll(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0')
      throw nx::Error(what + ": expected whole numbers, found '" + text + "'");
    v.push_back(x);
  }
  if (v.size() != count)
    throw nx::Error(what + ": expected " + std::to_string(count) + " numbers, found '" + text +
                    "'");
  return v;
}

long long envInteger(const char* name) {
  const char* v = std::getenv(name);
  if (!v || !*v)
    throw nx::Error(std::string("--tile-of-array: the environment variable ") + name +
                    " is not set");
  char* end = nullptr;
  const long long x = std::strtoll(v, &end, 10);
  if (*end != '\0' || x < 0)
    throw nx::Error(std::string("--tile-of-array: ") + name + "='" + v + "' is not a whole number");
  return x;
}

// Progress on stderr: a live bar on a terminal, a plain line every few seconds otherwise.
class Progress {
public:
  Progress() : tty_(isatty(STDERR_FILENO) == 1), start_(std::chrono::steady_clock::now()) {}
  void update(int64_t done, int64_t total) {
    const double elapsed = seconds();
    const double fraction = static_cast<double>(done) / static_cast<double>(total);
    const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
    if (tty_) {
      if (elapsed - last_ < 0.1 && done != total) return;
      const int width = 40, filled = static_cast<int>(fraction * width);
      std::fprintf(stderr, "\r[%s%s] %3.0f%%  %.1f s elapsed, ETA %.1f s ",
                   std::string(filled, '=').c_str(), std::string(width - filled, ' ').c_str(),
                   100 * fraction, elapsed, eta);
      if (done == total) {
        std::fprintf(stderr, "\n");
        ended_ = true;
      }
    } else {
      if (elapsed - last_ < 5.0) return;
      std::fprintf(stderr, "nxrender: %.0f%% done, %.1f s elapsed, ETA %.1f s\n", 100 * fraction,
                   elapsed, eta);
    }
    last_ = elapsed;
  }
  /// Ends the bar's line if the render stopped before it was full.
  void finish() const {
    if (tty_ && !ended_) std::fprintf(stderr, "\n");
  }

private:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  bool tty_;
  std::chrono::steady_clock::time_point start_;
  double last_ = 0;
  bool ended_ = false;
};

// The items of a comma list (empty items skipped).
std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    if (!item.empty()) out.push_back(item);
    start = comma + 1;
  }
  return out;
}

// An image's provenance attribute, "" when it has none.
std::string attributeOf(const nx::SpectralImage& image, const char* key) {
  const auto it = image.attributes.find(key);
  return it == image.attributes.end() ? std::string() : it->second;
}

// Seconds spent in each step of the process, from the start of main (for --timings).
class PhaseClock {
public:
  /// Ends the current step under `name`.
  void mark(const char* name) {
    const auto now = std::chrono::steady_clock::now();
    steps_.emplace_back(name, std::chrono::duration<double>(now - last_).count());
    last_ = now;
  }
  /// Prints the steps and their total on stderr.
  void print() const {
    double total = 0;
    for (const auto& [name, s] : steps_) {
      std::fprintf(stderr, "nxrender: timing: %-30s %8.3f s\n", name.c_str(), s);
      total += s;
    }
    std::fprintf(stderr, "nxrender: timing: %-30s %8.3f s\n", "total after start-up", total);
  }

private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, double>> steps_;
};

// A partial render (--resume) or a pilot (--adaptive-from) continues only with the sampler
// that made it; the default changed (sobol -> stratified), so the error says how to continue.
void requireSameSampler(const std::string& path, const std::string& made,
                        const std::string& wanted) {
  if (made != wanted)
    throw nx::Error(path + ": was rendered with --sampler " + made + ", this render uses " +
                    wanted + " (stratified is the default now, sobol was before; give --sampler " +
                    made + " to continue it)");
}

int run(int argc, char** argv) {
  CLI::App app{
      "nxrender: spectral path tracer for fluorescence research\n"
      "Renders SCENE to a spectral OpenEXR (Fichet et al. 2021 layout) and a tone-mapped preview."};
  app.set_version_flag("--version", std::string("nxrender ") + NX_VERSION);
  int threads = 0, spp = 0;
  long long seed = -1;
  double checkpointSeconds = 0, targetError = 0, timeLimit = 0;
  std::string output, bandsText, sensorText, sensorCentres,
      errorOf = "luminance", aovText, compression, adaptiveFrom, scenePath, cropText, rangeText,
      resumePath;
  bool noFluorescence = false, tileOfArray = false, noVariance = false, halfFloat = false,
       envi = false, timings = false, adaptive = false, relightable = false;
  double relightStep = 5;
  std::vector<std::string> relightFor;
  int adaptiveMinSpp = 16;
  app.add_option("--threads", threads, "Worker threads (default: all cores)")
      ->check(nx::numberIn(1, 4096));
  app.add_option("--spp", spp, "Samples per pixel (default: the scene's <sampl>)")
      ->check(nx::numberIn(1, 1 << 30));
  app.add_option("-o,--output", output,
                 "Spectral EXR to write; the preview goes beside it as .png "
                 "(default: the preview at the scene's <path>, the EXR beside it)");
  app.add_option("--bands", bandsText,
                 "Output bands START:END:STEP in nm, uniform boxes (default: the scene's, else "
                 "400:700:10)");
  app.add_option("--sensor", sensorText,
                 "The camera's bands: a CSV of measured responses (header nm,<band>,...), or "
                 "gaussian:CENTRES@FWHM (CENTRES a,b,c or START:END:STEP; one FWHM or one per "
                 "centre), or boxes:LO-HI,LO-HI,... (default: the scene's <bands>/<sensor>)");
  app.add_option("--sensor-centres", sensorCentres,
                 "Nominal centres naming the --sensor CSV's bands (a,b,c or START:END:STEP, one "
                 "per band), when its header does not name them by wavelength");
  app.add_option("--seed", seed, "Random seed (default: the scene's <seed>, else 0)")
      ->check(nx::numberIn(0LL, 2147483647LL));
  // The strategies from their one table (values, default, help): RenderChoices' fields.
  nx::RenderChoices strategies;
  for (const nx::StrategyOption& o : nx::strategyOptions())
    app.add_option(o.option, strategies.*o.field, o.help)->check(CLI::IsMember(o.values));
  app.add_flag("--no-fluorescence", noFluorescence,
               "Render fluorescent materials as their ordinary reflectance (for comparisons)");
  app.add_flag("--no-variance", noVariance,
               "Leave out the Variance channels (error estimates; a resume from such a file "
               "restarts its estimates)");
  app.add_option("--aov", aovText, nx::aovOptionHelp());
  app.add_flag("--relightable", relightable,
               "Also keep, per light group, the transport from each excitation bin to each "
               "band (relight.GROUP.T.<excitation>nm.<band>nm channels), so that nxrelight "
               "renders the image under any new emission spectra (docs/relighting.md)");
  app.add_option("--relight-step", relightStep,
                 "Width of the excitation bins of --relightable in nm: a divisor of 5 (1, 2.5, "
                 "5) or a multiple of 5 (default 5; finer for line spectra, docs/relighting.md)");
  app.add_option("--relight-for", relightFor,
                 "With --relightable: a spectrum the render will be relit to, [GROUP=]FILE|NAME "
                 "(a CSV nm,value or a built-in emission such as D65, F11; without GROUP for "
                 "every light group; repeatable): lights are chosen and fluorescent excitation "
                 "drawn for the targets, so that relit images under narrow lamps are about as "
                 "noisy as direct renders (docs/relighting.md)");
  app.add_flag("--envi", envi,
               "Also write the bands as an ENVI cube beside the EXR: OUT.img (BSQ float32) and "
               "OUT.hdr (wavelength and fwhm lists), for spectral-imaging tools");
  app.add_flag("--half", halfFloat,
               "Store the EXR's channels as half floats (16 bits, ~3 digits, up to 65504; "
               "falls back to floats with a warning when a value does not fit)");
  app.add_option("--compression", compression,
                 "EXR compression: none (default for floats: a render's noise does not "
                 "compress), piz (default with --half), zip, zips, rle (all lossless), or the "
                 "lossy pxr24, b44, b44a, dwaa, dwab (docs/output.md)");
  app.add_option("--crop", cropText,
                 "Render only pixels X0,Y0,X1,Y1 (half-open) of the full image");
  app.add_option("--spp-range", rangeText, "Render samples A..B-1 of each pixel's sequence (A:B)");
  app.add_flag("--tile-of-array", tileOfArray,
               "Render the horizontal strip SLURM_ARRAY_TASK_ID of SLURM_ARRAY_TASK_COUNT, to "
               "OUT.part<ID>.exr");
  app.add_option("--checkpoint", checkpointSeconds,
                 "Also write the EXR every SECONDS while rendering")
      ->check(nx::numberIn(1.0, 1e9));
  app.add_option("--target-error", targetError,
                 "Stop once the estimated relative RMS error named by --error-of is at most E "
                 "(checked after each pass)")
      ->check(nx::numberIn(1e-9, 1e9));
  app.add_option("--error-of", errorOf,
                 "The error --target-error aims at: luminance (default; Y, CIE 1931 over 360-830 "
                 "nm, whatever the bands), bands (the worst band's relative RMS error), or "
                 "bands:LO-HI (the worst among the bands whose centroid lies in LO-HI nm)");
  app.add_flag("--adaptive", adaptive,
               "Adaptive sampling: spend the samples where the error is, in 8x8-pixel blocks, "
               "until --target-error is met (--spp: the most a pixel may take)");
  app.add_option("--adaptive-min-spp", adaptiveMinSpp,
                 "The uniform pilot of --adaptive, samples per pixel (default 16)")
      ->check(nx::numberIn(2, 1 << 30));
  app.add_option("--adaptive-from", adaptiveFrom,
                 "One adaptive round planned from this whole-image EXR of the same render (a "
                 "farm round: every --crop part plans alike; docs/farm.md)");
  app.add_option("--time-limit", timeLimit, "Stop before a pass that would end after SECONDS")
      ->check(nx::numberIn(1e-3, 1e12));
  app.add_option("--resume", resumePath,
                 "Continue the render stored in this EXR (written by an interrupted run)");
  app.add_flag("--timings", timings,
               "Print the seconds of each step of the whole process (load, build, render, "
               "image, EXR, preview) on stderr");
  app.add_option("scene", scenePath, "Scene file (.scn)")->required();
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxrender"); status >= 0)
    return status;

  PhaseClock clock;
  nx::SceneDesc desc = nx::loadScene(scenePath);
  clock.mark("load scene file");
  for (const auto& w : desc.warnings) std::fprintf(stderr, "%s\n", w.c_str());
  if (noFluorescence) nx::removeFluorescence(desc);
  if (app.count("--relight-step") > 0 && !relightable)
    throw nx::Error("--relight-step: only with --relightable (the excitation grid it keeps)");
  if (relightable) nx::checkRelightStep(relightStep, "--relight-step");
  desc.relightable = relightable;
  if (!relightFor.empty() && !relightable)
    throw nx::Error("--relight-for: only with --relightable (the targets it draws for)");
  for (const std::string& t : relightFor)
    desc.relightTargets.push_back(nx::relightTargetFromText(t, "--relight-for"));
  const nx::RenderScene scene = nx::buildRenderScene(desc);
  for (const auto& w : scene.warnings) std::fprintf(stderr, "%s\n", w.c_str());
  clock.mark("build scene (spectra, BVH)");
  const int width = scene.settings.width, height = scene.settings.height;

  nx::RenderChoices choices;
  choices.samples = spp;
  if (seed >= 0) choices.seed = static_cast<uint32_t>(seed);
  if (!bandsText.empty() && !sensorText.empty())
    throw nx::Error("expected one of --bands and --sensor, found both");
  if (!bandsText.empty()) choices.bands = nx::Sensor(nx::SpectralBands::parse(bandsText));
  if (!sensorText.empty()) choices.bands = nx::sensorFromOption(sensorText, "--sensor");
  if (!sensorCentres.empty()) {
    if (sensorText.empty()) throw nx::Error("--sensor-centres: expected a --sensor CSV to name");
    choices.bands = choices.bands->withNominalCentres(sensorCentres, "--sensor-centres");
  }
  for (const nx::StrategyOption& o : nx::strategyOptions()) choices.*o.field = strategies.*o.field;
  choices.noFluorescence = noFluorescence;
  choices.relightable = relightable;
  choices.relightStepNm = relightStep;
  if (!rangeText.empty()) {
    if (spp > 0) throw nx::Error("--spp-range and --spp: give one of them");
    const auto r = integers(rangeText, ':', 2, "--spp-range");
    if (r[0] < 0 || r[1] <= r[0] || r[1] > (1LL << 30))
      throw nx::Error("--spp-range: expected 0 <= A < B <= 2^30, found " + rangeText);
    choices.firstSample = static_cast<int>(r[0]);
    choices.samples = static_cast<int>(r[1] - r[0]);
    choices.sampleRange = true;
  }
  if (!cropText.empty() && tileOfArray)
    throw nx::Error("--crop and --tile-of-array: give one of them");
  if (!cropText.empty()) {
    const auto c = integers(cropText, ',', 4, "--crop");
    if (c[0] < 0 || c[1] < 0 || c[2] > width || c[3] > height || c[2] <= c[0] || c[3] <= c[1])
      throw nx::Error("--crop: expected 0 <= X0 < X1 <= " + std::to_string(width) +
                      " and 0 <= Y0 < Y1 <= " + std::to_string(height) + ", found " + cropText);
    choices.crop = nx::PixelRect{static_cast<int>(c[0]), static_cast<int>(c[1]),
                                 static_cast<int>(c[2]), static_cast<int>(c[3])};
  }
  std::string arrayTask;
  if (tileOfArray) {
    if (output.empty())
      throw nx::Error("--tile-of-array needs -o OUT.exr (the parts are OUT.part<ID>.exr)");
    const long long minId =
        std::getenv("SLURM_ARRAY_TASK_MIN") ? envInteger("SLURM_ARRAY_TASK_MIN") : 0;
    const long long id = envInteger("SLURM_ARRAY_TASK_ID") - minId,
                    count = envInteger("SLURM_ARRAY_TASK_COUNT");
    if (count < 1 || count > height || id < 0 || id >= count)
      throw nx::Error("--tile-of-array: task " + std::to_string(id) + " of " +
                      std::to_string(count) + " does not fit an image of " +
                      std::to_string(height) + " rows");
    choices.crop = nx::PixelRect{0, static_cast<int>(height * id / count), width,
                                 static_cast<int>(height * (id + 1) / count)};
    arrayTask = std::to_string(id);
  }
  // A Slurm array task without a split option renders the whole image in every task.
  if (!tileOfArray && cropText.empty() && rangeText.empty())
    if (const char* task = std::getenv("SLURM_ARRAY_TASK_ID"))
      std::fprintf(stderr,
                   "nxrender: warning: SLURM_ARRAY_TASK_ID=%s is set (a Slurm array task) but no "
                   "split option is given: every task renders the whole image (give "
                   "--tile-of-array, --crop or --spp-range; docs/farm.md)\n",
                   task);
  for (const std::string& aov : splitList(aovText))
    if (!nx::addAov(choices, aov))
      throw nx::Error("--aov: expected a comma list of " + nx::aovOptionList("", " and ") +
                      ", found '" + aov + "'");
  choices.targetError = targetError;
  choices.errorOf = errorOf;
  choices.timeLimit = timeLimit;
  choices.adaptive = adaptive || !adaptiveFrom.empty();
  if (app.count("--adaptive-min-spp") > 0 && !adaptive)
    throw nx::Error("--adaptive-min-spp: only with --adaptive (the uniform pilot of an adaptive "
                    "render)");
  choices.adaptiveMinSamples = adaptiveMinSpp;
  if (!adaptiveFrom.empty() && !resumePath.empty())
    throw nx::Error("--adaptive-from and --resume: give one of them (a round continues the image "
                    "it is planned from)");
  nx::RenderJob job(scene, scenePath, choices);
  nx::RenderOptions& options = job.options();

  std::string exrPath, previewPath;
  if (!output.empty()) {
    nx::checkExrOutputName(output);
    exrPath = tileOfArray ? replaceExtension(output, ".part" + arrayTask + ".exr") : output;
    previewPath = replaceExtension(output, ".png");
  } else {
    previewPath = scene.settings.outputPath.empty()
                      ? std::filesystem::path(scenePath).stem().string() + ".png"
                      : scene.settings.outputPath;
    if (!nx::isPreviewPath(previewPath))
      throw nx::Error(desc.settings.loc.str() +
                      ": expected a <path> ending in .png or .bmp, found '" + previewPath + "'");
    exrPath = replaceExtension(previewPath, ".exr");
  }
  // A part of an image (crop or sample range) gets no preview: the merged image does.
  const bool wholeImage = !options.crop && rangeText.empty();
  // No output may replace an input (the scene's files were read above), but for the render a
  // resume continues: the output then holds all it held.
  for (const std::string& in : {resumePath, adaptiveFrom})
    if (!in.empty()) nx::noteInputFile(in);
  if (!resumePath.empty()) nx::allowReplacingInput(resumePath);
  nx::checkWritable(exrPath);
  if (wholeImage) nx::checkWritable(previewPath);
  const std::string enviPath = envi ? replaceExtension(exrPath, ".img") : std::string();
  if (envi) nx::checkEnviOutputName(enviPath);
  {
    // Upper bound of the EXR (uncompressed float channels: bands and their variances, RGB,
    // XYZ, a variance and a count) plus the preview.
    const nx::PixelRect r = job.rect();
    const double pixels = static_cast<double>(r.width()) * r.height();
    const int nb = job.bands().count();
    // The scene file's own bands were checked when loading; --bands may ask for more, and a
    // resume holds a second film.
    nx::requireMemory(nx::renderBufferBytes(r.width(), r.height(), nb) *
                          (resumePath.empty() ? 1 : 2),
                      scenePath, "a render",
                      std::to_string(r.width()) + "x" + std::to_string(r.height()) + " with " +
                          std::to_string(nb) + " bands");
    nx::checkFreeSpace(exrPath,
                       pixels * (2.0 * nb + 8) * 4 + (wholeImage ? pixels * 3 : 0) + (1 << 20));
  }

  const int firstSample = job.firstSample();
  const int sppTotal = job.samples();
  const uint32_t seedUsed = job.seed();
  const nx::Sensor& bands = job.bands();
  for (const auto& w :
       nx::extrapolationWarnings(scene, nx::Film::tracedMinNm(bands), nx::Film::tracedMaxNm(bands)))
    std::fprintf(stderr, "%s\n", w.c_str());

  std::optional<nx::Film> resumeFilm;
  if (!resumePath.empty()) {
    const nx::SpectralImage prev = nx::readSpectralExr(resumePath);
    auto attr = [&](const char* k) { return attributeOf(prev, k); };
    const nx::PixelRect want = job.rect();
    requireSameSampler(resumePath, attr("nxrender.sampler"), job.choices().sampler);
    // The ground-truth layers (part of the render key) named, rather than the key's message.
    std::vector<std::string> mine, held;
    for (const nx::AovImageLayer& l : prev.aovs) held.push_back(l.name);
    for (nx::AovKind k : job.choices().aovKinds) mine.emplace_back(nx::aovName(k));
    std::string layers;
    for (const std::string& n : mine) layers += (layers.empty() ? "" : ",") + n;
    std::sort(mine.begin(), mine.end());
    std::sort(held.begin(), held.end());
    if (mine != held) {
      std::string theirs;
      for (const nx::AovImageLayer& l : prev.aovs) theirs += (theirs.empty() ? "" : ",") + l.name;
      throw nx::Error(resumePath + ": holds the ground-truth layers '" + theirs +
                      "', this render '" + layers + "': resume with the same --aov");
    }
    if (attr("nxrender.renderKey") != job.renderKey())
      throw nx::Error(resumePath +
                      ": was rendered from another scene, other data files (CSV spectra, "
                      "matrices), other options or another nxrender version");
    if (attr("nxrender.seed") != std::to_string(seedUsed) ||
        attr("nxrender.bands") != bands.toString() ||
        attr("nxrender.sampleRange") !=
            std::to_string(firstSample) + ":" + std::to_string(firstSample + sppTotal))
      throw nx::Error(
          resumePath + ": has another seed, bands or sample range (" + attr("nxrender.seed") +
          ", " + prev.bands.summary() + ", " + attr("nxrender.sampleRange") +
          ") than this render (" + std::to_string(seedUsed) + ", " + bands.summary() + ", " +
          std::to_string(firstSample) + ":" + std::to_string(firstSample + sppTotal) + ")");
    if (prev.displayWidth() != width || prev.displayHeight() != height || prev.originX != want.x0 ||
        prev.originY != want.y0 || prev.width != want.width() || prev.height != want.height())
      throw nx::Error(resumePath + ": covers another image size or crop than this render");
    try {
      resumeFilm = nx::filmFromImage(prev, firstSample, sppTotal);
    } catch (const nx::Error& e) {
      throw nx::Error(resumePath + ": " + e.what());
    }
    options.resumeFrom = &*resumeFilm;
  }
  std::optional<nx::Film> planFilm;
  std::optional<nx::AdaptivePlan> plan;
  if (!adaptiveFrom.empty()) {
    const nx::SpectralImage from = nx::readSpectralExr(adaptiveFrom);
    auto attr = [&](const char* k) { return attributeOf(from, k); };
    requireSameSampler(adaptiveFrom, attr("nxrender.sampler"), job.choices().sampler);
    if (attr("nxrender.renderKey") != job.renderKey())
      throw nx::Error(adaptiveFrom +
                      ": was rendered from another scene, other data files, other options or "
                      "another nxrender version");
    const std::string range = attr("nxrender.sampleRange");
    if (attr("nxrender.seed") != std::to_string(seedUsed) ||
        attr("nxrender.bands") != bands.toString() ||
        range.rfind(std::to_string(firstSample) + ":", 0) != 0)
      throw nx::Error(adaptiveFrom + ": has another seed, bands or first sample (" +
                      attr("nxrender.seed") + ", " + from.bands.summary() + ", " + range +
                      ") than this render (" + std::to_string(seedUsed) + ", " + bands.summary() +
                      ", " + std::to_string(firstSample) + ":...)");
    if (from.displayWidth() != width || from.displayHeight() != height || from.originX != 0 ||
        from.originY != 0 || from.width != width || from.height != height)
      throw nx::Error(adaptiveFrom + ": expected the whole " + std::to_string(width) + "x" +
                      std::to_string(height) +
                      " image to plan from (merge the parts first), found a " +
                      std::to_string(from.width) + "x" + std::to_string(from.height) + " part");
    try {
      planFilm = nx::filmFromImage(from, firstSample, sppTotal);
      plan = nx::planAdaptiveSamples(*planFilm, options.errorMeasure, options.targetRelativeError,
                                     static_cast<uint32_t>(sppTotal));
    } catch (const nx::Error& e) {
      throw nx::Error(adaptiveFrom + ": " + e.what());
    }
    resumeFilm = planFilm->cropped(job.rect());
    options.resumeFrom = &*resumeFilm;
    options.adaptivePlan = &*plan;
  }
  auto imageOf = [&](const nx::Film& film, double seconds) { return job.image(film, seconds); };

  const int nThreads = threads > 0 ? threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(nThreads));
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  options.stop = &gStop;
  Progress progress;
  options.progress = [&](int64_t done, int64_t total) { progress.update(done, total); };
  // The EXR as asked: without the Variance channels, in half floats where every value fits.
  nx::ExrEncoding encoding;
  if (!compression.empty())
    encoding.compression = nx::parseExrCompression(compression, "--compression");
  else if (relightable) // mostly zeros (paths that do not reach a pattern's pair): zip, lossless
    encoding.compression = nx::ExrCompression::Zip;
  // The render's memory check counts the EXR's writer too (a relightable render passed it and
  // was lost at the write).
  options.output = nx::RenderFileOutput{encoding, halfFloat, noVariance};
  // (A copy only without the variances: a relightable image can take gigabytes.)
  auto writeImage = [&](const nx::SpectralImage& rendered) {
    std::optional<nx::SpectralImage> stripped;
    if (noVariance) {
      stripped.emplace(rendered);
      stripped->bandVariance.clear(), stripped->yVariance.clear();
      for (nx::ImageLayer& l : stripped->layers) l.variances.clear();
    }
    const nx::SpectralImage& image = stripped ? *stripped : rendered;
    if (halfFloat && nx::fitsInHalf(image))
      return nx::writeSpectralExrHalf(exrPath, image, encoding);
    if (halfFloat)
      std::fprintf(stderr,
                   "nxrender: warning: values beyond the half-float range (65504); "
                   "%s is written in floats\n",
                   exrPath.c_str());
    nx::writeSpectralExr(exrPath, image, encoding);
  };
  auto lastCheckpoint = std::chrono::steady_clock::now();
  const auto start = lastCheckpoint;
  if (checkpointSeconds > 0)
    options.afterPass = [&](const nx::Film& film) {
      const auto now = std::chrono::steady_clock::now();
      if (std::chrono::duration<double>(now - lastCheckpoint).count() < checkpointSeconds) return;
      const nx::OutputLock lock(exrPath);
      writeImage(imageOf(film, std::chrono::duration<double>(now - start).count()));
      lastCheckpoint = now;
    };
  clock.mark("set up the render");
  std::optional<nx::RenderOutput> rendered;
  try {
    rendered.emplace(nx::render(scene, options));
  } catch (const nx::StoppedBeforeRendering&) {
    progress.finish();
    std::fprintf(stderr,
                 "nxrender: stopped by signal %d while preparing the render; nothing "
                 "was rendered or written\n",
                 gSignal.load());
    return 3;
  }
  const nx::RenderOutput& result = *rendered;
  clock.mark("render");
  progress.finish();
  if (options.adaptive) {
    // Counts differ per pixel (SampleCount); the range stays the most a pixel may hold.
    std::fprintf(stderr,
                 "nxrender: adaptive: %s after %d round%s; this run took %.1f samples per pixel on "
                 "average, a pixel holds at most %d (estimated relative RMS error %.4g)\n",
                 result.stats.reachedTarget ? "reached the target error"
                 : result.stats.reachedTimeLimit
                     ? "stopped at the time limit"
                     : (options.adaptivePlan ? "rendered the planned round" : "stopped at --spp"),
                 result.stats.adaptiveRounds, result.stats.adaptiveRounds == 1 ? "" : "s",
                 static_cast<double>(result.stats.samples) /
                     (static_cast<double>(job.rect().width()) * job.rect().height()),
                 result.stats.samplesReached, result.stats.relativeError);
  } else if (result.stats.reachedTarget || result.stats.reachedTimeLimit) {
    std::fprintf(
        stderr, "nxrender: %s after %d samples per pixel (estimated relative RMS error %.4g)\n",
        result.stats.reachedTarget ? "reached the target error" : "stopped at the time limit",
        result.stats.samplesReached, result.stats.relativeError);
    job.setSamplesReached(result.stats.samplesReached); // the image holds exactly this range
  }

  nx::requireSomeFiniteSamples(result.stats, scenePath); // else nothing is written
  const nx::SpectralImage image = imageOf(result.film, result.stats.seconds);
  clock.mark("spectral image from the film");
  {
    // The EXR and its preview as one pair (another process writing the same output waits),
    // the preview also for a stopped render (an older one would sit beside the new EXR).
    // Replaced as one group: a kill between the two renames is completed by the next run.
    const nx::OutputLock lock(exrPath);
    nx::AtomicFileGroup pair;
    writeImage(image);
    clock.mark("write the EXR");
    if (wholeImage)
      nx::writePreview(previewPath, image.width, image.height,
                       nx::previewPixels(result.film, scene.previewWhite));
    pair.commit();
    clock.mark("write the preview");
    if (envi) nx::writeEnvi(enviPath, image);
    clock.mark("write the ENVI cube");
  }
  if (timings) clock.print();
  if (result.stats.stopped) {
    std::fprintf(stderr,
                 "nxrender: stopped by signal %d; wrote the %llu samples finished so far to %s "
                 "(continue with --resume %s)\n",
                 gSignal.load(), static_cast<unsigned long long>(result.stats.samples),
                 exrPath.c_str(), exrPath.c_str());
    return 3;
  }

  const double s = result.stats.seconds;
  std::fprintf(stderr,
               "nxrender: %dx%d, %d spp, %s, %d threads: %.2f s, %.3g samples/s, %.3g rays/s; "
               "wrote %s%s%s%s%s\n",
               image.width, image.height, job.samples(),
               image.attributes.at("nxrender.mode").c_str(), nThreads, s,
               static_cast<double>(result.stats.samples) / s,
               static_cast<double>(result.stats.rays) / s, exrPath.c_str(),
               wholeImage ? " and " : "", wholeImage ? previewPath.c_str() : "",
               envi ? " and the ENVI cube " : "", envi ? enviPath.c_str() : "");
  for (const std::string& w : nx::warningsOf(result.stats))
    std::fprintf(stderr, "nxrender: warning: %s\n", w.c_str());
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return nx::mainReportingErrors("nxrender", run, argc, argv);
}
