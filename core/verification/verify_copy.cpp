#include "core/verification/verify_copy.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/attacks/round_digits.hpp"
#include "core/attacks/similarity_transform.hpp"

namespace meshmark {

bool CopyVerification::passed() const {
  for (const CopyReading& r : readings)
    if (!r.passed) return false;
  return true;
}

double CopyVerification::seconds() const {
  double total = 0;
  for (const CopyReading& r : readings) total += r.seconds;
  return total;
}

namespace {

// A control whose every checkpoint is reported as `stage`, its progress over [from, to].
JobControl as_one_stage(const JobControl& parent, const std::string& stage, double from, double to) {
  JobControl part = parent;
  if (parent.report)
    part.report = [report = parent.report, stage, from, to](const std::string&, double progress) {
      report(stage, from + progress * (to - from));
    };
  return part;
}

// The copy with its vertices in the original's order, when its faces are the original's, corner
// for corner, over other vertex numbers (a format that stores triangles, as STL does, numbers them
// by first use when read back); else nullopt. Read in place, it is read as it was written:
// registering it instead would prove nothing the moved reading does not.
std::optional<Mesh> in_original_order(const Mesh& copy, const Mesh& original) {
  if (copy.V.rows() != original.V.rows() || copy.F.rows() != original.F.rows() || copy.F == original.F)
    return std::nullopt;
  std::vector<int> copy_vertex(static_cast<std::size_t>(original.V.rows()), -1);
  std::vector<char> taken(static_cast<std::size_t>(copy.V.rows()), 0);
  for (Eigen::Index f = 0; f < original.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      int& mapped = copy_vertex[static_cast<std::size_t>(original.F(f, k))];
      const int c = copy.F(f, k);
      if (mapped == c) continue;
      if (mapped >= 0 || taken[static_cast<std::size_t>(c)]) return std::nullopt;  // not one vertex for one
      mapped = c;
      taken[static_cast<std::size_t>(c)] = 1;
    }
  Mesh ordered{Vertices(copy.V.rows(), 3), original.F};
  for (std::size_t v = 0; v < copy_vertex.size(); ++v) {
    if (copy_vertex[v] < 0) return std::nullopt;  // a vertex of the original in no face
    ordered.V.row(static_cast<Eigen::Index>(v)) = copy.V.row(copy_vertex[v]);
  }
  return ordered;
}

bool reads_back(const DetectResult& r, const Bits& payload) {
  return r.detected && r.payload && *r.payload == payload && r.ber.value_or(1.0) == 0;
}

// `in_place`: the suspect is the copy as written, not moved since.
CopyReading read_copy(const std::string& name, bool in_place, const PreparedModel& model,
                      const RegistrationTarget& target, const Mesh& suspect, const std::string& key,
                      const Bits& payload, const WatermarkOptions& options, const JobControl* control) {
  const auto t0 = std::chrono::steady_clock::now();
  DetectOptions detect;
  detect.watermark = options;
  detect.payload_bits = static_cast<int>(payload.size());
  detect.expected = payload;
  // Registered as a copy that lost its vertex order would be: the order would name the pose at
  // once and prove nothing of the shape's registration.
  detect.align.try_order = false;
  detect.align.try_mirror = false;        // the moved copy is not mirrored: its reflection would only cost time
  detect.align.sweep_open_scale = false;  // nor cut: its whole surface fixes its scale
  // The copy as written has the original's vertices in their order (unless its format joined some):
  // it is read in place; the attacked one, moved, through registration.
  in_place = in_place && same_connectivity(suspect, model.mesh);
  const DetectResult r = in_place ? detect_in_place(model, suspect, key, detect, control)
                                  : detect_watermark(model, suspect, key, detect, &target, control);
  CopyReading reading;
  reading.name = name;
  reading.registered = !in_place;
  reading.poses = in_place ? 0 : r.alignment_candidates;
  reading.detected = r.detected;
  reading.payload_read = r.payload && *r.payload == payload;
  reading.ber = r.ber.value_or(1.0);
  reading.log10_p_value = r.log10_p_value;
  reading.passed = reads_back(r, payload);
  reading.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return reading;
}

}  // namespace

CopyVerification verify_copy(const PreparedModel& model, const RegistrationTarget& target, Mesh as_written,
                             const std::string& key, const Bits& payload, const WatermarkOptions& options,
                             const VerifyOptions& verify, const JobControl* control) {
  if (std::optional<Mesh> ordered = in_original_order(as_written, model.mesh)) as_written = std::move(*ordered);
  std::optional<JobControl> first, second;
  if (control) {
    first = as_one_stage(*control, "verify", 0.0, 0.5);
    second = as_one_stage(*control, "verify", 0.5, 1.0);
  }
  CopyVerification v;
  v.readings.push_back(
      read_copy("as written", true, model, target, as_written, key, payload, options, first ? &*first : nullptr));
  // The copy is then attacked in place: at millions of vertices each copy of it cost a few
  // hundred megabytes. Digits about its own centre: a model far from the origin would lose its
  // shape, not only its mark, to digits counted from the origin.
  Mesh& attacked = as_written;
  const Eigen::RowVector3d centre = 0.5 * (attacked.V.colwise().minCoeff() + attacked.V.colwise().maxCoeff());
  attacked.V.rowwise() -= centre;
  round_digits_in_place(attacked.V, verify.digits);
  attacked.V.rowwise() += centre;
  const std::string resave = "re-saved with " + std::to_string(verify.digits) + " digits";
  if (verify.registration_proven && !turns_ambiguous(target)) {
    v.readings.push_back(
        read_copy(resave, true, model, target, attacked, key, payload, options, second ? &*second : nullptr));
    return v;
  }
  attacked.V = random_similarity(attacked, verify.seed).apply_to_rows(attacked.V);
  v.readings.push_back(read_copy(resave + " and moved", false, model, target, attacked, key, payload, options,
                                 second ? &*second : nullptr));
  return v;
}

void require_readable(const CopyVerification& verification, const Bits& payload) {
  for (std::size_t k = 0; k < verification.readings.size(); ++k) {
    const CopyReading& r = verification.readings[k];
    if (r.passed) continue;
    char figures[96];
    std::snprintf(figures, sizeof figures, "%.0f of %zu bits wrong, p-value 1e%.1f", r.ber * payload.size(),
                  payload.size(), r.log10_p_value);
    const std::string failed = "the marked copy does not read back " + r.name + " (" + figures +
                               (r.detected ? ", detected but the payload is not the one embedded" : ", not detected") +
                               "), so it was not handed out";
    // Read as written but not once moved: the registration, not the mark's strength, failed. On
    // a nearly symmetric shape the pose found depends on the mark itself, so another payload can
    // register where this one did not (WaterBottle: 6 of 8 keys at 64 bits, and 16 bits where 64
    // failed).
    if (r.registered && verification.readings[0].passed)
      throw CopyUnreadable(failed + "; it reads as written, so registration did not find how it was moved: " +
                           (r.poses > 1 ? "the shape fits about as well in " + std::to_string(r.poses) +
                                              " poses (it is nearly symmetric), and none of them reads"
                                        : "the shape is nearly symmetric or too featureless to register") +
                           ", so a turned copy could not be traced; on a shape this symmetric the pose found "
                           "depends on the mark, so another payload (or a shorter one) may read back");
    throw CopyUnreadable(failed + "; try a shorter payload, a higher strength or the other basis");
  }
}

}  // namespace meshmark
