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
  /// Room for `edits` replacements of `text_bytes` bytes in all, when a writer knows them.
  void reserve(std::size_t edits, std::size_t text_bytes) {
    edits_.reserve(edits);
    texts_.reserve(text_bytes);
  }
  bool empty() const { return edits_.empty(); }
  /// `original` with every replacement applied.
  std::string apply(std::string_view original) const {
    const auto by_start = [](const Edit& a, const Edit& b) { return a.span.begin < b.span.begin; };
    std::vector<Edit> sorted;  // a writer's edits mostly come in file order: then they are used as they are
    if (!std::is_sorted(edits_.begin(), edits_.end(), by_start)) {
      sorted = edits_;
      std::stable_sort(sorted.begin(), sorted.end(), by_start);  // insertions at one place keep their order
    }
    const std::vector<Edit>& order = sorted.empty() ? edits_ : sorted;
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
