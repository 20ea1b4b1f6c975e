#include "core/util/binary_io.hpp"

#include <gtest/gtest.h>

namespace meshmark {
namespace {

using RowMajor3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// The bytes an entry-by-entry writer made: rows, columns, then each entry in row order.
std::string entry_by_entry(const Eigen::MatrixXd& m) {
  BinaryWriter w;
  w.put(static_cast<std::uint64_t>(m.rows()));
  w.put(static_cast<std::uint64_t>(m.cols()));
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) w.put(m(i, j));
  return w.bytes();
}

// Matrices go as blocks, in either storage order: the bytes are the entry-by-entry format's, and
// they read back into either order as they were.
TEST(BinaryIo, AMatrixIsWrittenInRowOrderWhateverItsStorageAndReadBackWhole) {
  const Eigen::MatrixXd column_major = Eigen::MatrixXd::Random(7, 3);
  const RowMajor3 row_major = column_major;
  BinaryWriter a, b;
  a.put_matrix(column_major);
  b.put_matrix(row_major);
  EXPECT_EQ(a.bytes(), entry_by_entry(column_major));
  EXPECT_EQ(b.bytes(), a.bytes());
  BinaryReader ra(a.bytes()), rb(a.bytes());
  EXPECT_EQ(ra.get_matrix<Eigen::MatrixXd>(), column_major);
  EXPECT_EQ(rb.get_matrix<RowMajor3>(), row_major);
  EXPECT_EQ(ra.remaining(), 0u);
}

// A stored shape its type cannot hold, or more entries than the bytes left, is corrupt data.
TEST(BinaryIo, AMatrixOfAnotherShapeOrLongerThanTheFileIsRefused) {
  BinaryWriter w;
  w.put_matrix(Eigen::MatrixXd::Random(4, 2));
  BinaryReader wrong_columns(w.bytes());
  EXPECT_THROW(wrong_columns.get_matrix<RowMajor3>(), std::runtime_error);
  const std::string cut = w.bytes().substr(0, w.bytes().size() - 1);
  BinaryReader truncated(cut);
  EXPECT_THROW(truncated.get_matrix<Eigen::MatrixXd>(), std::runtime_error);
}

}  // namespace
}  // namespace meshmark
