#pragma once
// One render as the command line and the Python module run it: the choices beyond the scene
// turned into RenderOptions, the render key that identifies what the image estimates, and the
// spectral image of a film with its provenance attributes. Both front ends go through this
// code, so the same scene, seed and samples give the same image bit for bit.

#include <optional>
#include <string>
#include <vector>

#include "integrators/renderer.h"
#include "io/scene_desc.h"

namespace nx {

/// What a render does beyond its scene: the command line's options, by their names there.
struct RenderChoices {
  int samples = 0;               ///< samples per pixel; 0 = the scene's <sampl>
  int firstSample = 0;           ///< first sample of each pixel's sequence (--spp-range A:B)
  std::optional<uint32_t> seed;  ///< default: the scene's <seed>
  std::optional<Sensor> bands;   ///< default: the scene's <bands>/<sensor>
  std::optional<PixelRect> crop; ///< default: the whole image
  bool sampleRange = false;      ///< firstSample/samples came from a sample range
  /// The strategies (strategyOptions(): each one's values, its default first).
  std::string sampler = "stratified";   ///< stratified, sobol or independent
  std::string lightSampling = "mis";    ///< mis, bsdf or nee
  std::string lightSelection = "local"; ///< local, power or uniform
  std::string density = "sensor";       ///< sensor or visible
  bool noFluorescence = false;          ///< fluorescent materials as their plain reflectance
  bool aovWhite = false, aovIds = false, aovDepth = false; ///< extra channels
  bool aovComponents = false, aovLightGroups = false;      ///< component layers
  std::vector<AovKind> aovKinds; ///< ground-truth layers (normals, position, albedo, ...)
  /// Keep the transport per light group (--relightable; the scene built with
  /// SceneDesc::relightable) on an excitation grid of relightStepNm (--relight-step).
  bool relightable = false;
  double relightStepNm = 5;
  double targetError = 0;            ///< stop at this relative RMS error; 0 = off
  std::string errorOf = "luminance"; ///< luminance, bands or bands:LO-HI
  double timeLimit = 0;              ///< seconds; 0 = off
  bool adaptive = false;             ///< adaptive sampling towards targetError
  int adaptiveMinSamples = 16;       ///< its uniform pilot, samples per pixel
};

/// A sensor from an option's text: a description (gaussian:..., boxes:..., table:...,
/// START:END:STEP) or the name of a CSV file of measured responses. `option` names it in errors.
Sensor sensorFromOption(const std::string& text, const std::string& option);

/// Asks for the layer `name` (--aov, aovs=: an extra layer or a ground-truth layer); false for
/// any other name.
bool addAov(RenderChoices& choices, const std::string& name);

/// Every name --aov and aovs= take: the extra layers (white, ids, ...), then the ground-truth
/// layers (NX_AOV_LAYERS), each quoted by `quote`, joined by ", " and `last` before the last.
std::string aovOptionList(const std::string& quote, const std::string& last);

/// --aov's help: every layer's name with its channels and what it holds.
std::string aovOptionHelp();

/// A strategy option of RenderChoices (sampler, light sampling, light selection, wavelength
/// density): its field, its command-line name, the values it takes (the default first: the
/// field's initial value, tested) and its help text.
struct StrategyOption {
  std::string RenderChoices::*field; ///< the choice
  const char* option;                ///< "--light-sampling"
  std::vector<std::string> values;   ///< {"mis", "bsdf", "nee"}
  const char* help;                  ///< what the option chooses, for --help and docs
};

/// The strategy options, checked by RenderJob; nxrender's options and the Python module's
/// parameters (named after them) are made from this table.
const std::vector<StrategyOption>& strategyOptions();

/// A render of one built scene with one set of choices.
class RenderJob {
public:
  /// Checks the choices against the scene (crop inside the image, sample range, names of
  /// samplers and strategies); throws nx::Error naming the option. `scenePath` is recorded in
  /// the image's attributes.
  RenderJob(const RenderScene& scene, std::string scenePath, const RenderChoices& choices);

  /// The choices it was made with.
  const RenderChoices& choices() const { return choices_; }
  /// The options for nx::render (hooks such as stop and progress are the caller's to set).
  RenderOptions& options() { return options_; }
  /// What the image estimates: scene content (text and files), options that change the image,
  /// lanes and version (hex).
  const std::string& renderKey() const { return renderKey_; }
  uint32_t seed() const { return seed_; }
  /// The bands rendered.
  const Sensor& bands() const { return bands_; }
  int firstSample() const { return firstSample_; }
  /// Samples per pixel of the image (after a target error or time limit: those reached).
  int samples() const { return samples_; }
  /// The pixels rendered.
  PixelRect rect() const;
  /// Records a render that ended early at `reached` samples per pixel.
  void setSamplesReached(int reached) { samples_ = reached; }
  /// The spectral image of a film of this render with its provenance attributes.
  SpectralImage image(const Film& film, double seconds) const;

private:
  const RenderScene& scene_;
  std::string scenePath_;
  RenderChoices choices_;
  RenderOptions options_;
  std::string renderKey_;
  uint32_t seed_ = 0;
  Sensor bands_;
  int firstSample_ = 0, samples_ = 0;
};

} // namespace nx
