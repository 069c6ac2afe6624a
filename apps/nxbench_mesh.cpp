// nxbench-mesh: loading and rendering a large mesh file.
//
//   nxbench-mesh [--triangles N] [--dir DIR]
//
// Writes a binary PLY heightfield of about N triangles (default 1,000,000) and a scene that
// shows it, then reports: the file's size, the time to read it (checks, Assimp, the mesh
// buffers), the time to build the Embree BVH, the bytes per triangle of the mesh buffers and of
// Embree (its memory monitor), the process's peak resident memory, and the time of a 64x36
// render at 1 spp.

#include <CLI/CLI.hpp>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "apps/command_line.h"
#include "apps/heightfield_scene.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "io/mesh_reader.h"

namespace {

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

double peakResidentMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0; // ru_maxrss is in KiB on Linux
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Load and render time, memory per triangle, for a large PLY mesh"};
  long long triangles = 1000000;
  std::string dir = "/tmp";
  app.add_option("--triangles", triangles, "About how many triangles (default 1,000,000)")
      ->check(nx::numberIn(2LL, 200000000LL));
  app.add_option("--dir", dir, "Where the PLY and the scene are written (default /tmp)");
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxbench-mesh"); status >= 0)
    return status;
  try {
    const int n = nx::bench::heightfieldGridFor(triangles);
    const std::string ply = dir + "/nxbench-mesh.ply", scn = dir + "/nxbench-mesh.scn";
    auto t0 = std::chrono::steady_clock::now();
    nx::bench::writeHeightfieldPly(ply, n);
    std::ofstream(scn) << nx::bench::heightfieldSceneXml("nxbench-mesh.ply", 64, 36, 1);
    const double writeS = seconds(t0);

    t0 = std::chrono::steady_clock::now();
    const nx::MeshFile file = nx::readMeshFile(ply);
    const double readS = seconds(t0);
    const double tris = static_cast<double>(file.mesh.triangleCount());

    t0 = std::chrono::steady_clock::now();
    const nx::RenderScene scene = nx::buildRenderScene(nx::loadScene(scn));
    const double loadS = seconds(t0);
    nx::RenderOptions o;
    t0 = std::chrono::steady_clock::now();
    const nx::RenderOutput out = nx::render(scene, o);
    const double renderS = seconds(t0);

    std::printf("triangles                      %.0f (%d x %d grid)\n", tris, n, n);
    std::printf("PLY file                       %.1f MB (written in %.2f s)\n",
                static_cast<double>(file.bytes.size()) / 1e6, writeS);
    std::printf("read (checks + Assimp)         %.2f s\n", readS);
    std::printf("scene load (read + BVH build)  %.2f s\n", loadS);
    std::printf("mesh buffers                   %.1f bytes/triangle\n",
                static_cast<double>(scene.meshBytes) / tris);
    std::printf("Embree (BVH)                   %.1f bytes/triangle\n",
                static_cast<double>(scene.geometry->embreeBytes()) / tris);
    std::printf("render 64x36, 1 spp            %.3f s\n", renderS);
    std::printf("peak resident memory           %.0f MB\n", peakResidentMb());
    return out.stats.nonFinite == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxbench-mesh: error: %s\n", e.what());
    return 1;
  }
}
