// Numbers read and written the same in every locale: a host that sets a decimal-comma locale
// (Python's locale.setlocale(locale.LC_ALL, "de_DE.UTF-8")) made strtod read "0.5" as 0, so
// every scene was refused, and printf wrote the number in a channel name "S0.412,500000nm"
// with a comma for its decimal point too. The test builds the de_DE locale with localedef
// (Debian's locales package) into a temporary folder, switches the process to it, then reads a
// scene, renders it, writes and reads its EXR and parses numbers.

#include <gtest/gtest.h>

#include <clocale>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "core/number_text.h"
#include "core/text_table.h"
#include "integrators/render_scene.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "io/spectral_exr.h"

namespace nx {
namespace {

// Switches LC_ALL to de_DE.UTF-8 (built into a temporary folder) for its lifetime.
class DecimalCommaLocale {
public:
  DecimalCommaLocale() {
    dir_ = std::filesystem::temp_directory_path() / "nx_locale_test";
    std::filesystem::create_directories(dir_);
    const std::string cmd =
        "localedef -i de_DE -f UTF-8 '" + (dir_ / "de_DE.UTF-8").string() + "' >/dev/null 2>&1";
    if (!std::filesystem::exists(dir_ / "de_DE.UTF-8")) (void)std::system(cmd.c_str());
    setenv("LOCPATH", dir_.c_str(), 1);
    ok_ = std::setlocale(LC_ALL, "de_DE.UTF-8") != nullptr;
  }
  ~DecimalCommaLocale() {
    std::setlocale(LC_ALL, "C");
    unsetenv("LOCPATH");
  }
  bool ok() const { return ok_; }

private:
  std::filesystem::path dir_;
  bool ok_ = false;
};

const char* kScene = R"(<scene><settings><xres>6</xres><yres>4</yres><mode>spectral_mcpt</mode>
<sampl>2</sampl><bands>400:700:12.5</bands></settings>
<camera><position>0,0.5,-3.5</position><look_at>0,0.25,0</look_at><fov>40.5</fov></camera>
<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>
<reflectance>0.5</reflectance></plane>
<sphere><center>0,0.5,0</center><radius>0.25</radius><material>matte</material>
<reflectance>0.75</reflectance><emission scale="0.5">D65</emission></sphere></scene>)";

TEST(LocaleIndependence, ScenesNumbersAndFilesUnderADecimalCommaLocale) {
  DecimalCommaLocale locale;
  ASSERT_TRUE(locale.ok()) << "could not build or select de_DE.UTF-8 (localedef, package locales)";
  ASSERT_EQ(std::strtod("0.5", nullptr), 0.0) << "the locale's decimal point is not a comma";
  EXPECT_EQ(strtodC("0.5"), 0.5);
  EXPECT_EQ(parseNumber("12.5", "t", "a number"), 12.5);
  EXPECT_EQ(exactNumberText(0.1), "0.1");
  EXPECT_EQ(numberText(2.5), "2.5");
  EXPECT_EQ(spectralChannelName(412.5), "S0.412,500000nm");
  const RenderScene scene = buildRenderScene(parseScene(kScene, "t.scn"));
  ASSERT_EQ(scene.settings.bands.count(), 25);
  EXPECT_DOUBLE_EQ(scene.settings.bands.channelNm(1), 412.5);
  const RenderOutput out = render(scene, RenderOptions{});
  const SpectralImage image = toSpectralImage(out.film);
  const std::string path =
      (std::filesystem::temp_directory_path() / "nx_locale_test" / "image.exr").string();
  writeSpectralExr(path, image);
  const SpectralImage back = readSpectralExr(path);
  ASSERT_EQ(back.bands.count(), image.bands.count());
  EXPECT_DOUBLE_EQ(back.bands.channelNm(1), image.bands.channelNm(1));
  EXPECT_EQ(back.radiance, image.radiance);
}

} // namespace
} // namespace nx
