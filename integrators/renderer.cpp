#include "integrators/renderer.h"

#include "integrators/aov_layers.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <mutex>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/float_mode.h"
#include "core/matrix3.h"
#include "core/memory.h"
#include "integrators/gradients/gradient_context.h"
#include "integrators/gradients/path_gradients.h"
#include "integrators/gradients/primary_boundary.h"
#include "integrators/render_memory.h"
#include "integrators/sampling.h"
#include "io/light_layer_name.h"
#include "spectra/colour.h"
#include "spectra/tonemap.h"
#include "spectra/wavelength_sampler.h"

namespace nx {
namespace {

// A sample's wavelengths from both coordinates of its next Sobol pair, the pair's third
// coordinate left for the path's first 1D decision (RenderOptions::stratifiedLanes): the
// offset, the hero's stratum and that decision stratified together, as one coordinate's
// wavelengths share their pair with it. Taken from a new pair instead, the decision loses its
// stratification against the wavelengths (3x the band variance of a glass sphere's
// reflect-or-refract choice, docs/performance.md).
SampledWavelengths sampleStratifiedLanes(const WavelengthSampler& wavelengths,
                                         PixelSampleStream& rng) {
  const Sample2 u = rng.next2DWithThirdPending();
  return wavelengths.sample(u.u, u.v);
}

constexpr uint32_t kOddReplicateSalt = 0x68e31da4U;
constexpr uint32_t kWhiteSalt = 0x1b56c4e9U;
constexpr uint32_t kAovSalt = 0x5f3759dfU;
constexpr uint32_t kPathBoundarySalt = 0x510e527fU;

// Samples of [first, first + n) with odd numbers.
uint32_t oddSamplesIn(int64_t first, int64_t n) {
  return static_cast<uint32_t>((first + n) / 2 - first / 2);
}
} // namespace

std::vector<std::string> componentLayerNames(const RenderScene& scene,
                                             const RenderOptions& options) {
  std::vector<std::string> names;
  if (options.components) names = {"reflected", "fluoresced", "direct", "indirect"};
  if (options.lightGroups)
    for (const std::string& g : scene.lightGroups.names) names.push_back(lightLayerName(g));
  if (options.gradients && !options.adjoint)
    for (uint32_t k = 0; k < options.gradients->slots(); ++k)
      names.push_back("gradient." + std::to_string(k));
  return names;
}

namespace {

// What a render request asks for, checked and set up: the bands, the pixels, the film (with
// its layers and relight transport), the layers' layout, the mode's flags and the samples.
struct RenderTarget {
  Sensor bands;
  PixelRect rect;
  RenderOutput out;
  ComponentLayout layout;
  std::shared_ptr<const AovEvaluator> aovs; ///< the ground-truth layers kept, or null
  bool differentiated = false, reverse = false, relightable = false;
  uint32_t seed = 0;
  int begin = 0, end = 0; ///< the sample numbers to render
};

// Differentiated renders: what they cannot be combined with, and the adjoint's size.
void checkGradientRequest(const RenderScene& scene, const RenderOptions& options,
                          const PixelRect& rect, const Sensor& bands) {
  const SceneTangents& t = *options.gradients;
  const bool reverse = options.adjoint != nullptr;
  if (scene.settings.mode == RenderMode::Rt)
    throw Error("gradients need a path-traced mode (spectral_mcpt or mcpt), found rt");
  if (scene.relight.enabled || options.components || options.lightGroups)
    throw Error("gradients cannot be combined with component, light-group or relightable "
                "outputs: render those separately");
  if (options.resumeFrom || options.adaptive || options.adaptivePlan)
    throw Error("gradients need a uniform render from its first sample (no --resume, no "
                "adaptive sampling)");
  if (t.reflectance.size() != scene.materials.size() ||
      t.emission.size() != scene.emission.size() || t.lights.size() != scene.lights.size())
    throw Error("internal error: gradient tangents made for another scene");
  if (!reverse && t.slots() > kMaxForwardSlots)
    throw Error("forward-mode gradients keep one spectral image per parameter: at most " +
                std::to_string(kMaxForwardSlots) + ", found " + std::to_string(t.slots()) +
                " (use reverse mode, nxrender.backward, for many parameters)");
  if (reverse) {
    const size_t expected = static_cast<size_t>(rect.width()) * rect.height() * bands.count();
    if (options.adjoint->size() != expected)
      throw Error("the adjoint image holds " + std::to_string(options.adjoint->size()) +
                  " values, expected " + std::to_string(expected) + " (" +
                  std::to_string(rect.width()) + "x" + std::to_string(rect.height()) + " x " +
                  std::to_string(bands.count()) + " bands)");
  }
}

// The pixels to render: the crop, checked to lie inside the image, or the whole image.
PixelRect renderRect(const RenderSettings& settings, const RenderOptions& options) {
  const PixelRect rect =
      options.crop ? *options.crop : PixelRect{0, 0, settings.width, settings.height};
  if (rect.x0 < 0 || rect.y0 < 0 || rect.x1 > settings.width || rect.y1 > settings.height ||
      rect.width() <= 0 || rect.height() <= 0)
    throw Error("crop " + std::to_string(rect.x0) + "," + std::to_string(rect.y0) + "," +
                std::to_string(rect.x1) + "," + std::to_string(rect.y1) +
                " is not a non-empty rectangle inside the " + std::to_string(settings.width) + "x" +
                std::to_string(settings.height) + " image");
  return rect;
}

// A relightable render's transport: one source per light group and spectrum, its spectrum
// averaged over the grid's bins, and the pattern of the transport's entries.
struct RelightSetup {
  std::shared_ptr<const RelightPattern> pattern;
  std::vector<std::vector<double>> sourceSpectra;
  std::vector<std::vector<std::vector<double>>> guides; ///< per source (RelightLayers::guides)
  std::vector<std::string> sources;
};
template <class StopIfAsked>
RelightSetup relightSetup(const RenderScene& scene, const RenderOptions& options,
                          const Sensor& bands, StopIfAsked&& stopIfAsked) {
  RelightSetup r;
  if (options.resumeFrom)
    throw Error("--relightable: continuing a relightable render (--resume) is not supported; "
                "render it again, or split it by --spp-range parts and merge them");
  if (scene.relight.ofSource.empty())
    throw Error("--relightable: the scene has no emitter to relight");
  checkRelightStep(options.relightStepNm, "--relight-step");
  const RelightGrid grid = RelightGrid::withStep(options.relightStepNm);
  // One transport per source: the emitters of a light group that share a spectrum.
  for (size_t s = 0; s < scene.relight.ofSource.size(); ++s) {
    stopIfAsked(); // thousands of sources at a fine step take a while
    r.sourceSpectra.push_back(binAverages(scene.relight.ofSource[s], grid));
    r.sources.push_back(scene.relight.name(s, scene.lightGroups));
    if (!scene.relight.targetsOfSource.empty()) {
      r.guides.emplace_back();
      for (const Spectrum& t : scene.relight.targetsOfSource[s])
        r.guides.back().push_back(binAverages(t, grid));
    }
  }
  stopIfAsked();
  r.pattern = std::make_shared<const RelightPattern>(grid, bands, scene);
  return r;
}

// Everything that scales with the layers and the transport, counted before it is allocated
// (the film's sums, the image, the tasks' accumulators and the file's writer).
void requireExtrasMemory(const RenderScene& scene, const RenderOptions& options,
                         const RenderTarget& t, const RelightSetup& relight) {
  RenderExtras extras;
  extras.width = t.rect.width(), extras.height = t.rect.height(), extras.bands = t.bands.count();
  extras.layers = t.layout.count;
  extras.lightGroupLayers =
      options.lightGroups ? static_cast<int>(scene.lightGroups.names.size()) : 0;
  extras.relightEntries = relight.pattern ? relight.pattern->size() : 0;
  extras.relightSources = relight.sources.size();
  extras.relightBins = relight.pattern ? static_cast<size_t>(relight.pattern->grid().bins) : 0;
  extras.whiteReference = options.whiteReference;
  extras.threads = static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  requireRenderExtrasMemory(extras, options.output);
}

// The request checked and its film set up (a new one, or the resumed one with the same layers).
template <class StopIfAsked>
RenderTarget renderTarget(const RenderScene& scene, const RenderOptions& options,
                          StopIfAsked&& stopIfAsked) {
  const RenderSettings& settings = scene.settings;
  const Sensor bands = options.bands ? *options.bands : settings.bands;
  if (options.targetRelativeError > 0) options.errorMeasure.requireBandsIn(bands);
  const PixelRect rect = renderRect(settings, options);
  RenderTarget t{bands,
                 rect,
                 RenderOutput{options.resumeFrom ? *options.resumeFrom
                                                 : Film(settings.width, settings.height, rect,
                                                        bands, options.whiteReference),
                              {},
                              options.firstSample,
                              0,
                              0,
                              {},
                              {}},
                 {},
                 {}};
  // Component layers: set on a new film, the same names on a resumed one.
  const std::vector<std::string> layerNames = componentLayerNames(scene, options);
  if (options.components) t.layout.classes = 0;
  if (options.lightGroups) t.layout.groups = options.components ? 4 : 0;
  t.layout.count = static_cast<int>(layerNames.size());
  if (t.layout.any() && settings.mode == RenderMode::Rt)
    throw Error("component images (--aov components, lightgroups) need a path-traced mode "
                "(spectral_mcpt or mcpt), found rt (Whitted ray tracing has no path classes)");
  t.differentiated = options.gradients != nullptr;
  t.reverse = t.differentiated && options.adjoint;
  if (t.differentiated) checkGradientRequest(scene, options, t.rect, t.bands);
  if (options.resumeFrom) {
    std::vector<std::string> held;
    for (int l = 0; l < t.out.film.layerCount(); ++l) held.push_back(t.out.film.layerName(l));
    if (held != layerNames)
      throw Error("cannot continue a render with other component layers: it holds " +
                  std::to_string(held.size()) + " (" + (held.empty() ? "none" : held.front()) +
                  (held.size() > 1 ? ", ..." : "") + "), this one asks for " +
                  std::to_string(layerNames.size()) + " (use the same --aov as the first run)");
  }
  // Ground-truth layers: set on a new film, the same ones on a resumed one.
  if (!options.aovs.empty())
    t.aovs = std::make_shared<const AovEvaluator>(scene, options.aovs, t.bands);
  if (options.resumeFrom) {
    const std::vector<AovKind> asked = t.aovs ? t.aovs->kinds() : std::vector<AovKind>{};
    if (t.out.film.aovKinds() != asked) {
      auto names = [](const std::vector<AovKind>& kinds) {
        std::string s;
        for (AovKind k : kinds) s += (s.empty() ? "" : ",") + std::string(aovName(k));
        return s.empty() ? std::string("none") : s;
      };
      throw Error("cannot continue a render with other ground-truth layers: it holds " +
                  names(t.out.film.aovKinds()) + ", this one asks for " + names(asked) +
                  " (use the same --aov as the first run)");
    }
  } else if (t.aovs) {
    t.out.film.setAovs(t.aovs->kinds());
  }
  // A relightable scene: the transport per light group on the excitation grid.
  t.relightable = scene.relight.enabled;
  RelightSetup relight;
  if (t.relightable) relight = relightSetup(scene, options, t.bands, stopIfAsked);
  stopIfAsked();
  requireExtrasMemory(scene, options, t, relight);
  if (!options.resumeFrom) t.out.film.setLayers(layerNames);
  if (t.relightable) {
    t.out.film.setRelight(std::move(relight.pattern), std::move(relight.sources),
                          std::move(relight.sourceSpectra));
    t.out.film.setRelightGuides(std::move(relight.guides));
  }
  t.out.samplesPerPixel = options.samples > 0 ? options.samples : settings.samples;
  t.out.seed = options.seed ? *options.seed : settings.seed;
  t.seed = t.out.seed;
  t.begin = options.firstSample, t.end = options.firstSample + t.out.samplesPerPixel;
  return t;
}

// The passes of a render over the target's tiles, their statistics and, in reverse mode, the
// gradient summed in tile order (so it does not depend on which thread ran which tile).
class PassRunner {
public:
  PassRunner(const RenderScene& scene, const RenderOptions& options, RenderTarget& target,
             const IntegratorContext& ctx, const WavelengthSampler& wavelengths,
             tbb::task_group_context& tileContext)
      : scene_(scene), options_(options), t_(target), out_(target.out), ctx_(ctx),
        wavelengths_(wavelengths), tileContext_(tileContext),
        whitted_(scene.settings.mode == RenderMode::Rt),
        // Adaptive renders use tiles of one plan block: late rounds add samples to few blocks,
        // and small tasks keep every thread busy (the image does not depend on the tiles).
        ts_(options.adaptive ? std::min(std::max(1, options.tileSize), kAdaptiveBlock)
                             : std::max(1, options.tileSize)),
        tilesX_((target.rect.width() + ts_ - 1) / ts_),
        tiles_(tilesX_ * ((target.rect.height() + ts_ - 1) / ts_)),
        passSize_(std::max(1, options.passSamples)),
        passes_((target.out.samplesPerPixel + passSize_ - 1) / passSize_),
        slots_(target.differentiated ? options.gradients->slots() : 0),
        // Progress counts tiles of passes; an adaptive render's passes are not known in
        // advance (its count is capped at the uniform render's).
        progressTotal_(static_cast<int64_t>(tiles_) * passes_),
        now_(options.clock ? options.clock : [] {
          return std::chrono::duration<double>(
                     std::chrono::steady_clock::now().time_since_epoch())
              .count();
        }),
        clockStart_(now_()), passStart_(clockStart_) {
    if (t_.reverse) {
      tileGradients_.resize(static_cast<size_t>(tiles_));
      gradientSum_.assign(slots_, 0.0);
      gradientVarianceSum_.assign(slots_, 0.0);
    }
  }

  // Passes of passSize samples up to the end, or until the error target is met.
  void uniformPasses() {
    for (int pass = 0; pass < passes_ && mayStartPass(); ++pass) {
      const int passEnd = std::min(t_.end, t_.begin + (pass + 1) * passSize_);
      runPass(passEnd, nullptr);
      if (!out_.stats.stopped) out_.stats.samplesReached = passEnd - t_.begin;
      if (!out_.stats.stopped && options_.targetRelativeError > 0 && passEnd < t_.end &&
          options_.errorMeasure.of(out_.film) <= options_.targetRelativeError) {
        out_.stats.reachedTarget = true;
        break;
      }
    }
  }

  // A uniform pilot (unless a plan is given), then rounds: plan from the film, render the plan
  // in passes, measure; a given plan is one round.
  void adaptiveRounds();

  // Differentiated with respect to shape: the boundary term of primary visibility, sampled on
  // the moving outlines (primary_boundary.h) and added to the gradient layers or sums.
  void boundaryTerms();

  // The statistics of the run and, in reverse mode, the gradient and its variance.
  RenderOutput finish(std::chrono::steady_clock::time_point start) {
    out_.stats.relativeError = options_.errorMeasure.of(out_.film);
    out_.stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out_.stats.samples = samples_;
    out_.stats.rays = rays_;
    out_.stats.nonFinite = nonFinite_;
    out_.stats.truncated = truncated_;
    out_.stats.bounceLimited = bounceLimited_;
    out_.stats.relightMissed = relightMissed_;
    out_.stats.gradientZeroValues = gradientZeros_;
    if (t_.reverse) {
      // Each replicate's sum estimates half the gradient; per tile, their difference squared
      // estimates the variance of the tile's share (the film's (A - B)^2 / 4 for the means).
      out_.gradient = std::move(gradientSum_);
      out_.gradientVariance = std::move(gradientVarianceSum_);
    }
    return std::move(out_);
  }

private:
  // A tile task's own buffers: the pixel being summed, the sample's layers and relight
  // contributions, the gradient tape and its forward or reverse sums.
  struct TileState {
    TraceCounters counters;
    uint64_t dropped = 0, taken = 0, missed = 0;
    Film::Pixel pixel;
    std::vector<SampledSpectrum> layers;
    RelightRecorder recorder;
    GradientTape tape;
    std::vector<SampledSpectrum> forward;
    std::vector<double> tileSums[2];
    std::vector<float> aov; ///< one sample's ground-truth channels
  };
  struct TileGradient {
    uint32_t slot;
    double even, odd; ///< the replicates' sums
  };

  // Whether another pass may start: not after a stop, nor when it would end after the time
  // limit (judged by the last pass; the first pass always runs).
  bool mayStartPass() {
    if (out_.stats.stopped) return false;
    passStart_ = now_();
    if (options_.timeLimitSeconds > 0 && anyPass_ &&
        passStart_ - clockStart_ + lastPassSeconds_ > options_.timeLimitSeconds) {
      out_.stats.reachedTimeLimit = true;
      return false;
    }
    return true;
  }

  // The stop flag is looked at before every sample (a relaxed load), so a stop takes effect
  // within one sample wherever the render is; each pixel keeps the samples it finished (its
  // count stays true, and a resume continues after them).
  bool stopping() const { return options_.stop && options_.stop->load(std::memory_order_relaxed); }

  // One pass: every pixel continues after the samples it holds up to `uniformEnd` (a sample
  // number), or with a plan up to min(planned, held + passSize) samples.
  void runPass(int uniformEnd, const AdaptivePlan* plan) {
    tbb::parallel_for(
        0, tiles_, [&](int tile) { renderTile(tile, uniformEnd, plan); }, tileContext_);
    if (options_.stop && options_.stop->load()) out_.stats.stopped = true;
    for (auto& kept : tileGradients_) {
      for (const TileGradient& g : kept) {
        gradientSum_[g.slot] += g.even + g.odd;
        gradientVarianceSum_[g.slot] += (g.even - g.odd) * (g.even - g.odd);
      }
      kept.clear();
    }
    lastPassSeconds_ = now_() - passStart_;
    anyPass_ = true;
    if (options_.afterPass) options_.afterPass(out_.film);
  }

  void renderTile(int tile, int uniformEnd, const AdaptivePlan* plan);
  // The samples of pixel (x, y) this pass adds; false when a stop halted it.
  bool renderPixel(int x, int y, int uniformEnd, const AdaptivePlan* plan, TileState& st);
  // Differentiated with respect to the camera: how its slots move the ray through film
  // position (x, y).
  void primaryMotion(double x, double y, std::vector<RayMotion>& out) const {
    out.clear();
    for (const CameraMotion& c : options_.gradients->shapes.camera) {
      Vec3d dOrigin, dDirection;
      c.ray(x, y, dOrigin, dDirection);
      out.push_back({c.slot, Vec3(dOrigin), Vec3(dDirection)});
    }
  }
  // One sample along `ray`, traced and recorded as the render's outputs ask: gradients
  // (reverse or forward), relightable transport, component layers, or the plain radiance.
  void traceSample(const Ray& ray, const SampledWavelengths& lambda, PixelSampleStream& rng,
                   bool odd, int x, int y, TileState& st) const;

  const RenderScene& scene_;
  const RenderOptions& options_;
  RenderTarget& t_;
  RenderOutput& out_;
  const IntegratorContext& ctx_;
  const WavelengthSampler& wavelengths_;
  tbb::task_group_context& tileContext_;
  const bool whitted_;
  const int ts_, tilesX_, tiles_, passSize_, passes_;
  const uint32_t slots_;
  const int64_t progressTotal_;
  std::atomic<uint64_t> rays_{0}, nonFinite_{0}, samples_{0}, truncated_{0}, bounceLimited_{0},
      relightMissed_{0}, gradientZeros_{0};
  // Reverse mode: each tile's sums per replicate (its non-zero slots), added up in tile order
  // after each pass. The gradient, and the variance of its estimate: the sum over tiles
  // (independent) of the squared differences of their replicates' sums.
  std::vector<std::vector<TileGradient>> tileGradients_;
  std::vector<double> gradientSum_, gradientVarianceSum_;
  std::atomic<int64_t> finished_{0};
  std::mutex progressMutex_;
  const std::function<double()> now_;
  double lastPassSeconds_ = 0;
  const double clockStart_;
  double passStart_;
  bool anyPass_ = false;
};

void PassRunner::renderTile(int tile, int uniformEnd, const AdaptivePlan* plan) {
  if (stopping()) return;
  const PixelRect& rect = t_.rect;
  const int x0 = rect.x0 + (tile % tilesX_) * ts_, y0 = rect.y0 + (tile / tilesX_) * ts_;
  const int x1 = std::min(x0 + ts_, rect.x1), y1 = std::min(y0 + ts_, rect.y1);
  TileState st;
  st.pixel = out_.film.newPixel();
  st.layers.resize(static_cast<size_t>(t_.layout.count));
  st.forward.resize(t_.reverse ? 0 : slots_);
  if (t_.reverse) st.tileSums[0].assign(slots_, 0.0), st.tileSums[1].assign(slots_, 0.0);
  if (t_.relightable) {
    st.recorder.spectra = &scene_.relight.ofSource;
    st.recorder.grid = out_.film.relightPattern()->grid();
    st.recorder.contributions.reserve(256);
  }
  bool halted = false;
  for (int y = y0; y < y1 && !halted; ++y)
    for (int x = x0; x < x1 && !halted; ++x) halted = !renderPixel(x, y, uniformEnd, plan, st);
  if (t_.reverse) {
    auto& kept = tileGradients_[static_cast<size_t>(tile)];
    for (uint32_t k = 0; k < slots_; ++k)
      if (st.tileSums[0][k] != 0 || st.tileSums[1][k] != 0)
        kept.push_back({k, st.tileSums[0][k], st.tileSums[1][k]});
  }
  gradientZeros_ += st.tape.zeroValues;
  rays_ += st.counters.rays;
  truncated_ += st.counters.truncated;
  bounceLimited_ += st.counters.bounceLimited;
  relightMissed_ += st.missed;
  nonFinite_ += st.dropped;
  samples_ += st.taken;
  const int64_t done = ++finished_;
  if (options_.progress) {
    std::lock_guard<std::mutex> lock(progressMutex_);
    options_.progress(std::min(done, progressTotal_), progressTotal_);
  }
}

bool PassRunner::renderPixel(int x, int y, int uniformEnd, const AdaptivePlan* plan,
                             TileState& st) {
  const int begin = t_.begin;
  const int held = static_cast<int>(out_.film.samples(x, y));
  // A planned pass adds passSize samples, or half what the pixel holds once that is more
  // (fewer passes, fewer waits at their ends; still several per round).
  const int sEnd = plan ? begin + std::min(static_cast<int>(plan->samplesAt(x, y)),
                                           held + std::max(passSize_, held / 2))
                        : uniformEnd;
  if (begin + held >= sEnd) return true;
  Film::resetPixel(st.pixel);
  const uint32_t pixelIndex =
      static_cast<uint32_t>(y) * static_cast<uint32_t>(scene_.settings.width) +
      static_cast<uint32_t>(x);
  // Two independently scrambled replicates, interleaved: even sample numbers use the seed, odd
  // ones a derived seed; each is one sequence of its own (index s / 2), and the difference of
  // their means estimates the error (randomized QMC).
  const PixelSequence replicates[2] = {
      PixelSequence(options_.sampler, pixelIndex, t_.seed),
      PixelSequence(options_.sampler, pixelIndex, t_.seed ^ kOddReplicateSalt)};
  // The white reference's own sequences, made only when it is rendered.
  std::optional<PixelSequence> whiteSequences[2];
  if (out_.film.hasWhite()) {
    whiteSequences[0].emplace(options_.sampler, pixelIndex, t_.seed ^ kWhiteSalt);
    whiteSequences[1].emplace(options_.sampler, pixelIndex,
                              t_.seed ^ kWhiteSalt ^ kOddReplicateSalt);
  }
  // Shape derivatives' boundary terms along the paths: their own sequences (salted seeds).
  std::optional<PixelSequence> boundarySequences[2];
  if (ctx_.gradients && ctx_.gradients->shapes) {
    boundarySequences[0].emplace(options_.sampler, pixelIndex, t_.seed ^ kPathBoundarySalt);
    boundarySequences[1].emplace(options_.sampler, pixelIndex,
                                 t_.seed ^ kPathBoundarySalt ^ kOddReplicateSalt);
  }
  // The ground-truth layers' own sequences (the albedo's directions), made only when kept.
  std::optional<PixelSequence> aovSequences[2];
  if (t_.aovs) {
    aovSequences[0].emplace(options_.sampler, pixelIndex, t_.seed ^ kAovSalt);
    aovSequences[1].emplace(options_.sampler, pixelIndex, t_.seed ^ kAovSalt ^ kOddReplicateSalt);
    st.aov.resize(static_cast<size_t>(t_.aovs->channels()));
  }
  bool halted = false;
  // Each pixel continues after the samples it already has (a resumed film or an adaptive plan
  // may hold more in some pixels than in others).
  for (int s = begin + held; s < sEnd; ++s) {
    if (stopping()) {
      halted = true;
      break;
    }
    const bool odd = (s & 1) != 0;
    PixelSampleStream rng(replicates[odd], static_cast<uint32_t>(s) >> 1);
    // With stratified lanes, the offset within the lanes' strata and the hero's stratum from
    // one Sobol pair (stratified jointly).
    const SampledWavelengths lambda = options_.stratifiedLanes
                                          ? sampleStratifiedLanes(wavelengths_, rng)
                                          : wavelengths_.sample(rng.next1D());
    const Sample2 jitter = rng.next2D();
    float lensX = 0, lensY = 0; // a point of the aperture, for a thin lens only
    if (scene_.camera.hasLens()) sampleConcentricDisk(rng.next2D(), lensX, lensY);
    const Ray ray = scene_.camera.generateRay(static_cast<double>(x) + jitter.u,
                                              static_cast<double>(y) + jitter.v, lensX, lensY);
    if (t_.differentiated)
      primaryMotion(static_cast<double>(x) + jitter.u, static_cast<double>(y) + jitter.v,
                    st.tape.motion.primary);
    std::optional<PixelSampleStream> boundaryRng;
    if (boundarySequences[odd])
      boundaryRng.emplace(*boundarySequences[odd], static_cast<uint32_t>(s) >> 1);
    st.tape.boundaryRng = boundaryRng ? &*boundaryRng : nullptr;
    traceSample(ray, lambda, rng, odd, x, y, st);
    if (t_.aovs) { // at the sample's own film position
      PixelSampleStream aovRng(*aovSequences[odd], static_cast<uint32_t>(s) >> 1);
      t_.aovs->evaluate(ray, aovRng, st.aov.data());
      Film::addAovSample(st.pixel, st.aov.data());
    }
    if (out_.film.hasWhite()) {
      // Its own random numbers (a salted seed): the same for every thread count.
      PixelSampleStream whiteRng(*whiteSequences[odd], static_cast<uint32_t>(s) >> 1);
      out_.film.addWhiteSample(st.pixel, lambda,
                               traceWhiteReference(ctx_, ray, lambda, whiteRng, st.counters));
    }
  }
  st.taken += Film::samplesIn(st.pixel);
  out_.film.add(x, y, st.pixel);
  return !halted;
}

void PassRunner::traceSample(const Ray& ray, const SampledWavelengths& lambda,
                             PixelSampleStream& rng, bool odd, int x, int y, TileState& st) const {
  Film& film = out_.film;
  if (t_.differentiated) {
    st.tape.clear();
    const SampledSpectrum L = tracePathGradients(ctx_, ray, lambda, rng, st.counters, st.tape);
    if (!film.addSample(st.pixel, lambda, L, odd)) {
      ++st.dropped;
    } else if (t_.reverse) {
      // d loss / d slot: each term weighted as the film weighs the lane, times d loss / d
      // band, over the pixel's sample count (uniform: the render's).
      const PixelRect& rect = t_.rect;
      const size_t p =
          static_cast<size_t>(y - rect.y0) * rect.width() + static_cast<size_t>(x - rect.x0);
      const SampledSpectrum a =
          film.adjointWeights(lambda, options_.adjoint->data() +
                                          p * static_cast<size_t>(t_.bands.count())) *
          (1.0f / static_cast<float>(out_.samplesPerPixel));
      double* sums = st.tileSums[odd].data();
      st.tape.sweep([&](uint32_t slot, int lane, float v) {
        sums[slot] += static_cast<double>(v * a[lane]);
      });
    } else {
      std::fill(st.forward.begin(), st.forward.end(), SampledSpectrum());
      st.tape.sweep([&](uint32_t slot, int lane, float v) { st.forward[slot][lane] += v; });
      bool finite = true;
      for (const SampledSpectrum& f : st.forward)
        for (int i = 0; i < kLanes; ++i) finite = finite && std::isfinite(f[i]);
      if (finite) film.addLayerSamples(st.pixel, lambda, st.forward.data(), odd);
    }
  } else if (t_.relightable) {
    std::fill(st.layers.begin(), st.layers.end(), SampledSpectrum());
    st.recorder.contributions.clear();
    const SampledSpectrum L = tracePathRelightable(ctx_, ray, lambda, rng, st.counters, t_.layout,
                                                   st.layers.data(), st.recorder);
    if (film.addSample(st.pixel, lambda, L, odd)) {
      if (t_.layout.any()) film.addLayerSamples(st.pixel, lambda, st.layers.data(), odd);
      st.missed += film.addRelightSamples(st.pixel, lambda, st.recorder.contributions, odd);
    } else {
      ++st.dropped;
    }
  } else if (t_.layout.any()) {
    std::fill(st.layers.begin(), st.layers.end(), SampledSpectrum());
    const SampledSpectrum L =
        tracePathComponents(ctx_, ray, lambda, rng, st.counters, t_.layout, st.layers.data());
    if (film.addSample(st.pixel, lambda, L, odd))
      film.addLayerSamples(st.pixel, lambda, st.layers.data(), odd);
    else
      ++st.dropped;
  } else {
    const SampledSpectrum L = whitted_ ? traceWhitted(ctx_, ray, lambda, rng, st.counters)
                                       : tracePath(ctx_, ray, lambda, rng, st.counters);
    if (!film.addSample(st.pixel, lambda, L, odd)) ++st.dropped;
  }
}

void PassRunner::boundaryTerms() {
  if (out_.stats.stopped) return;
  PrimaryBoundaryRequest req;
  req.sampler = options_.sampler;
  req.seed = t_.seed;
  req.samplesPerPixel = std::max(1, out_.stats.samplesReached);
  req.rect = t_.rect;
  req.wavelengths = [&](PixelSampleStream& rng) {
    return options_.stratifiedLanes ? sampleStratifiedLanes(wavelengths_, rng)
                                    : wavelengths_.sample(rng.next1D());
  };
  uint64_t rays = 0;
  Film& film = out_.film;
  const int bands = t_.bands.count();
  if (t_.reverse) {
    // Summed in the samples' order; the replicates' sums per slot give the variance as a
    // tile's do.
    std::vector<double> sums[2] = {std::vector<double>(slots_, 0.0),
                                   std::vector<double>(slots_, 0.0)};
    primaryBoundary(
        ctx_, req,
        [&](const BoundaryContribution& c) {
          const size_t p = static_cast<size_t>(c.y - t_.rect.y0) * t_.rect.width() +
                           static_cast<size_t>(c.x - t_.rect.x0);
          const SampledSpectrum a = film.adjointWeights(
              c.lambda, options_.adjoint->data() + p * static_cast<size_t>(bands));
          double v = 0;
          for (int i = 0; i < kLanes; ++i) v += static_cast<double>(c.value[i] * a[i]);
          sums[c.odd][c.slot] += v;
        },
        rays);
    rays_ += rays;
    for (uint32_t k = 0; k < slots_; ++k) {
      gradientSum_[k] += sums[0][k] + sums[1][k];
      gradientVarianceSum_[k] += (sums[0][k] - sums[1][k]) * (sums[0][k] - sums[1][k]);
    }
    return;
  }
  // Forward mode: each term joins its pixel's layer sums, scaled by the pixel's sample count
  // (the film divides the sums by it).
  Film::Pixel pixel = film.newPixel();
  std::vector<SampledSpectrum> layers(slots_); // a differentiated film's layers: the slots
  primaryBoundary(
      ctx_, req,
      [&](const BoundaryContribution& c) {
        Film::resetPixel(pixel);
        std::fill(layers.begin(), layers.end(), SampledSpectrum());
        const float n = static_cast<float>(film.samples(c.x, c.y));
        layers[c.slot] = c.value * n;
        film.addLayerSamples(pixel, c.lambda, layers.data(), c.odd);
        film.add(c.x, c.y, pixel);
      },
      rays);
  rays_ += rays;
}

void PassRunner::adaptiveRounds() {
  if (!(options_.targetRelativeError > 0))
    throw Error("adaptive sampling needs a target error (--target-error)");
  if (out_.samplesPerPixel < 2)
    throw Error("adaptive sampling needs at least 2 samples per pixel (one per replicate), "
                "found " +
                std::to_string(out_.samplesPerPixel));
  const auto maxSamples = static_cast<uint32_t>(out_.samplesPerPixel);
  const PixelRect& rect = t_.rect;
  const int begin = t_.begin;
  if (options_.adaptivePlan) {
    const PixelRect& pr = options_.adaptivePlan->region;
    if (rect.x0 < pr.x0 || rect.y0 < pr.y0 || rect.x1 > pr.x1 || rect.y1 > pr.y1)
      throw Error("internal error: an adaptive plan that does not cover the render's pixels");
  } else {
    // The uniform pilot: every pixel gets the same first samples (an even number, so both
    // replicates are alike), enough to estimate each block's noise.
    int pilot = std::min(std::max(options_.adaptiveMinSamples, 2), out_.samplesPerPixel);
    pilot = std::max(pilot - (pilot & 1), 2);
    for (int k = 0; begin + k * passSize_ < begin + pilot && mayStartPass(); ++k)
      runPass(std::min(begin + pilot, begin + (k + 1) * passSize_), nullptr);
  }
  // The error is judged at the end of a round only, so a round is the same work whether one
  // machine renders it or a farm renders its crops.
  constexpr int kMaxRounds = 40; // rounds at most double: 2^40 is beyond any count
  for (int round = 0; round < kMaxRounds && !out_.stats.stopped && !out_.stats.reachedTimeLimit;
       ++round) {
    if (!options_.adaptivePlan &&
        options_.errorMeasure.of(out_.film) <= options_.targetRelativeError) {
      out_.stats.reachedTarget = true;
      break;
    }
    // A given plan is used in place; a planned one lives for this round.
    std::optional<AdaptivePlan> planned;
    if (!options_.adaptivePlan)
      planned = planAdaptiveSamples(out_.film, options_.errorMeasure, options_.targetRelativeError,
                                    maxSamples);
    const AdaptivePlan& plan = options_.adaptivePlan ? *options_.adaptivePlan : *planned;
    if (!plan.addsSamplesTo(out_.film)) break;
    while (plan.addsSamplesTo(out_.film) && mayStartPass()) runPass(0, &plan);
    ++out_.stats.adaptiveRounds;
    if (options_.adaptivePlan) break;
  }
  if (!options_.adaptivePlan && !out_.stats.stopped && !out_.stats.reachedTarget &&
      options_.errorMeasure.of(out_.film) <= options_.targetRelativeError)
    out_.stats.reachedTarget = true;
  uint32_t most = 0;
  for (int y = rect.y0; y < rect.y1; ++y)
    for (int x = rect.x0; x < rect.x1; ++x) most = std::max(most, out_.film.samples(x, y));
  out_.stats.samplesReached = static_cast<int>(most);
}

} // namespace

RenderOutput render(const RenderScene& scene, const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // Every tile task runs in the same floating-point mode, whatever thread started the render:
  // the context captures the mode set here and TBB applies it to the workers' tasks.
  const FlushDenormalsScope floatMode;
  tbb::task_group_context tileContext;
  tileContext.capture_fp_settings();
  // The stop flag raised while the render is being prepared: nothing to write yet.
  const auto stopIfAsked = [&] {
    if (options.stop && options.stop->load()) throw StoppedBeforeRendering();
  };
  stopIfAsked();
  RenderTarget target = renderTarget(scene, options, stopIfAsked);
  const LightSampler lights(scene, options.lightSelection, options.triangleLightSampling);
  stopIfAsked();
  std::optional<GradientContext> gradientContext;
  if (target.differentiated) {
    gradientContext.emplace(scene, lights, *options.gradients);
    gradientContext->boundary = options.shapeBoundary;
  }
  stopIfAsked();
  const IntegratorContext ctx{&scene,
                              &lights,
                              options.lightSampling,
                              scene.hasFluorescence || options.forceFluorescencePath,
                              options.columnOnlyExcitation,
                              gradientContext ? &*gradientContext : nullptr};
  const Film& film = target.out.film;
  const WavelengthSampler wavelengths =
      options.wavelengthDensity == WavelengthDensity::Visible
          ? WavelengthSampler(film.tracedMinNm(), film.tracedMaxNm())
          : WavelengthSampler::forSensor(film.bands(), film.tracedMinNm(), film.tracedMaxNm());
  PassRunner runner(scene, options, target, ctx, wavelengths, tileContext);
  if (!options.adaptive)
    runner.uniformPasses();
  else
    runner.adaptiveRounds();
  if (gradientContext && gradientContext->shapes && options.shapeBoundary) runner.boundaryTerms();
  return runner.finish(start);
}

std::vector<std::string> warningsOf(const RenderStats& stats) {
  std::vector<std::string> out;
  const auto count = [](uint64_t n) { return std::to_string(static_cast<unsigned long long>(n)); };
  if (stats.truncated > 0)
    out.push_back(count(stats.truncated) + " rt samples reached the budget of " +
                  std::to_string(kWhittedRayBudget) +
                  " rays per sample (a tree of reflections and refractions branching at every "
                  "bounce) and kept what they had traced");
  if (stats.bounceLimited > 0) {
    char share[32];
    std::snprintf(share, sizeof share, "%.3g%%",
                  100.0 * static_cast<double>(stats.bounceLimited) /
                      static_cast<double>(std::max<uint64_t>(stats.samples, 1)));
    out.push_back(count(stats.bounceLimited) + " paths (" + share + " of the samples) reached " +
                  "the limit of " + std::to_string(kMaxPathBounces) +
                  " bounces still carrying light and were cut there: the image is darker than "
                  "the converged answer where they ended (an optically very thick medium, or "
                  "many dielectric interfaces); a thinner medium or a smaller scene in its units "
                  "renders it fully");
  }
  if (stats.relightMissed > 0)
    out.push_back(count(stats.relightMissed) +
                  " contributions of the relightable transport fell outside its pattern, or "
                  "outside its split into reflected and fluoresced light, and were dropped from "
                  "it (the radiance keeps them): relit images or their components miss that "
                  "light; this is a defect, please report the scene");
  if (stats.gradientZeroValues > 0)
    out.push_back(count(stats.gradientZeroValues) +
                  " path vertices met a differentiated value of 0 (a reflectance, an emission) "
                  "whose derivative is not 0: the estimator divides by the value, so their "
                  "share of the gradient is missed; start a fit from values above 0");
  if (stats.nonFinite > 0)
    out.push_back(count(stats.nonFinite) +
                  " samples with a NaN or infinite value were counted as zero (black)");
  return out;
}

void requireSomeFiniteSamples(const RenderStats& stats, const std::string& what) {
  if (stats.samples > 0 && stats.nonFinite == stats.samples)
    throw Error(what + ": every one of the " + std::to_string(stats.samples) +
                " samples had a NaN or infinite value; nothing was written");
}

SpectralImage toSpectralImage(const Film& film) {
  const FlushDenormalsScope floatMode; // the same float conversions on every caller's thread
  SpectralImage img;
  const PixelRect& r = film.rect();
  img.width = r.width();
  img.height = r.height();
  img.originX = r.x0;
  img.originY = r.y0;
  img.fullWidth = film.width();
  img.fullHeight = film.height();
  img.bands = film.bands();
  const int nb = film.bands().count();
  const size_t pixels = static_cast<size_t>(img.width) * img.height;
  img.radiance.resize(pixels * nb);
  img.rgb.resize(pixels * 3);
  img.xyz.resize(pixels * 3);
  img.sampleCount.resize(pixels);
  img.bandVariance.resize(pixels * nb);
  img.yVariance.resize(pixels);
  if (film.hasWhite()) img.white.resize(pixels * nb);
  for (int l = 0; l < film.layerCount(); ++l)
    img.layers.push_back(
        {film.layerName(l), std::vector<float>(pixels * nb), std::vector<float>(pixels * nb)});
  // Ground-truth layers: each its share of the film's channels, in order.
  std::vector<int> aovFirst;
  for (int at = 0; AovKind k : film.aovKinds()) {
    const int n = aovChannelCount(k, nb);
    img.aovs.push_back({aovName(k), std::vector<float>(pixels * static_cast<size_t>(n))});
    aovFirst.push_back(at);
    at += n;
  }
  if (const RelightPattern* pattern = film.relightPattern()) {
    RelightLayers& rl = img.relight;
    rl.grid = pattern->grid();
    rl.entries = pattern->entries();
    rl.split = true;
    rl.sources = film.relightSourceNames();
    rl.spectra = film.relightSourceSpectra();
    rl.guides = film.relightGuides();
    const size_t n = static_cast<size_t>(film.relightSources()) * rl.size() * pixels;
    rl.values.resize(n);
    rl.halfDifferences.resize(n);
  }
  // Rows in parallel (each value is computed the same way on any thread).
  tbb::parallel_for(0, img.height, [&](int row) {
    const FlushDenormalsScope rowMode;
    const int y = r.y0 + row;
    for (int x = r.x0; x < r.x1; ++x) {
      const size_t i = static_cast<size_t>(row) * img.width + static_cast<size_t>(x - r.x0);
      for (size_t l = 0; l < img.aovs.size(); ++l) {
        const size_t n = img.aovs[l].values.size() / pixels;
        for (size_t c = 0; c < n; ++c)
          img.aovs[l].values[i * n + c] =
              static_cast<float>(film.aovMean(x, y, aovFirst[l] + static_cast<int>(c)));
      }
      for (int b = 0; b < nb; ++b) {
        img.radiance[i * nb + b] = static_cast<float>(film.bandMean(x, y, b));
        img.bandVariance[i * nb + b] = static_cast<float>(film.bandVariance(x, y, b));
        if (film.hasWhite()) img.white[i * nb + b] = static_cast<float>(film.whiteMean(x, y, b));
        for (int l = 0; l < film.layerCount(); ++l) {
          ImageLayer& layer = img.layers[static_cast<size_t>(l)];
          layer.values[i * nb + b] = static_cast<float>(film.layerMean(x, y, l, b));
          layer.variances[i * nb + b] = static_cast<float>(film.layerVariance(x, y, l, b));
        }
      }
      img.yVariance[i] = static_cast<float>(film.yVariance(x, y));
      setPixelColour(img, i, film.xyzMean(x, y));
      img.sampleCount[i] = film.samples(x, y);
      RelightLayers& rl = img.relight;
      for (int g = 0; g < film.relightSources(); ++g)
        for (size_t e = 0; e < rl.size(); ++e) {
          const size_t k = (static_cast<size_t>(g) * rl.size() + e) * pixels + i;
          const int entry = static_cast<int>(e);
          rl.values[k] = static_cast<float>(film.relightMean(x, y, g, entry));
          rl.halfDifferences[k] = static_cast<float>(film.relightHalfDifference(x, y, g, entry));
        }
    }
  });
  return img;
}

Film filmFromImage(const SpectralImage& img, int firstSample, int maxSamples) {
  if (img.sampleCount.empty() || img.xyz.empty())
    throw Error("the image holds no per-pixel sample counts or XYZ channels to continue from");
  const int nb = img.bands.count();
  const size_t pixels = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
  // What a render of ours can hold: counts within the range, finite non-negative values.
  // Anything else (a file edited or made by another tool) would be copied into the output.
  auto where = [&](size_t i) {
    return "pixel " + std::to_string(img.originX + static_cast<int>(i % img.width)) + "," +
           std::to_string(img.originY + static_cast<int>(i / img.width));
  };
  auto check = [&](const std::vector<float>& v, size_t perPixel, const char* what) {
    for (size_t k = 0; k < v.size(); ++k)
      if (!(v[k] >= 0 && std::isfinite(v[k])))
        throw Error(where(k / perPixel) + ": expected finite values >= 0 in " + what +
                    " to continue from, found " + numberText(v[k]));
  };
  check(img.radiance, static_cast<size_t>(nb), "the spectral channels");
  check(img.xyz, 3, "X, Y, Z");
  check(img.bandVariance, static_cast<size_t>(nb), "the Variance channels");
  check(img.yVariance, 1, "Variance.Y");
  check(img.white, static_cast<size_t>(nb), "the white-reference channels");
  for (const ImageLayer& l : img.layers) {
    check(l.values, static_cast<size_t>(nb), "a component layer");
    check(l.variances, static_cast<size_t>(nb), "a component layer's variances");
  }
  for (size_t i = 0; i < pixels; ++i)
    if (img.sampleCount[i] > static_cast<uint32_t>(maxSamples))
      throw Error(where(i) + ": expected at most the " + std::to_string(maxSamples) +
                  " samples of the render's range, found " + std::to_string(img.sampleCount[i]));
  Film film(img.displayWidth(), img.displayHeight(),
            {img.originX, img.originY, img.originX + img.width, img.originY + img.height},
            img.bands, !img.white.empty());
  std::vector<std::string> layerNames;
  for (const ImageLayer& l : img.layers) layerNames.push_back(l.name);
  film.setLayers(layerNames);
  // Ground-truth layers: finite values (normals and positions may be negative).
  std::vector<AovKind> aovKinds;
  for (const AovImageLayer& l : img.aovs) {
    const auto k = aovKindNamed(l.name);
    if (!k) throw Error("the image holds a ground-truth layer nxrender does not make: " + l.name);
    aovKinds.push_back(*k);
    for (size_t v = 0; v < l.values.size(); ++v)
      if (!std::isfinite(l.values[v]))
        throw Error(where(v / (l.values.size() / pixels)) + ": expected finite values in the " +
                    l.name + " layer to continue from, found " + numberText(l.values[v]));
  }
  film.setAovs(aovKinds);
  std::vector<float> aovMeans(static_cast<size_t>(film.aovChannels()));
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const size_t i = static_cast<size_t>(y) * img.width + x;
      const double xyz[3] = {img.xyz[i * 3], img.xyz[i * 3 + 1], img.xyz[i * 3 + 2]};
      film.setFromMeans(img.originX + x, img.originY + y, &img.radiance[i * nb],
                        img.bandVariance.empty() ? nullptr : &img.bandVariance[i * nb], xyz,
                        img.yVariance.empty() ? 0.0 : img.yVariance[i], img.sampleCount[i],
                        oddSamplesIn(firstSample, img.sampleCount[i]),
                        img.white.empty() ? nullptr : &img.white[i * nb]);
      for (size_t l = 0, at = 0; l < img.aovs.size(); ++l) {
        const size_t n = img.aovs[l].values.size() / pixels;
        std::copy_n(&img.aovs[l].values[i * n], n, aovMeans.begin() + static_cast<long>(at));
        at += n;
      }
      if (!aovMeans.empty())
        film.setAovFromMeans(img.originX + x, img.originY + y, aovMeans.data());
      for (size_t l = 0; l < img.layers.size(); ++l)
        film.setLayerFromMeans(
            img.originX + x, img.originY + y, static_cast<int>(l), &img.layers[l].values[i * nb],
            img.layers[l].variances.empty() ? nullptr : &img.layers[l].variances[i * nb]);
    }
  return film;
}

void addGeometryAovs(const RenderScene& scene, SpectralImage& image) {
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  image.objectId.assign(pixels, 0);
  image.materialId.assign(pixels, 0);
  image.depth.assign(pixels, 0.0f);
  const Vec3d eye = scene.camera.position(), forward = scene.camera.forward();
  tbb::parallel_for(0, image.height, [&](int row) {
    for (int col = 0; col < image.width; ++col) {
      const double x = image.originX + col + 0.5, y = image.originY + row + 0.5;
      const Ray ray = scene.camera.generateRay(x, y, 0.0f, 0.0f); // the pixel centre, lens centre
      SurfaceHit hit;
      if (!scene.geometry->intersect(ray, hit)) continue;
      const size_t i = static_cast<size_t>(row) * image.width + col;
      const ShapeAppearance& app = scene.appearance(hit);
      image.objectId[i] = app.objectId;
      image.materialId[i] = app.materialId;
      const Vec3d p(hit.p.x, hit.p.y, hit.p.z);
      image.depth[i] = static_cast<float>(dot(p - eye, forward));
    }
  });
}

std::vector<uint8_t> previewPixels(const SpectralImage& image) {
  Xyz white = d65WhiteXyz();
  if (const auto it = image.attributes.find("nxrender.previewWhite");
      it != image.attributes.end()) {
    std::stringstream in(it->second);
    char comma;
    in >> white.x >> comma >> white.y >> comma >> white.z;
    if (!in || !(white.y > 0)) white = d65WhiteXyz();
  }
  std::vector<Xyz> xyz;
  for (size_t i = 0; i + 2 < image.xyz.size(); i += 3)
    xyz.push_back({image.xyz[i], image.xyz[i + 1], image.xyz[i + 2]});
  return previewPixels(xyz, white);
}

std::vector<uint8_t> previewPixels(const std::vector<Xyz>& xyz, const Xyz& w) {
  // Bradford cone response matrix (Lam 1985), von Kries scaling from `w` to D65.
  const Matrix3 bradford{
      {{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
  const Xyz d65 = d65WhiteXyz();
  const Vector3d src = multiply(bradford, {w.x / w.y, 1.0, w.z / w.y});
  const Vector3d dst = multiply(bradford, {d65.x, d65.y, d65.z});
  const Matrix3 inv = inverse(bradford);
  Matrix3 adapt{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) adapt[i][j] += inv[i][k] * (dst[k] / src[k]) * bradford[k][j];
  std::vector<Rgb> rgb;
  rgb.reserve(xyz.size());
  for (const Xyz& c : xyz) {
    const Vector3d a = multiply(adapt, {c.x, c.y, c.z});
    rgb.push_back(xyzToLinearSrgb({a[0], a[1], a[2]}));
  }
  return tonemapReinhard(rgb, {});
}

std::vector<uint8_t> previewPixels(const Film& film, const Spectrum& white) {
  std::vector<Xyz> xyz;
  const PixelRect& r = film.rect();
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) xyz.push_back(film.xyzMean(x, y));
  return previewPixels(xyz, spectrumToXyz(white));
}

} // namespace nx
