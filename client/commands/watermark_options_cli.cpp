#include "client/commands/watermark_options_cli.hpp"

namespace meshmark::cli {

void SchemeArgs::add_to(CLI::App* cmd) {
  cmd->add_option("--scheme", scheme, "spread (default) or paper")->capture_default_str();
  cmd->add_option("--wavelet", wavelet, "lazy, linear, linear-lifting, butterfly or butterfly-lifting")
      ->capture_default_str();
  cmd->add_option("--base", base, "Grid base solid: tetra, octa or icosa")->capture_default_str();
  cmd->add_option("--strength", strength,
                  "Distortion budget: RMS surface displacement in percent of the bounding-box diagonal")
      ->capture_default_str();
}

WatermarkOptions SchemeArgs::watermark() const {
  WatermarkOptions options;
  options.scheme = parse_scheme(scheme);
  options.wavelet = parse_wavelet_type(wavelet);
  options.strength_percent = strength;
  return options;
}

}  // namespace meshmark::cli
