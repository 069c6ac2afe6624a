// nxbench-rays: nxrender's ray queries against raw Embree on the same BVH, and what batched
// (wavefront) queries would buy.
//
//   nxbench-rays [scene.scn] [--triangles N] [--rays N] [--batch N] [--threads N] [--dir DIR]
//
// Without a scene it writes a heightfield of about N triangles (default 1,000,000) and uses
// that. Three sets of the path tracer's kinds of rays are made from the scene before any clock
// starts: camera rays (pixel after pixel), diffuse bounces from their hits (cosine about the
// normal, in the same order, as a depth-first path tracer issues them) and shadow rays from those
// hits to the scene's lights. Each set is queried on the given threads in batches, by:
//   nxrender        GeometryScene::intersect / occluded, one ray at a time: what the path tracer
//                   calls (the planes' exact pass, Embree, the hit's re-projection);
//   rtcIntersect1   Embree alone on the same BVH, one ray at a time (the BVH holds the spheres
//                   and meshes; planes are outside it, so this is the query's floor);
//   stream          rtcIntersect1M / rtcOccluded1M over each batch, coherent flag;
//   packets16       rtcIntersect16 / rtcOccluded16 over consecutive 16-ray packets;
//   sorted ...      the same after sorting each batch by direction octant, then the Morton code
//                   of the origin (the sort and the gather are timed and added).
// Then the path tracer renders the scene, and the program prints its rays/s against Embree's
// and an estimate of a wavefront design's time per ray (see docs/performance.md).

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <vector>

#include "apps/bench_util.h"
#include "apps/command_line.h"
#include "apps/heightfield_scene.h"
#include "core/error.h"
#include "core/frame.h"
#include "core/hash.h"
#include "core/ray_offset.h"
#include "integrators/film.h"
#include "integrators/lights/light_sampler.h"
#include "integrators/renderer.h"
#include "integrators/sampling.h"
#include "integrators/scene_reader.h"
#include "spectra/wavelength_sampler.h"

namespace {

using namespace nx;

// A set of rays of one kind, and whether they are shadow rays (occlusion queries).
struct RaySet {
  const char* name;
  bool shadow;
  std::vector<Ray> rays;
};

float unit(uint32_t k, uint32_t d) {
  return bitsToUnitFloat(hash4(k, d, 0x7a15, 0));
}

// Camera rays pixel after pixel (enough samples per pixel for `count`), their hits' cosine
// bounces and shadow rays towards a light sample, in the camera rays' order.
std::vector<RaySet> makeRaySets(const RenderScene& scene, size_t count) {
  const int w = scene.settings.width, h = scene.settings.height;
  const size_t pixels = static_cast<size_t>(w) * static_cast<size_t>(h);
  const uint32_t spp = static_cast<uint32_t>((count + pixels - 1) / pixels);
  const LightSampler lights(scene);
  const WavelengthSampler wavelengths(Film::tracedMinNm(scene.settings.bands),
                                      Film::tracedMaxNm(scene.settings.bands));
  RaySet camera{"camera", false, {}}, bounce{"bounce", false, {}}, shadow{"shadow", true, {}};
  // Fewer rays than pixels: a centred window of the image's shape.
  const int ww =
      std::min(w, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count) * w / h))));
  const int wh = std::min(
      h, static_cast<int>((count + static_cast<size_t>(ww) - 1) / static_cast<size_t>(ww)));
  const int x0 = (w - ww) / 2, y0 = (h - wh) / 2;
  for (size_t p = 0;
       p < static_cast<size_t>(ww) * static_cast<size_t>(wh) && camera.rays.size() < count; ++p)
    for (uint32_t s = 0; s < spp && camera.rays.size() < count; ++s) {
      const uint32_t k = static_cast<uint32_t>(p * spp + s);
      const Ray r =
          scene.camera.generateRay(static_cast<double>(x0 + static_cast<int>(p % ww)) + unit(k, 0),
                                   static_cast<double>(y0 + static_cast<int>(p / ww)) + unit(k, 1));
      camera.rays.push_back(r);
      SurfaceHit hit;
      if (!scene.geometry->intersect(r, hit)) continue;
      const Vec3 n = dot(hit.ng, r.d) < 0 ? hit.ng : -hit.ng;
      const Vec3 wi =
          Frame::fromNormal(n).toWorld(sampleCosineHemisphere({unit(k, 2), unit(k, 3)}));
      bounce.rays.push_back({offsetRayOrigin(hit.p, hit.pError, hit.ng, wi), wi});
      LightSample ls;
      if (lights.sample(hit.p, unit(k, 4), {unit(k, 5), unit(k, 6)}, wavelengths.sample(unit(k, 7)),
                        ls))
        shadow.rays.push_back(shadowRayTo(hit.p, hit.pError, hit.ng, ls));
    }
  std::vector<RaySet> sets;
  for (RaySet* s : {&camera, &bounce, &shadow})
    if (!s->rays.empty()) sets.push_back(std::move(*s));
  return sets;
}

RTCRayHit toRayHit(const Ray& r) {
  RTCRayHit e{};
  e.ray.org_x = r.o.x, e.ray.org_y = r.o.y, e.ray.org_z = r.o.z;
  e.ray.dir_x = r.d.x, e.ray.dir_y = r.d.y, e.ray.dir_z = r.d.z;
  e.ray.tnear = r.tMin, e.ray.tfar = r.tMax;
  e.ray.mask = 0xFFFFFFFFu;
  e.hit.geomID = e.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return e;
}

// 10 bits per axis interleaved (the Morton code of a point in [0, 1)^3).
uint32_t morton30(float x, float y, float z) {
  auto spread = [](float v) {
    uint32_t b = static_cast<uint32_t>(std::clamp(v, 0.0f, 0.999f) * 1024.0f);
    b = (b | (b << 16)) & 0x030000FFu;
    b = (b | (b << 8)) & 0x0300F00Fu;
    b = (b | (b << 4)) & 0x030C30C3u;
    return (b | (b << 2)) & 0x09249249u;
  };
  return (spread(x) << 2) | (spread(y) << 1) | spread(z);
}

// The rays of a set reordered batch by batch by (direction octant, Morton code of the origin).
// Returns the set sorted; `seconds` gets the time of the sort and gather on the given threads.
std::vector<Ray> sortedByBatch(const std::vector<Ray>& rays, size_t batch, double& seconds) {
  BoundingBox box;
  for (const Ray& r : rays) box.add(Vec3d(r.o));
  const Vec3d lo = box.lo, ext = box.hi - box.lo;
  auto scaled = [](double v, double e) { return e > 0 ? static_cast<float>(v / e) : 0.0f; };
  std::vector<Ray> out(rays.size());
  const size_t batches = (rays.size() + batch - 1) / batch;
  seconds = bench::fastestSeconds(3, [&] {
    tbb::parallel_for(size_t(0), batches, [&](size_t b) {
      const size_t begin = b * batch, end = std::min(rays.size(), begin + batch);
      std::vector<uint64_t> keys(end - begin);
      for (size_t i = begin; i < end; ++i) {
        const Ray& r = rays[i];
        const uint64_t octant = (r.d.x < 0) | ((r.d.y < 0) << 1) | ((r.d.z < 0) << 2);
        const uint64_t code = morton30(scaled(r.o.x - lo.x, ext.x), scaled(r.o.y - lo.y, ext.y),
                                       scaled(r.o.z - lo.z, ext.z));
        keys[i - begin] = (octant << 62) | (static_cast<uint64_t>(code) << 32) | (i - begin);
      }
      std::sort(keys.begin(), keys.end());
      for (size_t i = begin; i < end; ++i) out[i] = rays[begin + (keys[i - begin] & 0xFFFFFFFFu)];
    });
  });
  return out;
}

// Seconds (fastest of three) to query every ray of `rays` with `method`, batch by batch.
enum class Method { Nxrender, One, Stream, Packets16 };

double querySeconds(const RenderScene& scene, const std::vector<Ray>& rays, bool shadow,
                    Method method, size_t batch) {
  const RTCScene es = scene.geometry->embreeScene();
  const size_t batches = (rays.size() + batch - 1) / batch;
  std::vector<RTCRayHit> pristine(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) pristine[i] = toRayHit(rays[i]);
  std::vector<RTCRayHit> work;
  // 16-ray packets (structure of arrays) of consecutive rays; batches are multiples of 16.
  struct Valid {
    alignas(64) int lanes[16];
  };
  std::vector<RTCRayHit16> pristinePackets, packets;
  std::vector<Valid> packetValid;
  if (method == Method::Packets16) {
    pristinePackets.resize((rays.size() + 15) / 16);
    packetValid.resize(pristinePackets.size());
    for (size_t i = 0; i < rays.size(); ++i) {
      RTCRayHit16& p = pristinePackets[i / 16];
      const size_t l = i % 16;
      const RTCRayHit& e = pristine[i];
      p.ray.org_x[l] = e.ray.org_x, p.ray.org_y[l] = e.ray.org_y, p.ray.org_z[l] = e.ray.org_z;
      p.ray.dir_x[l] = e.ray.dir_x, p.ray.dir_y[l] = e.ray.dir_y, p.ray.dir_z[l] = e.ray.dir_z;
      p.ray.tnear[l] = e.ray.tnear, p.ray.tfar[l] = e.ray.tfar;
      p.ray.mask[l] = 0xFFFFFFFFu;
      p.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
      packetValid[i / 16].lanes[l] = -1;
    }
  }
  std::atomic<uint64_t> hits{0};
  double best = 1e300;
  for (int repeat = 0; repeat < 3; ++repeat) {
    // Outside the clock: a wavefront tracer writes its rays in place, in the layout it queries.
    work = pristine;
    packets = pristinePackets;
    const auto start = std::chrono::steady_clock::now();
    tbb::parallel_for(size_t(0), batches, [&](size_t b) {
      const size_t begin = b * batch, end = std::min(rays.size(), begin + batch);
      uint64_t local = 0;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      if (method == Method::Nxrender) {
        SurfaceHit h;
        for (size_t i = begin; i < end; ++i)
          local +=
              shadow ? scene.geometry->occluded(rays[i]) : scene.geometry->intersect(rays[i], h);
      } else if (method == Method::One) {
        for (size_t i = begin; i < end; ++i) {
          if (shadow) {
            rtcOccluded1(es, &context, &work[i].ray);
            local += work[i].ray.tfar < 0;
          } else {
            rtcIntersect1(es, &context, &work[i]);
            local += work[i].hit.geomID != RTC_INVALID_GEOMETRY_ID;
          }
        }
      } else if (method == Method::Stream) {
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        const unsigned m = static_cast<unsigned>(end - begin);
        if (shadow)
          rtcOccluded1M(es, &context, &work[begin].ray, m, sizeof(RTCRayHit));
        else
          rtcIntersect1M(es, &context, &work[begin], m, sizeof(RTCRayHit));
        for (size_t i = begin; i < end; ++i)
          local += shadow ? work[i].ray.tfar < 0 : work[i].hit.geomID != RTC_INVALID_GEOMETRY_ID;
      } else {
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        for (size_t i = begin; i < end; i += 16) {
          RTCRayHit16& packet = packets[i / 16];
          const int* valid = packetValid[i / 16].lanes;
          if (shadow)
            rtcOccluded16(valid, es, &context, &packet.ray);
          else
            rtcIntersect16(valid, es, &context, &packet);
          for (int l = 0; l < 16; ++l)
            if (valid[l])
              local +=
                  shadow ? packet.ray.tfar[l] < 0 : packet.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID;
        }
      }
      hits += local;
    });
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

// Seconds per ray of reading and writing back `bytes` of path state for each of `count` paths
// (a wavefront: batch x threads paths), `passes` times over, on the given threads: what a
// wavefront design adds per ray at the least, as its paths' state leaves the registers between
// the kernels (one load and one store of the whole state per ray; real kernels make several).
double stateTrafficSeconds(size_t count, size_t bytes, int passes) {
  std::vector<unsigned char> buffer(count * bytes);
  const double s = bench::fastestSeconds(3, [&] {
    for (int pass = 0; pass < passes; ++pass)
      tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 1024),
                        [&](const tbb::blocked_range<size_t>& r) {
                          alignas(64) unsigned char state[4096];
                          for (size_t i = r.begin(); i != r.end(); ++i) {
                            std::memcpy(state, &buffer[i * bytes], bytes);
                            state[i % bytes] ^= static_cast<unsigned char>(pass + 1);
                            std::memcpy(&buffer[i * bytes], state, bytes);
                          }
                        });
  });
  uint64_t check = 0;
  for (size_t i = 0; i < buffer.size(); i += 4096) check += buffer[i];
  if (check == 0xFFFFFFFFFFFFull) std::printf(" "); // keeps the traffic observable
  return s / (static_cast<double>(count) * passes);
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"nxrender's ray queries against raw Embree, and batched queries"};
  std::string scenePath, dir = "/tmp";
  long long triangles = 1000000;
  size_t rayCount = 1000000, batch = 65536, stateBytes = 256;
  int threads = 2, spp = 8;
  app.add_option("scene", scenePath, "Scene file (default: a generated heightfield mesh)");
  app.add_option("--triangles", triangles, "Triangles of the generated mesh (default 1,000,000)")
      ->check(nx::numberIn(2LL, 200000000LL));
  app.add_option("--dir", dir, "Where the generated mesh and scene go (default /tmp)");
  app.add_option("--rays", rayCount, "Camera rays made (default 1,000,000)")
      ->check(nx::numberIn(size_t(1000), size_t(100000000)));
  app.add_option("--batch", batch, "Rays per batch (default 65536)")
      ->check(nx::numberIn(size_t(16), size_t(1) << 30));
  app.add_option("--state-bytes", stateBytes, "Path state per ray of the wavefront estimate")
      ->check(nx::numberIn(size_t(16), size_t(4096)));
  app.add_option("--spp", spp, "Samples per pixel of the path tracer's render (default 8)")
      ->check(nx::numberIn(1, 1 << 16));
  app.add_option("--threads", threads, "Threads (default 2)")->check(nx::numberIn(1, 4096));
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxbench-rays"); status >= 0)
    return status;
  try {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<size_t>(threads));
    if (batch % 16 != 0)
      throw nx::Error("--batch: expected a multiple of 16 (whole 16-ray packets), found " +
                      std::to_string(batch));
    if (scenePath.empty()) {
      const int n = bench::heightfieldGridFor(triangles);
      bench::writeHeightfieldPly(dir + "/nxbench-rays.ply", n);
      scenePath = dir + "/nxbench-rays.scn";
      std::ofstream(scenePath) << bench::heightfieldSceneXml("nxbench-rays.ply", 320, 180, spp,
                                                             "0,0.6,-1.1");
    }
    const RenderScene scene = buildRenderScene(loadScene(scenePath));
    const std::vector<RaySet> sets = makeRaySets(scene, rayCount);
    const RTCDevice device = rtcGetSceneDevice(scene.geometry->embreeScene());
    std::printf(
        "scene %s; Embree %s, native 16-ray packets %s, streams %s; %d threads, "
        "batches of %zu rays\n\n",
        std::filesystem::path(scenePath).filename().c_str(), RTC_VERSION_STRING,
        rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) ? "yes" : "no",
        rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_RAY_STREAM_SUPPORTED) ? "yes" : "no",
        threads, batch);
    std::printf(
        "core-ns per ray (sort: its own cost per ray, not included in the sorted columns)\n");
    std::printf("%-8s %9s %10s %10s %10s %10s %10s %10s %10s %10s\n", "rays", "count", "nxrender",
                "rtc1", "stream", "packets16", "sort", "sorted 1", "sort strm", "sort pk16");
    // Per set: nxrender's and the best batched query's core-ns per ray.
    struct PerRay {
      double nxrender, raw, batched;
    };
    std::vector<PerRay> perRay;
    for (const RaySet& set : sets) {
      const double n = static_cast<double>(set.rays.size());
      auto ns = [&](double s) { return s * 1e9 * threads / n; };
      const double nx = ns(querySeconds(scene, set.rays, set.shadow, Method::Nxrender, batch));
      const double one = ns(querySeconds(scene, set.rays, set.shadow, Method::One, batch));
      const double stream = ns(querySeconds(scene, set.rays, set.shadow, Method::Stream, batch));
      const double pack = ns(querySeconds(scene, set.rays, set.shadow, Method::Packets16, batch));
      double sortS = 0;
      const std::vector<Ray> sorted = sortedByBatch(set.rays, batch, sortS);
      const double sort = ns(sortS);
      const double sOne = ns(querySeconds(scene, sorted, set.shadow, Method::One, batch));
      const double sStream = ns(querySeconds(scene, sorted, set.shadow, Method::Stream, batch));
      const double sPack = ns(querySeconds(scene, sorted, set.shadow, Method::Packets16, batch));
      std::printf("%-8s %9zu %10.1f %10.1f %10.1f %10.1f %10.1f %10.1f %10.1f %10.1f\n", set.name,
                  set.rays.size(), nx, one, stream, pack, sort, sOne, sStream, sPack);
      perRay.push_back(
          {nx, one, std::min({one, stream, pack, sort + sOne, sort + sStream, sort + sPack})});
    }

    // The path tracer on the same scene and threads.
    RenderOptions o;
    o.samples = spp;
    bench::fastestSeconds(1, [&] { render(scene, o); }); // warm-up
    const RenderOutput out = render(scene, o);
    const double rays = static_cast<double>(out.stats.rays);
    const double ptNs = out.stats.seconds * 1e9 * threads / rays;
    // Its queries: camera rays once per sample, the rest split evenly between bounces and
    // shadow rays (the sets' mean when a kind is missing).
    auto mix = [&](double PerRay::*field) {
      const double samples = static_cast<double>(out.stats.samples);
      double rest = 0;
      for (size_t k = 1; k < perRay.size(); ++k) rest += perRay[k].*field;
      rest = perRay.size() > 1 ? rest / static_cast<double>(perRay.size() - 1) : perRay[0].*field;
      return (samples * (perRay[0].*field) + (rays - samples) * rest) / rays;
    };
    const double qNx = mix(&PerRay::nxrender), qRaw = mix(&PerRay::raw),
                 qBatched = mix(&PerRay::batched);
    const size_t wavefrontPaths = batch * static_cast<size_t>(threads);
    const double state =
        stateTrafficSeconds(wavefrontPaths, stateBytes,
                            std::max(1, static_cast<int>((size_t(1) << 22) / wavefrontPaths))) *
        1e9 * threads;
    const double wavefront = ptNs - qNx + (qNx - qRaw) + qBatched + state;
    std::printf("\npath tracer at %d spp: %.4g rays/s, %.1f core-ns per ray (%.2f rays per "
                "sample)\n",
                spp, rays / out.stats.seconds, ptNs, rays / static_cast<double>(out.stats.samples));
    std::printf("its queries (this mix): nxrender %.1f, rtcIntersect1 %.1f, best batched %.1f "
                "core-ns per ray\n",
                qNx, qRaw, qBatched);
    std::printf("path tracer rays/s against raw Embree (rtcIntersect1, this mix): %.2f\n",
                qRaw / ptNs);
    std::printf("queries' share of the path tracer's time: %.0f%%\n", 100 * qNx / ptNs);
    std::printf("path state traffic (%zu bytes written and read per ray, a wavefront of %zu "
                "paths): %.1f core-ns\n",
                stateBytes, wavefrontPaths, state);
    std::printf("wavefront estimate: %.1f core-ns per ray = %.2fx the path tracer's speed\n"
                "(its shading as now, its queries the best batched ones plus nxrender's hit\n"
                " re-projection, plus the path state's memory traffic)\n",
                wavefront, ptNs / wavefront);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxbench-rays: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
