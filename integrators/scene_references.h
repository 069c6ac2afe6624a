#pragma once
// What a scene refers to, resolved once while it is built: spectra by name (the scene's
// <spectrum> definitions, the built-in tables and illuminants, CSV files), every file it reads
// folded into the content digest (the render key of resume and merge), and the tables it uses
// without an extrapolation choice (for the warnings of renders that trace beyond them).

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "integrators/materials/material_kind.h"
#include "integrators/render_scene.h"
#include "io/scene_desc.h"

namespace nx {

/// The references of one scene being built.
class SceneReferences {
public:
  /// Starts from the scene text's digest and its <spectrum> definitions.
  explicit SceneReferences(const SceneDesc& desc);

  /// A spectrum reference resolved; an emission is checked to lie within [0, kMaxEmission].
  /// Errors name the reference's file:line.
  Spectrum resolve(const SpectrumDesc& s, SpectrumRole role) const;
  /// A file the scene refers to, read (bounded: a regular file of at most maxBytes) and folded
  /// into the digest with its path.
  std::string readFile(const std::string& path, std::uintmax_t maxBytes, const char* what) const;
  /// Folds bytes that stand for `path` (a mesh's, an edit's) into the digest.
  void fold(std::string_view bytes, const std::string& path) const;
  /// Notes a table used over [lo, hi] nm only (0 beyond).
  void noteTable(TabulatedRange t) const { tables_.push_back(std::move(t)); }

  /// Digest of the scene text and every file read so far.
  uint64_t digest() const { return digest_; }
  /// Tables used without an extrapolate="..." choice.
  const std::vector<TabulatedRange>& tables() const { return tables_; }
  /// Warnings of the resolution ("file:line: warning: ...": negative values clamped).
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// Throws "<loc>: expected an emission within [0, 1e12] ..." unless `s` is one at every
  /// traced wavelength.
  static void checkEmission(const Spectrum& s, const SourceLocation& loc);

private:
  Spectrum extrapolated(Spectrum r, SpectrumDesc::Extrapolation mode, const SourceLocation& loc,
                        const std::string& what) const;
  Spectrum resolveUnchecked(const SpectrumDesc& s, SpectrumRole role, int depth,
                            SpectrumDesc::Extrapolation mode) const;

  std::map<std::string, const NamedSpectrumDesc*> named_;
  mutable std::vector<TabulatedRange> tables_;
  mutable std::vector<std::string> warnings_;
  /// A table with negative="clamp": its negative values set to 0, counted in a warning.
  TabulatedSpectrum clamped(TabulatedSpectrum t, const SpectrumDesc& s,
                            const std::string& what) const;
  mutable uint64_t digest_;
};

} // namespace nx
