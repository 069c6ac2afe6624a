// nxbench-gradients: what a differentiated render costs against a plain one.
//
//   nxbench-gradients [--spp N] [--width W] [--threads N] [--knots K] [--matrix N]
//                     [--mesh-vertices V]
//
// A fluorescent sphere on a tabulated floor under a blue-heavy lamp (docs/inverse.md). Prints
// render seconds (fastest of repeats) for a plain render, forward mode with 1 and 4 parameters
// (the dye's Stokes shift, quantum yield, the lamp's scale, the sphere's reflectance), reverse
// mode with those 4, the shape and camera rows (the sphere's centre forward, its centre and
// radius in reverse, the camera's position forward), reverse mode with the floor table's K
// knots added, and the finite-difference route; the measured matrix's rows; a mesh of V vertices
// in reverse mode
// (two renders per parameter); then the process's peak memory after reverse renders of
// increasing samples per pixel (it must not grow with them).

#include <CLI/CLI.hpp>
#include <sys/resource.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "apps/bench_util.h"
#include "apps/command_line.h"
#include "apps/program_main.h"
#include "integrators/gradients/gradient_setup.h"
#include "integrators/renderer.h"
#include "integrators/scene_params/scene_fields.h"
#include "integrators/scene_reader.h"

namespace {

using namespace nx;

// The scene's parameters, in the order of `values`.
struct Values {
  double stokes = 90, yield = 0.8, lampScale = 5e-3, rho = 0.4;
  std::vector<double> floor; ///< the floor table's knot values (400-700 nm, evenly)
};

std::string text(const Values& v, int width, int spp) {
  std::string floor;
  for (size_t k = 0; k < v.floor.size(); ++k) {
    const double nm =
        400 + 300.0 * static_cast<double>(k) / static_cast<double>(v.floor.size() - 1);
    floor += (k ? ", " : "") + std::to_string(nm) + ":" + std::to_string(v.floor[k]);
  }
  return "<scene><settings><xres>" + std::to_string(width) + "</xres><yres>" +
         std::to_string(width * 3 / 4) +
         "</yres><mode>spectral_mcpt</mode><depth>5</depth><sampl>" + std::to_string(spp) +
         "</sampl><bands>400:700:10</bands></settings><camera><position>0,0.9,-2.6</"
         "position><look_at>0,0.5,0</look_at><fov>40</fov></camera><plane><normal>0,1,0</"
         "normal><distance>0</distance><material>matte</material><reflectance>" +
         floor +
         "</reflectance></plane><sphere><center>0,0.7,0</center><radius>0.7</radius><material>"
         "matte</material><reflectance>" +
         std::to_string(v.rho) +
         "</reflectance><fluorescence><absorption>460</absorption><stokes>" +
         std::to_string(v.stokes) + "</stokes><width>25</width><yield>" + std::to_string(v.yield) +
         "</yield></fluorescence></sphere><sphere><center>-1.5,2.5,-1</center><radius>0.5</"
         "radius><material>matte</material><reflectance>0</reflectance><emission scale=\"" +
         std::to_string(v.lampScale) +
         "\">380:1, 480:1, 520:0.1, 800:0.1</emission></sphere></scene>";
}

long peakKilobytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

// A measured N x N matrix (excitation 350-550 nm, emission 401-701 nm: no diagonal) of a dye
// absorbing around 460 nm and emitting around 540 nm, yield 0.7.
std::shared_ptr<const MeasuredMatrix> benchMatrix(int n) {
  auto m = std::make_shared<MeasuredMatrix>();
  for (int k = 0; k < n; ++k) {
    m->excitationNm.push_back(350 + 200.0 * k / (n - 1));
    m->emissionNm.push_back(401 + 300.0 * k / (n - 1));
  }
  std::vector<double> e;
  double sum = 0;
  for (double em : m->emissionNm) sum += e.emplace_back(std::exp(-std::pow((em - 540) / 25, 2)));
  for (double ex : m->excitationNm)
    for (size_t c = 0; c < e.size(); ++c)
      m->cells.push_back(m->emissionNm[c] > ex
                             ? 0.8 * std::exp(-std::pow((ex - 460) / 30, 2)) * 0.7 * e[c] / sum
                             : 0.0);
  m->source = "the bench's matrix";
  return m;
}

// The measured matrix's rows: its scene's plain render, setting up its cells' slots (seconds,
// and as renders of it), and a reverse render with them.
void matrixRows(SceneDesc desc, int n, int spp, const std::vector<float>& adjoint) {
  setSceneField(desc, "objects[1].fluorescence.matrix", benchMatrix(n));
  const RenderScene scene = buildRenderScene(desc);
  RenderOptions plain;
  plain.samples = spp;
  const double t0 = bench::fastestSeconds(3, [&] { render(scene, plain); });
  const auto start = std::chrono::steady_clock::now();
  const SceneTangents cells =
      gradientSetup(desc, {"objects[1].fluorescence.matrix"}, scene, true).tangents;
  const double setup =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RenderOptions o = plain;
  o.gradients = &cells;
  o.adjoint = &adjoint;
  const double t = bench::fastestSeconds(3, [&] { render(scene, o); });
  std::printf("\nmeasured matrix %dx%d (%u slots):\n", n, n, cells.slots());
  std::printf("%-34s %9.3f %8.2f\n", "plain", t0, 1.0);
  std::printf("%-34s %9.3f %8.2f\n", "set-up of its cells' tangents", setup, setup / t0);
  std::printf("%-34s %9.3f %8.2f\n", "reverse render", t, t / t0);
  std::printf("%-34s %9.3f %8.2f\n", "backward call (set-up + reverse)", setup + t,
              (setup + t) / t0);
}

// The reverse-mode row of a mesh's vertices: a sphere of `vertices` vertices as rows (a latitude
// by longitude grid) on the floor under the lamp, every coordinate differentiated.
void meshRow(int vertices, int width, int spp) {
  const int rings = std::max(3, static_cast<int>(std::sqrt(vertices / 2.0)));
  const int segments = std::max(3, vertices / rings);
  std::string v, f;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double theta = kPi * (i + 0.5) / rings, phi = 2 * kPi * j / segments;
      char b[96];
      std::snprintf(b, sizeof b, "%s%.6f %.6f %.6f", v.empty() ? "" : ", ",
                    0.6 * std::sin(theta) * std::cos(phi), 0.7 + 0.6 * std::cos(theta),
                    0.6 * std::sin(theta) * std::sin(phi));
      v += b;
    }
  for (int i = 0; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const int a = i * segments + j, b = i * segments + (j + 1) % segments;
      const int c = a + segments, d = b + segments;
      f += (f.empty() ? "" : ", ") + std::to_string(a) + " " + std::to_string(c) + " " +
           std::to_string(b) + ", " + std::to_string(b) + " " + std::to_string(c) + " " +
           std::to_string(d);
    }
  const std::string text =
      "<scene><settings><xres>" + std::to_string(width) + "</xres><yres>" +
      std::to_string(width * 3 / 4) + "</yres><mode>spectral_mcpt</mode><depth>5</depth><sampl>" +
      std::to_string(spp) +
      "</sampl><bands>400:700:10</bands></settings><camera><position>0,0.9,-2.6</position>"
      "<look_at>0,0.5,0</look_at><fov>40</fov></camera><plane><normal>0,1,0</normal><distance>0"
      "</distance><material>matte</material><reflectance>0.5</reflectance></plane><mesh>"
      "<vertices>" +
      v + "</vertices><faces>" + f +
      "</faces><material>matte</material><reflectance>0.4</reflectance></mesh><sphere><center>"
      "-1.5,2.5,-1</center><radius>0.5</radius><material>matte</material><reflectance>0"
      "</reflectance><emission scale=\"5e-3\">D65</emission></sphere></scene>";
  const SceneDesc desc = parseScene(text, "mesh.scn");
  const RenderScene scene = buildRenderScene(desc);
  const SceneTangents t = gradientSetup(desc, {"objects[1].vertices"}, scene, true).tangents;
  const std::vector<float> adjoint(static_cast<size_t>(scene.settings.width) *
                                       scene.settings.height * scene.settings.bands.count(),
                                   1.0f);
  RenderOptions plain;
  const double t0 = bench::fastestSeconds(3, [&] { render(scene, plain); });
  RenderOptions o;
  o.gradients = &t;
  o.adjoint = &adjoint;
  const double tr = bench::fastestSeconds(3, [&] { render(scene, o); });
  std::printf("\nmesh of %d vertices (%u slots):\n", rings * segments, t.slots());
  std::printf("%-34s %9.3f %8.2f\n", "plain", t0, 1.0);
  std::printf("%-34s %9.3f %8.2f\n", "reverse, every vertex", tr, tr / t0);
}

int run(int argc, char** argv) {
  CLI::App app{"nxbench-gradients: the cost of forward- and reverse-mode gradients"};
  int spp = 32, width = 96, threads = 2, knots = 31, matrixSize = 21, meshVertices = 10000;
  app.add_option("--spp", spp, "Samples per pixel (default 32)")->check(numberIn(1, 1 << 20));
  app.add_option("--width", width, "Image width (default 96)")->check(numberIn(8, 4096));
  app.add_option("--threads", threads, "Worker threads (default 2)")->check(numberIn(1, 4096));
  app.add_option("--knots", knots, "Knots of the floor's table (default 31)")
      ->check(numberIn(2, 100000));
  app.add_option("--matrix", matrixSize, "Rows and columns of the measured matrix (default 21)")
      ->check(numberIn(2, 1000));
  app.add_option("--mesh-vertices", meshVertices,
                 "Vertices of the mesh row's sphere (default 10000)")
      ->check(numberIn(12, 1000000));
  if (const int status = parseCommandLine(app, argc, argv, "nxbench-gradients"); status >= 0)
    return status;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(threads));
  Values v;
  for (int k = 0; k < knots; ++k) v.floor.push_back(0.3 + 0.5 * k / (knots - 1.0));
  const SceneDesc desc = parseScene(text(v, width, spp), "bench.scn");
  const RenderScene scene = buildRenderScene(desc);
  // The tangents by parameter name, as render(gradients=...) makes them.
  const std::vector<std::string> fourNames = {
      "objects[1].fluorescence.stokes_nm", "objects[1].fluorescence.quantum_yield",
      "objects[2].emission_scale", "objects[1].reflectance"};
  const SceneTangents one =
      gradientSetup(desc, {"objects[1].fluorescence.stokes_nm"}, scene, true).tangents;
  const SceneTangents four = gradientSetup(desc, fourNames, scene, true).tangents;
  std::vector<std::string> manyNames = fourNames;
  manyNames.push_back("objects[0].reflectance"); // one slot per knot of the floor's table
  const SceneTangents many = gradientSetup(desc, manyNames, scene, true).tangents;
  std::printf("scene: %dx%d, %d spp, %d threads, 31 bands\n", scene.settings.width,
              scene.settings.height, spp, threads);
  RenderOptions plain;
  const double t0 = bench::fastestSeconds(3, [&] { render(scene, plain); });
  std::printf("%-34s %9s %8s\n", "render", "seconds", "x plain");
  auto row = [&](const char* what, double t) {
    std::printf("%-34s %9.3f %8.2f\n", what, t, t / t0);
  };
  row("plain", t0);
  auto forward = [&](const SceneTangents& t) {
    RenderOptions o;
    o.gradients = &t;
    return bench::fastestSeconds(3, [&] { render(scene, o); });
  };
  row("forward, 1 parameter", forward(one));
  row("forward, 4 parameters", forward(four));
  const std::vector<float> adjoint(static_cast<size_t>(scene.settings.width) *
                                       scene.settings.height * scene.settings.bands.count(),
                                   1.0f);
  auto reverse = [&](const SceneTangents& t, int samples) {
    RenderOptions o;
    o.gradients = &t;
    o.adjoint = &adjoint;
    o.samples = samples;
    return bench::fastestSeconds(3, [&] { render(scene, o); });
  };
  row("reverse, 4 parameters", reverse(four, spp));
  // Shape and camera: the sphere's centre and radius, the camera's position (the boundary
  // terms on the film and at every vertex included).
  const SceneTangents centre = gradientSetup(desc, {"objects[1].center"}, scene, true).tangents;
  const SceneTangents pose =
      gradientSetup(desc, {"objects[1].center", "objects[1].radius"}, scene, true).tangents;
  const SceneTangents camera = gradientSetup(desc, {"camera.position"}, scene, true).tangents;
  row("forward, sphere centre (3)", forward(centre));
  row("reverse, sphere centre + radius", reverse(pose, spp));
  row("forward, camera position (3)", forward(camera));
  const double knotSetup = bench::fastestSeconds(
      3, [&] { gradientSetup(desc, {"objects[0].reflectance"}, scene, true); });
  const std::string setupLabel = "set-up of " + std::to_string(knots) + " knots' tangents";
  row(setupLabel.c_str(), knotSetup);
  const std::string label = "reverse, 4 + " + std::to_string(knots) + " knots";
  row(label.c_str(), reverse(many, spp));
  const std::string fd = "differences, " + std::to_string(4 + knots) + " parameters";
  row(fd.c_str(), 2.0 * (4 + knots) * t0);
  matrixRows(desc, matrixSize, spp, adjoint);
  std::printf("\npeak memory of reverse renders (%u slots):\n", many.slots());
  for (int s : {spp / 4 > 0 ? spp / 4 : 1, spp, spp * 4}) {
    reverse(many, s);
    std::printf("  %6d spp: %8.1f MB\n", s, static_cast<double>(peakKilobytes()) / 1024.0);
  }
  meshRow(meshVertices, width, spp);
  std::printf("  peak memory after it: %.1f MB\n", static_cast<double>(peakKilobytes()) / 1024.0);
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return mainReportingErrors("nxbench-gradients", run, argc, argv);
}
