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
  void replace(ByteSpan span, std::string_view text) {
    edits_.push_back({span, texts_.size(), text.size()});
    texts_.append(text);
  }
  bool empty() const { return edits_.empty(); }
  /// `original` with every replacement applied.
  std::string apply(std::string_view original) const {
    std::vector<Edit> order = edits_;
    const auto by_start = [](const Edit& a, const Edit& b) { return a.span.begin < b.span.begin; };
    if (!std::is_sorted(order.begin(), order.end(), by_start))  // a writer's edits mostly come in file order
      std::stable_sort(order.begin(), order.end(), by_start);   // insertions at one place keep their order
    std::size_t removed = 0;
    for (const Edit& e : order) removed += e.span.end - e.span.begin;
    std::string out;
    out.reserve(original.size() - std::min(removed, original.size()) + texts_.size());
    std::size_t at = 0;
    for (const Edit& e : order) {
      out.append(original.substr(at, e.span.begin - at));
      out.append(texts_, e.text_begin, e.text_size);
      at = e.span.end;
    }
    out.append(original.substr(at));
    return out;
  }

 private:
  // Every replacement's text lives in one string: a copy's hundred thousand coordinates are one
  // allocation, not one each.
  struct Edit {
    ByteSpan span;
    std::size_t text_begin, text_size;
  };
  std::vector<Edit> edits_;
  std::string texts_;
};

}  // namespace meshmark
