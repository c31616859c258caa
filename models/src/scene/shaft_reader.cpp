// Reading one [[shaft]] table (sections, material, gears at stations) and placing the shafts'
// nodes once the bearings' stations are known.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scene/element_names.hpp"
#include "scene/section_readers.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {
namespace {

// Plausibility bounds (documented in docs/scene-format.md).
constexpr double kMaxShaftDiameter = 5.0;  // m
constexpr double kMaxShaftLength = 50.0;   // m, per section
constexpr int kMaxElementsPerSection = 1000;
constexpr int kMaxShaftElements = 5000;  // per shaft: 6·5001 DOFs, dense modes of ~1 GB
// Stations closer than this fraction of the shaft length share a node (round-off of typed
// positions; a real gap of 1e-9 L is far below any element length).
constexpr double kMergeTol = 1e-9;

// One section: length, diameters, element count or length.
ShaftSectionDef ReadSection(const Fields& shaft, const toml::table& t, std::size_t k,
                            std::optional<double> max_element_length) {
  const Fields f(shaft.context(), t, shaft.Key("sections") + "[" + std::to_string(k) + "]");
  f.CheckKnown({"length", "outer_diameter", "inner_diameter", "elements"});
  ShaftSectionDef s;
  const Number length = f.ReqNumber("length", "section length in m, > 0");
  f.Metres("length", length, kMaxShaftLength);
  s.length = length.value;
  const Number d_o = f.ReqNumber("outer_diameter", "outer diameter in m, > 0");
  f.Metres("outer_diameter", d_o, kMaxShaftDiameter);
  s.section.outer_diameter = d_o.value;
  if (auto d_i = f.OptNumber("inner_diameter")) {
    f.NonNegative("inner_diameter", *d_i);
    if (d_i->value >= d_o.value) {
      f.Fail("inner_diameter", "must be less than outer_diameter = " + FormatNumber(d_o.value) +
                                   " m (a hollow section), got " + FormatNumber(d_i->value));
    }
    s.section.inner_diameter = d_i->value;
  }
  if (auto n = f.OptInt("elements", 1, kMaxElementsPerSection)) {
    s.element_length = s.length / *n;
  } else if (max_element_length) {
    s.element_length = *max_element_length;
  } else {
    f.Missing("elements",
              "number of beam elements of the section (or max_element_length of the shaft)");
  }
  return s;
}

// E, G (or ν) and ρ of the shaft.
ShaftMaterial ReadMaterial(const Fields& f) {
  ShaftMaterial m;
  m.youngs_modulus = f.ReqPositive("youngs_modulus", "Young's modulus E in Pa, > 0");
  m.density = f.ReqPositive("density", "density in kg/m^3, > 0");
  const auto nu = f.OptNumber("poisson_ratio");
  const auto g = f.OptPositive("shear_modulus");
  if (nu && g) f.Fail("shear_modulus", "give shear_modulus or poisson_ratio, not both");
  if (!nu && !g) f.Missing("poisson_ratio", "poisson_ratio (or shear_modulus in Pa)");
  if (nu) {
    if (!(nu->value > -1.0 && nu->value <= 0.5)) {
      f.Fail("poisson_ratio", "must be in (-1, 0.5], got " + FormatNumber(nu->value));
    }
    m.shear_modulus = m.youngs_modulus / (2.0 * (1.0 + nu->value));
  } else {
    m.shear_modulus = *g;
    const double implied = m.PoissonRatio();
    if (!(implied > -1.0 && implied <= 0.5)) {
      f.Fail("shear_modulus",
             "gives Poisson's ratio E/(2G) - 1 = " + FormatNumber(implied) + " outside (-1, 0.5]");
    }
  }
  return m;
}

// A length for a message: 12 significant digits (a sum of section lengths such as 0.1 + 0.2
// prints as 0.3, not 0.30000000000000004).
std::string FormatLength(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.12g", v);
  return buffer;
}

}  // namespace

double ReadStation(const Fields& f, std::string_view key, const ShaftDef& shaft) {
  const Number s =
      f.ReqNumber(key, "axial position on shaft '" + shaft.name + "' in m from its start, in [0, " +
                           FormatNumber(shaft.length()) + "]");
  if (!(s.value >= 0.0 && s.value <= shaft.length() * (1.0 + kMergeTol))) {
    f.context().Fail(s.node, f.Key(key),
                     "station " + FormatNumber(s.value) + " m is outside shaft '" + shaft.name +
                         "' (length " + FormatLength(shaft.length()) + " m)");
  }
  return std::min(s.value, shaft.length());
}

ShaftDef ReadShaft(const ErrorContext& ctx, const toml::table& t, std::size_t index,
                   const Scene& scene) {
  ShaftDef shaft;
  CheckElementKeys(ctx, t, "shaft", index,
                   {"name", "sections", "youngs_modulus", "shear_modulus", "poisson_ratio",
                    "density", "max_element_length", "gears"});
  shaft.name = ReadElementName(ctx, t, "shaft", index);
  const Fields f(ctx, t, "shaft." + shaft.name);
  for (const GearDef& g : scene.gears) {
    if (g.name == shaft.name) f.Fail("name", "'" + shaft.name + "' is already a gear's name");
  }
  shaft.material = ReadMaterial(f);
  std::optional<double> max_element_length;
  if (auto h = f.OptNumber("max_element_length")) {
    f.Metres("max_element_length", *h, kMaxShaftLength);
    max_element_length = h->value;
  }
  const toml::node* sections = f.Find("sections");
  if (sections == nullptr) {
    f.Missing("sections", "an array of sections {length, outer_diameter, elements}");
  }
  const toml::array* a = sections->as_array();
  if (a == nullptr || a->empty()) {
    f.Fail("sections", "must be a non-empty array of tables, got " + Describe(*sections));
  }
  double elements = 0.0;
  for (std::size_t k = 0; k < a->size(); ++k) {
    const toml::table* st = a->get(k)->as_table();
    if (st == nullptr) {
      ctx.Fail(a->get(k), f.Key("sections") + "[" + std::to_string(k) + "]",
               "must be a table {length, outer_diameter, ...}, got " + Describe(*a->get(k)));
    }
    shaft.sections.push_back(ReadSection(f, *st, k, max_element_length));
    elements += std::ceil(shaft.sections.back().length / shaft.sections.back().element_length);
  }
  if (elements > kMaxShaftElements) {
    f.Fail(max_element_length ? "max_element_length" : "sections",
           "gives " + FormatNumber(elements) + " elements, more than " +
               std::to_string(kMaxShaftElements) + " per shaft (" +
               FormatNumber(6.0 * (elements + 1)) + " DOFs)");
  }

  if (const toml::node* gears = f.Find("gears")) {
    const toml::array* ga = gears->as_array();
    if (ga == nullptr)
      f.Fail("gears", "must be an array of {gear, station}, got " + Describe(*gears));
    for (std::size_t k = 0; k < ga->size(); ++k) {
      const toml::table* gt = ga->get(k)->as_table();
      const std::string key = f.Key("gears") + "[" + std::to_string(k) + "]";
      if (gt == nullptr) {
        ctx.Fail(ga->get(k), key, "must be a table {gear, station}, got " + Describe(*ga->get(k)));
      }
      const Fields gf(ctx, *gt, key);
      gf.CheckKnown({"gear", "station"});
      ShaftGearDef g;
      g.gear = ReadGearName(gf, "gear", "name of the [[gear]] on this shaft", scene);
      for (const ShaftGearDef& other : shaft.gears) {
        if (other.gear == g.gear) gf.Fail("gear", "'" + g.gear + "' is already on this shaft");
      }
      if (const auto on = scene.FindGearShaft(g.gear)) {
        gf.Fail("gear", "'" + g.gear + "' is already on shaft '" + on->first->name +
                            "' (a gear sits on one shaft)");
      }
      g.station = ReadStation(gf, "station", shaft);
      shaft.gears.push_back(g);
    }
  }
  return shaft;
}

void PlaceShaftNodes(Scene* scene) {
  for (ShaftDef& shaft : scene->shafts) {
    const double length = shaft.length();
    // Key points: section ends and every station of a gear or bearing.
    std::vector<double> keys{0.0};
    double end = 0.0;
    for (const ShaftSectionDef& s : shaft.sections) keys.push_back(end += s.length);
    for (const ShaftGearDef& g : shaft.gears) keys.push_back(g.station);
    for (const BearingDef& b : scene->bearings) {
      if (b.body == shaft.name) keys.push_back(*b.station);
      if (b.other == shaft.name) keys.push_back(*b.other_station);
    }
    std::sort(keys.begin(), keys.end());
    std::vector<double> unique;
    for (const double k : keys) {
      if (unique.empty() || k - unique.back() > kMergeTol * length) unique.push_back(k);
    }
    unique.back() = length;
    // Between key points: equal elements no longer than the section's element length.
    shaft.nodes = {0.0};
    for (std::size_t i = 1; i < unique.size(); ++i) {
      const double a = unique[i - 1], b = unique[i];
      const double h = shaft.sections[shaft.SectionAt(a, b)].element_length;
      const int n = std::max(1, static_cast<int>(std::ceil((b - a) / h * (1.0 - kMergeTol))));
      for (int j = 1; j < n; ++j) shaft.nodes.push_back(a + (b - a) * j / n);
      shaft.nodes.push_back(b);
    }
  }
}

}  // namespace geardyn::internal
