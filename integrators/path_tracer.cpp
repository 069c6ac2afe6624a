#include <cmath>

#include "core/ray_offset.h"
#include "integrators/fluorescent_vertex.h"
#include "integrators/gradients/gradient_context.h"
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
namespace {

// A path at the surface of a closed shape (a sphere, a closed mesh in a media scene),
// arriving from wo (pointing back along the path) and leaving along wi: when it transmits
// (wo and wi on opposite sides), it enters or leaves the medium the shape holds.
void crossBoundary(const SurfaceHit& hit, const ShapeAppearance& app, const Vec3& wo,
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
uint16_t relightSourceOf(const LightGroups& groups, int32_t e) {
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
const std::vector<MediumTangent>& noMediumTangents() {
  static const std::vector<MediumTangent> none;
  return none;
}

// The white reference's surface: a Lambertian reflector of reflectance 1.
const Material& whiteLambertian() {
  static const Material white = [] {
    Material m;
    m.kind = MaterialKind::Mixture;
    m.roughness = 1.0f;
    m.reflectance = Spectrum(ConstantSpectrum{1.0});
    return m;
  }();
  return white;
}

// kFluorescence: compiled in only for scenes with fluorescent materials, so that other
// scenes run exactly the code they would without the feature.
// kMedia: likewise for scenes with media or interface surfaces: the path tracks the media it
// is in, samples free flights through them and sees through interfaces in its shadow rays.
// kWhite: the first surface hit is replaced by a white Lambertian reflector that does not emit
// (the white-reference AOV); later bounces see the scene as it is.
// Sink: where contributions go (path_contributions.h); with Sink::kClasses the path's class
// (shifted lanes, scatterings, light group) is tracked for each of them.
template <bool kFluorescence, bool kMedia, bool kWhite, class Sink>
void tracePathImpl(const IntegratorContext& ctx, Ray ray, const SampledWavelengths& lambda,
                   PixelSampleStream& rng, TraceCounters& counters, Sink& sink) {
  const RenderScene& scene = *ctx.scene;
  const int rouletteStart = scene.settings.depth;
  // Differentiated renders: the tangents, and the two ways an event enters the tape (scaling
  // every later contribution, or the next one only).
  constexpr bool kGradients = recordsGradients<Sink>();
  [[maybe_unused]] const SceneTangents* tangents =
      ctx.gradients ? ctx.gradients->tangents : nullptr;
  [[maybe_unused]] auto event = [&](uint32_t slot, int lane, float g) {
    if constexpr (kGradients) sink.event(slot, lane, g);
  };
  [[maybe_unused]] auto local = [&](uint32_t slot, int lane, float g) {
    if constexpr (kGradients) sink.local(slot, lane, g);
  };
  // Where a shadow ray records what it passed through (differentiated renders), else null.
  [[maybe_unused]] auto shadowCrossings = [&]() -> ShadowCrossings* {
    if constexpr (kGradients) {
      sink.tape->crossings.clear();
      return &sink.tape->crossings;
    } else {
      return nullptr;
    }
  };
  // The local events of a sampled light's emission (its radiance or intensity at `lit`).
  [[maybe_unused]] auto lightEvents = [&](const LightSample& ls, const SampledWavelengths& lit) {
    if constexpr (kGradients) {
      const size_t l = static_cast<size_t>(ls.light);
      if (const Spectrum* emitted = ctx.gradients->spectrumOfSampledLight[l])
        ratioEvents(*ctx.gradients->ofSampledLight[l], lit, evaluate(*emitted, lit), sink, local);
    }
  };
  // lambda: the sensor wavelengths (where the film accumulates); current: what lights and
  // materials are evaluated at (they differ after a fluorescent shift).
  SampledWavelengths current = lambda;
  SampledSpectrum beta = SampledSpectrum::filled(1.0f);
  const LightGroups& groups = scene.lightGroups;
  // Lanes re-radiated so far (tracked for component sinks only).
  [[maybe_unused]] uint64_t shifted = 0;
  // The class of a contribution after `events` scatterings from an emitter of light group
  // `group` and relight source `source`, which the light left at wavelengths `emitted`; the
  // lanes of `extra` shifted in addition.
  auto classOf = [&]([[maybe_unused]] int events, [[maybe_unused]] uint16_t group,
                     [[maybe_unused]] uint16_t source,
                     [[maybe_unused]] const SampledWavelengths& emitted,
                     [[maybe_unused]] uint64_t extra = 0) {
    PathClass k;
    if constexpr (Sink::kClasses) k = {shifted | extra, events, group, source, &emitted};
    return k;
  };
  // Russian roulette looks at beta * rrScale: the throughput without the radiance scaling
  // 1 / eta^2 of refractions (a lossless path through glass keeps probability 1, as in pbrt-v4
  // and Mitsuba 3) and without the factor kLanes of a hero-only path.
  float rrScale = 1;
  bool heroAlone = kLanes == 1; // the secondary lanes were terminated (dispersion)
  bool specular = true;         // the previous bounce was specular (or the camera)
  float prevPdf = 0;
  Vec3 prevP = ray.o;
  Vec3 prevN; // shading normal at prevP (zero in a medium): light pdfs' cosine warp
  // The sum of the light weights next-event estimation found at prevP (LightSampler::choose;
  // 0: none), so the MIS weight of an emitter found from there does not weigh every light again.
  float prevWeights = 0;
  [[maybe_unused]] MediumStack media;
  // Spectral MIS through media: p_lane / p_hero of the path so far (free_flight.h); every
  // contribution is divided by their mean (1 while no medium event happened).
  [[maybe_unused]] SampledSpectrum misRatios = SampledSpectrum::filled(1.0f);
  // 1 / spectralMisDivisor(misRatios, heroAlone), kept up to date where either changes (after
  // each free flight, when the hero goes alone) rather than summed at every contribution.
  [[maybe_unused]] float invMisDivisor = 1.0f;
  if constexpr (kMedia) media = scene.cameraMedia;
  // beta for contributions: with media, divided by the spectral MIS divisor
  auto weighted = [&]() {
    if constexpr (kMedia)
      return beta * invMisDivisor;
    else
      return beta;
  };
  // Scattering vertices so far (surfaces and media; interfaces do not count): Russian roulette
  // starts after <depth> of them.
  int scatterings = 0;
  // Counts a scattering vertex and plays Russian roulette after <depth> of them, re-weighting
  // survivors by 1/q (unbiased); false: the path ends (terminated, or nothing left to carry).
  auto survivesRoulette = [&]() {
    if (++scatterings >= rouletteStart) {
      const float q = std::min(1.0f, weighted().maxValue() * rrScale);
      const float u = rng.next1D();
      if (!(q > 0) || u >= q) return false;
      beta *= 1.0f / q;
    }
    return !beta.isBlack();
  };

  for (int bounce = 0;; ++bounce) {
    SurfaceHit hit;
    ++counters.rays;
    // Weight of an emitter found by this BSDF-sampled ray that next-event estimation could
    // also have sampled, with density lightPdf.
    auto emitterWeight = [&](float lightPdf) {
      if (specular || ctx.lightSampling == LightSampling::BsdfOnly || !(lightPdf > 0)) return 1.0f;
      return ctx.lightSampling == LightSampling::NeeOnly ? 0.0f : powerHeuristic(prevPdf, lightPdf);
    };
    const bool found = scene.geometry->intersect(ray, hit);
    if constexpr (kMedia) {
      if (const int m = media.current(); m >= 0) {
        const HomogeneousMedium& medium = scene.media[static_cast<size_t>(m)];
        const float uDistance = rng.next1D(), uEvent = rng.next1D();
        // An emitting medium: the emission along the flight, weighted by the path before it.
        const SampledSpectrum before = medium.emission ? weighted() : SampledSpectrum();
        SampledSpectrum glow;
        const FreeFlight flight =
            sampleFreeFlight(medium, current, found ? hit.t : INFINITY, uDistance, uEvent, beta,
                             misRatios, medium.emission ? &glow : nullptr);
        if (medium.emission)
          sink.add(before * glow,
                   classOf(scatterings, groups.ofMedium[static_cast<size_t>(m)], 0, current));
        if constexpr (kGradients)
          freeFlightEvents(tangents->media[static_cast<size_t>(m)], medium, current, flight.event,
                           flight.event == MediumEvent::None ? (found ? hit.t : INFINITY)
                                                             : flight.t,
                           sink, event);
        // beta_i / mean(ratios) is all that counts, so both are divided by the mean after each
        // flight: the products stay near 1 on long chromatic paths (ratios' mean 1; the hero's
        // own ratio, once 1, becomes 1 / (the product of these means)).
        if (!heroAlone) {
          const float mean = spectralMisDivisor(misRatios, false);
          if (mean > 0) {
            misRatios *= 1.0f / mean;
            beta *= 1.0f / mean;
          }
        }
        invMisDivisor = 1.0f / spectralMisDivisor(misRatios, heroAlone);
        if (flight.event != MediumEvent::None) {
          if (bounce >= kMaxPathBounces) {
            ++counters.bounceLimited; // still carrying light: counted, reported
            break;
          }
          const Vec3 p = ray.at(flight.t);
          // A re-emission: every lane's excitation wavelength is chosen once (as at a
          // fluorescent surface), for next-event estimation and the continuation; the light
          // leaves isotropically. Its strength per lane is already in beta (sigma_fl).
          const bool reemitted = flight.event == MediumEvent::Fluoresce;
          const SampledWavelengths lit =
              reemitted
                  ? sampleFluorescentShift(*medium.dye, current, SampledSpectrum(), rng).excited
                  : current;
          auto phaseTo = [&](const Vec3& wi) {
            return reemitted ? static_cast<float>(1 / (4 * kPi))
                             : henyeyGreenstein(dot(ray.d, wi), medium.g);
          };
          [[maybe_unused]] const std::vector<MediumTangent>& mediumTangents =
              tangents ? tangents->media[static_cast<size_t>(m)] : noMediumTangents();
          if constexpr (kGradients)
            if (reemitted) reemissionEvents(mediumTangents, medium, current, lit, sink, event);
          float weightsHere = 0;
          if (ctx.lightSampling != LightSampling::BsdfOnly && ctx.lights->count() > 0) {
            const float uChoice = rng.next1D();
            const Sample2 uLight = rng.next2D();
            LightSample ls;
            if (ctx.lights->sample(p, uChoice, uLight, lit, ls, Vec3(), &weightsHere)) {
              const auto visible = [&](const Ray& r) {
                return shadowTransmittance(scene, r, media, lit, counters, shadowCrossings());
              };
              const SampledSpectrum direct = directLightAt(
                  p, Vec3(), Vec3(), ls,
                  [&](const Vec3& wi) { return SampledSpectrum::filled(phaseTo(wi)); }, phaseTo,
                  ctx.lightSampling != LightSampling::NeeOnly, visible);
              if constexpr (kGradients) {
                if (!direct.isBlack()) {
                  if (!reemitted) phaseEvents(mediumTangents, medium.g, dot(ray.d, ls.wi), local);
                  lightEvents(ls, lit);
                  shadowEvents(*tangents, scene, sink.tape->crossings, lit, sink, local);
                }
              }
              sink.add(weighted() * direct,
                       classOf(scatterings + 1, ctx.lights->group(ls.light),
                               ctx.lights->source(ls.light), lit,
                               Sink::kClasses ? shiftedLanes(lit, current) : uint64_t{0}));
            }
          }
          const Sample2 uDir = rng.next2D();
          const Vec3 wi =
              reemitted ? sampleUniformSphere(uDir) : sampleHenyeyGreenstein(ray.d, medium.g, uDir);
          if constexpr (Sink::kClasses) shifted |= shiftedLanes(lit, current);
          if constexpr (kGradients)
            if (!reemitted) phaseEvents(mediumTangents, medium.g, dot(ray.d, wi), event);
          current = lit;
          specular = false;
          prevPdf = phaseTo(wi);
          prevP = p;
          prevN = Vec3();
          prevWeights = weightsHere;
          if (!survivesRoulette()) break;
          ray.o = p;
          ray.d = wi;
          ray.tMin = 0;
          ray.tMax = INFINITY;
          continue;
        }
        if (beta.isBlack()) break;
      }
    }
    if (!found) {
      if (scene.background) {
        const SampledSpectrum le = evaluate(*scene.background, current);
        if constexpr (kGradients) ratioEvents(tangents->background, current, le, sink, local);
        sink.add(weighted() * le *
                     (specular
                          ? 1.0f
                          : emitterWeight(ctx.lights->pdfBackground(prevP, prevN, prevWeights))),
                 classOf(scatterings, groups.ofBackground, groups.sourceOfBackground, current));
      }
      for (int e = 0; e < ctx.lights->environmentCount(); ++e)
        sink.add(weighted() * ctx.lights->environmentRadiance(e, ray.d, current) *
                     (specular ? 1.0f
                               : emitterWeight(ctx.lights->pdfEnvironment(e, prevP, ray.d, prevN,
                                                                          prevWeights))),
                 classOf(scatterings, ctx.lights->environmentGroup(e), 0, current));
      break;
    }
    const ShapeAppearance& app = scene.appearance(hit);
    if constexpr (kMedia) {
      // An interface: the path goes straight on into (or out of) the medium it bounds; the
      // previous vertex stays the one MIS weights refer to (next-event estimation sees
      // through interfaces too).
      if (scene.materials[app.material].kind == MaterialKind::Interface) {
        if (bounce >= kMaxPathBounces) {
          ++counters.bounceLimited; // still carrying light: counted, reported
          break;
        }
        crossBoundary(hit, app, -ray.d, ray.d, media);
        ray.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, ray.d);
        ray.tMin = 0;
        ray.tMax = INFINITY;
        continue;
      }
    }
    const bool whiteHere = kWhite && scatterings == 0;
    if (app.emission >= 0 && !whiteHere) {
      const float w =
          specular ? 1.0f : emitterWeight(ctx.lights->pdf(prevP, hit, ray.d, prevN, prevWeights));
      if (w > 0) {
        const SampledSpectrum le =
            evaluate(scene.emission[static_cast<size_t>(app.emission)], current);
        if constexpr (kGradients)
          ratioEvents(tangents->emission[static_cast<size_t>(app.emission)], current, le, sink,
                      local);
        sink.add(weighted() * le * w,
                 classOf(scatterings, groups.ofEmission[static_cast<size_t>(app.emission)],
                         relightSourceOf(groups, app.emission), current));
      }
    }
    if (bounce >= kMaxPathBounces) {
      ++counters.bounceLimited; // still carrying light: counted, reported
      break;
    }

    const Material& material = whiteHere ? whiteLambertian() : scene.materials[app.material];
    const Vec3 wo = -ray.d;
    const SampledSpectrum rho = scene.reflectanceAt(material, hit, current);
    // A differentiated render: what rho's derivatives are here (its texture's at the hit's uv).
    [[maybe_unused]] RhoTangents rhoTangents;
    if constexpr (kGradients) {
      if (!whiteHere)
        rhoTangents = {&tangents->reflectance[app.material], material.texture.get(),
                       tangents->textureFirstSlot[app.material], hit.u, hit.v};
    }
    SurfaceBsdf bsdf(material, current, rho, hit.ng, hit.ns, wo);
    bsdf.orient(hit.dpdu);
    bsdf.setHeroAlone(heroAlone);
    // A rough conductor's roughness: d ln f / d alpha at direction wi, for each slot moving it.
    [[maybe_unused]] auto roughnessEvents = [&](const Vec3& wi, auto&& emit) {
      if constexpr (kGradients) {
        const auto& ts = tangents->roughness[app.material];
        float du = 0, dv = 0;
        if (ts.empty() || !bsdf.conductorRoughnessSlopes(wi, du, dv)) return;
        for (const RoughnessTangent& t : ts)
          if (const float g = t.alphaU * du + t.alphaV * dv; g != 0)
            for (int i = 0; i < kLanes; ++i) emit(t.slot, i, g);
      }
    };

    // A fluorescent diffuse lobe: every lane's excitation wavelength is chosen once, for both
    // next-event estimation and the continuation through the diffuse lobe.
    [[maybe_unused]] FluorescentShift shift;
    [[maybe_unused]] bool fluorescent = false;
    [[maybe_unused]] float concentration = 1; // of the dye here (a concentration map)
    [[maybe_unused]] ConcentrationTangents concentrationTangents;
    if constexpr (kFluorescence) {
      if (material.reradiation && bsdf.hasNonSpecular()) {
        if (material.concentration) {
          concentration = scene.concentrationAt(material, hit);
          if constexpr (kGradients)
            concentrationTangents = {material.concentration.get(),
                                     tangents->concentrationFirstSlot[app.material], hit.u, hit.v};
          shift = sampleFluorescentShift(*material.reradiation, current, rho, rng, &concentration);
        } else {
          shift = sampleFluorescentShift(*material.reradiation, current, rho, rng);
        }
        fluorescent = true;
      }
    }

    // Next-event estimation at a fluorescent vertex of a plain render: the excitation is also
    // drawn guided by the chosen light's spectrum (fluorescent_vertex.h); differentiated,
    // relightable and media renders keep the column's choice alone.
    constexpr bool kGuidedExcitation =
        kFluorescence && !kMedia && !kGradients && !std::is_same_v<Sink, RelightSink>;
    bool guidedDone = false;
    float weightsHere = 0; // LightSampler::choose's sum of weights at hit.p, for the next MIS
    if constexpr (kGuidedExcitation) {
      if (fluorescent && !ctx.columnOnlyExcitation && bsdf.hasNonSpecular() &&
          ctx.lightSampling != LightSampling::BsdfOnly && ctx.lights->count() > 0) {
        guidedDone = true;
        const float uChoice = rng.next1D();
        const Sample2 uLight = rng.next2D();
        const Sample2 uGuide = rng.next2D();
        float share = 0, uRest = 0;
        const int l = ctx.lights->choose(hit.p, hit.ns, uChoice, share, uRest, &weightsHere);
        LightSample ls, lsGuided;
        if (l >= 0 &&
            ctx.lights->sampleChosen(l, share, hit.p, uRest, uLight, shift.excited, ls, hit.ns)) {
          // Where the light meets the column evenly the column's event alone, at its weight.
          const bool guide = ctx.lights->guidanceHelps(l, app.material, current);
          const GuidedShift g =
              guide ? guideFluorescentShift(*material.reradiation, current, shift, rho,
                                            concentration, *ctx.lights->excitationGuide(l), uGuide)
                    : GuidedShift{current, shift.albedo, SampledSpectrum::filled(0.0f)};
          if (guide)
            ctx.lights->sampleChosen(l, share, hit.p, uRest, uLight, g.guided, lsGuided, hit.ns);
          // One shadow ray for both events: the light's geometry with unit radiance.
          LightSample unit = ls;
          unit.radiance = SampledSpectrum::filled(1.0f);
          const SampledSpectrum geometric = directLight(
              scene, hit, ray.d, unit, [&](const Vec3& wi) { return bsdf.diffuseLobe(wi); },
              [&](const Vec3& wi) { return bsdf.pdf(wi); },
              ctx.lightSampling != LightSampling::NeeOnly, counters);
          if (!geometric.isBlack()) {
            const uint16_t group = ctx.lights->group(l), source = ctx.lights->source(l);
            const auto lanesOf = [&](const SampledWavelengths& lit) {
              return Sink::kClasses ? shiftedLanes(lit, current) : uint64_t{0};
            };
            sink.add(
                beta * geometric * g.columnWeight * ls.radiance,
                classOf(scatterings + 1, group, source, shift.excited, lanesOf(shift.excited)));
            if (guide)
              sink.add(beta * geometric * g.guidedWeight * lsGuided.radiance,
                       classOf(scatterings + 1, group, source, g.guided, lanesOf(g.guided)));
          }
        }
      }
    }
    if (!guidedDone && bsdf.hasNonSpecular() && ctx.lightSampling != LightSampling::BsdfOnly &&
        ctx.lights->count() > 0) {
      const float uChoice = rng.next1D();
      const Sample2 uLight = rng.next2D();
      LightSample ls;
      const SampledWavelengths& lit = fluorescent ? shift.excited : current;
      if (ctx.lights->sample(hit.p, uChoice, uLight, lit, ls, hit.ns, &weightsHere)) {
        auto f = [&](const Vec3& wi) {
          return fluorescent ? shift.albedo * bsdf.diffuseLobe(wi) : bsdf.f(wi);
        };
        auto pdf = [&](const Vec3& wi) { return bsdf.pdf(wi); };
        const PathClass k =
            classOf(scatterings + 1, ctx.lights->group(ls.light), ctx.lights->source(ls.light), lit,
                    Sink::kClasses ? shiftedLanes(lit, current) : uint64_t{0});
        if constexpr (kGradients) {
          if (!whiteHere) {
            if (fluorescent)
              reradiationEvents(tangents->reradiation[app.material], rhoTangents,
                                *material.reradiation, current, shift.excited, rho, sink, local,
                                concentration, concentrationTangents);
            roughnessEvents(ls.wi, local);
            reflectanceEvents(rhoTangents, material, current, rho, false, !fluorescent, sink,
                              local);
          }
          lightEvents(ls, lit);
        }
        if constexpr (kMedia) {
          const auto visible = [&](const Ray& r) {
            return shadowTransmittance(scene, r, media, lit, counters, shadowCrossings());
          };
          const SampledSpectrum direct = directLightThrough(
              hit, ray.d, ls, f, pdf, ctx.lightSampling != LightSampling::NeeOnly, visible);
          if constexpr (kGradients)
            if (!direct.isBlack())
              shadowEvents(*tangents, scene, sink.tape->crossings, lit, sink, local);
          sink.add(weighted() * direct, k);
        } else {
          sink.add(beta * directLight(scene, hit, ray.d, ls, f, pdf,
                                      ctx.lightSampling != LightSampling::NeeOnly, counters),
                   k);
        }
      }
    }

    [[maybe_unused]] const SampledWavelengths lambdaBefore = current; // before a re-radiation
    BsdfSample bs;
    const float uLobe = rng.next1D();
    const Sample2 uDir = rng.next2D();
    if (!bsdf.sample(uLobe, uDir, bs)) break;
    if constexpr (kFluorescence) {
      if (fluorescent && !bs.specular) { // the diffuse lobe re-radiates; the mirror lobe does not
        bs.weight = shift.albedo * bs.diffuseScale;
        if constexpr (Sink::kClasses) shifted |= shiftedLanes(shift.excited, current);
        if constexpr (kGradients) {
          if (!whiteHere)
            reradiationEvents(tangents->reradiation[app.material], rhoTangents,
                              *material.reradiation, current, shift.excited, rho, sink, event,
                              concentration, concentrationTangents);
        }
        current = shift.excited;
      }
    }
    if constexpr (kGradients) {
      // The lobe taken scales the rest of the path (a fluorescent diffuse lobe's albedo came
      // from the matrix above; rho's other shares, a coat's, from here).
      if (!whiteHere) {
        if (!bs.specular) roughnessEvents(bs.wi, event);
        const bool reradiated = fluorescent && !bs.specular;
        reflectanceEvents(rhoTangents, material, lambdaBefore, rho, bs.specular, !reradiated, sink,
                          event);
      }
    }
    if constexpr (kMedia) {
      crossBoundary(hit, app, wo, bs.wi, media);
      if (bs.straight) {
        // Straight through a thin wall: like an interface, the MIS state stays the previous
        // vertex's (next-event estimation sees through the wall).
        beta *= bs.weight;
        if (beta.isBlack()) break;
        ray.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, bs.wi);
        ray.tMin = 0;
        ray.tMax = INFINITY;
        continue;
      }
    }
    beta *= bs.weight;
    rrScale *= bs.eta * bs.eta;
    if (bs.terminateSecondary && !heroAlone) {
      // From here on the hero's estimator stands alone; what L holds keeps its lane weights.
      // Its weight is f_hero / p_hero: beta's hero lane over the hero's ratio (1 unless
      // media rescaled both).
      beta = heroOnly(beta);
      if constexpr (kMedia) beta *= misRatios[0] > 0 ? 1.0f / misRatios[0] : 0.0f;
      rrScale *= 1.0f / static_cast<float>(kLanes);
      heroAlone = true;
      if constexpr (kMedia) invMisDivisor = 1.0f;
    }
    specular = bs.specular;
    prevPdf = bs.pdf;
    prevP = hit.p;
    prevN = hit.ns;
    prevWeights = weightsHere;

    if (!survivesRoulette()) break;
    ray.o = offsetRayOrigin(hit.p, hit.pError, hit.ng, bs.wi);
    ray.d = bs.wi;
    ray.tMin = 0;
    ray.tMax = INFINITY;
  }
}

} // namespace

namespace {
template <bool kWhite, class Sink>
void traceVariant(const IntegratorContext& ctx, const Ray& ray, const SampledWavelengths& lambda,
                  PixelSampleStream& rng, TraceCounters& counters, Sink& sink) {
  const bool media = ctx.scene->hasMedia;
  if (ctx.fluorescence) {
    if (media)
      tracePathImpl<true, true, kWhite>(ctx, ray, lambda, rng, counters, sink);
    else
      tracePathImpl<true, false, kWhite>(ctx, ray, lambda, rng, counters, sink);
  } else if (media) {
    tracePathImpl<false, true, kWhite>(ctx, ray, lambda, rng, counters, sink);
  } else {
    tracePathImpl<false, false, kWhite>(ctx, ray, lambda, rng, counters, sink);
  }
}
} // namespace

SampledSpectrum tracePath(const IntegratorContext& ctx, Ray ray, const SampledWavelengths& lambda,
                          PixelSampleStream& rng, TraceCounters& counters) {
  RadianceSink sink;
  traceVariant<false>(ctx, ray, lambda, rng, counters, sink);
  return sink.L;
}

SampledSpectrum tracePathGradients(const IntegratorContext& ctx, Ray ray,
                                   const SampledWavelengths& lambda, PixelSampleStream& rng,
                                   TraceCounters& counters, GradientTape& tape) {
  GradientSink sink;
  sink.tape = &tape;
  sink.tangents = ctx.gradients->tangents;
  traceVariant<false>(ctx, ray, lambda, rng, counters, sink);
  return sink.L;
}

SampledSpectrum tracePathComponents(const IntegratorContext& ctx, Ray ray,
                                    const SampledWavelengths& lambda, PixelSampleStream& rng,
                                    TraceCounters& counters, const ComponentLayout& layout,
                                    SampledSpectrum* layers) {
  ComponentSink sink;
  sink.layers = layers;
  sink.layout = &layout;
  traceVariant<false>(ctx, ray, lambda, rng, counters, sink);
  return sink.L;
}

SampledSpectrum traceWhiteReference(const IntegratorContext& ctx, Ray ray,
                                    const SampledWavelengths& lambda, PixelSampleStream& rng,
                                    TraceCounters& counters) {
  if (ctx.scene->relight.enabled) {
    // Built with unit spectra: the groups' spectra applied per contribution, nothing recorded.
    static const ComponentLayout none;
    RelightSink sink;
    sink.components.layout = &none;
    sink.spectra = &ctx.scene->relight.ofSource;
    traceVariant<true>(ctx, ray, lambda, rng, counters, sink);
    return sink.components.L;
  }
  RadianceSink sink;
  traceVariant<true>(ctx, ray, lambda, rng, counters, sink);
  return sink.L;
}

SampledSpectrum tracePathRelightable(const IntegratorContext& ctx, Ray ray,
                                     const SampledWavelengths& lambda, PixelSampleStream& rng,
                                     TraceCounters& counters, const ComponentLayout& layout,
                                     SampledSpectrum* layers, RelightRecorder& recorder) {
  RelightSink sink;
  sink.components.layers = layers;
  sink.components.layout = &layout;
  sink.recorder = &recorder;
  sink.spectra = recorder.spectra;
  traceVariant<false>(ctx, ray, lambda, rng, counters, sink);
  return sink.components.L;
}

} // namespace nx
