#!/usr/bin/env bash
# A mesh whose declared size exceeds the memory the process may use is refused with the
# figures before the mesh library allocates anything (it ended in a bare std::bad_alloc): a
# binary PLY of 5M faces and 2.5M vertices (95 MB) under an address-space limit of 2 GB.
# Usage: mesh_memory.sh NXRENDER
set -u
nxrender=$1
d=$(mktemp -d)
trap 'rm -rf "$d"' EXIT
{
  printf 'ply\nformat binary_little_endian 1.0\nelement vertex 2500000\nproperty float x\nproperty float y\nproperty float z\nelement face 5000000\nproperty list uchar int vertex_indices\nend_header\n'
  head -c $((2500000 * 12)) /dev/zero
  perl -e 'print "\x03\0\0\0\0\x01\0\0\0\x02\0\0\0" x 5000000'
} >"$d/big.ply"
cat >"$d/s.scn" <<'SCN'
<scene>
<settings><xres>8</xres><yres>6</yres><mode>spectral_mcpt</mode><sampl>1</sampl></settings>
<camera><position>0,0,-5</position><look_at>0,0,0</look_at></camera>
<mesh file="big.ply"><material>matte</material><reflectance>0.5</reflectance></mesh>
</scene>
SCN
cd "$d" || exit 1
(ulimit -v 2000000 && exec "$nxrender" -o out.exr s.scn) 2>err.txt
status=$?
want="nxrender: error: s.scn:4: big.ply: expected a mesh whose buffers fit in memory, found 2500000 vertices and 5000000 faces (needs "
if [ "$status" != 1 ] || [ "$(head -c ${#want} err.txt)" != "$want" ] || ! grep -q "address-space limit" err.txt; then
  echo "status $status:"; cat err.txt; exit 1
fi
[ ! -e out.exr ] || { echo "wrote out.exr"; exit 1; }
echo "refused with figures: $(cat err.txt)"
