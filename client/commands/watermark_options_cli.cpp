#include "client/commands/watermark_options_cli.hpp"

#include <stdexcept>

namespace meshmark::cli {

void SchemeArgs::add_to(CLI::App* cmd) {
  scheme_option = cmd->add_option("--scheme", scheme, "spread (default) or paper")->capture_default_str();
  wavelet_option = cmd->add_option("--wavelet", wavelet, "lazy, linear, linear-lifting, butterfly or butterfly-lifting")
                       ->capture_default_str();
  base_option = cmd->add_option("--base", base, "Grid base solid: tetra, octa or icosa")->capture_default_str();
  cmd->add_option("--strength", strength,
                  "Distortion budget: RMS surface displacement in percent of the bounding-box diagonal, " +
                      strength_range_text())
      ->capture_default_str()
      ->check(CLI::Range(kMinStrengthPercent, kMaxStrengthPercent));
}

void SchemeArgs::fill_from_record(const std::string& record_scheme, const std::string& record_wavelet,
                                  const std::string& record_base) {
  auto take = [](CLI::Option* given, std::string& value, const std::string& recorded, const char* name) {
    if (given && given->count() > 0 && value != recorded)
      throw std::invalid_argument(std::string("--") + name + " " + value + " contradicts the copy's record (" +
                                  recorded + ")");
    value = recorded;
  };
  take(scheme_option, scheme, record_scheme, "scheme");
  take(wavelet_option, wavelet, record_wavelet, "wavelet");
  take(base_option, base, record_base, "base");
}

WatermarkOptions SchemeArgs::watermark() const {
  WatermarkOptions options;
  options.scheme = parse_scheme(scheme);
  options.wavelet = parse_wavelet_type(wavelet);
  options.strength_percent = strength;
  return options;
}

}  // namespace meshmark::cli
