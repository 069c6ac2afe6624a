#include "spectra/bands.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"
#include "core/text_table.h"

namespace nx {

SpectralBands SpectralBands::parse(const std::string& text) {
  const auto c1 = text.find(':');
  const auto c2 = c1 == std::string::npos ? c1 : text.find(':', c1 + 1);
  if (c1 == std::string::npos || c2 == std::string::npos ||
      text.find(':', c2 + 1) != std::string::npos)
    throw Error("bands: expected START:END:STEP in nm (e.g. 400:700:10), found '" + text + "'");
  const std::string where = "bands '" + text + "'";
  SpectralBands b;
  b.startNm = parseNumber(text.substr(0, c1), where, "a start wavelength in nm");
  b.endNm = parseNumber(text.substr(c1 + 1, c2 - c1 - 1), where, "an end wavelength in nm");
  b.stepNm = parseNumber(text.substr(c2 + 1), where, "a step in nm");
  if (!(b.stepNm >= 1e-3))
    throw Error(where +
                ": expected a step of at least 0.001 nm (channel names hold 6 decimals), "
                "found " +
                text.substr(c2 + 1));
  if (!(b.endNm >= b.startNm)) throw Error(where + ": expected END >= START, found " + text);
  if (b.lower(0) < kTraceMinNm || b.endNm + 0.5 * b.stepNm > kTraceMaxNm)
    throw Error(where + ": expected bands within " + numberText(kTraceMinNm) + "-" +
                numberText(kTraceMaxNm) + " nm (edges included), found " + numberText(b.lower(0)) +
                "-" + numberText(b.endNm + 0.5 * b.stepNm) + " nm");
  const double n = (b.endNm - b.startNm) / b.stepNm;
  if (std::abs(n - std::round(n)) > 1e-6)
    throw Error(where + ": expected END - START to be a multiple of STEP, found " + text);
  if (n + 1 > 4096) throw Error(where + ": expected at most 4096 bands, found " + text);
  return b;
}

int SpectralBands::count() const {
  return static_cast<int>(std::lround((endNm - startNm) / stepNm)) + 1;
}

int SpectralBands::bandOf(double nm) const {
  const double x = (nm - lower(0)) / stepNm;
  if (!(x >= 0.0)) return -1;
  const int i = static_cast<int>(x);
  return i < count() ? i : -1;
}

std::string SpectralBands::toString() const {
  // Exact: the text is stored in the EXR and parsed back by nxmerge, nxdiff and --resume,
  // which find the channels by the centres it gives (6 significant digits lost 400.00001).
  return exactNumberText(startNm) + ":" + exactNumberText(endNm) + ":" + exactNumberText(stepNm);
}

} // namespace nx
