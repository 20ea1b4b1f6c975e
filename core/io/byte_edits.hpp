#pragma once
// Replacing byte ranges of a file: how documents write back what changed and keep every other byte.

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace meshmark {

/// A half-open byte range of a file.
struct ByteSpan {
  std::size_t begin = 0, end = 0;
};

class ByteEdits {
 public:
  /// Replaces span with `text` (spans must not overlap).
  void replace(ByteSpan span, std::string text) { edits_.push_back({span, std::move(text)}); }
  bool empty() const { return edits_.empty(); }
  /// `original` with every replacement applied.
  std::string apply(std::string_view original) const {
    std::vector<const Edit*> order;
    for (const Edit& e : edits_) order.push_back(&e);
    std::sort(order.begin(), order.end(), [](const Edit* a, const Edit* b) { return a->span.begin < b->span.begin; });
    std::string out;
    out.reserve(original.size() + 64 * edits_.size());
    std::size_t at = 0;
    for (const Edit* e : order) {
      out.append(original.substr(at, e->span.begin - at));
      out.append(e->text);
      at = e->span.end;
    }
    out.append(original.substr(at));
    return out;
  }

 private:
  struct Edit {
    ByteSpan span;
    std::string text;
  };
  std::vector<Edit> edits_;
};

}  // namespace meshmark
