# Sourced by the farm tests: a temporary folder $d (removed at exit) holding s.scn, an emitting
# matte sphere at 8x6 pixels and 8 samples per pixel, its reflectance element $REFLECTANCE
# (default <reflectance>0.5</reflectance>).
d="$(mktemp -d)"
trap 'rm -rf "$d"' EXIT
cat >"$d/s.scn" <<SCN
<scene>
<settings><xres>8</xres><yres>6</yres><mode>spectral_mcpt</mode><sampl>8</sampl></settings>
<camera><position>0,0,-5</position><look_at>0,0,0</look_at></camera>
<sphere><center>0,0,0</center><radius>1</radius><material>matte</material>${REFLECTANCE:-<reflectance>0.5</reflectance>}<emission>1</emission></sphere>
</scene>
SCN
