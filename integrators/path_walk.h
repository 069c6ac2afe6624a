// The path walk of the spectral path tracer (tracePath and its variants, integrator.h): one
// template over the features a scene has and the sink its contributions go to.
#pragma once

#include <cmath>
#include <type_traits>

#include "core/ray_offset.h"
#include "integrators/fluorescent_vertex.h"
#include "integrators/gradients/geometry_gradients.h"
#include "integrators/gradients/gradient_context.h"
#include "integrators/gradients/mesh_outlines.h"
#include "integrators/gradients/path_gradients.h"
#include "integrators/integrator.h"
#include "integrators/lights/direct_lighting.h"
#include "integrators/materials/bsdf.h"
#include "integrators/media/free_flight.h"
#include "integrators/media/henyey_greenstein.h"
#include "integrators/media/transmittance.h"
#include "integrators/path_contributions.h"
#include "integrators/sampling.h"

namespace nx {
// The path walk, shared by the translation units of the trace entry points (trace_*.cpp):
// each instantiates it for its own sink, so the build runs them in parallel.
namespace path_walk {

// A path at the surface of a closed shape (a sphere, a closed mesh in a media scene),
// arriving from wo (pointing back along the path) and leaving along wi: when it transmits
// (wo and wi on opposite sides), it enters or leaves the medium the shape holds.
inline void crossBoundary(const SurfaceHit& hit, const ShapeAppearance& app, const Vec3& wo,
                          const Vec3& wi, MediumStack& media) {
  if (app.boundary == 0) return;
  const Vec3 outward = app.boundary > 0 ? hit.ng : -hit.ng;
  const float a = dot(wo, outward), b = dot(wi, outward);
  if ((a < 0) == (b < 0)) return; // reflected: same side
  if (b < 0)
    media.enter(app.medium);
  else
    media.leave();
}

// The relight source of emission e (0 outside a relightable build).
inline uint16_t relightSourceOf(const LightGroups& groups, int32_t e) {
  return static_cast<size_t>(e) < groups.sourceOfEmission.size()
             ? groups.sourceOfEmission[static_cast<size_t>(e)]
             : uint16_t{0};
}

// True for sinks that differentiate the path (GradientSink): the path tracer then records
// the log-derivatives of its vertices (integrators/gradients/path_gradients.h).
template <class Sink>
constexpr bool recordsGradients() {
  if constexpr (requires { Sink::kGradients; })
    return Sink::kGradients;
  else
    return false;
}

// The tangents of a medium in a render that is not differentiated: none.
inline const std::vector<MediumTangent>& noMediumTangents() {
  static const std::vector<MediumTangent> none;
  return none;
}

// The white reference's surface: a Lambertian reflector of reflectance 1.
inline const Material& whiteLambertian() {
  static const Material white = [] {
    Material m;
    m.kind = MaterialKind::Mixture;
    m.roughness = 1.0f;
    m.reflectance = Spectrum(ConstantSpectrum{1.0});
    return m;
  }();
  return white;
}

// What a surface vertex holds for next-event estimation and the continuation: its material,
// reflectance and BSDF, and at a fluorescent diffuse lobe the excitation wavelengths chosen
// once for both.
struct SurfaceVertex {
  /// The vertex at `h` (the rest default-initialized, as locals would be: no per-vertex zeroing).
  SurfaceVertex(SurfaceHit& h, const ShapeAppearance& a, bool white, const Material& m,
                const Vec3& w, const SampledSpectrum& r, const SampledWavelengths& current)
      : hit(h), app(a), whiteHere(white), material(m), wo(w), rho(r),
        bsdf(m, current, r, h.ng, h.ns, w) {}
  SurfaceHit& hit; ///< (a sphere's uv is filled in when a texture or map needs it)
  const ShapeAppearance& app;
  bool whiteHere;
  const Material& material;
  Vec3 wo;
  SampledSpectrum rho;
  SurfaceBsdf bsdf;
  RhoTangents rhoTangents; ///< differentiated renders: what rho's derivatives are here
  FluorescentShift shift;
  bool fluorescent = false;
  float concentration = 1; ///< of the dye here (a concentration map)
  ConcentrationTangents concentrationTangents;
};

// One path from the camera: its state (wavelengths, throughput, the previous vertex for MIS,
// the media it is in) and one function per concept of the walk: free flights through media,
// escaping to the background, emitters hit, and at surfaces the excitation shift, next-event
// estimation (guided or not) and the BSDF's continuation.
// kFluorescence: compiled in only for scenes with fluorescent materials, so that other
// scenes run exactly the code they would without the feature.
// kMedia: likewise for scenes with media or interface surfaces: the path tracks the media it
// is in, samples free flights through them and sees through interfaces in its shadow rays.
// kWhite: the first surface hit is replaced by a white Lambertian reflector that does not emit
// (the white-reference AOV); later bounces see the scene as it is.
// Sink: where contributions go (path_contributions.h); with Sink::kClasses the path's class
// (shifted lanes, scatterings, light group) is tracked for each of them.
template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
class PathWalk {
public:
  PathWalk(const IntegratorContext& ctx, const Ray& ray, const SampledWavelengths& lambda,
           PixelSampleStream& rng, TraceCounters& counters, Sink& sink)
      : ctx_(ctx), scene_(*ctx.scene), groups_(scene_.lightGroups), rng_(rng), counters_(counters),
        sink_(sink), rouletteStart_(scene_.settings.depth),
        tangents_(ctx.gradients ? ctx.gradients->tangents : nullptr), ray0_(ray), lambda_(lambda),
        prevP_(ray.o) {
    if constexpr (kMedia) media_ = scene_.cameraMedia;
  }

  // The walk flattened: every step and what it calls in this file inlined into one function, as
  // it was when the walk was one function (without it GCC's growth limits left offsetRayOrigin
  // and the walk's set-up out of line: 1% more instructions). Only the plain radiance walk is
  // flattened: flattening costs each instantiation 5-9x its compile time (70.8 s against 8.2 s
  // for the fluorescent gradient walks at -O3), and the other sinks' walks spend their time in
  // what they record. Builds with NX_NO_FLATTEN (the sanitizer build) flatten nothing.
#ifndef NX_NO_FLATTEN
  [[gnu::flatten]]
#endif
  void
  runFlattened() {
    run();
  }

  // The walk: a bounce per ray until the path ends (escapes, is absorbed, loses the roulette or
  // reaches the bounce limit).
  void run() {
    Ray ray_ = ray0_;
    SampledWavelengths current_ = lambda_;
    if constexpr (kGradients) sink_.tape->motion.ray = sink_.tape->motion.primary;
    for (int bounce = 0;; ++bounce) {
      SurfaceHit hit;
      ++counters_.rays;
      const bool found = scene_.geometry->intersect(ray_, hit);
      if constexpr (kMedia) {
        const Flight f = throughMedium(ray_, current_, bounce, found, hit);
        if (f == Flight::PathEnds) break;
        if (f == Flight::Scattered) continue;
      }
      if (!found) {
        escape(ray_, current_);
        break;
      }
      const ShapeAppearance& app = scene_.appearance(hit);
      if constexpr (kMedia) {
        // An interface: the path goes straight on into (or out of) the medium it bounds; the
        // previous vertex stays the one MIS weights refer to (next-event estimation sees
        // through interfaces too).
        if (passesUnchanged(materialLobes(scene_.materials[app.material]))) {
          if (bounce >= kMaxPathBounces) {
            ++counters_.bounceLimited; // still carrying light: counted, reported
            break;
          }
          crossBoundary(hit, app, -ray_.d, ray_.d, media_);
          ray_.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, ray_.d);
          ray_.tMin = 0;
          ray_.tMax = INFINITY;
          continue;
        }
      }
      if constexpr (kGradients) moveVertex(ray_, hit);
      const bool whiteHere = kWhite && scatterings_ == 0;
      if (app.emission >= 0 && !whiteHere) addEmitterHit(ray_, current_, hit, app);
      if (bounce >= kMaxPathBounces) {
        ++counters_.bounceLimited; // still carrying light: counted, reported
        break;
      }
      if (!scatterAtSurface(ray_, current_, hit, app, whiteHere)) break;
    }
  }

private:
  // Differentiated renders: the two ways an event enters the tape (scaling every later
  // contribution, or the next one only).
  static constexpr bool kGradients = recordsGradients<Sink>();
  // Next-event estimation at a fluorescent vertex of a plain render: the excitation is also
  // drawn guided by the chosen light's spectrum (fluorescent_vertex.h), and in a relightable
  // render told its targets by their spectra (RelightSpectra::samplingOfSource);
  // differentiated and media renders, and relightable ones without targets, keep the column's
  // choice alone.
  static constexpr bool kGuidedExcitation = kFluorescence && !kMedia && !kGradients;
  // What a ray's flight through a medium did.
  enum class Flight { Through, Scattered, PathEnds };

  auto event() {
    return [this](uint32_t slot, int lane, float g) {
      if constexpr (kGradients) sink_.event(slot, lane, g);
    };
  }
  auto local() {
    return [this](uint32_t slot, int lane, float g) {
      if constexpr (kGradients) sink_.local(slot, lane, g);
    };
  }
  // Where a shadow ray records what it passed through (differentiated renders), else null.
  ShadowCrossings* shadowCrossings() {
    if constexpr (kGradients) {
      sink_.tape->crossings.clear();
      return &sink_.tape->crossings;
    } else {
      return nullptr;
    }
  }
  // The local events of a sampled light's emission (its radiance or intensity at `lit`).
  void lightEvents(const LightSample& ls, const SampledWavelengths& lit) {
    if constexpr (kGradients) {
      const size_t l = static_cast<size_t>(ls.light);
      if (const Spectrum* emitted = ctx_.gradients->spectrumOfSampledLight[l])
        ratioEvents(*ctx_.gradients->ofSampledLight[l], lit, evaluate(*emitted, lit), sink_,
                    local());
    }
  }
  // The class of a contribution after `events` scatterings from an emitter of light group
  // `group` and relight source `source`, which the light left at wavelengths `emitted`; the
  // lanes of `extra` shifted in addition.
  PathClass classOf([[maybe_unused]] int events, [[maybe_unused]] uint16_t group,
                    [[maybe_unused]] uint16_t source,
                    [[maybe_unused]] const SampledWavelengths& emitted,
                    [[maybe_unused]] uint64_t extra = 0) const {
    PathClass k;
    if constexpr (Sink::kClasses) k = {shifted_ | extra, events, group, source, &emitted};
    return k;
  }
  // beta for contributions: with media, divided by the spectral MIS divisor
  SampledSpectrum weighted() const {
    if constexpr (kMedia)
      return beta_ * invMisDivisor_;
    else
      return beta_;
  }
  // Counts a scattering vertex and plays Russian roulette after <depth> of them, re-weighting
  // survivors by 1/q (unbiased); false: the path ends (terminated, or nothing left to carry).
  bool survivesRoulette() {
    if (++scatterings_ >= rouletteStart_) {
      const float q = std::min(1.0f, weighted().maxValue() * rrScale_);
      const float u = rng_.next1D();
      if (!(q > 0) || u >= q) return false;
      beta_ *= 1.0f / q;
    }
    return !beta_.isBlack();
  }
  // Weight of an emitter found by this BSDF-sampled ray that next-event estimation could also
  // have sampled, with density lightPdf.
  float emitterWeight(float lightPdf) const {
    if (specular_ || ctx_.lightSampling == LightSampling::BsdfOnly || !(lightPdf > 0)) return 1.0f;
    return ctx_.lightSampling == LightSampling::NeeOnly ? 0.0f : powerHeuristic(prevPdf_, lightPdf);
  }

  [[gnu::always_inline]] inline Flight throughMedium([[maybe_unused]] Ray& ray_,
                                                     [[maybe_unused]] SampledWavelengths& current_,
                                                     int bounce, bool found, const SurfaceHit& hit);
  // A scattering or re-emission at distance t in medium m: next-event estimation there and the
  // phase function's (or an isotropic) continuation.
  [[gnu::always_inline]] inline Flight
  scatterInMedium([[maybe_unused]] Ray& ray_, [[maybe_unused]] SampledWavelengths& current_,
                  const HomogeneousMedium& medium, int m, float t, bool reemitted);
  // A ray that leaves the scene: the background's and the environment lights' radiance.
  [[gnu::always_inline]] inline void escape([[maybe_unused]] Ray& ray_,
                                            [[maybe_unused]] SampledWavelengths& current_);
  // An emitter the ray hit: its radiance, MIS-weighted against next-event estimation.
  [[gnu::always_inline]] inline void addEmitterHit([[maybe_unused]] Ray& ray_,
                                                   [[maybe_unused]] SampledWavelengths& current_,
                                                   const SurfaceHit& hit,
                                                   const ShapeAppearance& app);
  // A surface vertex: its excitation shift, next-event estimation and the continuation;
  // false: the path ends here.
  [[gnu::always_inline]] inline bool scatterAtSurface([[maybe_unused]] Ray& ray_,
                                                      [[maybe_unused]] SampledWavelengths& current_,
                                                      SurfaceHit& hit, const ShapeAppearance& app,
                                                      bool whiteHere);
  // A fluorescent diffuse lobe: every lane's excitation wavelength chosen once, for both
  // next-event estimation and the continuation through the diffuse lobe.
  [[gnu::always_inline]] inline void chooseExcitation([[maybe_unused]] Ray& ray_,
                                                      [[maybe_unused]] SampledWavelengths& current_,
                                                      SurfaceVertex& v);
  // A rough conductor's roughness: d ln f / d alpha at direction wi, for each slot moving it.
  template <class Emit>
  void roughnessEvents(const SurfaceVertex& v, const Vec3& wi, Emit&& emit);
  // f |cos| of the vertex's non-specular lobes towards wi (a fluorescent diffuse lobe's with
  // its re-radiation albedo).
  static SampledSpectrum scattered(const SurfaceVertex& v, const Vec3& wi) {
    return v.fluorescent ? v.shift.albedo * v.bsdf.diffuseLobe(wi) : v.bsdf.f(wi);
  }
  // Shape derivatives (geometry_gradients.h), kept out of line ([[gnu::flatten]] would inline
  // them and the paths they trace into every walk, for nothing: they run in differentiated
  // renders only): the motion of the vertex at `hit` from its ray's.
  [[gnu::noinline]] void moveVertex(const Ray& ray, const SurfaceHit& hit);
  // The vertex's BSDF value (its diffuse lobe alone at a fluorescent vertex) as a function of
  // its normals and directions, at wavelengths `at`.
  auto bsdfValue(const SurfaceVertex& v, const SampledWavelengths& at, bool diffuseLobe) const;
  // The shape slots' events of next-event estimation's light sample ls (its point held).
  template <class Emit>
  [[gnu::noinline]] void shapeLightEvents(const SurfaceVertex& v, const LightSample& ls,
                                          const SampledWavelengths& at, Emit&& emit);
  // The shape slots' events of the continuation bs, and the next ray's motion.
  [[gnu::noinline]] void shapeContinuation(const SurfaceVertex& v, const BsdfSample& bs,
                                           const SampledWavelengths& at);
  // Shape derivatives: an emitter found by a continuation, differentiated with its point held
  // (as next-event estimation holds it; ContinuationLobe): the local events turning the held
  // direction's derivative into the held point's.
  [[gnu::noinline]] void emitterPointHeld(const Ray& ray, const SurfaceHit& hit);
  // Shape derivatives: the boundary term of the vertex's scattering integral over directions,
  // on the silhouettes of the spheres that move relative to it and of the moving meshes.
  [[gnu::noinline]] void directionBoundary(const SampledWavelengths& current,
                                           const SurfaceVertex& v);
  // The analytic primitives' part of directionBoundary: one point of primitive k's outline
  // seen from the vertex (a curve chosen uniformly, a point along it), where it or the vertex
  // moves.
  void primitiveDirectionBoundary(const SampledWavelengths& lit, const SurfaceVertex& v,
                                  ShapeKind kind, uint32_t k, SelfLighting selfLighting);
  // The meshes' part of directionBoundary: a silhouette edge seen from the vertex, of each
  // moving mesh (its moving edges, the slots moving them and the vertex's other slots), and
  // as the camera moves the vertex, of every mesh (all its edges, the camera's slots).
  [[gnu::noinline]] void meshDirectionBoundary(const SampledWavelengths& lit,
                                               const SurfaceVertex& v);
  // One edge of mesh k chosen uniformly from `edges` seen from the vertex: the camera's slots'
  // share (`camera`) or the other slots' (the edge's vertices' velocities included).
  void meshEdgeBoundary(const SampledWavelengths& lit, const SurfaceVertex& v, uint32_t k,
                        const std::vector<MeshEdge>& edges, bool camera);
  // The radiance arriving at the vertex from targets[0] and targets[1] (either side of an
  // outline), traced with the same random numbers of the boundary stream (advanced past them).
  [[gnu::noinline]] void radianceEitherSide(const SurfaceVertex& v, const Vec3d (&targets)[2],
                                            const SampledWavelengths& lit, SampledSpectrum (&L)[2]);
  // The boundary terms of a jump `term` (the path's weight times the jump across an outline):
  // term * (-d phi / d slot) * scale per slot of the tape's rates.
  [[gnu::noinline]] void boundaryTerms(const SampledSpectrum& term, double scale);
  // Emitters either side of an outline (phi's gradient over directions dPhiDw, phi < 0 on
  // side 0), whose light is differentiated with its point held (next-event estimation's area
  // measure): the emitted radiance of the outline's own shape (kind, index) is taken out of
  // L (its outline is no discontinuity there); another emitter's outline crossing is measured
  // against its held point, not a held direction, so each slot moving the vertex (those of
  // `which`) gains weight * (Le_1 - Le_0 ... ) * (dPhiDw . d omega_y) * scale (omega_y the held
  // point's direction; its emitted radiance Le_s at distance t_s).
  enum class VertexSlots { All, Camera, NotCamera };
  void heldEmitterTerms(const SurfaceVertex& v, const Vec3d (&targets)[2],
                        const SampledWavelengths& lit, ShapeKind ownKind, uint32_t own,
                        const Vec3d& dPhiDw, const SampledSpectrum& weight, double scale,
                        VertexSlots which, SampledSpectrum (&L)[2]);
  // True when `slot` moves the camera.
  bool cameraSlot(uint32_t slot) const;
  // Next-event estimation with the excitation also drawn guided by the light (fluorescent
  // vertices of plain renders); false where it does not apply.
  [[gnu::always_inline]] inline bool
  guidedDirectLight([[maybe_unused]] Ray& ray_, [[maybe_unused]] SampledWavelengths& current_,
                    SurfaceVertex& v, float& weightsHere);
  // Next-event estimation at the vertex.
  [[gnu::always_inline]] inline void directLightHere([[maybe_unused]] Ray& ray_,
                                                     [[maybe_unused]] SampledWavelengths& current_,
                                                     SurfaceVertex& v, float& weightsHere);
  // The BSDF's sample and the path's state after it; false: the path ends.
  [[gnu::always_inline]] inline bool continueFrom([[maybe_unused]] Ray& ray_,
                                                  [[maybe_unused]] SampledWavelengths& current_,
                                                  SurfaceVertex& v, float weightsHere);

  const IntegratorContext& ctx_;
  const RenderScene& scene_;
  const LightGroups& groups_;
  PixelSampleStream& rng_;
  TraceCounters& counters_;
  Sink& sink_;
  const int rouletteStart_;
  [[maybe_unused]] const SceneTangents* tangents_; ///< differentiated renders' tangents
  // The camera ray and the sensor wavelengths (where the film accumulates). The walk's ray and
  // `current` wavelengths (what lights and materials are evaluated at: they differ after a
  // fluorescent shift) are run()'s locals, handed to each step: their addresses go to the
  // intersector and the lights, and the path's other state stays in registers.
  const Ray& ray0_;
  const SampledWavelengths& lambda_;
  SampledSpectrum beta_ = SampledSpectrum::filled(1.0f);
  // Lanes re-radiated so far (tracked for component sinks only).
  [[maybe_unused]] uint64_t shifted_ = 0;
  // Russian roulette looks at beta * rrScale: the throughput without the radiance scaling
  // 1 / eta^2 of refractions (a lossless path through glass keeps probability 1, as in pbrt-v4
  // and Mitsuba 3) and without the factor kLanes of a hero-only path.
  float rrScale_ = 1;
  bool heroAlone_ = kLanes == 1; // the secondary lanes were terminated (dispersion)
  bool specular_ = true;         // the previous bounce was specular (or the camera)
  float prevPdf_ = 0;
  Vec3 prevP_;
  Vec3 prevN_; // shading normal at prevP (zero in a medium): light pdfs' cosine warp
  // The sum of the light weights next-event estimation found at prevP (LightSampler::choose;
  // 0: none), so the MIS weight of an emitter found from there does not weigh every light again.
  float prevWeights_ = 0;
  [[maybe_unused]] MediumStack media_;
  // Spectral MIS through media: p_lane / p_hero of the path so far (free_flight.h); every
  // contribution is divided by their mean (1 while no medium event happened).
  [[maybe_unused]] SampledSpectrum misRatios_ = SampledSpectrum::filled(1.0f);
  // 1 / spectralMisDivisor(misRatios, heroAlone), kept up to date where either changes (after
  // each free flight, when the hero goes alone) rather than summed at every contribution.
  [[maybe_unused]] float invMisDivisor_ = 1.0f;
  // Scattering vertices so far (surfaces and media; interfaces do not count): Russian roulette
  // starts after <depth> of them.
  int scatterings_ = 0;
};

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
typename PathWalk<kFluorescence, kMedia, kWhite, Sink>::Flight
PathWalk<kFluorescence, kMedia, kWhite, Sink>::throughMedium(
    [[maybe_unused]] Ray& ray_, [[maybe_unused]] SampledWavelengths& current_, int bounce,
    bool found, const SurfaceHit& hit) {
  const int m = media_.current();
  if (m < 0) return Flight::Through;
  const HomogeneousMedium& medium = scene_.media[static_cast<size_t>(m)];
  const float uDistance = rng_.next1D(), uEvent = rng_.next1D();
  // An emitting medium: the emission along the flight, weighted by the path before it.
  const SampledSpectrum before = medium.emission ? weighted() : SampledSpectrum();
  SampledSpectrum glow;
  const FreeFlight flight =
      sampleFreeFlight(medium, current_, found ? hit.t : INFINITY, uDistance, uEvent, beta_,
                       misRatios_, medium.emission ? &glow : nullptr);
  if (medium.emission)
    sink_.add(before * glow,
              classOf(scatterings_, groups_.ofMedium[static_cast<size_t>(m)], 0, current_));
  if constexpr (kGradients)
    freeFlightEvents(tangents_->media[static_cast<size_t>(m)], medium, current_, flight.event,
                     flight.event == MediumEvent::None ? (found ? hit.t : INFINITY) : flight.t,
                     sink_, event());
  // beta_i / mean(ratios) is all that counts, so both are divided by the mean after each
  // flight: the products stay near 1 on long chromatic paths (ratios' mean 1; the hero's own
  // ratio, once 1, becomes 1 / (the product of these means)).
  if (!heroAlone_) {
    const float mean = spectralMisDivisor(misRatios_, false);
    if (mean > 0) {
      misRatios_ *= 1.0f / mean;
      beta_ *= 1.0f / mean;
    }
  }
  invMisDivisor_ = 1.0f / spectralMisDivisor(misRatios_, heroAlone_);
  if (flight.event != MediumEvent::None) {
    if (bounce >= kMaxPathBounces) {
      ++counters_.bounceLimited; // still carrying light: counted, reported
      return Flight::PathEnds;
    }
    return scatterInMedium(ray_, current_, medium, m, flight.t,
                           flight.event == MediumEvent::Fluoresce);
  }
  return beta_.isBlack() ? Flight::PathEnds : Flight::Through;
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
typename PathWalk<kFluorescence, kMedia, kWhite, Sink>::Flight
PathWalk<kFluorescence, kMedia, kWhite, Sink>::scatterInMedium(
    [[maybe_unused]] Ray& ray_, [[maybe_unused]] SampledWavelengths& current_,
    const HomogeneousMedium& medium, int m, float t, bool reemitted) {
  const Vec3 p = ray_.at(t);
  // A re-emission: every lane's excitation wavelength is chosen once (as at a fluorescent
  // surface), for next-event estimation and the continuation; the light leaves isotropically.
  // Its strength per lane is already in beta (sigma_fl).
  const SampledWavelengths lit =
      reemitted ? sampleFluorescentShift(*medium.dye, current_, SampledSpectrum(), rng_).excited
                : current_;
  auto phaseTo = [&](const Vec3& wi) {
    return reemitted ? static_cast<float>(1 / (4 * kPi))
                     : henyeyGreenstein(dot(ray_.d, wi), medium.g);
  };
  [[maybe_unused]] const std::vector<MediumTangent>& mediumTangents =
      tangents_ ? tangents_->media[static_cast<size_t>(m)] : noMediumTangents();
  if constexpr (kGradients)
    if (reemitted) reemissionEvents(mediumTangents, medium, current_, lit, sink_, event());
  float weightsHere = 0;
  if (ctx_.lightSampling != LightSampling::BsdfOnly && ctx_.lights->count() > 0) {
    const float uChoice = rng_.next1D();
    const Sample2 uLight = rng_.next2D();
    LightSample ls;
    if (ctx_.lights->sample(p, uChoice, uLight, lit, ls, Vec3(), &weightsHere)) {
      const auto visible = [&](const Ray& r) {
        return shadowTransmittance(scene_, r, media_, lit, counters_, shadowCrossings());
      };
      const SampledSpectrum direct = directLightAt(
          p, Vec3(), Vec3(), ls,
          [&](const Vec3& wi) { return SampledSpectrum::filled(phaseTo(wi)); }, phaseTo,
          ctx_.lightSampling != LightSampling::NeeOnly, visible);
      if constexpr (kGradients) {
        if (!direct.isBlack()) {
          if (!reemitted) phaseEvents(mediumTangents, medium.g, dot(ray_.d, ls.wi), local());
          lightEvents(ls, lit);
          shadowEvents(*tangents_, scene_, sink_.tape->crossings, lit, sink_, local());
        }
      }
      sink_.add(weighted() * direct,
                classOf(scatterings_ + 1, ctx_.lights->group(ls.light),
                        ctx_.lights->source(ls.light), lit,
                        Sink::kClasses ? shiftedLanes(lit, current_) : uint64_t{0}));
    }
  }
  const Sample2 uDir = rng_.next2D();
  const Vec3 wi =
      reemitted ? sampleUniformSphere(uDir) : sampleHenyeyGreenstein(ray_.d, medium.g, uDir);
  if constexpr (Sink::kClasses) shifted_ |= shiftedLanes(lit, current_);
  if constexpr (kGradients)
    if (!reemitted) phaseEvents(mediumTangents, medium.g, dot(ray_.d, wi), event());
  current_ = lit;
  specular_ = false;
  prevPdf_ = phaseTo(wi);
  prevP_ = p;
  prevN_ = Vec3();
  prevWeights_ = weightsHere;
  if (!survivesRoulette()) return Flight::PathEnds;
  ray_.o = p;
  ray_.d = wi;
  ray_.tMin = 0;
  ray_.tMax = INFINITY;
  return Flight::Scattered;
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::escape(
    [[maybe_unused]] Ray& ray_, [[maybe_unused]] SampledWavelengths& current_) {
  if (scene_.background) {
    const SampledSpectrum le = evaluate(*scene_.background, current_);
    if constexpr (kGradients) ratioEvents(tangents_->background, current_, le, sink_, local());
    sink_.add(weighted() * le *
                  (specular_
                       ? 1.0f
                       : emitterWeight(ctx_.lights->pdfBackground(prevP_, prevN_, prevWeights_))),
              classOf(scatterings_, groups_.ofBackground, groups_.sourceOfBackground, current_));
  }
  for (int e = 0; e < ctx_.lights->environmentCount(); ++e)
    sink_.add(weighted() * ctx_.lights->environmentRadiance(e, ray_.d, current_) *
                  (specular_ ? 1.0f
                             : emitterWeight(ctx_.lights->pdfEnvironment(e, prevP_, ray_.d, prevN_,
                                                                         prevWeights_))),
              classOf(scatterings_, ctx_.lights->environmentGroup(e), 0, current_));
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::addEmitterHit(
    [[maybe_unused]] Ray& ray_, [[maybe_unused]] SampledWavelengths& current_,
    const SurfaceHit& hit, const ShapeAppearance& app) {
  const float w =
      specular_ ? 1.0f : emitterWeight(ctx_.lights->pdf(prevP_, hit, ray_.d, prevN_, prevWeights_));
  if (!(w > 0)) return;
  const SampledSpectrum le = evaluate(scene_.emission[static_cast<size_t>(app.emission)], current_);
  if constexpr (kGradients) {
    ratioEvents(tangents_->emission[static_cast<size_t>(app.emission)], current_, le, sink_,
                local());
    if (!specular_) emitterPointHeld(ray_, hit);
  }
  sink_.add(weighted() * le * w,
            classOf(scatterings_, groups_.ofEmission[static_cast<size_t>(app.emission)],
                    relightSourceOf(groups_, app.emission), current_));
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
bool PathWalk<kFluorescence, kMedia, kWhite, Sink>::scatterAtSurface(
    [[maybe_unused]] Ray& ray_, [[maybe_unused]] SampledWavelengths& current_, SurfaceHit& hit,
    const ShapeAppearance& app, bool whiteHere) {
  const Material& material = whiteHere ? whiteLambertian() : scene_.materials[app.material];
  const Vec3 wo = -ray_.d;
  const SampledSpectrum rho = scene_.reflectanceAt(material, hit, current_);
  SurfaceVertex v(hit, app, whiteHere, material, wo, rho, current_);
  if constexpr (kGradients) {
    if (!whiteHere)
      v.rhoTangents = {&tangents_->reflectance[app.material], material.texture.get(),
                       tangents_->textureFirstSlot[app.material], hit.u, hit.v};
  }
  v.bsdf.orient(hit.dpdu);
  v.bsdf.setHeroAlone(heroAlone_);
  if constexpr (kFluorescence) chooseExcitation(ray_, current_, v);
  float weightsHere = 0; // LightSampler::choose's sum of weights at hit.p, for the next MIS
  bool guidedDone = false;
  if constexpr (kGuidedExcitation) guidedDone = guidedDirectLight(ray_, current_, v, weightsHere);
  if (!guidedDone && v.bsdf.hasNonSpecular() && ctx_.lightSampling != LightSampling::BsdfOnly &&
      ctx_.lights->count() > 0)
    directLightHere(ray_, current_, v, weightsHere);
  if constexpr (kGradients) directionBoundary(current_, v);
  return continueFrom(ray_, current_, v, weightsHere);
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::chooseExcitation(
    [[maybe_unused]] Ray& ray_, [[maybe_unused]] SampledWavelengths& current_, SurfaceVertex& v) {
  if (!(v.material.reradiation && v.bsdf.hasNonSpecular())) return;
  if (v.material.concentration) {
    v.concentration = scene_.concentrationAt(v.material, v.hit);
    if constexpr (kGradients)
      v.concentrationTangents = {v.material.concentration.get(),
                                 tangents_->concentrationFirstSlot[v.app.material], v.hit.u,
                                 v.hit.v};
    v.shift =
        sampleFluorescentShift(*v.material.reradiation, current_, v.rho, rng_, &v.concentration);
  } else {
    v.shift = sampleFluorescentShift(*v.material.reradiation, current_, v.rho, rng_);
  }
  v.fluorescent = true;
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
template <class Emit>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::roughnessEvents(
    [[maybe_unused]] const SurfaceVertex& v, [[maybe_unused]] const Vec3& wi,
    [[maybe_unused]] Emit&& emit) {
  if constexpr (kGradients) {
    const auto& ts = tangents_->roughness[v.app.material];
    float du = 0, dv = 0;
    if (ts.empty() || !v.bsdf.roughnessLogSlopes(wi, du, dv)) return;
    for (const RoughnessTangent& t : ts)
      if (const float g = t.alphaU * du + t.alphaV * dv; g != 0)
        for (int i = 0; i < kLanes; ++i) emit(t.slot, i, g);
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::moveVertex(
    [[maybe_unused]] const Ray& ray, [[maybe_unused]] const SurfaceHit& hit) {
  if constexpr (kGradients) {
    if (!ctx_.gradients->shapes) return;
    PathMotion& m = sink_.tape->motion;
    vertexMotion(tangents_->shapes, *scene_.geometry, ray, m.ray, hit, m.vertex);
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
auto PathWalk<kFluorescence, kMedia, kWhite, Sink>::bsdfValue(const SurfaceVertex& v,
                                                              const SampledWavelengths& at,
                                                              bool diffuseLobe) const {
  return [&v, &at, diffuseLobe, hero = heroAlone_](const Vec3& ng, const Vec3& ns, const Vec3& wo,
                                                   const Vec3& wi) {
    SurfaceBsdf b(v.material, at, v.rho, ng, ns, wo);
    b.setHeroAlone(hero);
    b.orient(v.hit.dpdu); // as the rendered BSDF (its tangent held, projected on ns's plane)
    return diffuseLobe ? b.diffuseLobe(wi) : b.f(wi);
  };
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
template <class Emit>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::shapeLightEvents(
    [[maybe_unused]] const SurfaceVertex& v, [[maybe_unused]] const LightSample& ls,
    [[maybe_unused]] const SampledWavelengths& at, [[maybe_unused]] Emit&& emit) {
  if constexpr (kGradients) {
    const std::vector<VertexMotion>& motion = sink_.tape->motion.vertex;
    if (motion.empty()) return;
    const auto value = bsdfValue(v, at, v.fluorescent);
    const BsdfDerivativeSteps step = bsdfDerivativeSteps(v.material);
    const SurfaceHit& hit = v.hit;
    const SampledSpectrum f = value(hit.ng, hit.ns, v.wo, ls.wi);
    const SpotLight* spot =
        ls.delta ? ctx_.gradients->spotOfSampledLight[static_cast<size_t>(ls.light)] : nullptr;
    for (const VertexMotion& m : motion) {
      // The light's point is held: its direction turns as the vertex moves; radiance arrives
      // with |cos_y| / d^2 (area lights) or I(direction) / d^2 (point and spot lights).
      const Vec3 dwi = ls.infinite ? Vec3() : towardsFixedPoint(ls.wi, ls.distance, m.dp);
      const SampledSpectrum df = directionalDerivative(value, step, hit.ng, hit.ns, v.wo, ls.wi,
                                                       m.dng, m.dns, -m.dDir, dwi);
      float extra = 0;
      if (!ls.infinite) {
        extra = 2 * dot(ls.wi, m.dp) / ls.distance;
        if (!ls.delta) {
          if (const float cy = dot(ls.n, ls.wi); cy != 0) extra += dot(ls.n, dwi) / cy;
        } else if (spot) {
          const float c = -dot(spot->axis, ls.wi), fall = spot->falloff(c);
          const float e = 1e-4f;
          if (fall > 0)
            extra += (spot->falloff(c + e) - spot->falloff(c - e)) / (2 * e) *
                     -dot(spot->axis, dwi) / fall;
        }
      }
      logDerivativeEvents(m.slot, df, f, extra, emit);
    }
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::shapeContinuation(
    [[maybe_unused]] const SurfaceVertex& v, [[maybe_unused]] const BsdfSample& bs,
    [[maybe_unused]] const SampledWavelengths& at) {
  if constexpr (kGradients) {
    PathMotion& pm = sink_.tape->motion;
    pm.ray.clear();
    if (pm.vertex.empty()) return;
    const SurfaceHit& hit = v.hit;
    pm.lobe.valid = false;
    if (!bs.specular) {
      // The sampled direction is held: the factor f |cos| / p changes with the frame.
      const auto value = bsdfValue(v, at, v.fluorescent);
      const SampledSpectrum f = value(hit.ng, hit.ns, v.wo, bs.wi);
      ContinuationLobe& lobe = pm.lobe;
      lobe = {true, bs.wi, {}, {}, f, {}, {}};
      const Frame basis = Frame::fromNormal(bs.wi);
      lobe.e1 = basis.s;
      lobe.e2 = basis.t;
      const BsdfDerivativeSteps step = bsdfDerivativeSteps(v.material);
      lobe.d1 = directionalDerivative(value, step, hit.ng, hit.ns, v.wo, bs.wi, Vec3(), Vec3(),
                                      Vec3(), lobe.e1);
      lobe.d2 = directionalDerivative(value, step, hit.ng, hit.ns, v.wo, bs.wi, Vec3(), Vec3(),
                                      Vec3(), lobe.e2);
      for (const VertexMotion& m : pm.vertex) {
        const SampledSpectrum df = directionalDerivative(value, step, hit.ng, hit.ns, v.wo, bs.wi,
                                                         m.dng, m.dns, -m.dDir, Vec3());
        logDerivativeEvents(m.slot, df, f, 0.0f, event());
        pm.ray.push_back({m.slot, m.dp, Vec3()});
      }
      return;
    }
    // A delta lobe: its direction and weight are functions of the frame and of wo.
    const bool reflected = (dot(bs.wi, hit.ng) > 0) == (dot(v.wo, hit.ng) > 0);
    auto lobe = [&](const Vec3& ng, const Vec3& ns, const Vec3& wo, SpecularLobe& out) {
      SurfaceBsdf b(v.material, at, v.rho, ng, ns, wo);
      SpecularLobe l[2];
      const int k = b.specularLobes(l);
      for (int j = 0; j < k; ++j)
        if (((dot(l[j].wi, ng) > 0) == (dot(wo, ng) > 0)) == reflected) {
          out = l[j];
          return true;
        }
      return false;
    };
    SpecularLobe at0;
    if (!lobe(hit.ng, hit.ns, v.wo, at0)) return;
    for (const VertexMotion& m : pm.vertex) {
      const Vec3 dwo = -m.dDir;
      const float scale = std::max({length(m.dng), length(m.dns), length(dwo)});
      Vec3 dDir;
      if (scale > 0 && std::isfinite(scale)) {
        // Richardson-extrapolated differences (richardsonDerivative) of the lobe's direction
        // and weight; none where a side has no such lobe (at total internal reflection).
        bool all = true;
        auto moved = [&](float s) {
          SpecularLobe l;
          all = all && lobe(normalize(hit.ng + m.dng * s), normalize(hit.ns + m.dns * s),
                            normalize(v.wo + dwo * s), l);
          return l;
        };
        const float h = bsdfDerivativeSteps(v.material).normals / scale;
        const SpecularLobe p1 = moved(h), m1 = moved(-h), p2 = moved(0.5f * h),
                           m2 = moved(-0.5f * h);
        if (all) {
          const float c = 1.0f / (6.0f * h);
          dDir = ((p2.wi - m2.wi) * 8.0f - (p1.wi - m1.wi)) * c;
          const SampledSpectrum dWeight =
              ((p2.weight + m2.weight * -1.0f) * 8.0f + (p1.weight + m1.weight * -1.0f) * -1.0f) *
              c;
          logDerivativeEvents(m.slot, dWeight, at0.weight, 0.0f, event());
        }
      }
      pm.ray.push_back({m.slot, m.dp, dDir});
    }
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::emitterPointHeld(
    [[maybe_unused]] const Ray& ray, [[maybe_unused]] const SurfaceHit& hit) {
  if constexpr (kGradients) {
    const PathMotion& pm = sink_.tape->motion;
    const ContinuationLobe& lobe = pm.lobe;
    if (!lobe.valid || pm.ray.empty()) return;
    const float t = length(hit.p - ray.o), cy = dot(hit.ng, lobe.wi);
    if (!(t > 0) || cy == 0) return;
    for (const RayMotion& r : pm.ray) {
      // The point y held, the vertex moving by do: wi turns by dwi; |cos_y| / t^2 changes.
      const Vec3 dwi = towardsFixedPoint(lobe.wi, t, r.dOrigin);
      const SampledSpectrum df = lobe.d1 * dot(dwi, lobe.e1) + lobe.d2 * dot(dwi, lobe.e2);
      const float extra = 2 * dot(lobe.wi, r.dOrigin) / t + dot(hit.ng, dwi) / cy;
      logDerivativeEvents(r.slot, df, lobe.f, extra, local());
    }
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::directionBoundary(
    [[maybe_unused]] const SampledWavelengths& current, [[maybe_unused]] const SurfaceVertex& v) {
  if constexpr (kGradients) {
    GradientTape& tape = *sink_.tape;
    if (!ctx_.gradients->shapes || !ctx_.gradients->boundary || !tape.boundaryRng ||
        !v.bsdf.hasNonSpecular())
      return;
    // The incoming light the lobe re-radiates is at the excitation wavelengths.
    const SampledWavelengths& lit = v.fluorescent ? v.shift.excited : current;
    forEachAnalyticKind([&]<class P>() {
      for (uint32_t k = 0; k < scene_.geometry->primitives<P>().size(); ++k)
        primitiveDirectionBoundary(lit, v, kShapeKindOf<P>, k, P::kSelfLighting);
    });
    meshDirectionBoundary(lit, v);
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::primitiveDirectionBoundary(
    [[maybe_unused]] const SampledWavelengths& lit, [[maybe_unused]] const SurfaceVertex& v,
    [[maybe_unused]] ShapeKind kind, [[maybe_unused]] uint32_t k,
    [[maybe_unused]] SelfLighting selfLighting) {
  if constexpr (kGradients) {
    GradientTape& tape = *sink_.tape;
    const std::vector<VertexMotion>& motion = tape.motion.vertex;
    const ShapeTangents& shapes = tangents_->shapes;
    const SurfaceHit& hit = v.hit;
    const Vec3d x(hit.p);
    // Outlines move where the primitive moves or the vertex does; a convex or flat primitive
    // never hides itself.
    if (!primitiveMoves(shapes, kind, k) && motion.empty()) return;
    if (hit.kind == kind && hit.index == k && selfLighting != SelfLighting::Possible) return;
    OutlineCurves curves;
    primitiveOutlines(*scene_.geometry, kind, k, x, curves);
    if (curves.count == 0) return;
    // A curve chosen uniformly, a point uniformly along it.
    PixelSampleStream& brng = *tape.boundaryRng;
    const Sample2 u = brng.next2D();
    const OutlineCurve& curve = curves.curve[static_cast<size_t>(
        std::min(curves.count - 1, static_cast<int>(static_cast<double>(u.u) * curves.count)))];
    const Vec3d m = curve.at(u.v), dm = curve.tangent(u.v), toM = m - x;
    if (!curve.keeps(m)) return;
    const Vec3d ne = outlineNormal(x, m, dm);
    const double dist = length(toM);
    const Vec3d wd = toM / dist;
    const SampledSpectrum f = scattered(v, Vec3(wd));
    if (f.isBlack()) return;
    // phi(omega) = ne . (x + dist omega - m): |grad phi| over directions = dist; d phi / d x =
    // ne; d phi / d slot = -ne . (the velocity of the primitive's material point at m).
    std::vector<std::pair<uint32_t, double>>& rates = tape.motion.rates;
    rates.clear();
    forEachPrimitiveVelocity(
        shapes, *scene_.geometry, kind, k, m, curve.part,
        [&](uint32_t slot, const Vec3d& vel) { addRate(rates, slot, -dot(ne, vel)); });
    for (const VertexMotion& vm : motion) addRate(rates, vm.slot, dot(ne, Vec3d(vm.dp)));
    const double speed = length(dm - wd * dot(wd, dm)) / dist;
    if (!(dist > 0) || !(speed > 0) || !(length(ne) > 0)) return;
    // L either side of the outline (phi < 0 on side 0), with the same random numbers.
    const Vec3d side = ne * (1e-4 * dist);
    const Vec3d targets[2] = {m - side, m + side};
    SampledSpectrum L[2];
    radianceEitherSide(v, targets, lit, L);
    // The outline's length per sample: count times the chosen curve's speed; v_n = -d phi /
    // |grad phi|.
    const double scale = curves.count * speed / dist;
    heldEmitterTerms(v, targets, lit, kind, k, ne * dist, beta_ * f, scale, VertexSlots::All, L);
    boundaryTerms(beta_ * f * (L[0] + L[1] * -1.0f), scale);
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::radianceEitherSide(
    [[maybe_unused]] const SurfaceVertex& v, [[maybe_unused]] const Vec3d (&targets)[2],
    [[maybe_unused]] const SampledWavelengths& lit, [[maybe_unused]] SampledSpectrum (&L)[2]) {
  if constexpr (kGradients) {
    PixelSampleStream& brng = *sink_.tape->boundaryRng;
    const PixelSampleStream start = brng;
    for (int side = 0; side < 2; ++side) {
      PixelSampleStream r = start;
      Ray ray;
      ray.d = Vec3(normalize(targets[side] - Vec3d(v.hit.p)));
      ray.o = offsetRayOrigin(v.hit.p, v.hit.pError, v.hit.ng, ray.d);
      L[side] = tracePath(ctx_, ray, lit, r, counters_);
      if (side == 1) brng = r;
    }
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::boundaryTerms(
    [[maybe_unused]] const SampledSpectrum& term, [[maybe_unused]] double scale) {
  if constexpr (kGradients) {
    if (term.isBlack()) return;
    for (const auto& [slot, dPhi] : sink_.tape->motion.rates)
      if (dPhi != 0)
        for (int i = 0; i < kLanes; ++i)
          if (term[i] != 0) sink_.direct(slot, i, term[i] * static_cast<float>(-dPhi * scale));
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::meshDirectionBoundary(
    [[maybe_unused]] const SampledWavelengths& lit, [[maybe_unused]] const SurfaceVertex& v) {
  if constexpr (kGradients) {
    const ShapeTangents& shapes = tangents_->shapes;
    bool cameraMovesVertex = false;
    for (const VertexMotion& vm : sink_.tape->motion.vertex)
      cameraMovesVertex = cameraMovesVertex || cameraSlot(vm.slot);
    for (uint32_t k = 0; k < shapes.meshes.size(); ++k) {
      const MeshMotion& mm = shapes.meshes[k];
      if (mm.moves() && !mm.edges.empty()) meshEdgeBoundary(lit, v, k, mm.edges, false);
      if (cameraMovesVertex && !mm.cameraEdges.empty())
        meshEdgeBoundary(lit, v, k, mm.cameraEdges, true);
    }
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::meshEdgeBoundary(
    [[maybe_unused]] const SampledWavelengths& lit, [[maybe_unused]] const SurfaceVertex& v,
    [[maybe_unused]] uint32_t k, [[maybe_unused]] const std::vector<MeshEdge>& edges,
    [[maybe_unused]] bool camera) {
  if constexpr (kGradients) {
    GradientTape& tape = *sink_.tape;
    const std::vector<VertexMotion>& motion = tape.motion.vertex;
    const SurfaceHit& hit = v.hit;
    const Vec3d x(hit.p);
    std::vector<std::pair<uint32_t, double>>& rates = tape.motion.rates;
    const ShapeTangents& shapes = tangents_->shapes;
    const MeshMotion& mm = shapes.meshes[k];
    // An edge chosen uniformly (its share of the outline is E times what it holds), a point
    // uniformly along it; only the outline seen from x jumps.
    const TriangleMesh& mesh = scene_.geometry->meshes()[k];
    PixelSampleStream& brng = *tape.boundaryRng;
    const Sample2 u = brng.next2D();
    const size_t count = edges.size();
    const MeshEdge& e =
        edges[std::min(count - 1, static_cast<size_t>(u.u * static_cast<double>(count)))];
    if (!outlineEdge(mesh, e, x)) return;
    if (hit.kind == ShapeKind::Triangle && hit.index == k &&
        (e.face0 == hit.prim || e.face1 == hit.prim))
      return; // an edge of x's own triangle: seen edge-on
    const Vec3d v0(mesh.position(e.v0)), v1(mesh.position(e.v1));
    const Vec3d m = v0 + (v1 - v0) * static_cast<double>(u.v), toM = m - x;
    const double dist = length(toM);
    const Vec3d wd = toM / dist;
    const Vec3 wi(wd);
    const SampledSpectrum f = scattered(v, wi);
    if (f.isBlack()) return;
    // phi(omega) = n_e . omega, n_e = (v0 - x) x (v1 - x): its gradient on the sphere of
    // directions n_e - omega (omega . n_e); d phi / d v0 = (v1 - x) x omega, d phi / d v1 =
    // omega x (v0 - x), d phi / d x = -(v1 - v0) x omega.
    const Vec3d ne = cross(v0 - x, v1 - x), g = ne - wd * dot(wd, ne);
    const double grad = length(g);
    const Vec3d dv = v1 - v0;
    const double speed = length(dv - wd * dot(wd, dv)) / dist;
    if (!(grad > 0) || !(speed > 0)) return;
    rates.clear();
    const Vec3d d0 = cross(v1 - x, wd), d1 = cross(wd, v0 - x), dx = cross(dv, wd) * -1.0;
    if (!camera) {
      mm.forEachVelocity(e.v0, [&](uint32_t slot, const Vec3d& velocity) {
        addRate(rates, slot, dot(d0, velocity));
      });
      mm.forEachVelocity(e.v1, [&](uint32_t slot, const Vec3d& velocity) {
        addRate(rates, slot, dot(d1, velocity));
      });
    }
    for (const VertexMotion& vm : motion)
      if (cameraSlot(vm.slot) == camera) addRate(rates, vm.slot, dot(dx, Vec3d(vm.dp)));
    if (rates.empty()) return;
    const Vec3d side = g * (1e-4 * dist / grad);
    const Vec3d targets[2] = {m - side, m + side};
    SampledSpectrum L[2];
    radianceEitherSide(v, targets, lit, L);
    const double scale = static_cast<double>(count) * speed / grad;
    heldEmitterTerms(v, targets, lit, ShapeKind::Triangle, k, ne, beta_ * f, scale,
                     camera ? VertexSlots::Camera : VertexSlots::NotCamera, L);
    boundaryTerms(beta_ * f * (L[0] + L[1] * -1.0f), scale);
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
bool PathWalk<kFluorescence, kMedia, kWhite, Sink>::cameraSlot(uint32_t slot) const {
  for (const CameraMotion& c : tangents_->shapes.camera)
    if (c.slot == slot) return true;
  return false;
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::heldEmitterTerms(
    [[maybe_unused]] const SurfaceVertex& v, [[maybe_unused]] const Vec3d (&targets)[2],
    [[maybe_unused]] const SampledWavelengths& lit, [[maybe_unused]] ShapeKind ownKind,
    [[maybe_unused]] uint32_t own, [[maybe_unused]] const Vec3d& dPhiDw,
    [[maybe_unused]] const SampledSpectrum& weight, [[maybe_unused]] double scale,
    [[maybe_unused]] VertexSlots which, [[maybe_unused]] SampledSpectrum (&L)[2]) {
  if constexpr (kGradients) {
    if (scene_.emission.empty()) return; // (no shape emits)
    const SurfaceHit& hit = v.hit;
    const Vec3d x(hit.p);
    const std::vector<VertexMotion>& motion = sink_.tape->motion.vertex;
    for (int s = 0; s < 2; ++s) {
      Ray in;
      in.d = Vec3(normalize(targets[s] - x));
      in.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, in.d);
      SurfaceHit first;
      ++counters_.rays;
      if (!scene_.geometry->intersect(in, first)) continue;
      const int32_t e = scene_.appearance(first).emission;
      if (e < 0) continue;
      const SampledSpectrum le = evaluate(scene_.emission[static_cast<size_t>(e)], lit);
      if (first.kind == ownKind && first.index == own) {
        L[s] = L[s] + le * -1.0f;
        continue;
      }
      // phi at the held point's direction: d phi = dPhiDw . d omega_y; side 0 (phi < 0)
      // enters the jump with +, side 1 with -, each as -d phi.
      const SampledSpectrum term = weight * le * static_cast<float>((s == 0 ? -1 : 1) * scale);
      for (const VertexMotion& vm : motion) {
        if (which != VertexSlots::All && cameraSlot(vm.slot) != (which == VertexSlots::Camera))
          continue;
        const Vec3 dw = towardsFixedPoint(in.d, first.t, vm.dp);
        const float rate = static_cast<float>(dot(dPhiDw, Vec3d(dw)));
        if (rate == 0) continue;
        for (int i = 0; i < kLanes; ++i)
          if (term[i] != 0) sink_.direct(vm.slot, i, term[i] * rate);
      }
    }
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
bool PathWalk<kFluorescence, kMedia, kWhite, Sink>::guidedDirectLight(
    [[maybe_unused]] Ray& ray_, [[maybe_unused]] SampledWavelengths& current_, SurfaceVertex& v,
    float& weightsHere) {
  if (!(v.fluorescent && !ctx_.columnOnlyExcitation && v.bsdf.hasNonSpecular() &&
        ctx_.lightSampling != LightSampling::BsdfOnly && ctx_.lights->count() > 0))
    return false;
  if constexpr (std::is_same_v<Sink, RelightSink>)
    if (scene_.relight.samplingOfSource.empty()) return false; // lights of unknown spectra
  const SurfaceHit& hit = v.hit;
  const float uChoice = rng_.next1D();
  const Sample2 uLight = rng_.next2D();
  const Sample2 uGuide = rng_.next2D();
  float share = 0, uRest = 0;
  const int l = ctx_.lights->choose(hit.p, hit.ns, uChoice, share, uRest, &weightsHere);
  LightSample ls, lsGuided[kMaxExcitationGuides];
  if (l >= 0 &&
      ctx_.lights->sampleChosen(l, share, hit.p, uRest, uLight, v.shift.excited, ls, hit.ns)) {
    // Where the light meets the column evenly the column's event alone, at its weight.
    const bool guide = ctx_.lights->guidanceHelps(l, v.app.material, current_);
    GuidedShift g;
    if (guide) {
      // Guide t's sample: uGuide shifted by t times the R2 sequence's steps (each uniform, so
      // each technique's events are drawn as they should be; no further dimensions used).
      const ExcitationGuides guides = ctx_.lights->excitationGuides(l);
      Sample2 u[kMaxExcitationGuides];
      for (int t = 0; t < guides.count; ++t) {
        const float su = 0.7548776662f * static_cast<float>(t),
                    sv = 0.5698402910f * static_cast<float>(t);
        u[t] = {rotateUnit(uGuide.u, su - std::floor(su)),
                rotateUnit(uGuide.v, sv - std::floor(sv))};
      }
      g = guideFluorescentShift(*v.material.reradiation, current_, v.shift, v.rho, v.concentration,
                                guides, u);
      for (int t = 0; t < g.count; ++t)
        ctx_.lights->sampleChosen(l, share, hit.p, uRest, uLight, g.guided[t], lsGuided[t], hit.ns);
    } else {
      g.columnWeight = v.shift.albedo;
    }
    // One shadow ray for both events: the light's geometry with unit radiance.
    LightSample unit = ls;
    unit.radiance = SampledSpectrum::filled(1.0f);
    const SampledSpectrum geometric = directLight(
        scene_, hit, ray_.d, unit, [&](const Vec3& wi) { return v.bsdf.diffuseLobe(wi); },
        [&](const Vec3& wi) { return v.bsdf.pdf(wi); },
        ctx_.lightSampling != LightSampling::NeeOnly, counters_);
    if (!geometric.isBlack()) {
      const uint16_t group = ctx_.lights->group(l), source = ctx_.lights->source(l);
      const auto lanesOf = [&](const SampledWavelengths& lit) {
        return Sink::kClasses ? shiftedLanes(lit, current_) : uint64_t{0};
      };
      sink_.add(
          beta_ * geometric * g.columnWeight * ls.radiance,
          classOf(scatterings_ + 1, group, source, v.shift.excited, lanesOf(v.shift.excited)));
      for (int t = 0; t < g.count; ++t)
        sink_.add(beta_ * geometric * g.guidedWeight[t] * lsGuided[t].radiance,
                  classOf(scatterings_ + 1, group, source, g.guided[t], lanesOf(g.guided[t])));
    }
  }
  return true;
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void PathWalk<kFluorescence, kMedia, kWhite, Sink>::directLightHere(
    [[maybe_unused]] Ray& ray_, [[maybe_unused]] SampledWavelengths& current_, SurfaceVertex& v,
    float& weightsHere) {
  const SurfaceHit& hit = v.hit;
  const float uChoice = rng_.next1D();
  const Sample2 uLight = rng_.next2D();
  LightSample ls;
  const SampledWavelengths& lit = v.fluorescent ? v.shift.excited : current_;
  if (!ctx_.lights->sample(hit.p, uChoice, uLight, lit, ls, hit.ns, &weightsHere)) return;
  auto f = [&](const Vec3& wi) { return scattered(v, wi); };
  auto pdf = [&](const Vec3& wi) { return v.bsdf.pdf(wi); };
  const PathClass k =
      classOf(scatterings_ + 1, ctx_.lights->group(ls.light), ctx_.lights->source(ls.light), lit,
              Sink::kClasses ? shiftedLanes(lit, current_) : uint64_t{0});
  if constexpr (kGradients) {
    if (!v.whiteHere) {
      if (v.fluorescent)
        reradiationEvents(tangents_->reradiation[v.app.material], v.rhoTangents,
                          *v.material.reradiation, current_, v.shift.excited, v.rho, sink_, local(),
                          v.concentration, v.concentrationTangents);
      roughnessEvents(v, ls.wi, local());
      reflectanceEvents(v.rhoTangents, v.bsdf, ls.wi, current_, v.rho, false, !v.fluorescent, sink_,
                        local());
    }
    lightEvents(ls, lit);
    shapeLightEvents(v, ls, current_, local());
  }
  if constexpr (kMedia) {
    const auto visible = [&](const Ray& r) {
      return shadowTransmittance(scene_, r, media_, lit, counters_, shadowCrossings());
    };
    const SampledSpectrum direct = directLightThrough(
        hit, ray_.d, ls, f, pdf, ctx_.lightSampling != LightSampling::NeeOnly, visible);
    if constexpr (kGradients)
      if (!direct.isBlack())
        shadowEvents(*tangents_, scene_, sink_.tape->crossings, lit, sink_, local());
    sink_.add(weighted() * direct, k);
  } else {
    sink_.add(beta_ * directLight(scene_, hit, ray_.d, ls, f, pdf,
                                  ctx_.lightSampling != LightSampling::NeeOnly, counters_),
              k);
  }
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
bool PathWalk<kFluorescence, kMedia, kWhite, Sink>::continueFrom(
    [[maybe_unused]] Ray& ray_, [[maybe_unused]] SampledWavelengths& current_, SurfaceVertex& v,
    float weightsHere) {
  const SurfaceHit& hit = v.hit;
  [[maybe_unused]] const SampledWavelengths lambdaBefore = current_; // before a re-radiation
  BsdfSample bs;
  const float uLobe = rng_.next1D();
  const Sample2 uDir = rng_.next2D();
  if (!v.bsdf.sample(uLobe, uDir, bs)) return false;
  if constexpr (kFluorescence) {
    if (v.fluorescent && !bs.specular) { // the diffuse lobe re-radiates; the mirror lobe does not
      bs.weight = v.shift.albedo * bs.diffuseScale;
      if constexpr (Sink::kClasses) shifted_ |= shiftedLanes(v.shift.excited, current_);
      if constexpr (kGradients) {
        if (!v.whiteHere)
          reradiationEvents(tangents_->reradiation[v.app.material], v.rhoTangents,
                            *v.material.reradiation, current_, v.shift.excited, v.rho, sink_,
                            event(), v.concentration, v.concentrationTangents);
      }
      current_ = v.shift.excited;
    }
  }
  if constexpr (kGradients) {
    // The lobe taken scales the rest of the path (a fluorescent diffuse lobe's albedo came from
    // the matrix; rho's other shares, a coat's, from here).
    if (!v.whiteHere) {
      if (!bs.specular) roughnessEvents(v, bs.wi, event());
      const bool reradiated = v.fluorescent && !bs.specular;
      reflectanceEvents(v.rhoTangents, v.bsdf, bs.wi, lambdaBefore, v.rho, bs.specular, !reradiated,
                        sink_, event());
    }
    shapeContinuation(v, bs, lambdaBefore);
  }
  if constexpr (kMedia) {
    crossBoundary(hit, v.app, v.wo, bs.wi, media_);
    if (bs.straight) {
      // Straight through a thin wall: like an interface, the MIS state stays the previous
      // vertex's (next-event estimation sees through the wall).
      beta_ *= bs.weight;
      if (beta_.isBlack()) return false;
      ray_.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, bs.wi);
      ray_.tMin = 0;
      ray_.tMax = INFINITY;
      return true;
    }
  }
  beta_ *= bs.weight;
  rrScale_ *= bs.eta * bs.eta;
  if (bs.terminateSecondary && !heroAlone_) {
    // From here on the hero's estimator stands alone; what L holds keeps its lane weights. Its
    // weight is f_hero / p_hero: beta's hero lane over the hero's ratio (1 unless media rescaled
    // both).
    beta_ = heroOnly(beta_);
    if constexpr (kMedia) beta_ *= misRatios_[0] > 0 ? 1.0f / misRatios_[0] : 0.0f;
    rrScale_ *= 1.0f / static_cast<float>(kLanes);
    heroAlone_ = true;
    if constexpr (kMedia) invMisDivisor_ = 1.0f;
  }
  specular_ = bs.specular;
  prevPdf_ = bs.pdf;
  prevP_ = hit.p;
  prevN_ = hit.ns;
  prevWeights_ = weightsHere;
  if (!survivesRoulette()) return false;
  ray_.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, bs.wi);
  ray_.d = bs.wi;
  ray_.tMin = 0;
  ray_.tMax = INFINITY;
  return true;
}

template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void tracePathImpl(const IntegratorContext& ctx, Ray ray, const SampledWavelengths& lambda,
                   PixelSampleStream& rng, TraceCounters& counters, Sink& sink) {
  PathWalk<kFluorescence, kMedia, kWhite, Sink> walk(ctx, ray, lambda, rng, counters, sink);
  if constexpr (std::is_same_v<Sink, RadianceSink> && !kWhite)
    walk.runFlattened();
  else
    walk.run();
}

// The walk for the scene's media (with or without), fluorescence fixed.
template <bool kFluorescence, bool kWhite, class Sink>
void traceMediaVariant(const IntegratorContext& ctx, const Ray& ray,
                       const SampledWavelengths& lambda, PixelSampleStream& rng,
                       TraceCounters& counters, Sink& sink) {
  if (ctx.scene->hasMedia)
    tracePathImpl<kFluorescence, true, kWhite>(ctx, ray, lambda, rng, counters, sink);
  else
    tracePathImpl<kFluorescence, false, kWhite>(ctx, ray, lambda, rng, counters, sink);
}

// The walk compiled for the scene's features (fluorescence, media).
template <bool kWhite, class Sink>
void traceVariant(const IntegratorContext& ctx, const Ray& ray, const SampledWavelengths& lambda,
                  PixelSampleStream& rng, TraceCounters& counters, Sink& sink) {
  if (ctx.fluorescence)
    traceMediaVariant<true, kWhite>(ctx, ray, lambda, rng, counters, sink);
  else
    traceMediaVariant<false, kWhite>(ctx, ray, lambda, rng, counters, sink);
}
} // namespace path_walk
} // namespace nx
