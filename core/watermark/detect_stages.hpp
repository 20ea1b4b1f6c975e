#pragma once
// The stages of an embedding and of a detection, named once: the progress a JobControl reports,
// the keys of EmbedResult::seconds and DetectResult::seconds, and the benchmark's rows all use
// these words.

namespace meshmark::embed_stage {

inline constexpr const char* plan = "plan";            ///< carriers, chips and amplitudes
inline constexpr const char* synthesis = "synthesis";  ///< the change synthesized and mapped to the vertices
inline constexpr const char* apply = "apply";          ///< the vertices moved, scaled to the budget

}  // namespace meshmark::embed_stage

namespace meshmark::detect_stage {

inline constexpr const char* align = "align";        ///< registering the suspect to the original
inline constexpr const char* read = "read";          ///< its offset at the original's vertices, nuisances removed
inline constexpr const char* estimate = "estimate";  ///< the carriers' estimates (matched filter, regularized solves)
inline constexpr const char* decode = "decode";      ///< decoding each estimate, choosing one, scoring the payloads

}  // namespace meshmark::detect_stage
