#pragma once
// The options `embed` and `detect` share (detection must be given the embedding's options).

#include <CLI/CLI.hpp>
#include <string>

#include "core/grid/sphere_grid.hpp"
#include "core/watermark/watermark_options.hpp"

namespace meshmark::cli {

struct SchemeArgs {
  std::string scheme = "spread";
  std::string wavelet = "linear-lifting";
  std::string base = "tetra";
  double strength = WatermarkOptions{}.strength_percent;
  // Set by add_to: whether the user gave each option (a copy's record fills in the others).
  CLI::Option* scheme_option = nullptr;
  CLI::Option* wavelet_option = nullptr;
  CLI::Option* base_option = nullptr;

  void add_to(CLI::App* cmd);
  /// Takes each setting from the record unless the user gave it; one the user gave that differs
  /// from the record is refused (std::invalid_argument): the copy was made otherwise.
  void fill_from_record(const std::string& record_scheme, const std::string& record_wavelet,
                        const std::string& record_base);
  WatermarkOptions watermark() const;
  BaseSolid base_solid() const { return parse_base_solid(base); }
};

}  // namespace meshmark::cli
