#include "client/commands/eval_report.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <array>
#include <map>

namespace meshmark::cli {

namespace {

std::string today() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char buffer[16];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d", std::gmtime(&now));
  return buffer;
}

std::string format(const char* spec, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, spec, value);
  return buffer;
}

// Compact BER: 0 stays "0", small values in 3 decimals.
std::string ber(double value) { return value == 0 ? "0" : format("%.3f", value); }

struct Cell {
  double ber = 0, raw = 0;
  int trials = 0, detected = 0;
};

std::map<std::string, Cell> cells(const EvalResults& r) {
  std::map<std::string, Cell> out;
  for (const EvalOutcome& o : r.outcomes) {
    Cell& c = out[o.mesh + "|" + o.scheme + "|" + o.table + "|" + o.row];
    c.ber += o.ber;
    c.raw += std::max(0.0, o.raw_ber);
    c.trials += 1;
    c.detected += o.detected;
  }
  for (auto& [k, c] : out) c.ber /= c.trials, c.raw /= c.trials;
  return out;
}

// Jin et al. 2004, Table 1 (per-carrier BER; in brackets when embedded in the details only).
const std::map<std::string, std::pair<std::string, std::string>>& published() {
  static const std::map<std::string, std::pair<std::string, std::string>> table = {
      {"bunny|Reordering", {"1e-4", "1e-4"}},
      {"bunny|Simplification 1/4", {"0.087 (0.135)", "0.065"}},
      {"bunny|Simplification 1/8", {"0.165 (0.326)", "0.107"}},
      {"bunny|Noise 0.3%", {"0.063", "0.042"}},
      {"bunny|Noise 0.6%", {"0.125", "0.103"}},
      {"mannequin|Reordering", {"1e-4", "1e-4"}},
      {"mannequin|Simplification 1/4", {"0.085 (0.167)", "0.072"}},
      {"mannequin|Simplification 1/8", {"0.221 (0.302)", "0.108"}},
      {"mannequin|Noise 0.3%", {"0.067", "0.038"}},
      {"mannequin|Noise 0.6%", {"0.143", "0.088"}}};
  return table;
}

// A per-carrier rate as the paper prints it: three decimals, or two digits where it is below 1e-2
// (its reordering row is 1e-4).
std::string carrier_rate(double rate) { return rate > 0 && rate < 0.01 ? format("%.1e", rate) : format("%.3f", rate); }

std::string detected(const Cell& c) { return std::to_string(c.detected) + "/" + std::to_string(c.trials); }

// The title, what was run, and how to read the tables.
std::string intro_section(const EvalResults& r, const std::string& command) {
  std::string md = "# Robustness evaluation\n\n";
  md += "Produced by `" + command + "` on " + today() + ", " + format("%.0f", r.seconds) + " s with " +
        std::to_string(r.options.threads) + " threads. Meshes:";
  for (const EvalMesh& m : r.meshes)
    md += " " + m.name + " (" + std::to_string(m.vertices) + " vertices, " + m.basis + ")";
  md += ". " + std::to_string(r.options.trials) +
        " trial(s) per cell; each trial marks the mesh with its own random key and 64-bit payload "
        "(reproducible from the trial number), at strength " +
        format("%.2f", r.options.strength_percent) + " % of the bounding-box diagonal" +
        (r.options.strength_percent == WatermarkOptions{}.strength_percent ? " (the default)" : "") + ".\n\n";
  md +=
      "BER is the payload's bit error rate averaged over the trials (the blind decode against the payload "
      "embedded); *detected* counts the trials whose decision p-value is below 1e-6: the blind decode and the "
      "embedded payload as expected, each tested and charged for both (docs/method.md, Decide), as an owner checking "
      "a copy would.\n\n";
  return md;
}

bool has_table(const EvalResults& r, const std::string& table) {
  return std::any_of(r.rows.begin(), r.rows.end(), [&](const EvalRow& row) { return row.table == table; });
}

// Table 1 of Jin et al. beside our paper and spread schemes (only when the paper table was run).
std::string paper_section(const EvalResults& r, const std::map<std::string, Cell>& c) {
  std::string md;
  if (has_table(r, "paper")) {
    md += "## Table 1 of Jin et al. (2004), side by side\n\n";
    md +=
        "Their figures are per-carrier bit error rates (in brackets: watermark in the detail bands only). For "
        "our `paper` scheme we give the same per-carrier rate, then the payload BER after the majority vote; for "
        "the default `spread` scheme, the payload BER and detections.\n\n";
    md +=
        "| Attack | Mesh | Jin et al., linear | ours, paper linear: carriers / payload | Jin et al., linear lifting | "
        "ours, paper linear lifting: carriers / payload | ours, spread: payload (detected) |\n";
    md += "|---|---|---|---|---|---|---|\n";
    for (const EvalRow& row : r.rows) {
      if (row.table != "paper") continue;
      for (const EvalMesh& m : r.meshes) {
        const auto pub = published().find(m.name + "|" + row.label);
        const std::string base = m.name + "|";
        auto paper_cell = [&](const std::string& scheme) {
          const auto it = c.find(base + scheme + "|paper|" + row.label);
          return it == c.end() ? std::string("—") : carrier_rate(it->second.raw) + " / " + ber(it->second.ber);
        };
        const auto spread = c.find(base + "spread|paper|" + row.label);
        md += "| " + row.label + " | " + m.name + " | " + (pub != published().end() ? pub->second.first : "—") + " | " +
              paper_cell("paper linear") + " | " + (pub != published().end() ? pub->second.second : "—") + " | " +
              paper_cell("paper linear lifting") + " | " +
              (spread == c.end() ? "—" : ber(spread->second.ber) + " (" + detected(spread->second) + ")") + " |\n";
      }
    }
    md += "\n";
  }
  return md;
}

// One table of attack rows for the default scheme: BER (detections) per mesh, with the noise
// cells' SNR bounds.
std::string attack_table(const EvalResults& r, const std::map<std::string, Cell>& c, const std::string& table) {
  std::string md = "| Attack |";
  for (const EvalMesh& m : r.meshes) md += " " + m.name + " |";
  md += "\n|---|";
  for (std::size_t i = 0; i < r.meshes.size(); ++i) md += "---|";
  md += "\n";
  for (const EvalRow& row : r.rows) {
    if (row.table != table) continue;
    md += "| " + row.label + " |";
    for (const EvalMesh& m : r.meshes) {
      const auto it = c.find(m.name + "|spread|" + table + "|" + row.label);
      std::string cell = it == c.end() ? "—" : ber(it->second.ber) + " (" + detected(it->second) + ")";
      if (const double bound = noise_snr_bound(m, row); bound > 0) cell += " [bound " + format("%.1f", bound) + "]";
      md += " " + cell + " |";
    }
    md += "\n";
  }
  return md + "\n";
}

std::string benchmark_section(const EvalResults& r, const std::map<std::string, Cell>& c) {
  if (!has_table(r, "benchmark")) return "";  // `--tables beyond`: no empty table
  std::string md;
  md += "## Benchmark layout (Wang, Lavoué, Denis, Baskurt 2010), default scheme\n\n";
  md +=
      "Payload BER (detections). Noise is uniform per coordinate, in percent of the mean vertex–centroid "
      "distance; beside each noise cell, the bound on the per-bit signal-to-noise ratio that any detector "
      "faces, w·√(N/b)/σ (w the watermark's RMS displacement, N vertices, b = 64 bits, σ the noise along a "
      "normal): below about 2 no 64-bit payload can come through.\n\n";
  return md + attack_table(r, c, "benchmark");
}

std::string beyond_section(const EvalResults& r, const std::map<std::string, Cell>& c) {
  if (!has_table(r, "beyond")) return "";
  std::string md = "## Beyond the benchmark, default scheme\n\n";
  md +=
      "Attacks no published method reports: most of the surface cut away on one side of a random plane, "
      "then a random similarity; a crop, a simplification and noise together; the copy twisted about or "
      "bent along its longest axis (the angle from one end to the other), then moved; the surface "
      "re-extracted from its signed distance field on a grid of the given step (every vertex new), then "
      "moved. Payload BER (detections); noise and steps in percent of the bounding-box diagonal.\n\n";
  return md + attack_table(r, c, "beyond");
}

// MRMS and Hausdorff distance of the marked meshes.
std::string distortion_section(const EvalResults& r) {
  std::string md;
  md +=
      "## Distortion of the watermarked meshes\n\nMRMS and Hausdorff distance in percent of the bounding-box "
      "diagonal (mean over trials; 100,000 samples per surface).\n\n| Mesh | Scheme | MRMS | Hausdorff "
      "|\n|---|---|---|---|\n";
  std::map<std::string, std::array<double, 3>> distortion;
  for (const EvalDistortion& d : r.distortions) {
    auto& acc = distortion[d.mesh + "|" + d.scheme];
    acc[0] += d.mrms, acc[1] += d.hausdorff, acc[2] += 1;
  }
  for (const auto& [key, acc] : distortion) {
    const auto bar = key.find('|');
    md += "| " + key.substr(0, bar) + " | " + key.substr(bar + 1) + " | " + format("%.4f %%", 100 * acc[0] / acc[2]) +
          " | " + format("%.4f %%", 100 * acc[1] / acc[2]) + " |\n";
  }
  md += "\n";
  return md;
}

// Detections on the unmarked original and with a wrong key.
std::string false_alarm_section(const EvalResults& r) {
  std::string md;
  md +=
      "## False alarms\n\nThe default scheme's detector on the unmarked original and on the marked mesh with a "
      "wrong key: how often it reported a watermark, and the smallest p-value it gave.\n\n"
      "| Mesh | unmarked: detected | wrong key: detected | smallest p-value |\n|---|---|---|---|\n";
  for (const EvalMesh& m : r.meshes) {
    int unmarked = 0, wrong = 0, n_unmarked = 0, n_wrong = 0;
    double least = 0;
    for (const EvalFalseAlarm& f : r.false_alarms) {
      if (f.mesh != m.name) continue;
      (f.kind == "unmarked" ? unmarked : wrong) += f.detected;
      (f.kind == "unmarked" ? n_unmarked : n_wrong) += 1;
      least = std::min(least, f.log10_p);
    }
    md += "| " + m.name + " | " + std::to_string(unmarked) + "/" + std::to_string(n_unmarked) + " | " +
          std::to_string(wrong) + "/" + std::to_string(n_wrong) + " | " + (least == 0 ? "1" : format("1e%.1f", least)) +
          " |\n";
  }
  md += "\n";
  return md;
}

// The null distribution of the p-values (eval --null).
std::string null_section(const EvalResults& r) {
  std::string md;
  if (!r.nulls.empty()) {
    md += "## Null distribution\n\n" + std::to_string(r.options.null_detections) +
          " detections per mesh where no watermark of the key is (half the unmarked original, half the "
          "marked copy read with another key, and half of each bent by 20° and moved first, so that what the "
          "non-rigid fit could add is measured; each with its own key and expected payload, so both tests of a "
          "local detection are made: blind decode and expected payload). An honest p-value is exceeded by chance no "
          "more often than it says: "
          "the share of null detections at or below each p must not exceed it.\n\n"
          "| Mesh | detected | p ≤ 0.1 | p ≤ 0.01 | p ≤ 0.001 | smallest p-value |\n|---|---|---|---|---|---|\n";
    for (const EvalMesh& m : r.meshes) {
      int n = 0, detected = 0, below[3] = {0, 0, 0};
      double least = 0;
      for (const EvalFalseAlarm& f : r.nulls) {
        if (f.mesh != m.name) continue;
        ++n;
        detected += f.detected;
        for (int k = 0; k < 3; ++k) below[k] += f.log10_p <= -(k + 1);
        least = std::min(least, f.log10_p);
      }
      md += "| " + m.name + " | " + std::to_string(detected) + "/" + std::to_string(n);
      for (int k = 0; k < 3; ++k) md += " | " + format("%.3f", n ? static_cast<double>(below[k]) / n : 0.0);
      md += " | " + (least > -3 ? format("%.2g", std::pow(10.0, least)) : format("1e%.1f", least)) + " |\n";
    }
    md += "\n";
  }
  return md;
}

// BER against strength under strong noise (eval --sweep).
std::string sweep_section(const EvalResults& r) {
  std::string md;
  if (!r.sweep.empty()) {
    md +=
        "## BER against strength, noise 0.6 % of the bounding-box diagonal\n\nPayload BER (measured MRMS): "
        "the price of robustness to strong noise on each mesh.\n\n| Strength |";
    for (const EvalMesh& m : r.meshes) md += " " + m.name + " |";
    md += "\n|---|";
    for (std::size_t i = 0; i < r.meshes.size(); ++i) md += "---|";
    md += "\n";
    for (double s : r.options.strength_sweep) {
      md += "| " + format("%.2f %%", s) + " |";
      for (const EvalMesh& m : r.meshes) {
        double b = 0, mrms = 0;
        int n = 0;
        for (const EvalSweep& e : r.sweep)
          if (e.mesh == m.name && e.strength == s) b += e.ber, mrms += e.mrms, ++n;
        md += n ? " " + ber(b / n) + " (" + format("%.3f %%", 100 * mrms / n) + ") |" : " — |";
      }
      md += "\n";
    }
    md += "\n";
  }
  return md;
}

// The promised figures: met, or what was missed.
std::string requirements_section(const EvalResults& r) {
  std::string md;
  const auto missed = check_requirements(r);
  md += "## Requirements\n\n";
  if (missed.empty()) {
    md += "All met: BER 0 with the default scheme on every promised row, no false alarm, MRMS ≤ 0.05 %.\n";
  } else {
    md += "Missed:\n\n";
    for (const auto& m : missed) md += "- " + m + "\n";
  }
  return md;
}

}  // namespace

std::string eval_markdown(const EvalResults& r, const std::string& command) {
  const auto c = cells(r);
  return intro_section(r, command) + paper_section(r, c) + benchmark_section(r, c) + beyond_section(r, c) +
         distortion_section(r) + false_alarm_section(r) + null_section(r) + sweep_section(r) + requirements_section(r);
}

nlohmann::json eval_json(const EvalResults& r, const std::string& command) {
  nlohmann::json j;
  j["command"] = command;
  j["date"] = today();
  j["seconds"] = r.seconds;
  j["trials"] = r.options.trials;
  for (const EvalMesh& m : r.meshes)
    j["meshes"].push_back({{"name", m.name}, {"vertices", m.vertices}, {"basis", m.basis}});
  for (const EvalOutcome& o : r.outcomes)
    j["outcomes"].push_back({{"mesh", o.mesh},
                             {"scheme", o.scheme},
                             {"table", o.table},
                             {"attack", o.row},
                             {"trial", o.trial},
                             {"ber", o.ber},
                             {"raw_ber", o.raw_ber},
                             {"detected", o.detected},
                             {"z", o.z},
                             {"log10_p", o.log10_p}});
  for (const EvalDistortion& d : r.distortions)
    j["distortion"].push_back(
        {{"mesh", d.mesh}, {"scheme", d.scheme}, {"trial", d.trial}, {"mrms", d.mrms}, {"hausdorff", d.hausdorff}});
  for (const EvalFalseAlarm& f : r.false_alarms)
    j["false_alarms"].push_back(
        {{"mesh", f.mesh}, {"kind", f.kind}, {"trial", f.trial}, {"detected", f.detected}, {"log10_p", f.log10_p}});
  for (const EvalFalseAlarm& f : r.nulls)
    j["null_detections"].push_back(
        {{"mesh", f.mesh}, {"kind", f.kind}, {"index", f.trial}, {"detected", f.detected}, {"log10_p", f.log10_p}});
  for (const EvalSweep& s : r.sweep)
    j["strength_sweep"].push_back(
        {{"mesh", s.mesh}, {"trial", s.trial}, {"strength", s.strength}, {"mrms", s.mrms}, {"ber", s.ber}});
  j["requirements_missed"] = check_requirements(r);
  return j;
}

}  // namespace meshmark::cli
