#pragma once
// A material kind: its name, the parameters it takes (with defaults and meaning) and how it is
// built from them. Each kind is one file of integrators/materials/kinds/; the registry
// (material_kind.cpp) lists them. The scene loader checks parameters against the schema (a
// parameter a kind does not take is an error at its file:line), the builder calls `build`,
// the reference docs (docs/reference/materials.md) are printed from it.

#include <array>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "core/params/parameter_set.h"
#include "integrators/materials/material.h"

namespace nx {

/// What a spectrum reference stands for: its names and checks differ (an emission takes the
/// illuminant names and is checked to be within [0, kMaxEmission]; a coefficient takes the
/// medium tables' names and the reflectance names).
enum class SpectrumRole {
  Reflectance,
  Emission,      ///< emitted radiance: held to [0, kMaxEmission]
  EmissionShape, ///< an emission's shape, any scale (a dye's): named emissions, no limit
  Coefficient
};

/// What a kind's build needs from the scene around it: references resolved (spectra by name,
/// files read into the render key), and the object it is built for. Implemented by the scene
/// builder; called once per material, never while rendering.
class MaterialInputs {
public:
  virtual ~MaterialInputs() = default;
  /// A spectrum reference resolved (emission spectra checked to lie within range).
  virtual Spectrum spectrum(const SpectrumDesc& d, SpectrumRole role) const = 0;
  /// An index of refraction checked over the traced range.
  virtual IorModel ior(const IorDesc& d) const = 0;
  /// The parametric re-radiation model, checked.
  virtual FluorescenceModel fluorescenceModel(const FluorescenceDesc& d) const = 0;
  /// A measured matrix read from its CSV file (or given as numbers); `rho`: the surface's
  /// reflectance, the elastic part of a matrix without a diagonal (null: a texture's).
  virtual std::shared_ptr<const ReradiationMatrix> measuredMatrix(const FluorescenceDesc& d,
                                                                  const Spectrum* rho) const = 0;
  /// A surface dye's concentration map read from its CSV file (or given as numbers), its
  /// content in the render key.
  virtual std::shared_ptr<const ConcentrationMap>
  concentrationMap(const FluorescenceDesc& d) const = 0;
  /// Records a warning ("file:line: warning: ...") the render prints.
  virtual void warn(const std::string& message) const = 0;
  /// A reflectance texture read from its file (or the built-in chart).
  virtual std::shared_ptr<const ReflectanceTexture> texture(const SpectrumDesc& d) const = 0;
  /// An sRGB reflectance colour upsampled to a spectrum (rt and mcpt's <color>).
  virtual Spectrum srgbReflectance(const std::array<double, 3>& rgb) const = 0;

  bool emitter = false;     ///< the object also emits light
  bool spectral = true;     ///< spectral_mcpt (else rt or mcpt: <color> preferred)
  SourceLocation objectLoc; ///< the object (or <material id>) the material is built for
  std::string kindName;     ///< the kind as written
};

/// One parameter a kind takes.
struct KindParameter {
  const char* name;        ///< a name of materialParameters() (core/params/material_parameters.h)
  const char* defaultText; ///< its default as a scene would write it ("" : none)
  const char* doc;         ///< what it does for this kind ("": the parameter's own line)
};

/// A material kind.
struct MaterialKindSpec {
  const char* name;                      ///< as written in <material>kind</material>
  const char* doc;                       ///< one line for the reference docs
  std::span<const KindParameter> params; ///< the parameters it takes
  /// Why a parameter it does not take is refused, where that is not obvious ({param, why}).
  std::span<const std::pair<const char*, const char*>> refusals;
  /// Builds the material from its checked parameters.
  Material (*build)(const MaterialKindSpec& kind, const ParameterSet& params,
                    const MaterialInputs& in);
  /// Parameters (scene text after `<material>name</material>`) that reach its scattering
  /// model in the ways that change its lobes (rough and smooth, narrow, anisotropic,
  /// dispersive): the conformance tests check each one, the reference docs list them.
  std::span<const char* const> examples;

  /// The declaration of a parameter it takes, or null.
  const KindParameter* param(std::string_view name) const;
  /// The default of a number parameter it takes (its defaultText as a number).
  double numberDefault(std::string_view name) const;
};

/// The registered kinds, in the order lists of them are written.
std::span<const MaterialKindSpec* const> materialKinds();

/// The kind called `name`, or null.
const MaterialKindSpec* findMaterialKind(std::string_view name);

/// "matte, metal, ..., conductor or coated": the kinds' names for messages.
std::string materialKindList();

/// Checks that `kind` takes every parameter in `params`; throws nx::Error at the first one it
/// does not take: "file:line: expected only <color>, <reflectance>, <roughness> or
/// <fluorescence> on matte, found <alpha>".
void checkMaterialParameters(const MaterialKindSpec& kind, const ParameterSet& params);

// ---- what the kinds' builds share (material_kind.cpp) ----

/// The kind's reflectance (or transmission tint) from <reflectance> (spectral_mcpt first) or
/// <color> (rt and mcpt first), a texture, or a fallback when neither is given: `clear` for
/// dielectrics (1), black for an emitter, else an error.
void setSurfaceReflectance(Material& m, const ParameterSet& p, const MaterialInputs& in, bool clear,
                           const char* what);
/// The <fluorescence> of the diffuse lobe, if given.
void setFluorescence(Material& m, const ParameterSet& p, const MaterialInputs& in);
/// GGX roughness from <alpha> or <alpha_u> and <alpha_v> (0, 0 if absent).
void setGgxAlpha(Material& m, const ParameterSet& p);
/// The thin-film <coating>, if given.
void setCoating(Material& m, const ParameterSet& p, const MaterialInputs& in);
/// Throws "file:line: expected a WHAT within [0, 1] at every wavelength ..." if `s` leaves it.
void checkUnitRange(const Spectrum& s, const SourceLocation& loc, const char* what);
/// "300-1100 nm": the traced range, where every spectrum is checked.
std::string tracedRange();

} // namespace nx
