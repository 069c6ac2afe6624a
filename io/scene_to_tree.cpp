#include "io/scene_to_tree.h"

#include <charconv>
#include <filesystem>

#include "core/error.h"
#include "core/number_text.h"
#include "core/params/array_values.h"
#include "io/scene_tree_text.h"

namespace nx {
namespace {

using Dict = SceneTree::Dict;
using List = SceneTree::List;
using Array = SceneTree::Array;

std::string exact(double v) {
  return shortestText(v);
}

SceneTree numbers(std::initializer_list<double> v) {
  List l;
  for (double x : v) l.emplace_back(x);
  return l;
}

SceneTree numbers(const std::vector<double>& v) {
  List l;
  for (double x : v) l.emplace_back(x);
  return l;
}

class TreeOfDesc {
public:
  explicit TreeOfDesc(std::string base) : base_(std::move(base)) {}

  SceneTree scene(const SceneDesc& d) {
    Dict root{{"settings", settings(d.settings)}, {"camera", camera(d.camera)}};
    if (!d.spectra.empty()) {
      Dict spectra;
      for (const NamedSpectrumDesc& n : d.spectra)
        spectra.emplace_back(n.name, spectrum(n.spectrum, "spectra['" + n.name + "']"));
      root.emplace_back("spectra", std::move(spectra));
    }
    if (!d.materials.empty()) {
      List materials;
      for (const NamedMaterialDesc& m : d.materials) {
        Dict item{{"id", m.id}, {"type", m.material.material}};
        parameters(m.material.params, "materials['" + m.id + "']", item);
        materials.emplace_back(std::move(item));
      }
      root.emplace_back("materials", std::move(materials));
    }
    List objects, lights;
    for (size_t i = 0; i < d.objects.size(); ++i)
      objects.push_back(object(d.objects[i], "objects[" + std::to_string(i) + "]"));
    for (size_t i = 0; i < d.lights.size(); ++i)
      lights.push_back(light(d.lights[i], "lights[" + std::to_string(i) + "]"));
    root.emplace_back("objects", std::move(objects));
    root.emplace_back("lights", std::move(lights));
    return root;
  }

  SceneTree light(const LightDesc& l, const std::string& where) {
    Dict item{{"type", l.kind}};
    if (!l.group.empty()) item.emplace_back("group", l.group);
    parameters(l.params, where, item);
    return item;
  }

  SceneTree object(const ObjectDesc& o, const std::string& where) {
    Dict d{{"shape", o.shape}};
    if (!o.name.empty()) d.emplace_back("name", o.name);
    if (!o.group.empty()) d.emplace_back("group", o.group);
    parameters(o.geometry, where, d);
    d.emplace_back("material", o.material);
    parameters(o.params, where, d);
    if (o.emission) {
      d.emplace_back("emission", spectrum(*o.emission, where + ".emission"));
      if (o.emissionScale != 1) d.emplace_back("emission_scale", o.emissionScale);
      if (o.emissionAt) d.emplace_back("emission_at", *o.emissionAt);
      if (o.emissionFlux) d.emplace_back("emission_quantity", std::string("flux"));
    }
    if (o.medium) {
      Dict m{{"type", o.medium->kind}};
      parameters(o.medium->params, where + ".medium", m);
      d.emplace_back("medium", std::move(m));
    }
    return d;
  }

private:
  // A file name as the text will be read from `base_`.
  std::string file(const std::string& path) const {
    if (base_.empty() || std::filesystem::path(path).is_absolute()) return path;
    const std::filesystem::path rel =
        std::filesystem::path(path).lexically_relative(std::filesystem::path(base_));
    return rel.empty() ? path : rel.string();
  }

  [[noreturn]] static void noText(const std::string& where, const std::string& what) {
    throw Error(where + ": expected a value with a scene-text form, found " + what +
                " given as numbers (write it to a file and name the file)");
  }

  SceneTree settings(const SettingsDesc& s) {
    Dict d{{"xres", static_cast<double>(s.width)},
           {"yres", static_cast<double>(s.height)},
           {"mode", std::string(renderModeName(s.mode))}};
    if (!s.outputPath.empty()) d.emplace_back("path", s.outputPath);
    d.emplace_back("depth", static_cast<double>(s.depth));
    d.emplace_back("sampl", static_cast<double>(s.samples));
    d.emplace_back("seed", static_cast<double>(s.seed));
    if (s.illuminant) d.emplace_back("illum", spectrum(*s.illuminant, "settings.illum"));
    if (s.background) {
      d.emplace_back("background", spectrum(*s.background, "settings.background"));
      if (!s.backgroundGroup.empty()) d.emplace_back("background_group", s.backgroundGroup);
    }
    if (!s.sensorFile.empty()) {
      Dict sensor{{"csv", file(s.sensorFile)}};
      if (!s.sensorCentres.empty()) sensor.emplace_back("centres", s.sensorCentres);
      d.emplace_back("sensor", std::move(sensor));
    } else if (s.bands.uniformBoxes()) {
      d.emplace_back("bands", s.bands.toString());
    } else {
      const std::string t = s.bands.toString();
      if (t.rfind("boxes:", 0) == 0) {
        d.emplace_back("sensor", Dict{{"boxes", t.substr(6)}});
      } else if (t.rfind("gaussian:", 0) == 0) {
        const size_t at = t.find('@');
        d.emplace_back("sensor",
                       Dict{{"gaussian", t.substr(9, at - 9)}, {"fwhm", t.substr(at + 1)}});
      } else {
        noText("settings.sensor", "a measured sensor");
      }
    }
    return d;
  }

  SceneTree camera(const CameraDesc& c) {
    Dict d;
    d.reserve(8); // (also keeps GCC 12's -Warray-bounds from a false alarm on the empty vector)
    if (c.extrinsics) {
      d.emplace_back("extrinsics",
                     numbers(std::vector<double>(c.extrinsics->begin(), c.extrinsics->end())));
    } else {
      d.emplace_back("position", numbers({c.position.x, c.position.y, c.position.z}));
      d.emplace_back("look_at", numbers({c.lookAt.x, c.lookAt.y, c.lookAt.z}));
      d.emplace_back("up", numbers({c.up.x, c.up.y, c.up.z}));
    }
    if (c.intrinsics)
      d.emplace_back("intrinsics",
                     numbers(std::vector<double>(c.intrinsics->begin(), c.intrinsics->end())));
    else
      d.emplace_back("fov", c.fovDegrees);
    bool distorted = false;
    for (double k : c.distortion) distorted = distorted || k != 0;
    if (distorted)
      d.emplace_back("distortion",
                     numbers(std::vector<double>(c.distortion.begin(), c.distortion.end())));
    if (c.thinLens) d.emplace_back("thin_lens", numbers({(*c.thinLens)[0], (*c.thinLens)[1]}));
    return d;
  }

  void parameters(const ParameterSet& p, const std::string& where, Dict& out) {
    for (const Parameter& x : p.items())
      out.emplace_back(x.name, value(x.value, where + "." + x.name));
  }

  SceneTree value(const ParamValue& v, const std::string& where) {
    if (const double* x = std::get_if<double>(&v)) return *x;
    if (const auto* c = std::get_if<std::array<double, 4>>(&v))
      return numbers({(*c)[0], (*c)[1], (*c)[2], (*c)[3]});
    if (const auto* s = std::get_if<SpectrumDesc>(&v)) return spectrum(*s, where);
    if (const auto* i = std::get_if<IorDesc>(&v)) return ior(*i);
    if (const auto* f = std::get_if<FluorescenceDesc>(&v)) return fluorescence(*f, where);
    if (const auto* c = std::get_if<CoatingDesc>(&v))
      return Dict{{"thickness", c->thicknessNm}, {"ior", ior(c->ior)}};
    if (const auto* s = std::get_if<std::string>(&v))
      return where.ends_with(".file") ? file(*s) : *s;
    if (const auto* p = std::get_if<Vec3d>(&v)) return numbers({p->x, p->y, p->z});
    if (const auto* a = std::get_if<AffineDesc>(&v)) {
      List rows;
      for (int i = 0; i < 3; ++i)
        rows.push_back(numbers({a->m[i][0], a->m[i][1], a->m[i][2],
                                i == 0   ? a->t.x
                                : i == 1 ? a->t.y
                                         : a->t.z}));
      return rows;
    }
    const ArrayDesc& a = std::get<ArrayDesc>(v);
    Array out;
    out.rows = a.rows();
    out.columns = a.columns;
    if (a.reals) {
      out.kind = Array::Kind::Float32;
      out.values.assign(a.reals->begin(), a.reals->end());
    } else {
      out.kind = Array::Kind::Integer;
      out.values.assign(a.indices->begin(), a.indices->end());
    }
    return out;
  }

  SceneTree spectrum(const SpectrumDesc& s, const std::string& where) {
    Dict d;
    switch (s.kind) {
    case SpectrumDesc::Kind::Number:
      d.emplace_back("value", s.number);
      break;
    case SpectrumDesc::Kind::Name:
      d.emplace_back("value", s.name);
      break;
    case SpectrumDesc::Kind::Pairs:
      d.emplace_back("value", List{numbers(s.nm), numbers(s.value)});
      break;
    case SpectrumDesc::Kind::CsvFile:
      d.emplace_back("csv", file(s.path));
      if (!s.column.empty()) d.emplace_back("column", s.column);
      break;
    case SpectrumDesc::Kind::Texture:
      if (s.texels) noText(where, "a texture");
      d.emplace_back("texture", s.texture == "colorchecker" ? s.texture : file(s.texture));
      break;
    }
    if (s.extrapolate != SpectrumDesc::Extrapolation::Unset)
      d.emplace_back(
          "extrapolate",
          std::string(s.extrapolate == SpectrumDesc::Extrapolation::Hold ? "hold" : "zero"));
    if (s.clampNegative) d.emplace_back("negative", std::string("clamp"));
    if (d.size() == 1 && d[0].first == "value") return d[0].second;
    return d;
  }

  static SceneTree ior(const IorDesc& i) {
    switch (i.kind) {
    case IorDesc::Kind::Number:
      return i.value;
    case IorDesc::Kind::Named:
      return i.name;
    case IorDesc::Kind::Cauchy:
    case IorDesc::Kind::Sellmeier: {
      std::string t = i.kind == IorDesc::Kind::Cauchy ? "cauchy:" : "sellmeier:";
      for (size_t k = 0; k < i.coefficients.size(); ++k)
        t += (k ? ", " : " ") + exact(i.coefficients[k]);
      return t;
    }
    }
    return {};
  }

  SceneTree fluorescence(const FluorescenceDesc& f, const std::string& where) {
    Dict d;
    if (f.matrix) noText(where, "a measured matrix");
    if (f.concentration) noText(where, "a concentration map");
    if (f.absorptionName) d.emplace_back("absorption", *f.absorptionName);
    if (f.absorptionNm) d.emplace_back("absorption", *f.absorptionNm);
    if (f.stokesNm) d.emplace_back("stokes", *f.stokesNm);
    if (f.widthNm) d.emplace_back("width", *f.widthNm);
    if (f.skew) d.emplace_back("skew", *f.skew);
    if (f.quantumYield) d.emplace_back("yield", *f.quantumYield);
    if (f.peakAbsorptance) d.emplace_back("peak", *f.peakAbsorptance);
    if (f.spectra) {
      d.emplace_back("absorptance", spectrum(f.spectra->absorptance, where));
      d.emplace_back("emission", spectrum(f.spectra->emission, where));
    }
    if (f.matrixCsv) d.emplace_back("matrix", file(*f.matrixCsv));
    if (f.concentrationCsv) d.emplace_back("concentration", file(*f.concentrationCsv));
    if (f.eem) {
      const EemDesc& e = *f.eem;
      const EemLayout& l = e.layout;
      Dict x{{"file", file(e.file)},
             {"layout", std::string(l.emissionRows ? "emission_rows" : "excitation_rows")},
             {"units", std::string(l.energyUnits ? "energy" : "photons")},
             {"rayleigh_width", l.rayleighWidthNm},
             {"second_order", std::string(l.secondOrder ? "true" : "false")},
             {"emission_shape", std::string(l.meanEmissionShape ? "mean" : "rows")}};
      if (l.ramanShiftCm != 0) {
        x.emplace_back("raman_shift", l.ramanShiftCm);
        x.emplace_back("raman_width", l.ramanWidthNm);
      }
      d.emplace_back("eem", std::move(x));
      if (e.absorptance) d.emplace_back("absorptance", spectrum(*e.absorptance, where));
      if (!e.referenceFile.empty()) {
        Dict r{{"file", file(e.referenceFile)},
               {"yield", e.referenceYield},
               {"absorptance", e.referenceAbsorptance}};
        if (e.referenceExcitationNm) r.emplace_back("excitation", *e.referenceExcitationNm);
        d.emplace_back("reference", std::move(r));
      }
    }
    return d;
  }

  std::string base_;
};

} // namespace

SceneTree objectToTree(const ObjectDesc& o, const std::string& where) {
  return TreeOfDesc("").object(o, where);
}

SceneTree lightToTree(const LightDesc& l, const std::string& where) {
  return TreeOfDesc("").light(l, where);
}

SceneTree sceneToTree(const SceneDesc& d, const std::string& base) {
  return TreeOfDesc(base).scene(d);
}

std::string sceneToText(const SceneDesc& d, const std::string& base) {
  return sceneTreeText(sceneToTree(d, base)).text;
}

} // namespace nx
