#include "core/watermark/watermark.hpp"

#include "core/watermark/combine_evidence.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "core/mesh/coordinate_precision.hpp"
#include "core/watermark/paper_scheme.hpp"
#include "core/watermark/detect_stages.hpp"
#include "core/watermark/nuisance_fields.hpp"
#include "core/watermark/read_suspect.hpp"
#include "core/watermark/spread_scheme.hpp"

namespace meshmark {

double log10_false_alarm_bound(double z, int bits) {
  if (z <= 0) return 0.0;
  return std::min(0.0, (bits * std::log(2.0) - 0.5 * z * z) / std::log(10.0));
}

double false_alarm_bound(double z, int bits) { return std::pow(10.0, log10_false_alarm_bound(z, bits)); }

namespace {

void check_key(const std::string& key) {
  if (key.empty()) throw std::invalid_argument("the key is empty; give the owner's secret key");
}

// The paper's scheme moves grid samples along the sphere's wavelets; it has no meaning on bumps.
void check_scheme(const PreparedModel& model, Scheme scheme) {
  if (scheme == Scheme::paper && !model.spherical())
    throw std::invalid_argument("the paper's scheme needs the spherical basis, but this mesh is marked with " +
                                to_string(model.basis) + " (" + model.basis_reason + "); use the spread scheme");
}

}  // namespace

EmbedResult embed_watermark(const PreparedModel& model, const std::string& key, const Bits& payload,
                            const WatermarkOptions& options, const JobControl* control) {
  check_key(key);
  check_scheme(model, options.scheme);
  if (payload.empty()) throw std::invalid_argument("the payload is empty");
  if (!strength_in_range(options.strength_percent))
    throw std::invalid_argument("the strength must be in " + strength_range_text());
  switch (options.scheme) {
    case Scheme::spread:
      return embed_spread(model, key, payload, options, control);
    case Scheme::paper:
      return embed_paper(model, key, payload, options, control);
  }
  return {};
}

namespace {

// Bonferroni over the registrations a detection may read: every p-value times their number.
void charge_for_alignments(DetectResult& r, int candidates) {
  const double factor = static_cast<double>(candidates), log_factor = std::log10(factor);
  r.blind_log10_p_value = std::min(0.0, r.blind_log10_p_value + log_factor);
  if (r.expected_p_value) r.expected_p_value = std::min(1.0, *r.expected_p_value * factor);
  if (r.expected_log10_p_value) r.expected_log10_p_value = std::min(0.0, *r.expected_log10_p_value + log_factor);
  for (double& c : r.candidate_log10_p) c = std::min(0.0, c + log_factor);
}

// The scheme's estimate, choice and score of a measured offset.
DetectResult read_offset(const PreparedModel& model, const Displacement& measured, const std::string& key,
                         const DetectOptions& options, const JobControl* control) {
  checkpoint(control, detect_stage::estimate, 0.6);
  DetectResult r = options.watermark.scheme == Scheme::spread ? detect_spread(model, measured, key, options, control)
                                                              : detect_paper(model, measured, key, options, control);
  r.samples = static_cast<std::size_t>(measured.t.size());
  r.missing = measured.missing;
  return r;
}

// The suspect's offset at the original's vertices. The paper's carriers move vertices off the
// normal: it keeps the whole 3-D offsets beside the projection. The spread scheme reads a copy
// whose vertices are the original's, rigidly placed, at those vertices (exact, and no surface
// to sample): paired by their order when it kept it (registered by it, or by its shape where
// the order was not tried, as the embed's self-check does), else as mutual nearest vertices
// (which a mark on a dense mesh defeats: it moves vertices further than half an edge); a bent
// copy's offsets would hold the bend, and the rest have no partners.
Displacement read_measurement(const PreparedModel& model, const Mesh& suspect, const Mesh& aligned,
                              const Alignment& alignment, const RegistrationTarget& target,
                              const DetectOptions& options, const JobControl* control) {
  const int threads = threads_of(control);
  const bool paper = options.watermark.scheme == Scheme::paper;
  const bool rigid_or_paper = paper || alignment.deformation.identity();
  std::optional<VertexOffsets> offsets;
  if (alignment.by_order() || (rigid_or_paper && same_connectivity(suspect, model.mesh)))
    offsets = offsets_in_order(target.mesh.V, aligned.V, suspect.V, VertexMatchOptions{}.tolerance * model.diagonal);
  if (!offsets && !alignment.by_order() && rigid_or_paper)
    offsets = corresponding_offsets(target.mesh, aligned, suspect.V, median_edge_length(target.mesh),
                                    VertexOffsetOptions{.threads = threads});
  if (!paper && offsets) return read_at_vertices(model, *offsets, options.displacement, threads);
  Displacement measured = read_suspect(model, target, aligned, options.displacement, threads);
  if (paper) measured.vertex_offsets = std::move(offsets);
  return measured;
}

// One registration of the suspect and its offset at the original's vertices.
struct MeasuredAlignment {
  Alignment alignment;
  Displacement displacement;
};

MeasuredAlignment measure_alignment(const PreparedModel& model, const Mesh& suspect, const Alignment& alignment,
                                    const RegistrationTarget& target, const DetectOptions& options,
                                    const JobControl* control) {
  // A mirrored copy is read as registered: reflected, so that its vertices refit by a proper
  // similarity and its faces face out once placed.
  const std::optional<Mesh> reflected =
      alignment.mirrored ? std::optional<Mesh>(as_registered(suspect, alignment)) : std::nullopt;
  const Mesh& registered = reflected ? *reflected : suspect;
  const Mesh aligned{alignment.apply_to_rows(suspect.V), registered.F};
  checkpoint(control, detect_stage::read, 0.4);
  return {alignment, read_measurement(model, registered, aligned, alignment, target, options, control)};
}

// The estimate lists the scheme of `options` reads with (the paper's vector reading has its own).
std::vector<const std::vector<double>*> scheme_estimates(const DetectOptions& options) {
  const EstimateOptions& e = options.estimate;
  if (options.watermark.scheme == Scheme::spread) return {&e.spread_regularizations};
  return {&e.paper_regularizations, &e.paper_vector_regularizations};
}

// The matched filter alone, its bound charged for every estimate `options` tries. When it decides,
// the whole detector would have too: its union bound covers this estimate at the same charge.
DetectOptions matched_filter_only(const DetectOptions& options) {
  DetectOptions quick = options;
  EstimateOptions& estimate = quick.estimate;
  for (const std::vector<double>* list : scheme_estimates(options))
    estimate.charged_estimates = std::max(estimate.charged_estimates, list->size());
  estimate.spread_regularizations = estimate.paper_regularizations = estimate.paper_vector_regularizations = {0.0};
  return quick;
}

bool tries_solves(const DetectOptions& options) {
  for (const std::vector<double>* list : scheme_estimates(options))
    for (double relative : *list)
      if (relative != 0) return true;
  return false;
}

// Decades of p-value a matched-filter reading must pass the threshold by to decide alone: callers
// charge a detection again for the readings they try (payload lengths, groups of copies), and a
// reading that decides here must still detect after a million of them.
constexpr double kMatchedFilterMarginDecades = 6;

// A reading that needs no other estimate: detected with that margin, and its decode's checksum
// matching and the payload expected (the expected payload's own test may detect where the decode
// is wrong).
bool decided(const DetectResult& r, const DetectOptions& options) {
  return r.detected && r.log10_p_value <= std::log10(options.false_alarm) - kMatchedFilterMarginDecades &&
         r.checksum_ok && (!options.expected || r.decoded == *options.expected);
}

// Reads with the matched filter first and with every estimate only when that does not decide:
// the regularized solves are most of a reading's time, and a copy in light noise needs none.
// `read(options, control)` reads with the given estimates, its checkpoints over [0.4, 1]; they are
// reported over [from, 1], the first reading's over its first half when there are two.
template <typename Read>
DetectResult read_matched_first(const DetectOptions& options, double from, const JobControl* control, Read&& read) {
  const bool two = options.estimate.matched_first && tries_solves(options);
  const double middle = two ? (from + 1) / 2 : 1.0;
  std::optional<JobControl> first, second;
  if (control) first = rescaled(*control, 0.4, 1.0, from, middle), second = rescaled(*control, 0.4, 1.0, middle, 1.0);
  if (!two) return read(options, first ? &*first : nullptr);
  DetectResult quick = read(matched_filter_only(options), first ? &*first : nullptr);
  if (decided(quick, options)) return quick;
  DetectResult full = read(options, second ? &*second : nullptr);
  for (const auto& [stage, seconds] : quick.seconds) full.seconds[stage] += seconds;
  return full;
}

// Every measured registration read with `options`' estimates (checkpoints over [0.4, 1]); the
// strongest counts, its p-value charged for every candidate there could have been.
DetectResult strongest_reading(const PreparedModel& model, const std::vector<MeasuredAlignment>& measured,
                               const std::string& key, const DetectOptions& options, const JobControl* control) {
  const double n = static_cast<double>(measured.size());
  DetectResult strongest;
  std::map<std::string, double> spent;
  for (std::size_t a = 0; a < measured.size(); ++a) {
    std::optional<JobControl> part;
    if (control) part = rescaled(*control, 0.4, 1.0, 0.4 + 0.6 * a / n, 0.4 + 0.6 * (a + 1) / n);
    DetectResult r = read_offset(model, measured[a].displacement, key, options, part ? &*part : nullptr);
    r.alignment = measured[a].alignment;
    for (const auto& [stage, seconds] : r.seconds) spent[stage] += seconds;
    const bool better =
        a == 0 || (r.checksum_ok != strongest.checksum_ok ? r.checksum_ok
                                                          : r.blind_log10_p_value < strongest.blind_log10_p_value);
    if (better) strongest = std::move(r);
  }
  strongest.seconds = spent;
  // Which poses are candidates follows from the shapes alone, not from the key: charging for the
  // candidates read is a Bonferroni bound (never below 2, what a suspect's own pose may add).
  charge_for_alignments(strongest, std::max<int>(2, static_cast<int>(measured.size())));
  combine_evidence(strongest, options);
  return strongest;
}

// What every detection checks of its arguments.
void check_detect_arguments(const PreparedModel& model, const Mesh& suspect, const std::string& key,
                            const DetectOptions& options) {
  check_key(key);
  check_scheme(model, options.watermark.scheme);
  if (options.payload_bits <= 0 || options.payload_bits % 4 != 0)
    throw std::invalid_argument("the payload length must be a positive multiple of 4 bits");
  if (options.expected && static_cast<int>(options.expected->size()) != options.payload_bits)
    throw std::invalid_argument("the expected payload has " + std::to_string(options.expected->size()) + " bits but " +
                                std::to_string(options.payload_bits) + " were asked for");
  if (suspect.F.rows() == 0) throw std::invalid_argument("the suspect mesh has no faces");
  if (auto lost = coordinate_precision_problem(suspect.V)) throw std::invalid_argument("the suspect: " + *lost);
  for (const Bits& c : options.candidates)
    if (static_cast<int>(c.size()) != options.payload_bits)
      throw std::invalid_argument("a candidate payload has " + std::to_string(c.size()) + " bits, not " +
                                  std::to_string(options.payload_bits));
}

// The bit error rate against the expected payload, when there is one.
void score_against_expected(DetectResult& result, const DetectOptions& options) {
  if (!options.expected) return;
  std::size_t errors = 0;
  for (std::size_t i = 0; i < options.expected->size(); ++i) errors += (*options.expected)[i] != result.decoded[i];
  result.ber = static_cast<double>(errors) / static_cast<double>(options.expected->size());
}

}  // namespace

DetectResult detect_watermark(const PreparedModel& model, const Mesh& suspect, const std::string& key,
                              const DetectOptions& options, const RegistrationTarget* target,
                              const JobControl* control) {
  check_detect_arguments(model, suspect, key, options);
  checkpoint(control, detect_stage::align, 0.0);
  auto t0 = std::chrono::steady_clock::now();
  std::optional<RegistrationTarget> own;
  if (!target) target = &own.emplace(model.outward_mesh());
  const std::vector<Alignment> alignments = align_candidates(suspect, *target, options.align, control);
  const double align_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Each candidate registration is measured once, then read (strongest_reading).
  const double n = static_cast<double>(alignments.size());
  std::vector<MeasuredAlignment> measured;
  t0 = std::chrono::steady_clock::now();
  for (std::size_t a = 0; a < alignments.size(); ++a) {
    // Each measurement takes its share of [0.4, 0.5], each reading its share of the readings' range.
    std::optional<JobControl> part;
    if (control) part = rescaled(*control, 0.4, 1.0, 0.4 + 0.1 * a / n, 0.4 + 0.1 * (a + 1) / n);
    measured.push_back(measure_alignment(model, suspect, alignments[a], *target, options, part ? &*part : nullptr));
  }
  const double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  DetectResult result = read_matched_first(options, 0.5, control, [&](const DetectOptions& o, const JobControl* c) {
    return strongest_reading(model, measured, key, o, c);
  });
  result.seconds[detect_stage::align] = align_seconds;
  result.seconds[detect_stage::read] = read_seconds;
  result.alignment_candidates = alignments.size();
  score_against_expected(result, options);
  return result;
}

DetectResult detect_in_place(const PreparedModel& model, const Mesh& copy, const std::string& key,
                             const DetectOptions& options, const JobControl* control) {
  check_detect_arguments(model, copy, key, options);
  if (copy.V.rows() != model.mesh.V.rows())
    throw std::invalid_argument("the copy has " + std::to_string(copy.V.rows()) + " vertices, the original " +
                                std::to_string(model.mesh.V.rows()) + ": it cannot be read in place");
  const auto t0 = std::chrono::steady_clock::now();
  checkpoint(control, detect_stage::read, 0.4);
  Displacement measured;
  measured.t = (copy.V - model.mesh.V).cwiseProduct(model.normals).rowwise().sum();
  measured.found.assign(static_cast<std::size_t>(copy.V.rows()), 1);
  measured.vertex_offsets = VertexOffsets{copy.V - model.mesh.V, measured.found};
  remove_fit(measured.t, measured.found, nuisance_fields(model, threads_of(control)));
  const double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  DetectResult result = read_matched_first(options, 0.4, control, [&](const DetectOptions& o, const JobControl* c) {
    DetectResult r = read_offset(model, measured, key, o, c);
    combine_evidence(r, o);
    return r;
  });
  result.seconds[detect_stage::read] = read_seconds;
  score_against_expected(result, options);
  return result;
}

}  // namespace meshmark
