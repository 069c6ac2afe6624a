// Ground-truth layers (integrators/aov_layers.h) against closed forms: a sphere's normals and
// positions against the ray-sphere intersection averaged over each pixel (an independent
// supersampling here), a fronto-parallel quad's positions and uv (affine in the film position,
// so the pixel mean is the value at its centre), a matte surface's albedo against its
// reflectance, a rough conductor's against the furnace (its radiance under a uniform white
// background after one bounce), a datasheet dye's spectra against the datasheet; and the layers
// merged from sample ranges and resumed equal to one render's.

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "integrators/aov_layers.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "io/part_merge.h"
#include "io/spectral_exr.h"
#include "support/errors.h"
#include "support/part_attributes.h"
#include "support/statistics.h"

namespace nx {
namespace {

constexpr int kSize = 24;

std::string settings(int spp, const std::string& extra = "") {
  return "<settings><xres>" + std::to_string(kSize) + "</xres><yres>" + std::to_string(kSize) +
         "</yres><mode>spectral_mcpt</mode><depth>2</depth><sampl>" + std::to_string(spp) +
         "</sampl><bands>400:700:50</bands>" + extra + "</settings>";
}

const std::string kCamera =
    "<camera><position>0,0,-4</position><look_at>0,0,0</look_at><fov>30</fov></camera>";
const std::string kLight =
    "<light><position>1,2,-3</position><color>1,1,1</color><emission scale=\"0.1\">D65"
    "</emission></light>";

SpectralImage renderAovs(const std::string& text, std::vector<AovKind> kinds, uint32_t seed = 0,
                         int first = 0, int samples = 0) {
  const RenderScene scene = buildRenderScene(parseScene(text, "t.scn"));
  RenderOptions o;
  o.aovs = std::move(kinds);
  o.seed = seed;
  o.firstSample = first;
  o.samples = samples;
  SpectralImage img = toSpectralImage(render(scene, o).film);
  test::setPartAttributes(img, seed, first, samples);
  return img;
}

const AovImageLayer& layer(const SpectralImage& img, const std::string& name) {
  for (const AovImageLayer& l : img.aovs)
    if (l.name == name) return l;
  throw Error("no layer " + name);
}

// Value of channel c of layer `name` at pixel (x, y).
float at(const SpectralImage& img, const std::string& name, int x, int y, int c) {
  const AovImageLayer& l = layer(img, name);
  const size_t n = l.values.size() / (static_cast<size_t>(img.width) * img.height);
  return l.values[(static_cast<size_t>(y) * img.width + x) * n + static_cast<size_t>(c)];
}

TEST(AovLayers, SphereNormalsAndPositionsAreThePixelAverages) {
  const Vec3d c(0.1, -0.05, 0.3);
  const double r = 0.8;
  const std::string text = "<scene>" + settings(64) + kCamera + "<sphere><center>0.1,-0.05,0.3" +
                           "</center><radius>0.8</radius><material>matte</material>" +
                           "<reflectance>0.5</reflectance></sphere>" + kLight + "</scene>";
  const SpectralImage img =
      renderAovs(text, {AovKind::Normals, AovKind::Position, AovKind::GeometricNormals});
  const RenderScene scene = buildRenderScene(parseScene(text, "t.scn"));
  // The intersection solved here, on a 16 x 16 grid per pixel; pixels whose grid all hits.
  auto hitAt = [&](double x, double y, Vec3d& p) {
    const Ray ray = scene.camera.generateRay(x, y);
    const Vec3d o(ray.o), d = normalize(Vec3d(ray.d)), oc = o - c;
    const double b = dot(oc, d), disc = b * b - (dot(oc, oc) - r * r);
    if (disc < 0) return false;
    p = o + d * (-b - std::sqrt(disc));
    return true;
  };
  int compared = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      Vec3d sumP, sumN;
      bool all = true;
      for (int j = 0; j < 16 && all; ++j)
        for (int i = 0; i < 16 && all; ++i) {
          Vec3d p;
          all = hitAt(x + (i + 0.5) / 16, y + (j + 0.5) / 16, p);
          sumP = sumP + p / 256.0;
          sumN = sumN + normalize(p - c) / 256.0;
        }
      if (!all) continue;
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(at(img, "position", x, y, k), (&sumP.x)[k], 2e-3) << x << "," << y;
        EXPECT_NEAR(at(img, "normals", x, y, k), (&sumN.x)[k], 3e-3) << x << "," << y;
        EXPECT_NEAR(at(img, "geometric_normals", x, y, k), (&sumN.x)[k], 3e-3) << x << "," << y;
      }
      ++compared;
    }
  EXPECT_GT(compared, kSize * kSize / 4);
  // Where nothing is hit, zeros; a pixel half on the outline holds about half a normal.
  EXPECT_EQ(at(img, "normals", 0, 0, 2), 0.0f);
}

TEST(AovLayers, QuadPositionsAndUvAreAffineInTheFilm) {
  // A quad facing the camera squarely at z = 1: position and uv are affine in the film
  // position, so each pixel's average is the value at its centre; 16 samples estimate it to
  // about 1% of a pixel (0.11 scene units here).
  const std::string text = "<scene>" + settings(16) + kCamera +
                           "<quad><origin>-3,-3,1</origin><edge_u>6,0,0</edge_u><edge_v>0,6,0"
                           "</edge_v><material>matte</material><reflectance>0.5</reflectance>"
                           "</quad>" +
                           kLight + "</scene>";
  const SpectralImage img = renderAovs(text, {AovKind::Position, AovKind::Uv});
  const RenderScene scene = buildRenderScene(parseScene(text, "t.scn"));
  int compared = 0;
  for (int y = 2; y < kSize - 2; ++y)
    for (int x = 2; x < kSize - 2; ++x) {
      const Ray ray = scene.camera.generateRay(x + 0.5, y + 0.5);
      const Vec3d o(ray.o), d(ray.d);
      const Vec3d p = o + d * ((1 - o.z) / d.z);
      EXPECT_NEAR(at(img, "position", x, y, 0), p.x, 3e-3);
      EXPECT_NEAR(at(img, "position", x, y, 1), p.y, 3e-3);
      EXPECT_NEAR(at(img, "position", x, y, 2), 1.0, 1e-5);
      // (u, v) = ((x + 3) / 6, (y + 3) / 6): the quad's corners at (0, 0), (1, 0), (0, 1)
      EXPECT_NEAR(at(img, "uv", x, y, 0), (p.x + 3) / 6, 5e-4) << x << "," << y;
      EXPECT_NEAR(at(img, "uv", x, y, 1), (p.y + 3) / 6, 5e-4) << x << "," << y;
      ++compared;
    }
  EXPECT_GT(compared, 300);
}

TEST(AovLayers, MatteAlbedoIsItsReflectanceAveragedOverTheBand) {
  // A linear reflectance: each 50 nm band's mean is its value at the band's centre; the
  // band 600-650 of a table with a knot inside it, the mean of the two pieces.
  const std::string text = "<scene>" + settings(4) + kCamera +
                           "<sphere><center>0,0,0</center><radius>1.2</radius><material>matte"
                           "</material><reflectance>350:0.1, 620:0.64, 750:0.12</reflectance>"
                           "</sphere>" +
                           kLight + "</scene>";
  const SpectralImage img = renderAovs(text, {AovKind::Albedo});
  auto rho = [](double nm) {
    return nm < 620 ? 0.1 + 0.54 * (nm - 350) / 270 : 0.64 - 0.52 * (nm - 620) / 130;
  };
  for (int b = 0; b < img.bands.count(); ++b) {
    const double lo = img.bands.channel(b).lo, hi = img.bands.channel(b).hi;
    double mean = 0;
    for (int k = 0; k < 10000; ++k) mean += rho(lo + (k + 0.5) * (hi - lo) / 10000) / 10000;
    EXPECT_NEAR(at(img, "albedo", kSize / 2, kSize / 2, b), mean, 2e-3) << "band " << b;
  }
  EXPECT_EQ(at(img, "albedo", 0, 0, 0), 0.0f); // (nothing hit)
}

TEST(AovLayers, RoughConductorAlbedoIsTheFurnaceValue) {
  // Under a uniform white background, one bounce off a convex rough metal carries the
  // directional albedo towards the camera: the render and the layer, summed over the pixels
  // inside the sphere, agree within the seeds' spread.
  const std::string text = "<scene>" + settings(32, "<background>1</background>") + kCamera +
                           "<sphere><center>0,0,0</center><radius>1.2</radius><material>"
                           "conductor</material><metal>gold</metal><alpha>0.4</alpha></sphere>"
                           "</scene>";
  const RenderScene scene = buildRenderScene(parseScene(text, "t.scn"));
  std::vector<test::RunningStats> diff(static_cast<size_t>(scene.settings.bands.count()));
  std::vector<double> albedoSum(diff.size(), 0.0);
  for (uint32_t seed = 0; seed < 8; ++seed) {
    RenderOptions o;
    o.seed = seed;
    o.aovs = {AovKind::Albedo};
    const SpectralImage img = toSpectralImage(render(scene, o).film);
    for (size_t b = 0; b < diff.size(); ++b) {
      double a = 0, l = 0;
      for (int y = 6; y < kSize - 6; ++y)
        for (int x = 6; x < kSize - 6; ++x) {
          a += at(img, "albedo", x, y, static_cast<int>(b));
          l += img.radiance[(static_cast<size_t>(y) * kSize + x) * diff.size() + b];
        }
      diff[b].add(a - l);
      albedoSum[b] += a / 8;
    }
  }
  for (size_t b = 0; b < diff.size(); ++b) {
    EXPECT_LE(std::abs(diff[b].mean), 5 * diff[b].standardError() + 1e-6 * albedoSum[b])
        << "band " << b << ": albedo sum " << albedoSum[b] << ", difference " << diff[b].mean;
    EXPECT_LT(diff[b].standardError(), 0.01 * albedoSum[b]) << "band " << b << ": no power";
  }
}

TEST(AovLayers, DatasheetDyeSpectraAreTheDatasheets) {
  // Absorptance a(l) with yield Q and an emission beyond every absorbed wavelength: photons
  // re-emitted per photon absorbed at l are a(l) Q; the emission layer is the datasheet's
  // emission normalised to area 1 per nm.
  const std::string text =
      "<scene>" + settings(4) + kCamera +
      "<sphere><center>0,0,0</center><radius>1.2</radius><material>matte</material>"
      "<reflectance>0.2</reflectance><fluorescence><absorptance>380:0, 425:0.8, 470:0"
      "</absorptance><emission>500:0, 575:1, 650:0</emission><yield>0.6</yield></fluorescence>"
      "</sphere>" +
      kLight + "</scene>";
  const SpectralImage img = renderAovs(text, {AovKind::Fluorescence});
  const int nb = img.bands.count();
  auto absorptance = [](double nm) {
    return nm < 380 || nm > 470 ? 0.0 : 0.8 * (1 - std::abs(nm - 425) / 45);
  };
  auto emission = [](double nm) { // triangle of area 75: per nm, normalised
    return nm < 500 || nm > 650 ? 0.0 : (1 - std::abs(nm - 575) / 75) / 75;
  };
  for (int b = 0; b < nb; ++b) {
    const double lo = img.bands.channel(b).lo, hi = img.bands.channel(b).hi;
    double a = 0, e = 0;
    for (int k = 0; k < 1000; ++k) {
      const double nm = lo + (k + 0.5) * (hi - lo) / 1000;
      a += 0.6 * absorptance(nm) / 1000, e += emission(nm) / 1000;
    }
    // (the dye is resampled onto 5 nm bins: within a few percent of the peak)
    EXPECT_NEAR(at(img, "fluorescence", kSize / 2, kSize / 2, b), a, 0.02) << "band " << b;
    EXPECT_NEAR(at(img, "fluorescence", kSize / 2, kSize / 2, nb + b), e, 4e-4) << "band " << b;
  }
}

TEST(AovLayers, MergedAndResumedEqualOneRender) {
  const std::string text = "<scene>" + settings(16) + kCamera +
                           "<sphere><center>0,0,0</center><radius>1</radius><material>"
                           "conductor</material><metal>gold</metal><alpha>0.3</alpha></sphere>" +
                           kLight + "</scene>";
  const std::vector<AovKind> kinds = {AovKind::Normals, AovKind::Albedo};
  const SpectralImage whole = renderAovs(text, kinds, 3, 0, 16);
  const SpectralImage a = renderAovs(text, kinds, 3, 0, 8), b = renderAovs(text, kinds, 3, 8, 8);
  const SpectralImage merged = mergeParts({{"a", a}, {"b", b}});
  // Resumed: the first 8 samples' image continued to 16.
  const RenderScene scene = buildRenderScene(parseScene(text, "t.scn"));
  const Film stored = filmFromImage(a, 0, 16);
  RenderOptions o;
  o.aovs = kinds;
  o.seed = 3;
  o.samples = 16;
  o.resumeFrom = &stored;
  const SpectralImage resumed = toSpectralImage(render(scene, o).film);
  for (const SpectralImage* img : {&merged, &resumed}) {
    ASSERT_EQ(img->aovs.size(), 2u);
    for (size_t l = 0; l < 2; ++l)
      for (size_t k = 0; k < whole.aovs[l].values.size(); ++k)
        ASSERT_NEAR(img->aovs[l].values[k], whole.aovs[l].values[k],
                    1e-6 * (1 + std::abs(whole.aovs[l].values[k])))
            << whole.aovs[l].name << " value " << k;
  }
  // Written and read back: the same layers and values (float channels).
  const std::string path = ::testing::TempDir() + "/aov_layers.exr";
  writeSpectralExr(path, whole);
  const SpectralImage read = readSpectralExr(path);
  ASSERT_EQ(read.aovs.size(), whole.aovs.size());
  for (size_t l = 0; l < read.aovs.size(); ++l) {
    EXPECT_EQ(read.aovs[l].name, whole.aovs[l].name);
    EXPECT_EQ(read.aovs[l].values, whole.aovs[l].values);
  }
  // A resume that asks for other layers is refused, naming both.
  o.aovs = {AovKind::Normals};
  EXPECT_NE(test::errorMessage([&] { render(scene, o); }).find("other ground-truth layers"),
            std::string::npos);
}

} // namespace
} // namespace nx

namespace nx {
namespace {

TEST(AovLayers, MismatchedPartsAndBrokenFilesAreRefused) {
  const std::string text = "<scene>" + settings(4) + kCamera +
                           "<sphere><center>0,0,0</center><radius>1</radius><material>matte"
                           "</material><reflectance>0.5</reflectance></sphere>" +
                           kLight + "</scene>";
  const SpectralImage a = renderAovs(text, {AovKind::Normals}, 0, 0, 2);
  const SpectralImage b = renderAovs(text, {AovKind::Albedo}, 0, 2, 2);
  EXPECT_NE(test::errorMessage([&] {
              mergeParts({{"a", a}, {"b", b}});
            })
                .find("b: does not belong with a: its ground-truth layers are 'albedo', not "
                      "'normals'"),
            std::string::npos);
  // Band sets are not stitched with ground-truth layers.
  SpectralImage other = a;
  other.bands = Sensor(SpectralBands{750, 800, 50});
  other.attributes["nxrender.bands"] = other.bands.toString();
  other.radiance.assign(static_cast<size_t>(a.width * a.height) * 2, 0.0f);
  other.bandVariance.clear();
  other.aovs.clear();
  EXPECT_NE(test::errorMessage([&] {
              mergeParts({{"a", a}, {"c", other}});
            }).find("cannot be stitched with other band sets: it holds ground-truth layers"),
            std::string::npos);
  // A file whose attribute lists a layer nxrender does not make, or one without its channels.
  SpectralImage plain = renderAovs(text, {}, 0, 0, 2);
  const std::string path = ::testing::TempDir() + "/aov_broken.exr";
  plain.attributes["nxrender.aovLayers"] = "normals";
  writeSpectralExr(path, plain);
  EXPECT_NE(test::errorMessage([&] {
              readSpectralExr(path);
            }).find("expected a channel normals.X (nxrender.aovLayers lists the layer normals)"),
            std::string::npos);
  plain.attributes["nxrender.aovLayers"] = "curvature";
  writeSpectralExr(path, plain);
  EXPECT_NE(test::errorMessage([&] { readSpectralExr(path); })
                .find("expected ground-truth layers named as nxrender names them in "
                      "nxrender.aovLayers, found 'curvature'"),
            std::string::npos);
}

} // namespace
} // namespace nx
