#pragma once
// Little-endian binary writing and bounds-checked reading, for files the service writes and
// must read back (a truncated or foreign file is an error, never a crash).

#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace meshmark {

template <typename Scalar>
using RowMajor = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class BinaryWriter {
 public:
  template <typename T>
  void put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    bytes_.append(raw, sizeof(T));
  }
  void put(const std::string& s) {
    put(static_cast<std::uint64_t>(s.size()));
    bytes_ += s;
  }
  /// Rows, columns, then the entries row by row.
  template <typename Derived>
  void put_matrix(const Eigen::DenseBase<Derived>& m) {
    put(static_cast<std::uint64_t>(m.rows()));
    put(static_cast<std::uint64_t>(m.cols()));
    if constexpr (std::endian::native == std::endian::little) {  // the entries' bytes as they lie in row order
      using Scalar = typename Derived::Scalar;
      const RowMajor<Scalar> rows = m;
      bytes_.append(reinterpret_cast<const char*>(rows.data()), static_cast<std::size_t>(rows.size()) * sizeof(Scalar));
    } else {
      for (Eigen::Index i = 0; i < m.rows(); ++i)
        for (Eigen::Index j = 0; j < m.cols(); ++j) put(m(i, j));
    }
  }
  const std::string& bytes() const { return bytes_; }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class BinaryReader {
 public:
  explicit BinaryReader(std::string_view bytes) : bytes_(bytes) {}

  template <typename T>
  T get() {
    static_assert(std::is_arithmetic_v<T>);
    need(sizeof(T));
    char raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + pos_, sizeof(T));
    if constexpr (std::endian::native == std::endian::big)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    pos_ += sizeof(T);
    T value;
    std::memcpy(&value, raw, sizeof(T));
    return value;
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    need(n);
    std::string s(bytes_.substr(pos_, n));
    pos_ += n;
    return s;
  }
  template <typename Matrix>
  Matrix get_matrix(std::size_t element_bytes = sizeof(typename Matrix::Scalar)) {
    const auto rows = get<std::uint64_t>(), cols = get<std::uint64_t>();
    if (cols != 0 && rows > remaining() / (cols * element_bytes))
      throw std::runtime_error("corrupt data: a matrix larger than the file");
    if ((Matrix::RowsAtCompileTime != Eigen::Dynamic && rows != std::uint64_t(Matrix::RowsAtCompileTime)) ||
        (Matrix::ColsAtCompileTime != Eigen::Dynamic && cols != std::uint64_t(Matrix::ColsAtCompileTime)))
      throw std::runtime_error("corrupt data: a matrix of another shape");
    using Scalar = typename Matrix::Scalar;
    Matrix m(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
    if constexpr (std::endian::native == std::endian::little) {
      if (element_bytes == sizeof(Scalar)) {  // the entries' bytes copied at once, in row order
        if constexpr (Matrix::IsRowMajor || Matrix::ColsAtCompileTime == 1) {
          copy_entries(m.data(), m.size());
        } else {
          RowMajor<Scalar> in_rows(m.rows(), m.cols());
          copy_entries(in_rows.data(), in_rows.size());
          m = in_rows;
        }
        return m;
      }
    }
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      for (Eigen::Index j = 0; j < m.cols(); ++j) m(i, j) = get<Scalar>();
    return m;
  }
  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return bytes_.size() - pos_; }

 private:
  void need(std::size_t n) const {
    if (n > remaining()) throw std::runtime_error("corrupt data: the file ends too early");
  }
  template <typename Scalar>
  void copy_entries(Scalar* out, Eigen::Index count) {
    const std::size_t size = static_cast<std::size_t>(count) * sizeof(Scalar);
    need(size);
    std::memcpy(static_cast<void*>(out), bytes_.data() + pos_, size);
    pos_ += size;
  }
  std::string_view bytes_;
  std::size_t pos_ = 0;
};

}  // namespace meshmark
