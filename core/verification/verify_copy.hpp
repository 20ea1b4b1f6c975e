#pragma once
// Before a copy leaves, the real detector reads it back: as written (in its format's own
// precision, read back from its bytes; in place when it has the original's faces, in the
// original's vertex order or numbered anew as a triangle format reads back) and after one mild
// standard attack (a re-save with six significant digits about the copy's centre and a random
// similarity, its pose found by its shape as a copy that lost its order would be registered,
// then read at its vertices). A copy that does not give its payload with no bit wrong and a
// decision is never handed out: the loss would be found only on the day of the leak.

#include <cstdint>
#include <string>
#include <vector>

#include "core/registration/align_meshes.hpp"
#include "core/util/input_error.hpp"
#include "core/watermark/watermark.hpp"

namespace meshmark {

/// One reading of the copy.
struct CopyReading {
  std::string name;         ///< "as written" or the attack read
  bool registered = false;  ///< read through registration (the copy was moved), not in place
  std::size_t poses = 0;    ///< registered: the candidate poses read (several: the shape has symmetries)
  bool passed = false;
  bool detected = false;
  bool payload_read = false;  ///< the checksum matched and the payload is the one embedded
  double ber = 1;
  double log10_p_value = 0;
  double seconds = 0;
};

struct CopyVerification {
  std::vector<CopyReading> readings;
  bool skipped = false;  ///< --no-verify: nothing was read
  bool passed() const;
  double seconds() const;
};

/// A copy that did not read back; the message says which reading failed, how, and what to try.
class CopyUnreadable : public InputError {
 public:
  explicit CopyUnreadable(const std::string& message) : InputError(message) {}
};

struct VerifyOptions {
  int digits = 6;          ///< the re-save's significant digits
  std::uint64_t seed = 1;  ///< of the random similarity
  /// An earlier copy of this model was read through registration after the mild attack: whether
  /// registration finds a moved copy depends on the shape, not on the payload, so this copy's
  /// re-save is read in place (the daemon proves it once per prepared model; the cost of a copy
  /// is then two in-place readings). Not for a shape whose axes leave turns to search
  /// (turns_ambiguous): there the pose found can depend on the mark, and every copy is moved and
  /// registered.
  bool registration_proven = false;
};

/// Reads `as_written` (the copy's surface as a reader of its bytes finds it; taken by value and
/// attacked in place, so pass it by move where it is not needed after) and its mildly attacked version against `model`
/// with the real detector, expecting `payload` embedded with `key` and `options`. `target`: the model's registration
/// data. Progress is reported as the stage "verify". Throws what detect_watermark throws.
CopyVerification verify_copy(const PreparedModel& model, const RegistrationTarget& target, Mesh as_written,
                             const std::string& key, const Bits& payload, const WatermarkOptions& options,
                             const VerifyOptions& verify = {}, const JobControl* control = nullptr);

/// Throws CopyUnreadable when `verification` did not pass.
void require_readable(const CopyVerification& verification, const Bits& payload);

}  // namespace meshmark
