#include "server/store/sql_database.hpp"

#include <charconv>
#include <stdexcept>

namespace meshmark::server::sql {

namespace {

template <typename Number>
Number number(const std::optional<std::string>& text) {
  Number value{};
  if (!text) return value;
  const auto [end, error] = std::from_chars(text->data(), text->data() + text->size(), value);
  if (error != std::errc() || end != text->data() + text->size())
    throw std::runtime_error("the store holds '" + *text + "' where a number belongs");
  return value;
}

}  // namespace

long long Row::integer(std::size_t column) const { return number<long long>(columns_.at(column)); }
double Row::real(std::size_t column) const { return number<double>(columns_.at(column)); }

}  // namespace meshmark::server::sql
