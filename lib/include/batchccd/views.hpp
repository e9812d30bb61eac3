#pragma once

#include <cstdint>
#include <type_traits>

#include <Eigen/Core>

// The caller's arrays, read where they lie: a simulator's positions and
// index matrices in whatever layout it keeps them (Eigen column- or
// row-major, a block of a larger matrix, a NumPy buffer), never copied
// before the call. Views hold pointers: the arrays must outlive the view,
// and a view cannot be made from a temporary Eigen matrix (it would die at
// the end of the statement that made the view).
namespace batchccd {

// A rows x cols matrix of T: entry (i, j) at data[i * row_stride +
// j * column_stride] (strides in elements, any sign). Default: 0 x 0, the
// empty matrix.
template <class T>
class MatrixView {
 public:
  MatrixView() = default;
  MatrixView(const T* data, std::int64_t rows, std::int64_t cols, std::int64_t row_stride,
             std::int64_t column_stride)
      : data_(data), rows_(rows), cols_(cols), row_stride_(row_stride), column_stride_(column_stride) {}

  // Any Eigen matrix, block, Map or Ref over T with direct access to its
  // entries, in either storage order and with any strides.
  template <class Derived>
    requires(std::is_same_v<typename Derived::Scalar, T> && (Derived::Flags & Eigen::DirectAccessBit) != 0)
  MatrixView(const Eigen::DenseBase<Derived>& matrix)  // NOLINT(google-explicit-constructor): a view converts
      : MatrixView(matrix.derived().data(), matrix.rows(), matrix.cols(), matrix.derived().rowStride(),
                   matrix.derived().colStride()) {}
  // Not from a temporary matrix: the view would outlive its entries.
  template <class Derived>
  MatrixView(const Eigen::PlainObjectBase<Derived>&&) = delete;

  std::int64_t rows() const { return rows_; }
  std::int64_t cols() const { return cols_; }
  const T& operator()(std::int64_t i, std::int64_t j) const { return data_[i * row_stride_ + j * column_stride_]; }

 private:
  const T* data_ = nullptr;
  std::int64_t rows_ = 0, cols_ = 0, row_stride_ = 0, column_stride_ = 0;
};

// Vertex positions, n x 3, in double or in float (every float is a double,
// so nothing is rounded: the float positions are evaluated exactly as given).
class PositionsView {
 public:
  PositionsView() = default;
  PositionsView(MatrixView<double> doubles) : doubles_(doubles), is_float_(false) {}  // NOLINT: converts
  PositionsView(MatrixView<float> floats) : floats_(floats), is_float_(true) {}       // NOLINT: converts
  template <class Derived>
    requires(std::is_constructible_v<MatrixView<double>, const Derived&> ||
             std::is_constructible_v<MatrixView<float>, const Derived&>)
  PositionsView(const Eigen::DenseBase<Derived>& matrix)  // NOLINT(google-explicit-constructor)
      : PositionsView(as_view(matrix.derived())) {}
  template <class Derived>
  PositionsView(const Eigen::PlainObjectBase<Derived>&&) = delete;

  std::int64_t rows() const { return is_float_ ? floats_.rows() : doubles_.rows(); }
  std::int64_t cols() const { return is_float_ ? floats_.cols() : doubles_.cols(); }
  double operator()(std::int64_t i, std::int64_t j) const { return is_float_ ? floats_(i, j) : doubles_(i, j); }

  // Calls f with the MatrixView<double> or MatrixView<float> this holds, so
  // that a loop over many entries decides the type once.
  template <class F>
  decltype(auto) visit(F&& f) const {
    return is_float_ ? f(floats_) : f(doubles_);
  }

 private:
  template <class Derived>
  static auto as_view(const Derived& matrix) {
    return MatrixView<typename Derived::Scalar>(matrix);
  }
  MatrixView<double> doubles_;
  MatrixView<float> floats_;
  bool is_float_ = false;
};

// Vertex ids: faces (m x 3), edges (k x 2).
using IdsView = MatrixView<int>;

}  // namespace batchccd
