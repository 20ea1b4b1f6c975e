#pragma once
// The stages of a detection, named once: the progress a JobControl reports, the keys of
// DetectResult::seconds and the benchmark's rows all use these words.

namespace meshmark::detect_stage {

inline constexpr const char* align = "align";        ///< registering the suspect to the original
inline constexpr const char* read = "read";          ///< its offset at the original's vertices, nuisances removed
inline constexpr const char* estimate = "estimate";  ///< the carriers' estimates (matched filter, regularized solves)
inline constexpr const char* decode = "decode";      ///< decoding each estimate, choosing one, scoring the payloads

}  // namespace meshmark::detect_stage
