#include "core/attacks/attack_registry.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/attacks/add_noise.hpp"
#include "core/attacks/bend_twist.hpp"
#include "core/attacks/crop.hpp"
#include "core/attacks/draco_compress.hpp"
#include "core/attacks/quantize.hpp"
#include "core/attacks/remesh.hpp"
#include "core/attacks/reorder.hpp"
#include "core/attacks/resample.hpp"
#include "core/attacks/round_digits.hpp"
#include "core/attacks/similarity_transform.hpp"
#include "core/attacks/simplify.hpp"
#include "core/mesh/laplacian_smooth.hpp"
#include "core/attacks/split_vertices.hpp"
#include "core/attacks/subdivide.hpp"

namespace meshmark {

namespace {

double number(const AttackParameters& p, const std::string& name) {
  const std::string& text = p.at(name);
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(value))
    throw std::invalid_argument("attack parameter " + name + "=" + text + " is not a number");
  return value;
}

int integer(const AttackParameters& p, const std::string& name) {
  const double v = number(p, name);
  if (v != std::floor(v) || std::abs(v) > 1e9)
    throw std::invalid_argument("attack parameter " + name + "=" + p.at(name) + " is not a whole number");
  return static_cast<int>(v);
}

Eigen::Vector3d vector3(const AttackParameters& p, const std::string& name) {
  std::stringstream in(p.at(name));
  Eigen::Vector3d v;
  char comma;
  if (!(in >> v.x() >> comma >> v.y() >> comma >> v.z()) || !in.eof())
    throw std::invalid_argument("attack parameter " + name + "=" + p.at(name) + " must be three numbers x,y,z");
  return v;
}

Mesh similarity(const Mesh& m, const AttackParameters& p, std::uint64_t seed) {
  if (p.at("angle").empty() && p.at("scale").empty() && p.at("translate").empty())
    return transform_mesh(m, random_similarity(m, seed));
  Similarity T;
  if (!p.at("angle").empty())
    T.R = Eigen::AngleAxisd(number(p, "angle") * M_PI / 180, vector3(p, "axis").normalized()).toRotationMatrix();
  if (!p.at("scale").empty()) T.scale = number(p, "scale");
  if (!p.at("translate").empty()) T.t = vector3(p, "translate");
  if (!(T.scale > 0)) throw std::invalid_argument("the similarity's scale must be positive");
  return transform_mesh(m, T);
}

// Attacks that grow a mesh are bounded: a parameter that would make more faces than this is refused.
constexpr double kMaxAttackFaces = 50e6;

void check_growth(double faces, const std::string& what) {
  if (!(faces <= kMaxAttackFaces))
    throw std::invalid_argument(what + " would make about " +
                                std::to_string(static_cast<long long>(std::min(faces, 1e18))) +
                                " faces, more than the 50,000,000 an attack may make");
}

Mesh subdivision(const Mesh& m, const AttackParameters& p, std::uint64_t) {
  const SubdivisionScheme scheme = parse_subdivision_scheme(p.at("scheme"));
  const int steps = integer(p, "steps");
  check_growth(static_cast<double>(m.F.rows()) * std::pow(scheme == SubdivisionScheme::sqrt3 ? 3.0 : 4.0, steps),
               "subdivision steps=" + p.at("steps"));
  return subdivide(m, scheme, steps);
}

Mesh remeshing(const Mesh& m, const AttackParameters& p, std::uint64_t) {
  const double edge = number(p, "edge");
  const int iterations = integer(p, "iterations");
  if (edge < 0) throw std::invalid_argument("the remeshing edge length must not be negative");
  if (iterations < 0 || iterations > 100) throw std::invalid_argument("remeshing iterations must be in 0..100");
  if (edge > 0) {  // equilateral triangles of side `edge` over the surface
    double area = 0;
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
      const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
      area += 0.5 * (b - a).cross(c - a).norm();
    }
    check_growth(area / (0.433 * edge * edge), "remeshing edge=" + p.at("edge"));
  }
  return remesh(m, {edge, iterations});
}

Mesh simplification(const Mesh& m, const AttackParameters& p, std::uint64_t) {
  if (!p.at("remove").empty() && !p.at("keep").empty())
    throw std::invalid_argument("simplification takes keep or remove, not both (keep=" + p.at("keep") +
                                ", remove=" + p.at("remove") + ")");
  const double keep = !p.at("remove").empty() ? 1.0 - number(p, "remove")
                      : p.at("keep").empty()  ? 0.5
                                              : number(p, "keep");
  return simplify(m, keep);
}

}  // namespace

const std::vector<AttackKind>& attack_kinds() {
  static const std::vector<AttackKind> kinds = {
      {"reorder",
       "random permutation of the vertices and of the faces",
       {},
       [](const Mesh& m, const AttackParameters&, std::uint64_t seed) { return reorder(m, seed); }},
      {"similarity",
       "rotation, uniform scale and translation (random unless given)",
       {{"angle", "", "rotation in degrees about `axis`"},
        {"axis", "0,0,1", "rotation axis x,y,z"},
        {"scale", "", "uniform scale factor"},
        {"translate", "", "translation x,y,z"}},
       similarity},
      {"mirror",
       "mirror image through a plane through the centre, faces rewound (a tool's mirror, the other handedness)",
       {{"axis", "", "x, y or z: the plane normal to that axis (default: a random plane)"}},
       [](const Mesh& m, const AttackParameters& p, std::uint64_t seed) {
         const std::string& axis = p.at("axis");
         if (!axis.empty() && axis != "x" && axis != "y" && axis != "z")
           throw std::invalid_argument("attack parameter axis=" + axis + " must be x, y or z");
         return mirror_mesh(m, axis.empty() ? -1 : axis[0] - 'x', seed);
       }},
      {"noise",
       "uniform noise on every coordinate",
       {{"amplitude", "0.3", "in percent of the reference length"},
        {"relative-to", "bbox", "bbox (bounding-box diagonal) or centroid (mean vertex-centroid distance)"}},
       [](const Mesh& m, const AttackParameters& p, std::uint64_t seed) {
         return add_noise(m, number(p, "amplitude"), parse_noise_reference(p.at("relative-to")), seed);
       }},
      {"smooth",
       "Laplacian smoothing",
       {{"lambda", "0.03", "step towards the neighbours' average"}, {"iterations", "10", "number of steps"}},
       [](const Mesh& m, const AttackParameters& p, std::uint64_t) {
         const int iterations = integer(p, "iterations");
         if (iterations > 100000) throw std::invalid_argument("smoothing iterations must be at most 100000");
         return laplacian_smooth(m, number(p, "lambda"), iterations);
       }},
      {"quantize",
       "coordinates rounded to 2^bits levels over the bounding box",
       {{"bits", "8", "bits per coordinate"}},
       [](const Mesh& m, const AttackParameters& p, std::uint64_t) { return quantize(m, integer(p, "bits")); }},
      {"digits",
       "coordinates re-saved as text with this many significant digits",
       {{"digits", "6", "significant decimal digits"}},
       [](const Mesh& m, const AttackParameters& p, std::uint64_t) { return round_digits(m, integer(p, "digits")); }},
      {"draco",
       "Draco compression (libdraco): positions quantized over the bounding box, points renumbered",
       {{"bits", "14", "position quantization bits (glTF tools use 11 to 16)"}},
       [](const Mesh& m, const AttackParameters& p, std::uint64_t) { return draco_compress(m, integer(p, "bits")); }},
      {"split",
       "vertices stored once per face, as flat-shaded and seam-split exports store them",
       {{"fraction", "0.3", "share of the vertices split"}},
       [](const Mesh& m, const AttackParameters& p, std::uint64_t seed) {
         return split_vertices(m, number(p, "fraction"), seed);
       }},
      {"simplify",
       "quadric edge collapse with optimal placement",
       {{"keep", "", "fraction of the vertices kept (0.5 unless remove is given)"},
        {"remove", "", "or: fraction of the vertices removed"}},
       simplification},
      {"subdivide",
       "subdivision of every face",
       {{"scheme", "loop", "midpoint, loop or sqrt3"}, {"steps", "1", "number of subdivision steps"}},
       subdivision},
      {"crop",
       "removal of part of the surface on one side of a random plane",
       {{"remove", "0.1", "fraction of the surface area removed"}},
       [](const Mesh& m, const AttackParameters& p, std::uint64_t seed) { return crop(m, number(p, "remove"), seed); }},
      {"twist",
       "turn about the longest axis, growing along it (as posing or re-rigging does)",
       {{"degrees", "10", "turn from one end to the other"}},
       [](const Mesh& m, const AttackParameters& p, std::uint64_t) { return twist(m, number(p, "degrees")); }},
      {"bend",
       "the longest axis rolled onto a circular arc, its length kept",
       {{"degrees", "10", "angle the arc spans"}},
       [](const Mesh& m, const AttackParameters& p, std::uint64_t) { return bend(m, number(p, "degrees")); }},
      {"resample",
       "the surface re-extracted from its signed distance field on a grid (as voxel tools rebuild it)",
       {{"spacing", "0.5", "grid step in percent of the bounding-box diagonal (0.1 to 10)"}},
       [](const Mesh& m, const AttackParameters& p, std::uint64_t) {
         return resample_surface(m, number(p, "spacing") / 100);
       }},
      {"remesh",
       "isotropic remeshing: every vertex new",
       {{"edge", "0", "target edge length (0: the input's mean)"}, {"iterations", "5", "remeshing passes"}},
       remeshing},
  };
  return kinds;
}

const AttackKind& attack_kind(const std::string& name) {
  std::string known;
  for (const AttackKind& k : attack_kinds()) {
    if (k.name == name) return k;
    known += (known.empty() ? "" : ", ") + k.name;
  }
  throw std::invalid_argument("unknown attack '" + name + "' (known: " + known + ")");
}

AttackChain parse_attack_chain(const std::string& text) {
  AttackChain chain;
  std::stringstream steps(text);
  std::string step_text;
  while (std::getline(steps, step_text, '|')) {
    std::stringstream words(step_text);
    AttackStep step;
    if (!(words >> step.kind)) throw std::invalid_argument("an empty step in the attack chain '" + text + "'");
    const AttackKind& kind = attack_kind(step.kind);
    std::string word;
    while (words >> word) {
      const auto eq = word.find('=');
      if (eq == std::string::npos) throw std::invalid_argument("attack parameter '" + word + "' must be key=value");
      const std::string key = word.substr(0, eq);
      bool known = false;
      for (const auto& p : kind.parameters) known = known || p.name == key;
      if (!known) throw std::invalid_argument("the " + step.kind + " attack has no parameter '" + key + "'");
      step.parameters[key] = word.substr(eq + 1);
    }
    chain.push_back(std::move(step));
  }
  if (chain.empty()) throw std::invalid_argument("the attack chain is empty");
  return chain;
}

std::string to_string(const AttackChain& chain) {
  std::string out;
  for (const AttackStep& step : chain) {
    if (!out.empty()) out += " | ";
    out += step.kind;
    for (const auto& [k, v] : step.parameters) out += " " + k + "=" + v;
  }
  return out;
}

Mesh apply_attack(const Mesh& mesh, const AttackStep& step, std::uint64_t seed) {
  const AttackKind& kind = attack_kind(step.kind);
  AttackParameters p;
  for (const auto& parameter : kind.parameters) p[parameter.name] = parameter.default_value;
  for (const auto& [k, v] : step.parameters) p[k] = v;
  return kind.apply(mesh, p, seed);
}

Mesh apply_attack_chain(const Mesh& mesh, const AttackChain& chain, std::uint64_t seed) {
  Mesh out = mesh;
  for (std::size_t i = 0; i < chain.size(); ++i) out = apply_attack(out, chain[i], seed * 1000003 + i);
  return out;
}

}  // namespace meshmark
