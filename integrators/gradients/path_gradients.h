#pragma once
// Derivatives of a path's contributions with respect to the scene's parameters, estimated along
// the path with its sampling detached from the parameters (Vicini et al. 2021, "Path replay
// backpropagation"; Zeltner et al. 2021 on detached sampling). A contribution is
// c = prod_i f_i / p_i: its derivative is c sum_i (d f_i / d theta) / f_i, the densities p_i held
// at their sampled values. The path records each vertex's log-derivatives g_i = f_i' / f_i
// (per slot and lane) on a tape; each contribution records where on the tape it arrived. At the
// path's end one backward sweep gives every slot's derivative: sum_i g_i (sum of the
// contributions after event i) - forward mode per lane, reverse mode weighted by the adjoint.

#include <cstdint>
#include <vector>

#include "core/sampler.h"
#include "integrators/gradients/geometry_gradients.h"
#include "integrators/gradients/scene_tangents.h"
#include "integrators/materials/material.h"
#include "integrators/media/free_flight.h"
#include "integrators/media/transmittance.h"
#include "integrators/path_contributions.h"

namespace nx {

/// One log-derivative on a path: d log f / d slot at one lane.
struct TapeEntry {
  uint32_t slot;
  uint8_t lane;
  float g;
};

/// The events and contributions of one path (cleared per sample; reused without allocating).
struct GradientTape {
  /// A contribution: its value, how many path events precede it, its own (local) events.
  struct Record {
    SampledSpectrum c;
    uint32_t prefix, localBegin, localEnd;
  };
  std::vector<TapeEntry> events;  ///< events that scale everything after them
  std::vector<TapeEntry> locals;  ///< local events of the recorded contributions
  std::vector<TapeEntry> pending; ///< local events of the next contribution
  /// Terms of the derivative itself (a boundary term: the path's weight so far times a jump
  /// across a moving outline), added as they are
  std::vector<TapeEntry> direct;
  /// The random numbers of the boundary terms along the path (their own stream: the path's own
  /// draws stay those of a plain render), or null
  PixelSampleStream* boundaryRng = nullptr;
  std::vector<Record> records;
  ShadowCrossings crossings; ///< scratch for the shadow rays of media scenes
  PathMotion motion;         ///< how shape slots move the path's current ray and vertex
  /// Events skipped because the differentiated value was 0 where its derivative is not (the
  /// estimator divides by the value: such a path's derivative is missed, and reported).
  uint64_t zeroValues = 0;

  /// Empties it for the next sample (keeps the capacity).
  void clear() {
    events.clear();
    locals.clear();
    pending.clear();
    records.clear();
    direct.clear();
    motion.ray.clear();
    motion.vertex.clear();
  }

  /// Calls out(slot, lane, v) with every (slot, lane) derivative term of the path's radiance:
  /// v = g_i * (the contributions after event i at the lane), and each contribution's local
  /// events times it.
  template <class Out>
  void sweep(Out&& out) const {
    SampledSpectrum after;
    size_t j = records.size();
    for (size_t i = events.size(); i-- > 0;) {
      while (j > 0 && records[j - 1].prefix > i) after += records[--j].c;
      const TapeEntry& e = events[i];
      const float v = e.g * after[e.lane];
      if (v != 0) out(e.slot, e.lane, v);
    }
    for (const Record& r : records)
      for (uint32_t k = r.localBegin; k < r.localEnd; ++k) {
        const TapeEntry& e = locals[k];
        const float v = e.g * r.c[e.lane];
        if (v != 0) out(e.slot, e.lane, v);
      }
    for (const TapeEntry& e : direct)
      if (e.g != 0) out(e.slot, e.lane, e.g);
  }
};

/// The sink of a differentiated render: the radiance, and every contribution on the tape.
struct GradientSink {
  static constexpr bool kClasses = false;  ///< no path classes
  static constexpr bool kGradients = true; ///< the path tracer records its events
  SampledSpectrum L;                       ///< radiance of the sample
  GradientTape* tape = nullptr;
  const SceneTangents* tangents = nullptr;

  /// Adds contribution c with the pending local events.
  void add(const SampledSpectrum& c, const PathClass&) {
    L += c;
    GradientTape& t = *tape;
    if (!c.isBlack()) {
      const uint32_t begin = static_cast<uint32_t>(t.locals.size());
      t.locals.insert(t.locals.end(), t.pending.begin(), t.pending.end());
      t.records.push_back({c, static_cast<uint32_t>(t.events.size()), begin,
                           static_cast<uint32_t>(t.locals.size())});
    }
    t.pending.clear();
  }
  /// An event scaling every later contribution.
  void event(uint32_t slot, int lane, float g) {
    tape->events.push_back({slot, static_cast<uint8_t>(lane), g});
  }
  /// An event of the next contribution only.
  void local(uint32_t slot, int lane, float g) {
    tape->pending.push_back({slot, static_cast<uint8_t>(lane), g});
  }
  /// A term of the derivative itself (a boundary term).
  void direct(uint32_t slot, int lane, float v) {
    tape->direct.push_back({slot, static_cast<uint8_t>(lane), v});
  }
  /// The value of a differentiated quantity was 0 where its derivative was not.
  void zeroValue() { ++tape->zeroValues; }
};

/// Log-derivative events of a spectrum with derivatives `ts` and values `value` at the lanes:
/// emit(slot, lane, d / value) (an emitter's radiance, a light's intensity).
template <class Sink, class Emit>
void ratioEvents(const SpectrumTangents& ts, const SampledWavelengths& lambda,
                 const SampledSpectrum& value, Sink& sink, Emit&& emit) {
  ts.forEach(lambda, [&](uint32_t slot, int i, float d) {
    if (value[i] != 0)
      emit(slot, i, d / value[i]);
    else
      sink.zeroValue();
  });
}

/// The reflectance tangents at a vertex: its material's spectrum's and, for a material whose
/// image texture is differentiated, its texels' at the hit's (u, v).
struct RhoTangents {
  const SpectrumTangents* spectrum = nullptr;
  const ReflectanceTexture* texture = nullptr;
  int64_t firstSlot = -1; ///< the texture's first slot, or -1
  float u = 0, v = 0;
  /// Calls f(slot, lane, d rho / d slot) for every non-zero derivative at the lanes.
  template <class F>
  void forEach(const SampledWavelengths& lambda, F&& f) const {
    if (spectrum) spectrum->forEach(lambda, f);
    if (texture && firstSlot >= 0)
      texture->forEachValueWeight(u, v, lambda, [&](size_t q, int lane, float w) {
        f(static_cast<uint32_t>(firstSlot + static_cast<int64_t>(q)), lane, w);
      });
  }
  /// True when nothing here is differentiated.
  bool empty() const { return (!spectrum || spectrum->empty()) && firstSlot < 0; }
};

/// Reflectance events at a surface (tangents ts) for the lobe of `bsdf` that scattered towards
/// wi (`specular`: a delta lobe): emit(slot, lane, slope * d rho), the slope d ln f / d rho the
/// BSDF's own (SurfaceBsdf::reflectanceLogSlope; `albedo` false for a fluorescent lobe, whose
/// albedo comes from the matrix).
template <class Sink, class Emit>
void reflectanceEvents(const RhoTangents& ts, const SurfaceBsdf& bsdf, const Vec3& wi,
                       const SampledWavelengths& lambda, const SampledSpectrum& rho, bool specular,
                       bool albedo, Sink& sink, Emit&& emit) {
  if (ts.empty()) return;
  ts.forEach(lambda, [&](uint32_t slot, int i, float d) {
    bool zero = false;
    const float slope = bsdf.reflectanceLogSlope(wi, rho[i], specular, albedo, zero);
    if (zero)
      sink.zeroValue();
    else if (slope != 0)
      emit(slot, i, slope * d);
  });
}

/// Where a fluorescent vertex's dye concentration comes from (a concentration map whose values
/// are differentiated), for reradiationEvents.
struct ConcentrationTangents {
  const ConcentrationMap* map = nullptr;
  int64_t firstSlot = -1; ///< the map's first slot, or -1: not differentiated
  float u = 0, v = 0;     ///< the hit's
};

/// The re-radiation choice's events at a fluorescent vertex (fluorescent_vertex.h): per lane,
/// from `before` (its wavelength there) to `excited`, the chosen event's value f is the elastic
/// part D(o) = (1 - k a_o) rho (the measured diagonal; an EEM's rho) or a cell k M[i][o]
/// (outside the matrix's grid, rho), k the dye's concentration there (1 without a map); the
/// event is weighted f / p with p held: g = f' / f, f' from the matrix's tangents `ms`, the
/// reflectance's `rs` and the concentration map's `cs`.
template <class Sink, class Emit>
void reradiationEvents(const MatrixTangents& ms, const RhoTangents& rs,
                       const ReradiationMatrix& matrix, const SampledWavelengths& before,
                       const SampledWavelengths& excited, const SampledSpectrum& rho, Sink& sink,
                       Emit&& emit, float k = 1, const ConcentrationTangents& cs = {}) {
  int bins[kLanes], from[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    from[i] = ReradiationMatrix::binOf(before.lambda[i]);
    bins[i] =
        excited.lambda[i] == before.lambda[i] ? -1 : ReradiationMatrix::binOf(excited.lambda[i]);
  }
  auto elastic = [&](int i, double r) { return matrix.elastic(from[i], r, k); };
  if (!ms.empty())
    for (int i = 0; i < kLanes; ++i) {
      const int o = from[i];
      if (o < 0) continue;
      auto ratio = [&](uint32_t slot, float d, float value) {
        if (d == 0) return;
        if (value != 0)
          emit(slot, i, d / value);
        else
          sink.zeroValue();
      };
      if (bins[i] < 0) {
        const float value = static_cast<float>(elastic(i, rho[i]));
        ms.forEachElastic(o, [&](uint32_t slot, float scale, float constant) {
          ratio(slot, k * scale * rho[i] + constant, value);
        });
      } else {
        const float value = static_cast<float>(matrix(bins[i], o));
        ms.forEachCell(bins[i], o, [&](uint32_t slot, float d) { ratio(slot, d, value); });
      }
    }
  rs.forEach(before, [&](uint32_t slot, int i, float d) {
    if (bins[i] >= 0) return; // a re-radiated event does not use rho
    const int o = from[i];
    // outside the grid the surface reflects rho (or nothing, for a measured matrix)
    const float scale = o < 0
                            ? (matrix.measured() && !matrix.elasticFromReflectance() ? 0.0f : 1.0f)
                            : static_cast<float>(elastic(i, 1.0) - elastic(i, 0.0));
    const float value = o < 0 ? scale * rho[i] : static_cast<float>(elastic(i, rho[i]));
    if (scale == 0) return;
    if (value != 0)
      emit(slot, i, scale * d / value);
    else
      sink.zeroValue();
  });
  if (cs.map && cs.firstSlot >= 0) {
    // d f / d k: -a_o rho for the elastic part (0 for an EEM's), M[i][o] for a cell: so
    // g = -a_o rho / D or 1 / k, times each map value's bilinear weight.
    size_t index[4];
    float weight[4];
    cs.map->bilinear(cs.u, cs.v, index, weight);
    for (int i = 0; i < kLanes; ++i) {
      const int o = from[i];
      if (o < 0) continue;
      float g = 0;
      if (bins[i] >= 0) {
        g = 1 / k; // k > 0: a cell is chosen only where k c(o) > 0
      } else {
        const double slope = matrix.elastic(o, rho[i], 0.0) - matrix.elastic(o, rho[i], 1.0);
        const float value = static_cast<float>(elastic(i, rho[i]));
        if (slope == 0) continue;
        if (value == 0) {
          sink.zeroValue();
          continue;
        }
        g = static_cast<float>(-slope) / value;
      }
      for (int c = 0; c < 4; ++c)
        if (weight[c] != 0)
          emit(static_cast<uint32_t>(cs.firstSlot + static_cast<int64_t>(index[c])), i,
               g * weight[c]);
    }
  }
}

/// The lanes' derivatives of a medium's coefficients for tangent t: all absorption
/// (sigma_a + the dye's peak a), scattering sigma_s and the dye's in-scattering peak c.
inline void mediumTangentAt(const MediumTangent& t, const HomogeneousMedium& m,
                            const SampledWavelengths& lambda, SampledSpectrum& dAbsorption,
                            SampledSpectrum& dScattering, SampledSpectrum& dFluorescent) {
  t.sigmaA.evaluate(lambda, dAbsorption);
  t.sigmaS.evaluate(lambda, dScattering);
  dFluorescent = SampledSpectrum();
  if (!m.dye) return;
  for (int i = 0; i < kLanes; ++i) {
    const int bin = ReradiationMatrix::binOf(lambda.lambda[i]);
    if (bin < 0) continue;
    const size_t b = static_cast<size_t>(bin);
    dAbsorption[i] +=
        t.dyePeak * static_cast<float>(m.dye->absorptance(bin)) + m.dyePeak * t.dyeAbsorptance[b];
    dFluorescent[i] =
        t.dyePeak * static_cast<float>(m.dye->columnSum(bin)) + m.dyePeak * t.dyeColumnSum[b];
  }
}

/// A free flight's events (free_flight.h): lane i's weight is rate_i exp(-sigma_t,i t) (rate
/// sigma_s, the dye's sigma_fl, or 1 when the flight reached the surface), its density held:
/// g = rate' / rate - t sigma_t'.
template <class Sink, class Emit>
void freeFlightEvents(const std::vector<MediumTangent>& ts, const HomogeneousMedium& m,
                      const SampledWavelengths& lambda, MediumEvent event, float t, Sink& sink,
                      Emit&& emit) {
  if (ts.empty() || !std::isfinite(t)) return; // an endless flight carries nothing
  SampledSpectrum sa, ss, sfl;
  m.coefficients(lambda, sa, ss, sfl);
  for (const MediumTangent& tangent : ts) {
    SampledSpectrum da, ds, dfl;
    mediumTangentAt(tangent, m, lambda, da, ds, dfl);
    for (int i = 0; i < kLanes; ++i) {
      float g = -t * (da[i] + ds[i]);
      const float rate = event == MediumEvent::Scatter     ? ss[i]
                         : event == MediumEvent::Fluoresce ? sfl[i]
                                                           : 1.0f;
      const float dRate = event == MediumEvent::Scatter     ? ds[i]
                          : event == MediumEvent::Fluoresce ? dfl[i]
                                                            : 0.0f;
      if (dRate != 0) {
        if (rate > 0)
          g += dRate / rate;
        else
          sink.zeroValue();
      }
      if (g != 0) emit(tangent.slot, i, g);
    }
  }
}

/// The excitation bin chosen at a dye's re-emission (from `before` to `excited`): the flight's
/// rate held peak c(o); the event's value is peak M[j][o], so g = M' / M - c' / c.
template <class Sink, class Emit>
void reemissionEvents(const std::vector<MediumTangent>& ts, const HomogeneousMedium& m,
                      const SampledWavelengths& before, const SampledWavelengths& excited,
                      Sink& sink, Emit&& emit) {
  constexpr int n = ReradiationMatrix::kBins;
  for (const MediumTangent& t : ts) {
    if (t.dyeCells.empty()) continue;
    for (int i = 0; i < kLanes; ++i) {
      const int o = ReradiationMatrix::binOf(before.lambda[i]);
      if (o < 0 || excited.lambda[i] == before.lambda[i]) continue;
      const int j = ReradiationMatrix::binOf(excited.lambda[i]);
      const float cell = static_cast<float>((*m.dye)(j, o));
      const float column = static_cast<float>(m.dye->columnSum(o));
      if (!(cell > 0) || !(column > 0)) {
        sink.zeroValue();
        continue;
      }
      const float g = t.dyeCells[static_cast<size_t>(j) * n + o] / cell -
                      t.dyeColumnSum[static_cast<size_t>(o)] / column;
      if (g != 0) emit(t.slot, i, g);
    }
  }
}

/// The Henyey-Greenstein lobe's events for a scattering by cos theta (its value over the held
/// density): d log p / d g = -2 g / (1 - g^2) - 3 (g - cos) / (1 + g^2 - 2 g cos).
template <class Emit>
void phaseEvents(const std::vector<MediumTangent>& ts, float g, float cosTheta, Emit&& emit) {
  for (const MediumTangent& t : ts) {
    if (t.g == 0) continue;
    const float d = -2 * g / (1 - g * g) - 3 * (g - cosTheta) / (1 + g * g - 2 * g * cosTheta);
    for (int i = 0; i < kLanes; ++i) emit(t.slot, i, t.g * d);
  }
}

/// A shadow ray's events: each medium segment's transmittance exp(-sigma_t l) gives
/// -l sigma_t', each thin wall's tint rho gives rho' / rho.
template <class Sink, class Emit>
void shadowEvents(const SceneTangents& tangents, const RenderScene& scene,
                  const ShadowCrossings& crossings, const SampledWavelengths& lambda, Sink& sink,
                  Emit&& emit) {
  for (const auto& [medium, length] : crossings.media) {
    const auto& ts = tangents.media[static_cast<size_t>(medium)];
    for (const MediumTangent& t : ts) {
      SampledSpectrum da, ds, dfl;
      mediumTangentAt(t, scene.media[static_cast<size_t>(medium)], lambda, da, ds, dfl);
      for (int i = 0; i < kLanes; ++i)
        if (const float g = -length * (da[i] + ds[i]); g != 0 && std::isfinite(g))
          emit(t.slot, i, g);
    }
  }
  for (uint32_t material : crossings.walls) {
    const auto& ts = tangents.reflectance[material];
    if (ts.empty()) continue;
    SampledSpectrum tint;
    scene.materials[material].reflectance.evaluate(lambda, tint);
    ratioEvents(ts, lambda, tint, sink, emit);
  }
}

} // namespace nx
