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

  void add_to(CLI::App* cmd);
  WatermarkOptions watermark() const;
  BaseSolid base_solid() const { return parse_base_solid(base); }
};

}  // namespace meshmark::cli
