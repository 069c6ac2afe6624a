#!/usr/bin/env bash
# SIGINT stops a render within a few seconds even where one tile takes far longer: an rt
# scene whose every sample traces a tree of 16384 rays, with shadow rays to 32 lights at each vertex
# (metal planes: every vertex has a diffuse lobe; one sample takes ~80 ms, one 16x16 tile of 8
# samples per pixel more than two minutes on this machine: a stop used to wait for the
# tile to end). Resuming from such a partial is tested by interrupt_resume.sh.
#
#   stop_latency.sh BIN_DIR
set -euo pipefail
bin="$1"
d="$(mktemp -d)"
trap 'rm -rf "$d"' EXIT
{
  echo '<scene><settings><xres>16</xres><yres>16</yres><mode>rt</mode><sampl>8</sampl><depth>50</depth></settings>'
  echo '<camera><position>0,0,0</position><look_at>0,0.05,1</look_at><fov>20</fov></camera>'
  echo '<plane><normal>0,0,1</normal><distance>-5</distance><material>metal</material><reflectance>1</reflectance></plane>'
  echo '<plane><normal>0,0,-1</normal><distance>-5</distance><material>metal</material><reflectance>1</reflectance></plane>'
  echo '<plane><normal>0,0,1</normal><distance>-2</distance><material>glass</material></plane>'
  echo '<plane><normal>0,0,1</normal><distance>2</distance><material>glass</material></plane>'
  for i in $(seq 1 32); do
    echo "<sphere><center>$i,3,0</center><radius>0.2</radius><material>matte</material><emission>1</emission></sphere>"
  done
  echo '</scene>'
} >"$d/slow.scn"
"$bin/nxrender" --threads 1 -o "$d/slow.exr" "$d/slow.scn" 2>"$d/log" &
pid=$!
sleep 2
kill -INT "$pid"
start=$(date +%s%N)
set +e
wait "$pid"
rc=$?
set -e
took_ms=$((($(date +%s%N) - start) / 1000000))
echo "stopped $took_ms ms after SIGINT (exit $rc)"
[ "$rc" = 3 ] || { echo "expected exit status 3, got $rc"; cat "$d/log"; exit 1; }
# Within a few seconds (one sample takes ~80 ms; writing the file well under a second).
[ "$took_ms" -lt 5000 ] || { echo "took $took_ms ms to stop"; exit 1; }
grep -q "stopped by signal 2" "$d/log" || { cat "$d/log"; exit 1; }
