// nxbench-light-choice: how next-event estimation chooses among many lights - by the power each
// sends to the shading point weighed light by light (local), down the light tree (tree) or by
// emitted power (power) - measured on a floor under 4, 64 and 1024 lamps, and under one smooth
// spot among three other lamps.
//
//   nxbench-light-choice [--threads N] [--spp N] [--repeats N] [--lights N,N,...]
//
// Each scene is built in code (deterministic): spots aimed at the floor, ceiling panels (quads
// facing down), point lights and small emitting spheres over a region larger than the view.
// Each selection renders it --repeats times with different seeds; per lit pixel and band (and
// per pixel in luminance) the relative noise of one render about the mean is printed, the time
// per sample, and the time to equal error against the first row (variance times time).

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "apps/command_line.h"
#include "apps/seed_statistics.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"

namespace {

std::string num(double x) {
  return std::to_string(x);
}

std::string xyz(double x, double y, double z) {
  return num(x) + "," + num(y) + "," + num(z);
}

const char* kFloor =
    "<camera><position>0,1.45,-0.01</position><look_at>0,0,0</look_at><fov>110</fov></camera>"
    "<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>"
    "<reflectance>0.5</reflectance></plane>";

std::string settings(int size) {
  return "<settings><xres>" + std::to_string(size) + "</xres><yres>" + std::to_string(size) +
         "</yres><mode>spectral_mcpt</mode><depth>3</depth><sampl>16</sampl></settings>";
}

// n lamps over a 12 x 12 region above the camera (which sees 4 x 4 of the floor and no lamp):
// spots (40%) aimed at the floor, ceiling panels (30%), point lights (15%) and small spheres
// (15%), each about as bright on the floor below it.
std::string lamps(int n) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::string body;
  const double spread = 6;
  for (int i = 0; i < n; ++i) {
    const double x = spread * (2 * u(rng) - 1), z = spread * (2 * u(rng) - 1);
    const double h = 1.5 + 2.5 * u(rng), kind = u(rng);
    if (kind < 0.4) {
      const double cone = 15 + 25 * u(rng);
      body += "<light type=\"spot\"><position>" + xyz(x, h, z) + "</position><look_at>" +
              xyz(x + 2 * u(rng) - 1, 0, z + 2 * u(rng) - 1) + "</look_at><cone_angle>" +
              num(cone) + "</cone_angle><falloff_angle>" + num(0.6 * cone) +
              "</falloff_angle><color>1,1,1</color><emission>" + num(2 * h * h) +
              "</emission></light>";
    } else if (kind < 0.7) {
      body += "<quad><origin>" + xyz(x, h, z) +
              "</origin><edge_u>0.3,0,0</edge_u>"
              "<edge_v>0,0,0.3</edge_v><material>matte</material><emission>" +
              num(20 * h * h) + "</emission></quad>";
    } else if (kind < 0.85) {
      body += "<light><position>" + xyz(x, h, z) + "</position><color>1,1,1</color><emission>" +
              num(1 * h * h) + "</emission></light>";
    } else {
      body += "<sphere><center>" + xyz(x, h, z) +
              "</center><radius>0.1</radius><material>"
              "matte</material><emission>" +
              num(30 * h * h) + "</emission></sphere>";
    }
  }
  return body;
}

// The case that motivated the tree: one smooth spot lighting the middle of the view, three
// brighter lamps off to the side (a point light, a panel, a sphere) that light it little.
std::string spotAmongLamps() {
  return "<light type=\"spot\"><position>0,4,0</position><look_at>0,0,0</look_at>"
         "<cone_angle>15</cone_angle><falloff_angle>10</falloff_angle><color>1,1,1</color>"
         "<emission>40</emission></light>"
         "<light><position>30,4,0</position><color>1,1,1</color><emission>400</emission></light>"
         "<quad><origin>-30,4,0</origin><edge_u>1,0,0</edge_u><edge_v>0,0,1</edge_v>"
         "<material>matte</material><emission>200</emission></quad>"
         "<sphere><center>0,4,30</center><radius>0.5</radius><material>matte</material>"
         "<emission>300</emission></sphere>";
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Choosing among many lights: local, the light tree and by power"};
  int threads = 2, spp = 16, repeats = 4, size = 48;
  std::vector<int> counts{4, 64, 1024};
  app.add_option("--threads", threads, "Worker threads (default 2)")->check(nx::numberIn(1, 4096));
  app.add_option("--spp", spp, "Samples per pixel (default 16)")->check(nx::numberIn(1, 1 << 20));
  app.add_option("--repeats", repeats, "Seeds per selection (default 4)")
      ->check(nx::numberIn(2, 1000));
  app.add_option("--size", size, "Image width and height (default 48)")
      ->check(nx::numberIn(8, 4096));
  app.add_option("--lights", counts, "Lamp counts (default 4,64,1024)")
      ->delimiter(',')
      ->check(nx::numberIn(1, 100000));
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxbench-light-choice"); status >= 0)
    return status;
  try {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<size_t>(threads));
    std::vector<std::pair<std::string, std::string>> scenes{
        {"one spot among three lamps", spotAmongLamps()}};
    for (const int n : counts) scenes.push_back({std::to_string(n) + " lamps", lamps(n)});
    std::printf("%dx%d, %d spp, %d seeds, %d threads; time to equal error against the first "
                "row\n",
                size, size, spp, repeats, threads);
    for (const auto& [name, body] : scenes) {
      const nx::RenderScene scene = nx::buildRenderScene(
          nx::parseScene("<scene>" + settings(size) + kFloor + body + "</scene>", name));
      std::printf("\n%s\n%-8s %12s %15s %10s %22s\n", name.c_str(), "choice", "band noise",
                  "luminance noise", "ns/sample", "time to equal error");
      std::vector<std::pair<const char*, nx::LightSelection>> rows;
      const int lightCount = nx::LightSampler(scene).count();
      if (lightCount <= nx::kMaxLocalLights) rows.push_back({"local", nx::LightSelection::Local});
      rows.push_back({"tree", nx::LightSelection::Tree});
      rows.push_back({"power", nx::LightSelection::Power});
      double firstBand = 0, firstY = 0;
      for (size_t i = 0; i < rows.size(); ++i) {
        nx::RenderOptions o;
        o.samples = spp;
        o.lightSelection = rows[i].second;
        const nx::bench::SeedStatistics st = nx::bench::seedStatistics(scene, o, repeats);
        const double band = nx::bench::litNoise(st), luminance = nx::bench::litNoiseY(st);
        const double workBand = band * band * st.nsPerSample;
        const double workY = luminance * luminance * st.nsPerSample;
        if (i == 0) firstBand = workBand, firstY = workY;
        std::printf("%-8s %12.4f %15.4f %10.0f %10.2f / %-10.2f\n", rows[i].first, band, luminance,
                    st.nsPerSample, workBand / firstBand, workY / firstY);
      }
    }
    std::printf("\n(time to equal error: per band / in luminance)\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxbench-light-choice: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
