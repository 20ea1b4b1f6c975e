#pragma once
// Reading a copy whose payload length nobody recorded: every length a copy of this model could
// have been made with is read, the strongest reading counts, and its p-value is charged for the
// number of lengths read, so that trying more lengths never makes evidence look stronger.

#include <vector>

#include "core/watermark/watermark.hpp"

namespace meshmark {

/// The lengths a copy of `model` may carry with `options`: 64 bits when the model carries them
/// (the default payload), else 16, 32 and the longest it carries, those it can hold. Empty when
/// it carries none. The paper scheme has no such measure: its only length is 64.
std::vector<int> plausible_payload_lengths(const PreparedModel& model, const WatermarkOptions& options, int threads);

/// detect_watermark at each of `lengths` (options.payload_bits is ignored): the strongest reading
/// (a checksum match first, then the smaller p-value), charged for lengths.size() readings.
DetectResult detect_at_lengths(const PreparedModel& model, const Mesh& suspect, const std::string& key,
                               const std::vector<int>& lengths, DetectOptions options,
                               const RegistrationTarget* target = nullptr, const JobControl* control = nullptr);

}  // namespace meshmark
