#pragma once
// Rendering a scene: progressive passes of samples, each pass TBB tasks over image tiles;
// each sample a pure function of (pixel, sample index, seed), so the image does not depend
// on the thread count, and renders split by crops or sample ranges merge exactly.

#include <atomic>
#include <functional>
#include <optional>

#include "integrators/adaptive_plan.h"
#include "integrators/error_measure.h"
#include "integrators/film.h"
#include "integrators/gradients/scene_tangents.h"
#include "integrators/integrator.h"
#include "integrators/render_scene.h"
#include "io/exr_compression.h"
#include "io/spectral_exr.h"

namespace nx {

/// The density wavelengths are drawn from (see WavelengthSampler).
enum class WavelengthDensity { Sensor, Visible };

/// What render() throws when its stop flag is raised while the render is being prepared
/// (before its first sample: the relight pattern, the sources' spectra, the light sampler):
/// nothing was rendered.
class StoppedBeforeRendering : public Error {
public:
  StoppedBeforeRendering() : Error("stopped before rendering began") {}
};

/// The EXR a render will be written to, as far as its memory goes.
struct RenderFileOutput {
  ExrEncoding encoding;
  bool halfFloats = false;
  bool withoutVariance = false; ///< written from a copy without the variance channels
};

/// What to render beyond the scene itself.
struct RenderOptions {
  int samples = 0;     ///< samples per pixel; 0 = the scene's <sampl>
  int firstSample = 0; ///< render samples [firstSample, firstSample + samples) of each pixel
  std::optional<PixelRect> crop; ///< default: the whole image
  std::optional<uint32_t> seed;  ///< default: the scene's <seed>
  std::optional<Sensor> bands;   ///< default: the scene's <bands> or <sensor>
  LightSampling lightSampling = LightSampling::Mis;
  LightSelection lightSelection = LightSelection::Local; ///< how next-event estimation picks lights
  /// Where wavelengths are drawn: the sensor's bands and the colour range (default), or the
  /// visible density alone (the density of earlier versions, for comparisons).
  WavelengthDensity wavelengthDensity = WavelengthDensity::Sensor;
  /// Also estimate the white reference (traceWhiteReference) per band: one more path per
  /// sample, in every mode.
  bool whiteReference = false;
  /// Also split the radiance into component layers (path tracing only): reflected, fluoresced,
  /// direct, indirect (components) and one layer per light group (lightGroups); see
  /// componentLayerNames.
  bool components = false, lightGroups = false;
  /// Also keep these ground-truth layers of the first hit (integrators/aov_layers.h), averaged
  /// over each pixel's samples like the radiance.
  std::vector<AovKind> aovs;
  /// Excitation grid step (nm) of a relightable render (a scene built with
  /// SceneDesc::relightable): the film keeps the transport per light group on it.
  double relightStepNm = 5;
  SamplerKind sampler = SamplerKind::SobolOwen;
  int tileSize = 16;
  int passSamples = 8; ///< samples per pixel in one pass (progress, checkpoints, stops)
  /// Stop after the first pass whose estimated relative RMS error is at most this; 0: off.
  double targetRelativeError = 0;
  /// Which error targetRelativeError and RenderStats::relativeError mean.
  ErrorMeasure errorMeasure;
  /// Adaptive sampling (needs targetRelativeError): after a uniform pilot of
  /// adaptiveMinSamples, rounds of planAdaptiveSamples, each rendered to its plan in passes of
  /// passSamples, until the estimated error meets the target or no block may take more;
  /// `samples` is then the most any pixel takes.
  bool adaptive = false;
  int adaptiveMinSamples = 16; ///< the uniform pilot of adaptive sampling (at least 2)
  /// One adaptive round from a given plan instead (a farm round: every part renders its crop
  /// of the plan made from the whole image, continuing resumeFrom); no pilot.
  const AdaptivePlan* adaptivePlan = nullptr;
  /// Do not start a pass that would end after this many seconds (judged by the last pass's
  /// duration; the first pass always runs); 0: off.
  double timeLimitSeconds = 0;
  /// Seconds on some monotonic clock, for the time limit (default: the steady clock; tests
  /// substitute a simulated one).
  std::function<double()> clock;
  /// Runs the fluorescence-capable path tracer even without fluorescent materials (to
  /// measure what the feature costs when present but unused).
  bool forceFluorescencePath = false;
  /// Draws fluorescent vertices' excitation wavelengths from the matrix column alone, without
  /// the light-guided strategy (to measure what guiding buys; nxbench-fluorescence).
  bool columnOnlyExcitation = false;
  /// How emitting triangles are sampled (Area: the strategy before solid-angle sampling, to
  /// measure what it buys; nxbench-area-lights).
  TriangleLightSampling triangleLightSampling = TriangleLightSampling::SolidAngle;
  /// Draws each sample's wavelengths from both coordinates of the first Sobol pair
  /// (WavelengthSampler::sample(offset, heroStratum)), so that a pixel's lanes are stratified
  /// over its samples (`--sampler stratified`, the default): 1.8-3.4x less variance per band
  /// than one coordinate, u + i / kLanes (off: `--sampler sobol`; docs/performance.md).
  bool stratifiedLanes = true;
  /// When set, no new tile is started once it becomes true (SIGINT, SIGTERM, time limit);
  /// the film then holds every finished tile's samples with their true counts.
  const std::atomic<bool>* stop = nullptr;
  /// A film to continue (resume): each pixel continues after the samples it already has.
  const Film* resumeFrom = nullptr;
  /// Called after each finished tile with (finished, total); may be called from any thread,
  /// never concurrently.
  std::function<void(int64_t, int64_t)> progress;
  /// A differentiated render (docs/inverse.md): the derivatives of the scene's appearance data
  /// per slot. Forward mode (adjoint null): the film keeps one layer "gradient.<slot>" per slot,
  /// d radiance / d slot per band with its variance. Reverse mode: RenderOutput::gradient.
  const SceneTangents* gradients = nullptr;
  /// Shape derivatives: sample the boundary terms where visibility changes (false: the
  /// interior term alone, which misses them; for checks that they matter).
  bool shapeBoundary = true;
  /// Reverse mode: d loss / d image, [pixel of the render's rectangle, row by row][band]; the
  /// output is then d loss / d slot for every slot (RenderOutput::gradient).
  const std::vector<float>* adjoint = nullptr;
  /// Called on the calling thread after each pass with the film so far (checkpoints).
  std::function<void(const Film&)> afterPass;
  /// How the caller will write the image (nxrender's EXR), so that the memory check made before
  /// the layers and the transport are allocated counts the writer's buffers too; unset for an
  /// image kept in memory (Python).
  std::optional<RenderFileOutput> output;
};

/// Counters of a finished render.
struct RenderStats {
  double seconds = 0;
  uint64_t samples = 0;       ///< pixel samples taken by this run
  uint64_t rays = 0;          ///< camera, scattered and shadow rays
  uint64_t nonFinite = 0;     ///< samples with a NaN or infinite value (counted as zero)
  uint64_t truncated = 0;     ///< rt samples that reached kWhittedRayBudget
  uint64_t bounceLimited = 0; ///< paths ended by kMaxPathBounces still carrying light
  uint64_t relightMissed = 0; ///< relightable contributions outside the pattern (dropped)
  /// Differentiated renders: path events whose differentiated value was 0 where its derivative
  /// is not (their share of the derivative is missed; warningsOf reports it)
  uint64_t gradientZeroValues = 0;
  bool stopped = false;          ///< ended early by the stop flag
  bool reachedTarget = false;    ///< ended because the error target was met
  bool reachedTimeLimit = false; ///< ended because the next pass would pass the time limit
  int samplesReached = 0;        ///< samples per pixel after the last completed pass
  int adaptiveRounds = 0;        ///< planned rounds rendered (adaptive sampling)
  double relativeError = 0;      ///< estimated relative RMS error at the end
};

/// A finished (or stopped) render.
struct RenderOutput {
  Film film;
  RenderStats stats;
  int firstSample = 0, samplesPerPixel = 0; ///< the requested sample range
  uint32_t seed = 0;
  /// Reverse mode: d loss / d slot, and the variance of each estimate (from the two
  /// replicates); empty otherwise.
  std::vector<double> gradient, gradientVariance;
};

/// Most slots a forward-mode render keeps (each is a spectral layer of the film); reverse mode
/// has no such limit.
inline constexpr uint32_t kMaxForwardSlots = 64;

/// The warnings a finished render's counts call for, one sentence each (without a program
/// prefix): rt samples cut at the ray budget, paths cut at kMaxPathBounces still carrying light
/// (a dense medium or a deep stack of dielectrics renders darker than its converged answer),
/// non-finite samples counted as black. Empty when there is nothing to say.
std::vector<std::string> warningsOf(const RenderStats& stats);

/// Throws nx::Error naming `what` when every sample of a render was non-finite: such an
/// image holds nothing and must not be written as a black one.
void requireSomeFiniteSamples(const RenderStats& stats, const std::string& what);

/// The component layers a render with these options keeps, in film order: "reflected",
/// "fluoresced", "direct", "indirect" (components), then "light.NAME" per light group of the
/// scene (lightGroups).
std::vector<std::string> componentLayerNames(const RenderScene& scene,
                                             const RenderOptions& options);

/// Renders the scene with its mode (spectral_mcpt and mcpt: path tracing; rt: Whitted).
RenderOutput render(const RenderScene& scene, const RenderOptions& options);

/// The spectral image of a film (its rectangle inside the full image): band means, XYZ,
/// linear sRGB from XYZ with negatives clamped to 0, and per-pixel sample counts.
SpectralImage toSpectralImage(const Film& film);

/// Adds the geometry AOVs of the image's pixels: ObjectId and MaterialId of the surface seen
/// through each pixel's centre (0 for none) and its depth (camera-space z, 0 for none).
void addGeometryAovs(const RenderScene& scene, SpectralImage& image);

/// Loads a film from a spectral image whose pixels hold samples firstSample onwards (to
/// resume a render of maxSamples samples per pixel). Refuses, naming the pixel, counts above
/// maxSamples and values that are negative or not finite.
Film filmFromImage(const SpectralImage& image, int firstSample, int maxSamples);

/// An 8-bit preview of linear XYZ pixels: white-balanced from the chromaticity of `white`
/// to D65 (Bradford), converted to sRGB, tone-mapped (Reinhard 2002). Interleaved RGB bytes.
std::vector<uint8_t> previewPixels(const std::vector<Xyz>& xyz, const Xyz& white);

/// The preview of an image from its X, Y, Z, white-balanced to the chromaticity its attribute
/// nxrender.previewWhite gives (D65 without one).
std::vector<uint8_t> previewPixels(const SpectralImage& image);

/// The preview of a film's rectangle.
std::vector<uint8_t> previewPixels(const Film& film, const Spectrum& white);

} // namespace nx
