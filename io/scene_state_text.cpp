#include "io/scene_state_text.h"

#include <sstream>

#include "core/hash.h"

namespace nx {
namespace {

// Every field of the descriptions is written below (else two scenes differing only in it would
// share a render key): tests/build_checks/check_fields_written.py reads the declarations and
// checks this file names each.

struct StateWriter {
  std::ostringstream t;
  StateWriter() { t.precision(17); }
  void text(const std::string& s) { t << s.size() << ':' << s << ';'; }
  void number(double v) { t << v << ';'; }
  template <size_t N>
  void numbers(const std::array<double, N>& a) {
    for (double v : a) t << v << ',';
    t << ';';
  }
  template <typename T>
  void optional(const std::optional<T>& v) {
    if (!v) {
      t << "-;";
      return;
    }
    if constexpr (std::is_same_v<T, SpectrumDesc>)
      t << canonicalText(ParamValue(*v)) << ';';
    else if constexpr (std::is_same_v<T, double>)
      number(*v);
    else if constexpr (std::is_same_v<T, std::array<int, 2>>)
      t << (*v)[0] << ',' << (*v)[1] << ';';
    else
      numbers(*v);
  }
  void point(const Vec3d& p) { t << p.x << ',' << p.y << ',' << p.z << ';'; }
  void material(const MaterialDesc& m) {
    text(m.material);
    t << m.params.canonicalText() << ';';
  }
};

} // namespace

std::string sceneStateText(const SceneDesc& d) {
  StateWriter w;
  const SettingsDesc& s = d.settings;
  w.t << "settings:" << s.width << 'x' << s.height << ',' << static_cast<int>(s.mode) << ','
      << s.depth << ',' << s.samples << ',' << s.seed << ';';
  w.text(s.outputPath);
  w.optional(s.illuminant);
  w.text(s.bands.toString());
  w.text(s.sensorFile), w.text(s.sensorCentres);
  w.optional(s.background);
  w.text(s.backgroundGroup);
  const CameraDesc& c = d.camera;
  w.t << "camera:";
  w.point(c.position), w.point(c.lookAt), w.point(c.up);
  w.number(c.fovDegrees);
  w.optional(c.intrinsics), w.optional(c.extrinsics), w.numbers(c.distortion);
  w.optional(c.thinLens);
  w.text(c.calibrationFile);
  w.optional(c.calibrationSize);
  w.t << c.calibrationDigest << ';';
  w.t << "lights:" << d.lights.size() << ';';
  for (const LightDesc& l : d.lights) {
    w.text(l.kind), w.text(l.group);
    w.t << l.params.canonicalText() << ';';
  }
  w.t << "objects:" << d.objects.size() << ';';
  for (const ObjectDesc& o : d.objects) {
    w.text(o.shape), w.text(o.name);
    w.t << o.geometry.canonicalText() << ';';
    w.material(o);
    w.text(o.materialRef);
    w.optional(o.emission);
    w.number(o.emissionScale);
    w.optional(o.emissionAt);
    w.t << o.emissionFlux << ';';
    if (o.medium) {
      w.text(o.medium->kind);
      w.t << o.medium->params.canonicalText() << ';';
    } else {
      w.t << "-;";
    }
    w.text(o.group);
  }
  w.t << "spectra:" << d.spectra.size() << ';';
  for (const NamedSpectrumDesc& n : d.spectra) {
    w.text(n.name);
    w.t << canonicalText(ParamValue(n.spectrum)) << ';';
  }
  w.t << "materials:" << d.materials.size() << ';';
  for (const NamedMaterialDesc& m : d.materials) {
    w.text(m.id);
    w.material(m.material);
  }
  w.t << "relightable:" << d.relightable;
  return w.t.str();
}

uint64_t sceneStateDigest(const SceneDesc& d) {
  return fnv1a64(sceneStateText(d));
}

} // namespace nx
