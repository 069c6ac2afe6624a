#!/usr/bin/env bash
# The pictures of docs/relighting.md: the lab bench rendered once, relightable and with its
# component layers, then relit under CIE A, D65, F11 and its own warm LED; and the fluorescent
# card's components. Montages written to OUT_DIR (and copied into docs/ with --docs).
#
#   scenes/relight_example.sh [BUILD_DIR] [OUT_DIR] [--docs]   (defaults: build, /tmp/nxrelight-example)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-build}" out="${2:-/tmp/nxrelight-example}" docs="${3:-}"
mkdir -p "$out"

# 1. One render: relightable (5 nm excitation bins), with the component layers.
"$build/apps/nxrender" --threads "$(nproc)" --spp 128 --relightable --aov components,lightgroups \
  -o "$out/render.exr" "$here/lab_bench.scn"

# 2. The LED panel (light group "led") relit; the UV lamp (group "uv") keeps its spectrum.
for lamp in A D65 F11 "$here/data/warm_led.csv"; do
  name=$(basename "$lamp" .csv)
  "$build/apps/nxrelight" "$out/render.exr" --light "led=$lamp" -o "$out/led-$name.exr"
done

# 3. Montages: the relit previews side by side; the components at one exposure.
PYTHONPATH="$build/python" /usr/bin/python3 - "$out" <<'PY'
import sys
import numpy as np
import OpenImageIO as oiio
import nxrender

out = sys.argv[1]

def read_png(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT)[:, :, :3]

def write_png(path, rgb):
    spec = oiio.ImageSpec(rgb.shape[1], rgb.shape[0], 3, oiio.UINT8)
    o = oiio.ImageOutput.create(path)
    o.open(path, spec)
    o.write_image((np.clip(rgb, 0, 1) * 255 + 0.5).astype(np.uint8))
    o.close()

gap = lambda h: np.ones((h, 4, 3), np.float32)
tiles = [read_png(f"{out}/led-{n}.png") for n in ("A", "D65", "F11", "warm_led")]
write_png(f"{out}/relight-lab-bench.png",
          np.concatenate(sum([[t, gap(t.shape[0])] for t in tiles], [])[:-1], axis=1))

image = nxrender.read_exr(f"{out}/render.exr")
def srgb(radiance, exposure):
    rgb = nxrender.Image(radiance, wavelengths=image.wavelengths).rgb * exposure
    return np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * np.power(np.maximum(rgb, 0), 1 / 2.4) - 0.055)
exposure = 0.8 / np.percentile(image.rgb, 99)
parts = [image.radiance] + [image.components[n] for n in ("reflected", "fluoresced", "direct", "indirect")]
tiles = [srgb(p, exposure) for p in parts]
write_png(f"{out}/components-lab-bench.png",
          np.concatenate(sum([[t, gap(t.shape[0])] for t in tiles], [])[:-1], axis=1))
PY
if [ "$docs" = "--docs" ]; then
  cp "$out/relight-lab-bench.png" "$out/components-lab-bench.png" "$here/../docs/"
fi
echo "wrote $out/relight-lab-bench.png and $out/components-lab-bench.png"
